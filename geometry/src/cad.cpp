// CAD input and surface meshing through Gmsh. This file is the Gmsh adapter for CAD: Gmsh's
// 1-based size_t node tags and int entity tags stay in here; the caller gets a SurfaceMesh.
#include <strata/geometry/cad.h>

#include <strata/core/error.h>
#include <strata/core/format.h>
#include <strata/core/solver_checks.h>
#include <strata/geometry/prepare.h>
#include <strata/io/cad_units.h>
#include <strata/io/files.h>
#include <strata/io/gmsh_model.h>
#include <strata/io/gmsh_session.h>

#include "wall_size.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace strata {
namespace {

enum class CadFormat { Step, Iges, Brep, Geo };

std::optional<CadFormat> format_of(const std::string& path) {
    const std::string ext = lower_extension(path);
    if (ext == ".step" || ext == ".stp") return CadFormat::Step;
    if (ext == ".iges" || ext == ".igs") return CadFormat::Iges;
    if (ext == ".brep" || ext == ".brp") return CadFormat::Brep;
    if (ext == ".geo") return CadFormat::Geo;
    return std::nullopt;
}

const char* format_name(CadFormat f) {
    switch (f) {
        case CadFormat::Step:
            return "STEP";
        case CadFormat::Iges:
            return "IGES";
        case CadFormat::Brep:
            return "BREP";
        case CadFormat::Geo:
            return "Gmsh .geo";
    }
    return "CAD";
}

// "1-11, 14, 20-22": the valid tags of a model with many surfaces stay one readable line.
std::string format_tags(std::vector<int> tags) {
    std::sort(tags.begin(), tags.end());
    std::string out;
    for (std::size_t i = 0; i < tags.size();) {
        std::size_t j = i;
        while (j + 1 < tags.size() && tags[j + 1] == tags[j] + 1) ++j;
        if (!out.empty()) out += ", ";
        out += std::to_string(tags[i]);
        if (j > i) out += "-" + std::to_string(tags[j]);
        i = j + 1;
    }
    return out;
}

void validate(const CadParams& p) {
    if (!(p.size >= 0.0) || !std::isfinite(p.size))
        throw InputError("CAD meshing: size must be a finite number >= 0 (0 = automatic), got " +
                         format_number(p.size));
    if (!(p.size_min >= 0.0) || !std::isfinite(p.size_min))
        throw InputError("CAD meshing: size_min must be a finite number >= 0 (0 = automatic), got " +
                         format_number(p.size_min));
    if (p.size > 0.0 && p.size_min > p.size)
        throw InputError("CAD meshing: size_min (" + format_number(p.size_min) + ") is larger than size (" +
                         format_number(p.size) + "); give a smaller size_min");
    if (!p.units.empty() && !parse_length_unit(p.units))
        throw InputError("CadParams::units = '" + p.units + "': unknown length unit; use one of " +
                         std::string(length_unit_names()));
    if (!(p.first_height >= 0.0) || !std::isfinite(p.first_height))
        throw InputError("CAD meshing: first_height must be a finite number >= 0 (0 = no aspect-ratio limit), got " +
                         format_number(p.first_height));
    if (!(p.max_aspect_ratio == 0.0 || p.max_aspect_ratio >= 10.0) || !std::isfinite(p.max_aspect_ratio))
        throw InputError("CadParams::max_aspect_ratio = " + format_number(p.max_aspect_ratio) +
                         ": give 0 (no limit) or a ratio of at least 10 (OpenFOAM's checkMesh fails above 1000)");
    if (!(p.wall_faces_budget > 0.0))
        throw InputError("CAD meshing: wall_faces_budget must be positive, got " + format_number(p.wall_faces_budget));
    if (p.curvature_points < 0)
        throw InputError("CAD meshing: curvature_points must be >= 0 (0 = off), got " +
                         std::to_string(p.curvature_points));
    // Gmsh 4.8's 2D algorithms. Left out: 3 ("initial mesh only") leaves an unrefined mesh;
    // 7 (BAMG) aborts the whole process (an uncaught std::string, std::terminate) on curved
    // surfaces, seen on a sphere; 8 (Frontal-Delaunay for quads) segfaults on every surface in
    // Debian's Gmsh 4.8.4, a plane square included, through the API and the gmsh CLI alike.
    // Unknown values would silently fall back to Gmsh's default.
    static constexpr std::array<int, 5> kAlgorithms{1, 2, 5, 6, 9};
    if (std::find(kAlgorithms.begin(), kAlgorithms.end(), p.algorithm) == kAlgorithms.end()) {
        const std::string why = p.algorithm == 7   ? " (BAMG aborts the process on curved surfaces in Gmsh 4.8)"
                                : p.algorithm == 8 ? " (Frontal-Delaunay for quads crashes Gmsh 4.8.4; for quads use "
                                                     "algorithm 6 with quad elements, which recombines)"
                                                   : "";
        throw InputError("CAD meshing: Gmsh 2D algorithm " + std::to_string(p.algorithm) + " is not supported" + why +
                         "; use 1 (MeshAdapt), 2 (Automatic), 5 (Delaunay), 6 (Frontal-Delaunay) "
                         "or 9 (packing of parallelograms)");
    }
}

// Gmsh's options are process-wide. One mesh_cad call must not leave its sizes (or whatever a
// .geo script set) to the next call, nor to a user who initialised Gmsh for their own work:
// the options this file sets, and those scripts commonly set, are saved and put back.
const std::vector<std::string> kSavedOptions = {
    "Mesh.MeshSizeMax",
    "Mesh.MeshSizeMin",
    "Mesh.MeshSizeFromCurvature",
    "Mesh.MeshSizeExtendFromBoundary",
    "Mesh.MeshSizeFromPoints",
    "Mesh.MeshSizeFactor",
    "Mesh.Algorithm",
    "Mesh.Algorithm3D",
    "Mesh.RecombineAll",
    "Mesh.RecombinationAlgorithm",
    "Mesh.ElementOrder",
    "Mesh.SubdivisionAlgorithm",
    "Mesh.Smoothing",
    "Mesh.MinimumCirclePoints",
    "Mesh.MinimumCurvePoints",
    "Mesh.Optimize",
    "Mesh.SaveAll",
    "Geometry.Tolerance",
    "Geometry.ToleranceBoolean",
    "Geometry.OCCFixDegenerated",
    "Geometry.OCCFixSmallEdges",
    "Geometry.OCCFixSmallFaces",
    "Geometry.OCCSewFaces",
    "Geometry.OCCMakeSolids",
    "Geometry.OCCScaling",
    "General.Terminal",
    "General.Verbosity",
    "General.NumThreads",
};

double get_number(const std::string& name) {
    double v = 0.0;
    gmsh_call("reading Gmsh option " + name, [&] { gmsh::option::getNumber(name, v); });
    return v;
}

void set_number(const std::string& name, double v) {
    gmsh_call("setting Gmsh option " + name, [&] { gmsh::option::setNumber(name, v); });
}

void load(const std::string& path, CadFormat format) {
    const std::string context = path + ": Gmsh could not read this " + std::string(format_name(format)) + " file";
    try {
        gmsh_call(context, [&] {
            if (format == CadFormat::Geo) {
                // merge, not open: gmsh::open renames the current model after the file (or
                // adds a new one), and the current model belongs to our GmshSession.
                gmsh::merge(path);
                // A script may have used either kernel; both must be visible to the model.
                gmsh::model::geo::synchronize();
                gmsh::model::occ::synchronize();
            } else {
                // The format is given explicitly: Gmsh guesses from the extension and knows
                // neither ".brp" nor upper-case extensions.
                const char* kind = format == CadFormat::Step ? "step" : format == CadFormat::Iges ? "iges" : "brep";
                gmsh::vectorpair imported;
                gmsh::model::occ::importShapes(path, imported, true, kind);
                gmsh::model::occ::synchronize();
            }
        });
    } catch (const BackendError& e) {
        const std::string hint = format == CadFormat::Geo
                                     ? "; fix the script (open it in Gmsh to see the error in context)"
                                     : "; check that it is a valid " + std::string(format_name(format)) +
                                           " file (export it again from the CAD tool)";
        throw InputError(std::string(e.what()) + hint);
    }
}

std::vector<int> entity_tags(int dim) {
    gmsh::vectorpair dim_tags;
    gmsh::model::getEntities(dim_tags, dim);
    std::vector<int> tags;
    tags.reserve(dim_tags.size());
    for (const auto& [d, t] : dim_tags) tags.push_back(t);
    // Tag order, so the same file always gives the same node and face numbering.
    std::sort(tags.begin(), tags.end());
    return tags;
}

void fuse_volumes(const std::string& path) {
    const std::vector<int> volumes = entity_tags(3);
    if (volumes.size() < 2) return;
    gmsh::vectorpair occ_volumes;
    gmsh_call(path + ": listing the solids", [&] { gmsh::model::occ::getEntities(occ_volumes, 3); });
    if (occ_volumes.size() != volumes.size())
        throw InputError(path + ": cannot fuse the " + std::to_string(volumes.size()) +
                         " solids: they are not OpenCASCADE entities (a built-in kernel .geo "
                         "script); add SetFactory(\"OpenCASCADE\") to the script, or do the "
                         "Boolean union in it and mesh without fuse");
    gmsh::vectorpair object{{3, volumes.front()}};
    gmsh::vectorpair tools;
    for (std::size_t i = 1; i < volumes.size(); ++i) tools.emplace_back(3, volumes[i]);
    gmsh_call(path + ": fusing the " + std::to_string(volumes.size()) +
                  " solids into one (Boolean union) failed; repair the CAD or mesh without fuse",
              [&] {
                  gmsh::vectorpair out;
                  std::vector<gmsh::vectorpair> out_map;
                  gmsh::model::occ::fuse(object, tools, out, out_map);
                  gmsh::model::occ::synchronize();
              });
}

// A script that meshed itself ("Mesh 2;") would keep its curve mesh: generate(2) meshes the
// surfaces again but not the curves, so the caller's sizes would apply only half. Clear it,
// except when the model has discrete entities, whose mesh may be their only geometry (an STL
// merged and classified by the script); Gmsh then re-meshes what it can.
void clear_script_mesh(const std::string& path) {
    gmsh_call(path + ": clearing the mesh the script made", [] {
        std::vector<int> types;
        std::vector<std::vector<std::size_t>> tags, nodes;
        gmsh::model::mesh::getElements(types, tags, nodes, -1, -1);
        if (types.empty()) return;
        gmsh::vectorpair entities;
        gmsh::model::getEntities(entities, -1);
        for (const auto& [dim, tag] : entities) {
            std::string type;
            gmsh::model::getType(dim, tag, type);
            if (type.find("Discrete") != std::string::npos) return;
        }
        gmsh::model::mesh::clear();
    });
}

/// The meshed surfaces as one SurfaceMesh, by the one conversion of the Gmsh adapter (patches
/// from the physical groups, gmsh_model.h), nodes numbered as the faces use them. Every surface
/// must have got elements: one without would leave a hole.
SurfaceMesh extract(const std::string& path, const std::vector<int>& surfaces, std::vector<int>& face_surface) {
    SurfaceMesh mesh = surface_from_gmsh_model(path, NodeOrder::FirstUse, &face_surface);
    std::vector<int> with_faces = face_surface;
    std::sort(with_faces.begin(), with_faces.end());
    for (int s : surfaces)
        if (!std::binary_search(with_faces.begin(), with_faces.end(), s))
            throw BackendError(path + ": surface " + std::to_string(s) +
                               " got no elements from Gmsh, which would leave a hole; the "
                               "surface may be degenerate or too small for the element size: "
                               "try a smaller size or another algorithm, or repair the CAD");
    return mesh;
}

/// The first layer's aspect ratio over the wall of a mesh just made (its faces' Gmsh surfaces
/// in \p face_surface), and the sizes that would bring it under the limit.
struct WallAspect {
    double worst = 0.0;                ///< the largest predicted, faces and fans
    std::vector<int> surfaces;         ///< wall surfaces with a face over the limit
    std::map<int, double> curve_need;  ///< fan curves over the limit → the edge length they need
    std::map<int, double> area;        ///< wall surface → its area
    std::map<int, Index> faces;        ///< wall surface → its faces
};

/// The point of each mesh node, to find Gmsh's curve nodes in \p mesh (the same coordinates).
std::map<std::array<double, 3>, Index> node_at(const SurfaceMesh& mesh) {
    std::map<std::array<double, 3>, Index> at;
    for (Index i = 0; i < mesh.num_points(); ++i) {
        const Vec3& p = mesh.points[static_cast<std::size_t>(i)];
        at.emplace(std::array<double, 3>{p.x(), p.y(), p.z()}, i);
    }
    return at;
}

WallAspect wall_aspect(const SurfaceMesh& mesh, const std::vector<int>& face_surface, const std::set<int>& walls,
                       const CadParams& params) {
    const double h = params.first_height, limit = params.max_aspect_ratio;
    WallAspect out;
    std::map<int, double> worst;
    std::map<int, double>& area = out.area;
    std::map<int, Index>& faces = out.faces;
    auto corner = [&](Index f, Index i) -> const Vec3& {
        return mesh.points[static_cast<std::size_t>(mesh.face_node(f, i))];
    };
    auto face_area = [&](Index f) -> Vec3 {
        Vec3 a = (corner(f, 1) - corner(f, 0)).cross(corner(f, 2) - corner(f, 0));
        if (mesh.face_size(f) == 4) a += (corner(f, 2) - corner(f, 0)).cross(corner(f, 3) - corner(f, 0));
        return 0.5 * a;
    };
    // Wall edges → their faces, for the fans below.
    std::map<std::array<Index, 2>, std::vector<Index>> faces_of_edge;
    for (Index f = 0; f < mesh.num_faces(); ++f) {
        const int s = face_surface[static_cast<std::size_t>(f)];
        if (!walls.count(s)) continue;
        std::array<Vec3, 4> c;
        const Index n = mesh.face_size(f);
        for (Index i = 0; i < n; ++i) c[static_cast<std::size_t>(i)] = corner(f, i);
        double& w = worst[s];
        w = std::max(w, right_prism_aspect_ratio(c.data(), static_cast<int>(n), h));
        area[s] += face_area(f).norm();
        ++faces[s];
        if (params.fan_angle_deg > 0.0)
            for (Index i = 0; i < n; ++i) {
                const Index a = mesh.face_node(f, i), b = mesh.face_node(f, (i + 1) % n);
                faces_of_edge[{std::min(a, b), std::max(a, b)}].push_back(f);
            }
    }
    for (const auto& [s, w] : worst) {
        out.worst = std::max(out.worst, w);
        if (w > limit) out.surfaces.push_back(s);
    }
    if (params.fan_angle_deg <= 0.0) return out;

    // Fans: the first cell of a fan on a wall edge whose faces turn by the fan angle or more. Only
    // the curve is meshed finer (Gmsh grades the surfaces beside it from their boundary sizes).
    const auto at = node_at(mesh);
    for (int c : entity_tags(1)) {
        std::vector<int> up, down;
        gmsh::model::getAdjacencies(1, c, up, down);
        if (up.size() != 2 || !walls.count(up[0]) || !walls.count(up[1])) continue;
        std::vector<std::size_t> tags, line_nodes;
        std::vector<double> xyz, uvw;
        gmsh::model::mesh::getNodes(tags, xyz, uvw, 1, c, true, false);
        std::map<std::size_t, Index> index_of;
        for (std::size_t i = 0; i < tags.size(); ++i) {
            const auto it = at.find({xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]});
            if (it != at.end()) index_of.emplace(tags[i], it->second);
        }
        std::vector<std::size_t> line_tags;
        gmsh::model::mesh::getElementsByType(1, line_tags, line_nodes, c);
        double curve_worst = 0.0, need = std::numeric_limits<double>::infinity();
        for (std::size_t l = 0; l + 1 < line_nodes.size(); l += 2) {
            const auto ia = index_of.find(line_nodes[l]), ib = index_of.find(line_nodes[l + 1]);
            if (ia == index_of.end() || ib == index_of.end()) continue;
            const Index a = ia->second, b = ib->second;
            const auto fe = faces_of_edge.find({std::min(a, b), std::max(a, b)});
            if (fe == faces_of_edge.end() || fe->second.size() != 2) continue;
            const Index f1 = fe->second[0], f2 = fe->second[1];
            // Gmsh orients each surface by its own parametrization: one whose faces run the edge the
            // same way as the other's is turned round.
            auto runs_forward = [&](Index f) {
                for (Index i = 0, n = mesh.face_size(f); i < n; ++i)
                    if (mesh.face_node(f, i) == a) return mesh.face_node(f, (i + 1) % n) == b;
                return false;
            };
            const Vec3 n1 = face_area(f1).normalized();
            Vec3 n2 = face_area(f2).normalized();
            if (runs_forward(f1) == runs_forward(f2)) n2 = -n2;
            const double turn = std::acos(std::clamp(n1.dot(n2), -1.0, 1.0)) * 180.0 / std::numbers::pi;
            const Vec3 pa = mesh.points[static_cast<std::size_t>(a)], pb = mesh.points[static_cast<std::size_t>(b)];
            if (turn < params.fan_angle_deg) continue;
            // The fan's first wedge: columns at most 90 degrees apart (fans.cpp), from n1 towards n2.
            const double wedge = turn / std::ceil(turn / 90.0) * std::numbers::pi / 180.0;
            const Vec3 t = (n2 - n1.dot(n2) * n1).normalized();
            const Vec3 d2 = std::cos(wedge) * n1 + std::sin(wedge) * t;
            const double ar = fan_wedge_aspect_ratio(pa, pb, n1, d2, h);
            if (!std::isfinite(ar)) continue;
            curve_worst = std::max(curve_worst, ar);
            // The aspect ratio grows with the edge's length: the length that gives 0.7 of the limit.
            need = std::min(need, (pb - pa).norm() * 0.7 * limit / ar);
        }
        out.worst = std::max(out.worst, curve_worst);
        if (curve_worst > limit) out.curve_need[c] = need;
    }
    return out;
}

/// CadParams::max_aspect_ratio: where the first layer over the wall of the mesh just made would
/// be too flat, the walls are meshed again finer there (and every other surface with them, so
/// their shared curves stay conforming), unless that would exceed the face budget. A surface
/// meshed again changes its neighbours' meshes too, and a capped one can stay over (a thin face
/// the geometry forces): up to three rounds, each adding what is still over, a surface capped
/// again at 0.7 of its last size.
SurfaceMesh limit_wall_aspect(const std::string& path, const CadParams& params, const std::vector<int>& surfaces,
                              SurfaceMesh mesh, std::vector<int>& face_surface, WallSizeReport& r) {
    r.max_aspect_ratio = params.max_aspect_ratio;
    std::set<int> walls;
    for (const auto& [s, name] : surface_patch_names(surfaces))
        if (patch_kind_of(name, params.wall_patch_kinds) == PatchKind::Wall) walls.insert(s);
    auto measure = [&](const SurfaceMesh& m) {
        WallAspect a;
        gmsh_call(path + ": measuring the first layer's aspect ratio over the walls",
                  [&] { a = wall_aspect(m, face_surface, walls, params); });
        return a;
    };
    WallAspect now = measure(mesh);
    r.worst_before = r.worst_after = now.worst;
    std::map<int, double> surface_cap, curve_cap;
    // Gmsh multiplies every size by Mesh.MeshSizeFactor, the callback's too.
    const double factor = get_number("Mesh.MeshSizeFactor");
    constexpr int kRounds = 3;
    for (int round = 0; round < kRounds && (!now.surfaces.empty() || !now.curve_need.empty()); ++round) {
        for (int s : now.surfaces) {
            const auto [it, fresh] = surface_cap.emplace(s, 0.7 * params.max_aspect_ratio * params.first_height);
            if (!fresh) it->second *= 0.7;
        }
        for (const auto& [c, need] : now.curve_need) {
            const auto [it, fresh] = curve_cap.emplace(c, need);
            if (!fresh) it->second = std::min(it->second, need);
        }
        // The faces to expect: the capped surfaces at their cap, the others as they are, and the
        // surfaces beside a finer curve graded from it (counted at the geometric mean of the two
        // sizes: a rough figure, for the budget only).
        double estimate = 0.0;
        for (const auto& [s, a] : now.area) {
            const auto capped = surface_cap.find(s);
            estimate +=
                capped != surface_cap.end() ? faces_at_size(a, capped->second) : static_cast<double>(now.faces.at(s));
        }
        EntitySizes sizes;
        gmsh_call(path + ": the entities the walls' sizes apply to", [&] {
            for (const auto& [s, size] : surface_cap) sizes.cap_surface(s, size);
            for (const auto& [c, need] : curve_cap) {
                sizes.cap_curve(c, need);
                std::vector<int> up, down;
                gmsh::model::getAdjacencies(1, c, up, down);
                for (int s : up) {
                    if (!now.area.count(s) || surface_cap.count(s)) continue;
                    const double a = now.area.at(s);
                    const double current = std::sqrt(a / (0.4330127 * static_cast<double>(now.faces.at(s))));
                    estimate += faces_at_size(a, std::sqrt(need * std::max(current, need))) -
                                static_cast<double>(now.faces.at(s));
                }
            }
        });
        r.faces_estimate = estimate;
        r.cap = std::numeric_limits<double>::infinity();
        for (const auto& [entity, size] : sizes.sizes()) r.cap = std::min(r.cap, size);
        if (estimate > params.wall_faces_budget) {
            r.over_budget = round == 0;  // later rounds keep the better mesh they have
            break;
        }
        {
            std::optional<SizeCallback> callback;
            gmsh_call(path + ": meshing the walls again finer for the first layer's aspect ratio (max_aspect_ratio " +
                          format_number(params.max_aspect_ratio) + ")",
                      [&] {
                          gmsh::model::mesh::clear();
                          callback.emplace(sizes, factor);
                          gmsh::model::mesh::generate(2);
                      });
        }
        face_surface.clear();
        mesh = extract(path, surfaces, face_surface);
        now = measure(mesh);
        r.worst_after = now.worst;
        r.surfaces = static_cast<Index>(surface_cap.size());
        r.curves = static_cast<Index>(curve_cap.size());
    }
    return mesh;
}

}  // namespace

bool is_cad_file(const std::string& path) {
    return format_of(path).has_value();
}

SurfaceMesh mesh_cad(const std::string& path, const CadParams& params, CadUnits* units, WallSizeReport* walls) {
    const std::optional<CadFormat> format = format_of(path);
    if (!format)
        throw InputError(path +
                         ": not a CAD file Strata reads; use .step/.stp, .iges/.igs, "
                         ".brep/.brp or a Gmsh .geo script");
    validate(params);
    check_input_file(path);
    const bool script = *format == CadFormat::Geo;

    GmshSession session("strata_cad");
    GmshOptionScope options;  // declared after the session: restored while Gmsh is still locked
    options.save(kSavedOptions);
    options.save_string("Geometry.OCCTargetUnit");

    // Units: OpenCASCADE converts STEP and IGES to millimetres; scaled back on import to the
    // unit the file declares, or the one asked.
    CadUnits read_in;
    const bool has_unit = *format == CadFormat::Step || *format == CadFormat::Iges;
    if (!has_unit && !params.units.empty())
        throw InputError(path + ": a " + std::string(format_name(*format)) +
                         " file declares no length unit, so CadParams::units (" + params.units +
                         ") cannot convert it; its numbers are kept as they are (scale them with "
                         "PrepareParams::scale)");
    double scaling = 1.0;
    if (has_unit) {
        const std::optional<LengthUnit> declared = declared_length_unit(path);
        const LengthUnit target =
            params.units.empty() ? declared.value_or(LengthUnit{"mm", 1.0}) : *parse_length_unit(params.units);
        read_in = {target.name, declared ? declared->name : ""};
        scaling = 1.0 / target.millimetres;
    }
    gmsh_call("setting Gmsh option Geometry.OCCTargetUnit",
              [] { gmsh::option::setString("Geometry.OCCTargetUnit", ""); });
    set_number("Geometry.OCCScaling", scaling);
    if (units) *units = read_in;

    load(path, *format);

    const std::vector<int> loaded_surfaces = entity_tags(2);
    if (loaded_surfaces.empty())
        throw InputError(path +
                         ": no surfaces in the model; the file holds only points or "
                         "curves (or nothing): export the surfaces or solids from the "
                         "CAD tool");
    if (params.fuse) fuse_volumes(path);
    const std::vector<int> surfaces = entity_tags(2);

    // A .geo script's own mesh settings stand unless the caller asked for something explicitly
    // (a CadParams field away from its default); everything else gets Strata's defaults, set
    // explicitly so that no earlier Gmsh user's settings leak in.
    auto script_set = [&](const char* name) { return script && options.changed(name); };

    double xmin = 0, ymin = 0, zmin = 0, xmax = 0, ymax = 0, zmax = 0;
    gmsh_call(path + ": computing the bounding box",
              [&] { gmsh::model::getBoundingBox(-1, -1, xmin, ymin, zmin, xmax, ymax, zmax); });
    const double diagonal =
        std::sqrt((xmax - xmin) * (xmax - xmin) + (ymax - ymin) * (ymax - ymin) + (zmax - zmin) * (zmax - zmin));
    if (!(diagonal > 0.0) || !std::isfinite(diagonal))
        throw InputError(path + ": the model has no extent (bounding-box diagonal " + format_number(diagonal) +
                         "); check the file's geometry");

    if (params.size > 0.0)
        set_number("Mesh.MeshSizeMax", params.size);
    else if (!script_set("Mesh.MeshSizeMax"))
        set_number("Mesh.MeshSizeMax", diagonal / 20.0);
    const double size = get_number("Mesh.MeshSizeMax");

    if (params.curvature_points > 0)
        set_number("Mesh.MeshSizeFromCurvature", params.curvature_points);
    else if (!script_set("Mesh.MeshSizeFromCurvature"))
        set_number("Mesh.MeshSizeFromCurvature", 0);
    const bool curvature = get_number("Mesh.MeshSizeFromCurvature") > 0;

    if (params.size_min > 0.0)
        set_number("Mesh.MeshSizeMin", params.size_min);
    else if (!script_set("Mesh.MeshSizeMin"))
        // The floor matters only for curvature refinement, which would otherwise resolve a
        // sharp edge's tiny radius with needle-small elements. Without it, no floor: a
        // script's point sizes are then never clamped.
        set_number("Mesh.MeshSizeMin", curvature ? size / 20.0 : 0.0);

    // Gmsh's default, explicit: sizes on curves (curvature-refined edges, a script's point
    // sizes) spread into the surfaces they bound instead of jumping to the maximum size.
    if (!script_set("Mesh.MeshSizeExtendFromBoundary")) set_number("Mesh.MeshSizeExtendFromBoundary", 1);
    if (!script_set("Mesh.MeshSizeFactor")) set_number("Mesh.MeshSizeFactor", 1);
    // Strata needs linear faces, whatever a script asks for.
    set_number("Mesh.ElementOrder", 1);
    if (!script_set("Mesh.SubdivisionAlgorithm")) set_number("Mesh.SubdivisionAlgorithm", 0);

    const int kDefaultAlgorithm = CadParams{}.algorithm;  // not constexpr: clang rejects the std::string members
    if (params.algorithm != kDefaultAlgorithm || !script_set("Mesh.Algorithm"))
        set_number("Mesh.Algorithm", params.algorithm);
    // A script's 7 or 8 would kill the process (see validate); 6 with the script's
    // recombination settings still gives it quads.
    if (const double a = get_number("Mesh.Algorithm"); a == 7 || a == 8)
        set_number("Mesh.Algorithm", kDefaultAlgorithm);
    if (!script_set("Mesh.RecombinationAlgorithm")) set_number("Mesh.RecombinationAlgorithm", 1);  // Blossom

    switch (params.elements) {
        case SurfaceElements::Triangles:
            if (!script_set("Mesh.RecombineAll")) set_number("Mesh.RecombineAll", 0);
            break;
        case SurfaceElements::Quads:
            set_number("Mesh.RecombineAll", 1);
            break;
        case SurfaceElements::Mixed: {
            set_number("Mesh.RecombineAll", 0);
            for (int tag : params.quad_surfaces) {
                if (!std::binary_search(surfaces.begin(), surfaces.end(), tag))
                    throw InputError(path + ": quad surface " + std::to_string(tag) + " is not a surface of the model" +
                                     (params.fuse ? " (after fusing the solids)" : "") + "; its surfaces are " +
                                     format_tags(surfaces));
                gmsh_call(path + ": asking for quads on surface " + std::to_string(tag),
                          [&] { gmsh::model::mesh::setRecombine(2, tag); });
            }
            break;
        }
    }

    if (script) clear_script_mesh(path);

    gmsh_call(path + ": Gmsh failed to mesh the surfaces (maximum size " + format_number(size) +
                  "); try a smaller size, another algorithm, or repair the CAD",
              [] { gmsh::model::mesh::generate(2); });

    std::vector<int> face_surface;
    SurfaceMesh mesh = extract(path, surfaces, face_surface);
    WallSizeReport wall_report;
    if (params.first_height > 0.0 && params.max_aspect_ratio > 0.0)
        mesh = limit_wall_aspect(path, params, surfaces, std::move(mesh), face_surface, wall_report);
    if (walls) *walls = wall_report;
    return mesh;
}

}  // namespace strata
