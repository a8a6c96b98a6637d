// A run's report as JSON, and the plots' data: write_report.h.

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

/// Whether \p v goes on one line: a scalar, a list of such lines, or a node of them that holds
/// no more than one level of lists or nodes (a patch, a wall node with its position). A list of
/// nodes is one per line, so a table reads as rows.
bool one_line(const ReportValue& v, int depth = 0) {
    switch (v.kind()) {
        case ReportValue::Kind::List:
            for (const ReportValue& e : v.list())
                if (e.kind() == ReportValue::Kind::Node || !one_line(e, depth + 1)) return false;
            return depth < 2;
        case ReportValue::Kind::Node:
            for (const ReportNode::Entry& e : v.node().entries())
                if (!one_line(e.value, depth + 1)) return false;
            return depth < 2;
        default:
            return true;
    }
}

void write_json(std::ostream& out, const ReportValue& v, int indent) {
    const bool inline_children = one_line(v);
    const std::string pad(static_cast<std::size_t>(indent + 2), ' ');
    const auto open = [&](bool first) {
        if (!first) out << ",";
        if (inline_children)
            out << (first ? "" : " ");
        else
            out << "\n" << pad;
    };
    const auto close = [&](bool empty, char bracket) {
        if (!inline_children && !empty) out << "\n" << std::string(static_cast<std::size_t>(indent), ' ');
        out << bracket;
    };
    switch (v.kind()) {
        case ReportValue::Kind::Flag:
            out << (v.flag() ? "true" : "false");
            break;
        case ReportValue::Kind::Integer:
            out << v.integer();
            break;
        case ReportValue::Kind::Number:
            out << number(v.number());
            break;
        case ReportValue::Kind::Text:
            out << quoted(v.text());
            break;
        case ReportValue::Kind::List:
            out << "[";
            for (std::size_t i = 0; i < v.list().size(); ++i) {
                open(i == 0);
                write_json(out, v.list()[i], indent + 2);
            }
            close(v.list().empty(), ']');
            break;
        case ReportValue::Kind::Node:
            out << "{";
            for (std::size_t i = 0; i < v.node().entries().size(); ++i) {
                const ReportNode::Entry& e = v.node().entries()[i];
                open(i == 0);
                out << quoted(e.key) << ": ";
                write_json(out, e.value, indent + 2);
            }
            close(v.node().empty(), '}');
            break;
    }
}

}  // namespace

std::string report_path(const std::string& mesh_path) {
    // Beside an output directory (an OpenFOAM polyMesh), not in it: "polyMesh/" as "polyMesh".
    std::string p = mesh_path;
    while (p.size() > 1 && p.back() == '/') p.pop_back();
    return p + ".report.json";
}

std::string report_json(const ReportNode& report) {
    std::ostringstream out;
    write_json(out, ReportValue(report), 0);
    out << "\n";
    return out.str();
}

void write_report(const ReportNode& report, const std::string& path, OutputSet* outputs) {
    OutputSet own;
    AtomicFile& file = (outputs ? *outputs : own).file(path);
    write_whole_file(file.temp_path(), path, report_json(report));
    if (!outputs) own.commit();
}

std::string plot_data_path(const std::string& mesh_path) {
    std::string p = mesh_path;
    while (p.size() > 1 && p.back() == '/') p.pop_back();
    return p + ".plot.json";
}

void write_plot_data(const std::vector<int>& node_layers, const std::vector<double>& node_share,
                     const SurfaceMesh& surface, const VolumeMesh& mesh, const std::string& path, int cut_axis,
                     double cut_value, OutputSet* outputs) {
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
    if (node_layers.size() != surface.points.size() || node_share.size() != surface.points.size())
        throw Error("write_plot_data: " + std::to_string(node_layers.size()) + " layer counts and " +
                    std::to_string(node_share.size()) + " shares for " + std::to_string(surface.points.size()) +
                    " surface nodes");
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
            out << (i ? "," : "") << node_layers[static_cast<std::size_t>(points[i])];
        out << "],\n\"share\": [";
        for (std::size_t i = 0; i < points.size(); ++i)
            out << (i ? "," : "") << short_number(node_share[static_cast<std::size_t>(points[i])]);
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
