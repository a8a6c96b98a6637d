// The layer coverage report as JSON: write_report.h.

#include <strata/core/cell_quality.h>
#include <strata/core/error.h>
#include <strata/core/format.h>
#include <strata/core/plane_cut.h>
#include <strata/io/files.h>
#include <strata/io/write_report.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

namespace strata {
namespace {

/// \p s as a JSON string literal.
std::string quoted(const std::string& s) {
    std::string out = "\"";
    for (const char c : s) {
        switch (c) {
            case '"':
                out += "\\\"";
                break;
            case '\\':
                out += "\\\\";
                break;
            case '\n':
                out += "\\n";
                break;
            case '\t':
                out += "\\t";
                break;
            default:
                if (static_cast<unsigned char>(c) < 0x20) {
                    char buf[8];
                    std::snprintf(buf, sizeof buf, "\\u%04x", static_cast<unsigned>(static_cast<unsigned char>(c)));
                    out += buf;
                } else {
                    out += c;
                }
        }
    }
    return out + "\"";
}

/// A finite number, or null (JSON has no infinity or NaN).
std::string number(double x) {
    return std::isfinite(x) ? format_number(x, 17) : "null";
}

/// A number for a picture: 7 significant digits, or null.
std::string short_number(double x) {
    return std::isfinite(x) ? format_number(x, 7) : "null";
}

/// "nodes", "cells" and "quality" (write_mesh_report), each line ending with ",\n".
void write_figures(std::ostream& out, const VolumeMesh& mesh, const ValidationReport& v) {
    out << "  \"nodes\": " << mesh.points.size() << ",\n  \"cells\": {";
    for (std::size_t k = 0; k < kCellTypes.size(); ++k)
        out << (k ? ", " : "") << quoted(std::string(to_string(kCellTypes[k]))) << ": "
            << mesh.num_cells(kCellTypes[k]);
    out << "},\n  \"quality\": {\n    \"min_scaled_jacobian\": {\"all\": " << number(v.min_scaled_jacobian);
    for (const CellType t : kCellTypes)
        if (mesh.num_cells(t) > 0)
            out << ", " << quoted(std::string(to_string(t))) << ": "
                << number(v.by_type[static_cast<std::size_t>(t)].min_scaled_jacobian);
    out << "},\n    \"bin_edges\": [0";
    for (int b = 0; b < kQualityBins; ++b) out << ", " << number(quality_bin_edge(b));
    out << "],\n    \"histograms\": {";
    bool first = true;
    for (const CellType t : kCellTypes) {
        if (mesh.num_cells(t) == 0) continue;
        out << (first ? "\n      " : ",\n      ") << quoted(std::string(to_string(t))) << ": [";
        first = false;
        const auto& h = v.by_type[static_cast<std::size_t>(t)].histogram;
        for (std::size_t b = 0; b < h.size(); ++b) out << (b ? ", " : "") << h[b];
        out << "]";
    }
    out << (first ? "}" : "\n    }");
    const SolverChecks& f = v.solver;
    out << ",\n    \"openfoam\": {\"max_non_orthogonality_deg\": " << number(f.max_non_orthogonality_deg)
        << ", \"mean_non_orthogonality_deg\": " << number(f.mean_non_orthogonality_deg)
        << ", \"severely_non_orthogonal_faces\": " << f.severely_non_orthogonal
        << ", \"non_orthogonality_errors\": " << f.non_orthogonality_errors
        << ", \"worst_non_orthogonal\": " << quoted(f.worst_non_orthogonal)
        << ",\n      \"max_skewness\": " << number(f.max_skewness) << ", \"skew_faces\": " << f.skew_faces
        << ", \"worst_skew\": " << quoted(f.worst_skew)
        << ",\n      \"max_aspect_ratio\": " << number(f.max_aspect_ratio)
        << ", \"high_aspect_cells\": " << f.high_aspect_cells << ", \"worst_aspect\": " << quoted(f.worst_aspect)
        << ",\n      \"negative_pyramids\": " << f.negative_pyramids
        << ", \"check_mesh_ok\": " << (f.ok() ? "true" : "false") << ", \"failures\": [";
    const std::vector<std::string> fails = f.failures();
    for (std::size_t i = 0; i < fails.size(); ++i) out << (i ? ", " : "") << quoted(fails[i]);
    out << "]}\n  },\n";
}

void write_report(const LayerReport& r, const std::string& path, const VolumeMesh* mesh,
                  const ValidationReport* quality, OutputSet* outputs) {
    OutputSet own;
    AtomicFile& file = (outputs ? *outputs : own).file(path);
    {
        std::ostringstream out;
        out << "{\n  \"layers\": " << r.layers << ",\n  \"first_height\": " << number(r.first_height)
            << ",\n  \"thickness\": " << number(r.thickness) << ",\n";
        if (mesh && quality) write_figures(out, *mesh, *quality);
        out << "  \"layer_stats\": [";
        for (std::size_t i = 0; i < r.per_layer.size(); ++i) {
            const LayerFigures& l = r.per_layer[i];
            out << (i ? ",\n" : "\n") << "    {\"layer\": " << i + 1 << ", \"height\": " << number(l.height)
                << ", \"min_scaled_jacobian\": " << number(l.min_scaled_jacobian)
                << ", \"mean_scaled_jacobian\": " << number(l.mean_scaled_jacobian)
                << ", \"max_orthogonality_deg\": " << number(l.max_orthogonality_deg) << ", \"columns\": " << l.columns
                << ", \"stopped_nodes\": " << l.stopped_nodes << ", \"held_nodes\": " << l.held_nodes << "}";
        }
        out << (r.per_layer.empty() ? "],\n" : "\n  ],\n") << "  \"patches\": [";
        for (std::size_t i = 0; i < r.patches.size(); ++i) {
            const PatchCoverage& c = r.patches[i];
            out << (i ? ",\n" : "\n") << "    {\"name\": " << quoted(c.name) << ", \"faces\": " << c.faces
                << ", \"nodes\": " << c.nodes << ", \"full_nodes\": " << c.full_nodes
                << ", \"all_layers\": " << c.all_layers << ", \"mean_share\": " << number(c.mean_share)
                << ", \"min_share\": " << number(c.min_share) << ", \"mean_layers\": " << number(c.mean_layers)
                << ", \"min_layers\": " << c.min_layers << ", \"short\": {";
            for (std::size_t k = 1; k < kShortfalls; ++k)  // every reason but None, by name
                out << (k > 1 ? ", " : "") << quoted(std::string(to_string(static_cast<Shortfall>(k)))) << ": "
                    << c.short_by[k];
            out << "}}";
        }
        out << (r.patches.empty() ? "],\n" : "\n  ],\n") << "  \"short_nodes\": [";
        for (std::size_t i = 0; i < r.short_nodes.size(); ++i) {
            const ShortNode& n = r.short_nodes[i];
            out << (i ? ",\n" : "\n") << "    {\"node\": " << n.node << ", \"position\": [" << number(n.position.x())
                << ", " << number(n.position.y()) << ", " << number(n.position.z())
                << "], \"share\": " << number(n.share) << ", \"layers\": " << n.layers
                << ", \"reason\": " << quoted(std::string(to_string(n.reason))) << "}";
        }
        out << (r.short_nodes.empty() ? "],\n" : "\n  ],\n") << "  \"no_fan_nodes\": [";
        for (std::size_t i = 0; i < r.no_fan.size(); ++i) {
            const NoFanNode& n = r.no_fan[i];
            out << (i ? ",\n" : "\n") << "    {\"node\": " << n.node << ", \"position\": [" << number(n.position.x())
                << ", " << number(n.position.y()) << ", " << number(n.position.z())
                << "], \"reason\": " << quoted(std::string(to_string(n.reason))) << "}";
        }
        out << (r.no_fan.empty() ? "]\n}\n" : "\n  ]\n}\n");
        write_whole_file(file.temp_path(), path, out.str());
    }
    if (!outputs) own.commit();
}

}  // namespace

std::string report_path(const std::string& mesh_path) {
    // Beside an output directory (an OpenFOAM polyMesh), not in it: "polyMesh/" as "polyMesh".
    std::string p = mesh_path;
    while (p.size() > 1 && p.back() == '/') p.pop_back();
    return p + ".report.json";
}

void write_layer_report(const LayerReport& r, const std::string& path, OutputSet* outputs) {
    write_report(r, path, nullptr, nullptr, outputs);
}

void write_mesh_report(const LayerReport& r, const VolumeMesh& mesh, const ValidationReport& quality,
                       const std::string& path, OutputSet* outputs) {
    write_report(r, path, &mesh, &quality, outputs);
}

std::string plot_data_path(const std::string& mesh_path) {
    std::string p = mesh_path;
    while (p.size() > 1 && p.back() == '/') p.pop_back();
    return p + ".plot.json";
}

void write_plot_data(const LayerReport& r, const SurfaceMesh& surface, const VolumeMesh& mesh, const std::string& path,
                     int cut_axis, double cut_value, OutputSet* outputs) {
    // The wall: its faces, and its points renumbered in surface order.
    std::vector<Index> faces;
    std::vector<Index> point_of(surface.points.size(), kNone);
    for (Index f = 0; f < surface.num_faces(); ++f) {
        if (surface.patches[static_cast<std::size_t>(surface.face_patch[f])].kind != PatchKind::Wall) continue;
        faces.push_back(f);
        for (const Index* v = surface.face_begin(f); v != surface.face_end(f); ++v)
            point_of[static_cast<std::size_t>(*v)] = 0;
    }
    std::vector<Index> points;  // surface node of each point
    for (std::size_t i = 0; i < point_of.size(); ++i)
        if (point_of[i] == 0) {
            point_of[i] = static_cast<Index>(points.size());
            points.push_back(static_cast<Index>(i));
        }
    std::vector<int> layers(surface.points.size(), r.layers);
    for (const ShortNode& n : r.short_nodes)
        if (n.node >= 0 && static_cast<std::size_t>(n.node) < layers.size())
            layers[static_cast<std::size_t>(n.node)] = n.layers;
    Vec3 lo = Vec3::Constant(0.0), hi = Vec3::Constant(0.0);
    for (std::size_t i = 0; i < points.size(); ++i) {
        const Vec3& p = surface.points[static_cast<std::size_t>(points[i])];
        lo = i ? Vec3(lo.cwiseMin(p)) : p;
        hi = i ? Vec3(hi.cwiseMax(p)) : p;
    }
    // The cut: across the wall box's longest side through its centre unless given.
    const Vec3 size = hi - lo;
    int axis = cut_axis;
    double value = cut_value;
    if (axis < 0 || axis > 2) {
        size.maxCoeff(&axis);
        value = 0.5 * (lo[axis] + hi[axis]);
    }
    const int u = axis == 0 ? 1 : 0, v = axis == 2 ? 1 : 2;
    // Half the body's larger extent in the plane round it both ways, so a thin body (a wing
    // cut along its chord) is seen with the cells above and below it too.
    const double pad = 0.5 * std::max(size[u], size[v]);
    const std::array<double, 4> window{lo[u] - pad, hi[u] + pad, lo[v] - pad, hi[v] + pad};
    const PlaneCut cut = cut_cells(mesh, axis, value, window);

    OutputSet own;
    AtomicFile& file = (outputs ? *outputs : own).file(path);
    {
        std::ostringstream out;
        out << "{\n\"wall\": {\"points\": [";
        for (std::size_t i = 0; i < points.size(); ++i) {
            const Vec3& p = surface.points[static_cast<std::size_t>(points[i])];
            out << (i ? ",\n[" : "\n[") << short_number(p.x()) << "," << short_number(p.y()) << ","
                << short_number(p.z()) << "]";
        }
        out << "],\n\"faces\": [";
        for (std::size_t i = 0; i < faces.size(); ++i) {
            out << (i ? ",\n[" : "\n[");
            for (const Index* n = surface.face_begin(faces[i]); n != surface.face_end(faces[i]); ++n)
                out << (n == surface.face_begin(faces[i]) ? "" : ",") << point_of[static_cast<std::size_t>(*n)];
            out << "]";
        }
        out << "],\n\"patches\": [";
        for (std::size_t p = 0; p < surface.patches.size(); ++p)
            out << (p ? ", " : "") << quoted(surface.patches[p].name);
        out << "],\n\"face_patch\": [";
        for (std::size_t i = 0; i < faces.size(); ++i) out << (i ? "," : "") << surface.face_patch[faces[i]];
        out << "],\n\"layers\": [";
        for (std::size_t i = 0; i < points.size(); ++i)
            out << (i ? "," : "") << layers[static_cast<std::size_t>(points[i])];
        const char* names = "xyz";
        out << "]},\n\"cut\": {\"axis\": \"" << names[axis] << "\", \"value\": " << short_number(value) << ", \"u\": \""
            << names[u] << "\", \"v\": \"" << names[v] << "\", \"window\": [" << short_number(window[0]) << ", "
            << short_number(window[1]) << ", " << short_number(window[2]) << ", " << short_number(window[3])
            << "],\n\"types\": [";
        for (Index p = 0; p < cut.num_polygons(); ++p)
            out << (p ? "," : "") << quoted(std::string(to_string(cut.types[static_cast<std::size_t>(p)])));
        out << "],\n\"polygons\": [";
        for (Index p = 0; p < cut.num_polygons(); ++p) {
            out << (p ? ",\n[" : "\n[");
            for (Index k = cut.offsets[static_cast<std::size_t>(p)]; k < cut.offsets[static_cast<std::size_t>(p) + 1];
                 ++k) {
                const auto& x = cut.points[static_cast<std::size_t>(k)];
                out << (k == cut.offsets[static_cast<std::size_t>(p)] ? "" : ",") << short_number(x[0]) << ","
                    << short_number(x[1]);
            }
            out << "]";
        }
        out << "]}\n}\n";
        write_whole_file(file.temp_path(), path, out.str());
    }
    if (!outputs) own.commit();
}

}  // namespace strata
