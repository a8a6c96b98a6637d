// A surface mesh made again with Gmsh: remesh.h. Gmsh's tags stay in here.

#include <strata/core/error.h>
#include <strata/core/face_geometry.h>
#include <strata/core/format.h>
#include <strata/geometry/check.h>
#include <strata/geometry/feature_cuts.h>
#include <strata/geometry/intersections.h>
#include <strata/geometry/topology.h>
#include <strata/io/gmsh_model.h>
#include <strata/io/gmsh_session.h>
#include <strata/surface/remesh.h>

#include "wall_size.h"

#include <strata/geometry/cgal_kernel.h>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace strata {
namespace {

constexpr double kPi = 3.141592653589793;

void validate(const RemeshParams& p, const std::string& source) {
    const std::string ctx = source + ": remeshing: ";
    if (!(p.size >= 0.0) || !std::isfinite(p.size))
        throw InputError(ctx + "size must be a finite number >= 0 (0 = the input's median edge), got " +
                         format_number(p.size));
    if (!(p.size_min >= 0.0) || !std::isfinite(p.size_min))
        throw InputError(ctx + "size_min must be a finite number >= 0, got " + format_number(p.size_min));
    if (p.size > 0.0 && p.size_min > p.size)
        throw InputError(ctx + "size_min (" + format_number(p.size_min) + ") is larger than size (" +
                         format_number(p.size) + "); give a smaller size_min");
    if (p.curvature_points < 0)
        throw InputError(ctx + "curvature_points must be >= 0 (0 = off), got " + std::to_string(p.curvature_points));
    if (!(p.feature_angle_deg > 0.0 && p.feature_angle_deg < 180.0))
        throw InputError(ctx + "the feature angle must be between 0 and 180 degrees, got " +
                         format_number(p.feature_angle_deg));
    static constexpr std::array<int, 5> kAlgorithms{1, 2, 5, 6, 9};
    if (std::find(kAlgorithms.begin(), kAlgorithms.end(), p.algorithm) == kAlgorithms.end())
        throw InputError(ctx + "Gmsh 2D algorithm " + std::to_string(p.algorithm) +
                         " is not supported; use 1, 2, 5, 6 or 9 (as for CAD meshing)");
    if (!(p.first_height >= 0.0) || !std::isfinite(p.first_height))
        throw InputError(ctx + "first_height must be a finite number >= 0, got " + format_number(p.first_height));
    if (!(p.max_aspect_ratio == 0.0 || p.max_aspect_ratio >= 10.0) || !std::isfinite(p.max_aspect_ratio))
        throw InputError("RemeshParams::max_aspect_ratio = " + format_number(p.max_aspect_ratio) +
                         ": give 0 (no limit) or a ratio of at least 10 (OpenFOAM's checkMesh fails above 1000)");
    if (!(p.wall_faces_budget > 0.0))
        throw InputError(ctx + "wall_faces_budget must be positive, got " + format_number(p.wall_faces_budget));
}

/// The input as triangles (a quad split along its shorter diagonal), each with its face.
struct Triangles {
    std::vector<std::array<Index, 3>> tri;
    std::vector<Index> face;  ///< the input face of each triangle
};

Triangles triangles_of(const SurfaceMesh& m) {
    Triangles t;
    for (Index f = 0; f < m.num_faces(); ++f) {
        const Index* n = m.face_begin(f);
        if (m.face_size(f) == 3) {
            t.tri.push_back({n[0], n[1], n[2]});
            t.face.push_back(f);
            continue;
        }
        if (quad_shorter_diagonal(m, f) == 0) {
            t.tri.push_back({n[0], n[1], n[2]});
            t.tri.push_back({n[0], n[2], n[3]});
        } else {
            t.tri.push_back({n[0], n[1], n[3]});
            t.tri.push_back({n[1], n[2], n[3]});
        }
        t.face.push_back(f);
        t.face.push_back(f);
    }
    return t;
}

/// The edges between faces of different patches, each once (smaller node first), sorted.
std::vector<std::array<Index, 2>> patch_seams(const SurfaceMesh& m) {
    std::map<std::array<Index, 2>, Index> first_patch;  // edge → patch of its first face (kNone: seam)
    std::vector<std::array<Index, 2>> seams;
    for (Index f = 0; f < m.num_faces(); ++f)
        for (Index i = 0, k = m.face_size(f); i < k; ++i) {
            const Index a = m.face_node(f, i), b = m.face_node(f, (i + 1) % k);
            const std::array<Index, 2> e{std::min(a, b), std::max(a, b)};
            const auto [it, fresh] = first_patch.emplace(e, m.face_patch[f]);
            if (!fresh && it->second != kNone && it->second != m.face_patch[f]) {
                seams.push_back(e);
                it->second = kNone;
            }
        }
    std::sort(seams.begin(), seams.end());
    return seams;
}

using Tree = CGAL::AABB_tree<CGAL::AABB_traits<
    cgal::Kernel, CGAL::AABB_triangle_primitive<cgal::Kernel, std::vector<cgal::Triangle>::const_iterator>>>;

/// The time budget of Gmsh's classification of the surface for one remeshing attempt (tried in a
/// child process first: remesh_once), seconds: a fixed part and a part per input triangle, far
/// above what it takes where it ends (0.2 s for 8,000 triangles).
constexpr double kClassifySeconds = 20.0;
constexpr double kClassifySecondsPerTriangle = 2e-3;

/// split_long_edges' cap on the triangles given to Gmsh: this many, or this many per input triangle.
constexpr Index kSplitFacesMin = 200000;
constexpr Index kSplitFacesPerFace = 4;

/// The time budget of Gmsh's meshing of the new surfaces in one attempt (in a child process:
/// remesh_once), seconds: a fixed part and a part per face expected (four per size squared of
/// the input's area, twice the faces of equilateral triangles), far above what it takes where
/// it ends (the needle M6: 0.2 s for 6,000 faces).
constexpr double kMeshSeconds = 60.0;
constexpr double kMeshSecondsPerFace = 1e-3;

/// The CPU seconds one attempt's two stages in Gmsh may take (each in a child process).
struct Budget {
    double classify = 0.0;
    double mesh = 0.0;
};

/// An attempt whose classification or meshing ran out of its time budget.
struct GmshTimeout : BackendError {
    using BackendError::BackendError;
};

/// One attempt's result: the new mesh and its faults.
struct Attempt {
    SurfaceMesh mesh;
    Index surfaces = 0;
    Index bad = 0;  ///< faces inverted against the old surface or without area
    Index first_bad = kNone;
    WallAspect aspect;            ///< with RemeshParams::first_height: the first layer over its walls
    std::string blossom_failure;  ///< RecombinationReport::blossom_failure
};

/// One run of Gmsh's route at feature angle \p angle_deg, the result checked against \p in; \p budget:
/// the CPU seconds its classification (RemeshParams::classify_seconds) and its meshing may take.
Attempt remesh_once(const SurfaceMesh& in, const Triangles& tris, const std::vector<std::array<Index, 2>>& seams,
                    const RemeshParams& p, double size, double angle_deg, const Budget& budget,
                    const std::string& source, const WallCaps* caps = nullptr) {
    const std::string ctx = source + ": remeshing with Gmsh (feature angle " + format_number(angle_deg) + " degrees)";
    // Gmsh scales its tolerances by the model's bounding box, which it computes when it reads a
    // file but not for entities made through the API (it then takes 1): the surface goes in
    // centred and scaled to a unit diagonal. Given in millimetres, the frontal mesher looped
    // for ever on the ONERA M6.
    struct Frame {
        Vec3 centre;
        double scale;
    };
    const BoundingBox box = bounding_box(in.points);
    const Frame frame{0.5 * (box.min + box.max), box.diagonal()};
    GmshSession session("strata_remesh");
    GmshOptionScope options;  // after the session: restored while Gmsh is still locked
    Attempt out;
    std::vector<int> face_surface;
    std::map<int, std::vector<std::size_t>> old_of_surface;  // Gmsh surface → its old triangles
    gmsh_call(ctx, [&] {
        options.set("General.NumThreads", 1);  // one thread: the same mesh on every run
        options.set("Mesh.MeshSizeMax", size / frame.scale);
        const bool curvature = p.curvature_points > 0;
        options.set("Mesh.MeshSizeMin", (p.size_min > 0.0 ? p.size_min : curvature ? size / 20.0 : 0.0) / frame.scale);
        options.set("Mesh.MeshSizeFromCurvature", p.curvature_points);
        options.set("Mesh.MeshSizeFromPoints", 0);
        options.set("Mesh.MeshSizeExtendFromBoundary", 1);
        options.set("Mesh.MeshSizeFactor", 1);
        options.set("Mesh.ElementOrder", 1);
        options.set("Mesh.SubdivisionAlgorithm", 0);
        options.set("Mesh.Algorithm", p.algorithm);
        options.set("Mesh.RecombineAll", p.quads ? 1 : 0);
        options.set("Mesh.RecombinationAlgorithm", p.simple_recombination ? 0 : 1);  // simple or Blossom
        // The old surface as one discrete surface, and as one discrete curve its patch
        // boundaries and the cuts that put every long sharp edge between two regions
        // (feature_cuts.h): classifySurfaces never lets a new surface cross an existing curve's
        // lines, and it keeps a sharp edge only where its two sides are different surfaces.
        std::vector<std::size_t> node_tags(in.points.size());
        std::vector<double> xyz;
        xyz.reserve(3 * in.points.size());
        for (std::size_t i = 0; i < in.points.size(); ++i) {
            node_tags[i] = i + 1;
            const Vec3 q = (in.points[i] - frame.centre) / frame.scale;
            xyz.insert(xyz.end(), {q.x(), q.y(), q.z()});
        }
        gmsh::model::addDiscreteEntity(2, 1);
        gmsh::model::mesh::addNodes(2, 1, node_tags, xyz);
        std::vector<std::size_t> elem_tags(tris.tri.size()), elem_nodes;
        elem_nodes.reserve(3 * tris.tri.size());
        for (std::size_t t = 0; t < tris.tri.size(); ++t) {
            elem_tags[t] = t + 1;
            for (Index v : tris.tri[t]) elem_nodes.push_back(static_cast<std::size_t>(v) + 1);
        }
        gmsh::model::mesh::addElementsByType(1, 2, elem_tags, elem_nodes);
        std::vector<std::array<Index, 2>> lines = feature_cuts(in.points, tris.tri, seams, angle_deg, 2.0 * size);
        lines.insert(lines.end(), seams.begin(), seams.end());
        std::sort(lines.begin(), lines.end());
        lines.erase(std::unique(lines.begin(), lines.end()), lines.end());
        if (!lines.empty()) {
            gmsh::model::addDiscreteEntity(1, 1);
            std::vector<std::size_t> line_tags(lines.size()), line_nodes;
            for (std::size_t s = 0; s < lines.size(); ++s) {
                line_tags[s] = tris.tri.size() + s + 1;
                line_nodes.push_back(static_cast<std::size_t>(lines[s][0]) + 1);
                line_nodes.push_back(static_cast<std::size_t>(lines[s][1]) + 1);
            }
            gmsh::model::mesh::addElementsByType(1, 1, line_tags, line_nodes);
        }
        // Gmsh 4.8 splits a surface again and again (METIS) until each piece can be
        // parametrized, which on poor triangles (a union's slivers, needles) can go on for ever:
        // the fused propeller STL ran 12 minutes in one attempt. So it is tried first in a child
        // process with a time budget; past it, this attempt fails and the next angle or size is
        // tried. It costs the classification's time once more (0.2 s on that propeller).
        const auto classify = [angle_deg] {
            gmsh::model::mesh::classifySurfaces(angle_deg * kPi / 180.0, true, true, kPi);
            gmsh::model::mesh::createGeometry();
        };
        DeadlineProgress deadline(budget.classify);
        GmshProbe trial;
        try {
            trial = gmsh_probe(classify, &deadline);
        } catch (const Cancelled&) {
            if (!deadline.expired()) throw;
            throw GmshTimeout(ctx + ": Gmsh's split of the surface for its parametrization did not end within " +
                              format_number(budget.classify, 3) +
                              " s (it splits again and again where the triangles are poor: slivers, needles)");
        }
        if (trial.ran && !trial.returned && !trial.threw)
            throw BackendError(ctx + ": Gmsh's split of the surface for its parametrization " + how_it_failed(trial));
        classify();
        gmsh::vectorpair surfaces;
        gmsh::model::getEntities(surfaces, 2);
        for (const auto& [dim, tag] : surfaces) {
            std::vector<std::size_t> tags, nodes;  // Gmsh 4.8: output vectors must start empty
            gmsh::model::mesh::getElementsByType(2, tags, nodes, tag);
            for (std::size_t& t : tags) t -= 1;
            old_of_surface[tag] = std::move(tags);
        }
        // The walls' sizes (RemeshParams::max_aspect_ratio), in the frame: the same input and angle
        // give the same entities, so the tags measured on the attempt before name them here.
        std::optional<SizeCallback> callback;
        if (caps) {
            WallCaps scaled = *caps;
            for (auto& [tag, s] : scaled.surface) s /= frame.scale;
            for (auto& [tag, s] : scaled.curve) s /= frame.scale;
            callback.emplace(entity_sizes(scaled), 1.0);
        }
        // The meshing in a child, its mesh brought back: on a surface it cannot parametrize
        // well Gmsh can refine for ever (a helicopter's BRepMesh STL: MeshAdapt's refinement
        // past 20 minutes and 2 GB in its 60-degree attempt) or abort the process ("Unable to
        // recover the edge", thrown out of its OpenMP loop). Either is this attempt's failure.
        // Blossom may abort the process on this surface: then Gmsh's simple recombination,
        // within the same budget.
        const auto generate = [] { gmsh::model::mesh::generate(2); };
        DeadlineProgress mesh_deadline(budget.mesh);
        try {
            out.blossom_failure = generate_surfaces_in_child(ctx, p.quads, options, generate, &mesh_deadline);
        } catch (const Cancelled&) {
            if (!mesh_deadline.expired()) throw;
            throw GmshTimeout(ctx + ": Gmsh's meshing of the surfaces did not end within " +
                              format_number(budget.mesh, 3) + " s");
        }
    });
    out.mesh = surface_from_gmsh_model("the remeshed " + source, NodeOrder::FirstUse, &face_surface);
    if (p.first_height > 0.0 && p.max_aspect_ratio > 0.0) {
        // The wall surfaces: those made mostly of a wall patch's old faces. Measured in the frame,
        // the sizes it asks for given back in the mesh's unit.
        std::set<int> walls;
        for (const auto& [surface, olds] : old_of_surface) {
            std::map<Index, std::size_t> votes;
            for (std::size_t t : olds) ++votes[in.face_patch[tris.face[t]]];
            if (votes.empty()) continue;
            const Index patch = std::max_element(votes.begin(), votes.end(), [](auto& x, auto& y) {
                                    return x.second < y.second;
                                })->first;
            if (in.patches[static_cast<std::size_t>(patch)].kind == PatchKind::Wall) walls.insert(surface);
        }
        const WallLimits limits{p.first_height / frame.scale, p.max_aspect_ratio, p.fan_angle_deg, p.wall_faces_budget};
        gmsh_call(ctx + ": measuring the first layer's aspect ratio over the walls",
                  [&] { out.aspect = wall_aspect(out.mesh, face_surface, walls, limits); });
        for (auto& [c, need] : out.aspect.curve_need) need *= frame.scale;
        for (auto& [surface, a] : out.aspect.area) a *= frame.scale * frame.scale;
    }
    for (Vec3& q : out.mesh.points) q = frame.centre + q * frame.scale;
    out.surfaces = static_cast<Index>(old_of_surface.size());

    // Each new surface's patch and orientation from the old triangles it was made of. A new face
    // is inverted where its normal turns more than 90 degrees from the old face nearest its
    // centroid (within its surface: no feature lies between them, so their normals differ
    // by less than the feature angle).
    SurfaceMesh& m = out.mesh;
    m.patches = in.patches;
    std::map<int, std::vector<Index>> faces_of_surface;
    for (Index f = 0; f < m.num_faces(); ++f) faces_of_surface[face_surface[static_cast<std::size_t>(f)]].push_back(f);
    std::vector<char> bad(static_cast<std::size_t>(m.num_faces()), 0);
    for (const auto& [surface, faces] : faces_of_surface) {
        const auto old = old_of_surface.find(surface);
        if (old == old_of_surface.end() || old->second.empty())
            throw BackendError(ctx + ": Gmsh made faces on surface " + std::to_string(surface) +
                               ", which holds none of the input");
        std::map<Index, std::size_t> votes;
        std::vector<cgal::Triangle> prims;
        std::vector<Vec3> normals;
        for (std::size_t t : old->second) {
            const auto& tri = tris.tri[t];
            ++votes[in.face_patch[tris.face[t]]];
            const Vec3 &a = in.points[static_cast<std::size_t>(tri[0])],
                       &b = in.points[static_cast<std::size_t>(tri[1])],
                       &c = in.points[static_cast<std::size_t>(tri[2])];
            prims.emplace_back(cgal::point(a), cgal::point(b), cgal::point(c));
            normals.push_back((b - a).cross(c - a));
        }
        const Index patch =
            std::max_element(votes.begin(), votes.end(), [](auto& x, auto& y) { return x.second < y.second; })->first;
        const Tree tree(prims.begin(), prims.end());
        std::vector<char> along(faces.size(), 0);
        Index agree = 0;
        for (std::size_t i = 0; i < faces.size(); ++i) {
            const Index f = faces[i];
            m.face_patch[f] = patch;
            const Vec3 c = face_centroid(m, m.points, f), n = face_area_vector(m, f);
            const double scale = std::max((m.points[static_cast<std::size_t>(m.face_node(f, 0))] - c).norm(), 1e-300);
            if (!(n.norm() > 1e-12 * scale * scale) || !(n.norm() > 1e-24 * frame.scale * frame.scale)) {
                bad[static_cast<std::size_t>(f)] = 1;
                continue;
            }
            const auto hit = tree.closest_point_and_primitive(cgal::point(c));
            const Vec3& on = normals[static_cast<std::size_t>(hit.second - prims.begin())];
            along[i] = n.dot(on) > 0.0;
            agree += along[i];
        }
        // Gmsh orients a surface's faces by its parametrization: the majority says whether the
        // whole surface is reversed; the others are folded.
        const bool reversed = 2 * agree < static_cast<Index>(faces.size());
        for (std::size_t i = 0; i < faces.size(); ++i) {
            const Index f = faces[i];
            if (!bad[static_cast<std::size_t>(f)] && static_cast<bool>(along[i]) == reversed)
                bad[static_cast<std::size_t>(f)] = 1;
            if (reversed) {
                Index* n = m.face_nodes.data() + m.face_offsets[static_cast<std::size_t>(f)];
                std::reverse(n + 1, n + m.face_size(f));
            }
        }
    }
    for (Index f = 0; f < m.num_faces(); ++f)
        if (bad[static_cast<std::size_t>(f)]) {
            if (out.first_bad == kNone) out.first_bad = f;
            ++out.bad;
        }
    return out;
}

}  // namespace

SurfaceMesh remesh_surface(const SurfaceMesh& mesh, const RemeshParams& params, const std::string& source,
                           RemeshReport* report) {
    validate(params, source);
    if (mesh.num_faces() == 0) throw InputError(source + ": remeshing: the surface has no faces");
    // The input as triangles, each on its face's patch: what Gmsh is given.
    SurfaceMesh triangles;
    triangles.points = mesh.points;
    triangles.patches = mesh.patches;
    {
        const Triangles t = triangles_of(mesh);
        for (std::size_t i = 0; i < t.tri.size(); ++i)
            triangles.add_face(t.tri[i].data(), 3, mesh.face_patch[t.face[i]]);
    }
    const double size = params.size > 0.0 ? params.size : median_edge_length(mesh);
    if (!(size > 0.0)) throw InputError(source + ": remeshing: the surface's edges have no length");

    RemeshReport rep;
    rep.faces_before = mesh.num_faces();
    rep.size = size;
    const NeedleReport before = needle_faces(mesh, kNeedleCornerDeg);
    rep.needles_before = before.needles;
    rep.sharpest_before_deg = before.sharpest_deg;

    // The angle asked, then lower ones: more edges become curves, the surfaces Gmsh
    // parametrizes get smaller and flatter (a surface that folded its faces). Then higher ones,
    // up to 1.5 times the angle asked: fewer curves, fewer and simpler surfaces, for a coarse
    // tessellation where Gmsh's split of a surface for its parametrization leaves "wrong
    // topology of boundary mesh" (the fused wing-fuselage STL: at 40, 30 and 22.5 degrees; 50
    // meshes it).
    std::vector<double> angles{params.feature_angle_deg};
    while (angles.back() * 0.75 >= 0.5 * params.feature_angle_deg - 1e-9) angles.push_back(angles.back() * 0.75);
    for (const double up : {1.25, 1.5})
        if (params.feature_angle_deg * up < 90.0) angles.push_back(params.feature_angle_deg * up);
    rep.asked_feature_angle_deg = params.feature_angle_deg;
    // With the size left to Strata (the input's median edge), then half of it: a coarse
    // tessellation's median edge can be as large as a thin part's diameter (the wing-fuselage's
    // tail cone, where Gmsh put a face across the cone at every angle).
    std::vector<double> sizes{size};
    if (!(params.size > 0.0)) sizes.push_back(0.5 * size);
    std::string failures;
    int out_of_time = 0;  // attempts in a row whose classification or meshing ran out of its budget
    // The input's own triangles at every angle and size, then, where all of them failed, the
    // same triangles bisected to edges no longer than the size (split_long_edges: the same
    // surface). Gmsh classifies and parametrizes the triangles it is given and can fold the new
    // mesh where they are far longer than it: a CAD export's facets along a whole cylinder, cut
    // into needles at a fin's root (a rocket's STL folded 411 faces at every angle and size;
    // bisected, the first angle works). A last resort only, for what it gives is often worse
    // where the input's own triangles work: bisected from the start, the car STL's remeshing
    // took 2.7 times as long and the winglet STL's wall sizing lost its finer walls; as a retry
    // at each angle, the three cones' STL took needles of 0.4 degrees where 60 degrees on its own
    // triangles left 3 degrees; and before the half size, the glider STL took 120 needles and
    // a tetrahedron of 1.6e-5 where the half size on its own triangles leaves 4 and 0.030.
    struct Input {
        const SurfaceMesh* mesh;
        Triangles tris;
        std::vector<std::array<Index, 2>> seams;
        Index split = 0;
    };
    const Input whole{&triangles, triangles_of(triangles), patch_seams(triangles), 0};
    // The classification's time budget by the input's triangles, bisected or not: it is there to
    // end Gmsh's endless splitting, not to wait longer for more triangles.
    const double classify_budget =
        params.classify_seconds > 0.0
            ? params.classify_seconds
            : kClassifySeconds + kClassifySecondsPerTriangle * static_cast<double>(whole.tris.tri.size());
    double area = 0.0;
    for (Index f = 0; f < triangles.num_faces(); ++f) area += face_area_vector(triangles, f).norm();
    // The meshing's budget by the faces expected at size h, and with the walls' sizes
    // (refine_walls) by those the walls may take on top.
    const auto budget_at = [&](double h, bool walls_capped) {
        const double faces = 4.0 * area / (h * h) + (walls_capped ? params.wall_faces_budget : 0.0);
        return Budget{classify_budget,
                      params.mesh_seconds > 0.0 ? params.mesh_seconds : kMeshSeconds + kMeshSecondsPerFace * faces};
    };
    for (int pass = 0; pass < 2; ++pass) {
        for (const double h : sizes) {
            SurfaceMesh fine;
            Input bisected{&fine, {}, {}, 0};
            if (pass == 1) {
                fine = split_long_edges(triangles, h,
                                        std::max<Index>(kSplitFacesMin, kSplitFacesPerFace * triangles.num_faces()),
                                        &bisected.split);
                if (bisected.split == 0) continue;  // nothing longer than the size: the attempts made
                bisected.tris = triangles_of(fine);
                bisected.seams = patch_seams(fine);
            }
            const Input& in = pass == 0 ? whole : bisected;
            for (double angle : angles) {
                ++rep.attempts;
                std::optional<Attempt> a;
                const std::string at =
                    "at " + format_number(angle) + " degrees" +
                    (sizes.size() > 1 ? " and size " + format_number(h) : std::string()) +
                    (pass == 1 ? " on the input's edges bisected to the size (" + std::to_string(in.split) + " splits)"
                               : std::string());
                try {
                    a = remesh_once(*in.mesh, in.tris, in.seams, params, h, angle, budget_at(h, false), source);
                    out_of_time = 0;
                } catch (const BackendError& e) {
                    failures += std::string(failures.empty() ? "" : "; ") + at + " Gmsh failed (" + e.what() + ")";
                    out_of_time = dynamic_cast<const GmshTimeout*>(&e) ? out_of_time + 1 : 0;
                    if (out_of_time == 2)
                        throw BackendError(source + ": remeshing failed: " + failures +
                                           ". Two attempts in a row ran out of time in Gmsh (its parametrization or "
                                           "its meshing), so no more were made: the surface's triangles are too poor "
                                           "for it (slivers, needles); export the surface finer, or mesh the CAD "
                                           "model itself");
                    continue;
                }
                if (a->bad > 0) {
                    failures += std::string(failures.empty() ? "" : "; ") + at + " " + std::to_string(a->bad) +
                                " faces came out folded or without area, the first " +
                                describe_face(a->mesh, a->first_bad);
                    continue;
                }
                rep.size_halved = h != size;
                rep.split_edges = in.split;
                rep.size = h;
                rep.faces_after = a->mesh.num_faces();
                rep.surfaces = a->surfaces;
                rep.feature_angle_deg = angle;
                if (params.first_height > 0.0 && params.max_aspect_ratio > 0.0) {
                    // RemeshParams::max_aspect_ratio: the route again with the walls' sizes, as long
                    // as it succeeds; the last good mesh stands.
                    const WallLimits limits{params.first_height, params.max_aspect_ratio, params.fan_angle_deg,
                                            params.wall_faces_budget};
                    refine_walls(limits, a->aspect, rep.walls, [&](const WallCaps& caps, WallAspect& measured) {
                        std::optional<Attempt> b;
                        try {
                            b = remesh_once(*in.mesh, in.tris, in.seams, params, h, angle, budget_at(h, true), source,
                                            &caps);
                        } catch (const BackendError&) {
                            return false;
                        }
                        if (b->bad > 0) return false;
                        measured = b->aspect;
                        a = std::move(b);
                        return true;
                    });
                    rep.faces_after = a->mesh.num_faces();
                    rep.surfaces = a->surfaces;
                }
                rep.recombination.blossom_failure = a->blossom_failure;
                const NeedleReport final_needles = needle_faces(a->mesh, kNeedleCornerDeg);
                rep.needles_after = final_needles.needles;
                rep.sharpest_after_deg = final_needles.sharpest_deg;
                if (report) *report = rep;
                return std::move(a->mesh);
            }
        }
    }
    throw BackendError(source + ": remeshing failed: " + failures +
                       ". Try another feature angle (--feature-angle) or size, or repair the surface in a CAD tool");
}

}  // namespace strata
