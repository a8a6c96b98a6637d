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

/// Gmsh scales its tolerances by the model's bounding box, which it computes when it reads a
/// file but not for entities made through the API (it then takes 1): the surface goes in
/// centred and scaled to a unit diagonal (in millimetres, the frontal mesher can loop for ever).
struct Frame {
    Vec3 centre;
    double scale;
};

Frame frame_of(const SurfaceMesh& in) {
    const BoundingBox box = bounding_box(in.points);
    return Frame{0.5 * (box.min + box.max), box.diagonal()};
}

/// Gmsh's options for remeshing at element size \p size (in the frame of \p scale).
void set_remesh_options(GmshOptionScope& options, const RemeshParams& p, double size, double scale) {
    options.set("General.NumThreads", 1);  // one thread: the same mesh on every run
    options.set("Mesh.MeshSizeMax", size / scale);
    const bool curvature = p.curvature_points > 0;
    options.set("Mesh.MeshSizeMin", (p.size_min > 0.0 ? p.size_min : curvature ? size / 20.0 : 0.0) / scale);
    options.set("Mesh.MeshSizeFromCurvature", p.curvature_points);
    options.set("Mesh.MeshSizeFromPoints", 0);
    options.set("Mesh.MeshSizeExtendFromBoundary", 1);
    options.set("Mesh.MeshSizeFactor", 1);
    options.set("Mesh.ElementOrder", 1);
    options.set("Mesh.SubdivisionAlgorithm", 0);
    options.set("Mesh.Algorithm", p.algorithm);
    options.set("Mesh.RecombineAll", p.quads ? 1 : 0);
    options.set("Mesh.RecombinationAlgorithm", p.simple_recombination ? 0 : 1);  // simple or Blossom
}

/// The old surface into the Gmsh model as one discrete surface, and as one discrete curve its
/// patch boundaries and the cuts that put every long sharp edge between two regions
/// (feature_cuts.h): classifySurfaces never lets a new surface cross an existing curve's
/// lines, and it keeps a sharp edge only where its two sides are different surfaces.
void add_old_surface(const SurfaceMesh& in, const Triangles& tris, const std::vector<std::array<Index, 2>>& seams,
                     double angle_deg, double size, const Frame& frame) {
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
    if (lines.empty()) return;
    gmsh::model::addDiscreteEntity(1, 1);
    std::vector<std::size_t> line_tags(lines.size()), line_nodes;
    for (std::size_t s = 0; s < lines.size(); ++s) {
        line_tags[s] = tris.tri.size() + s + 1;
        line_nodes.push_back(static_cast<std::size_t>(lines[s][0]) + 1);
        line_nodes.push_back(static_cast<std::size_t>(lines[s][1]) + 1);
    }
    gmsh::model::mesh::addElementsByType(1, 1, line_tags, line_nodes);
}

/// Gmsh's classification of the model's surface at \p angle_deg into surfaces it can
/// parametrize. Gmsh 4.8 splits a surface again and again (METIS) until each piece can be
/// parametrized, which on poor triangles (a union's slivers, needles) can go on for ever; so
/// it is tried first in a child process within \p seconds (GmshTimeout past them), which costs
/// the classification's time once more.
void classify_within(const std::string& ctx, double angle_deg, double seconds) {
    const auto classify = [angle_deg] {
        gmsh::model::mesh::classifySurfaces(angle_deg * kPi / 180.0, true, true, kPi);
        gmsh::model::mesh::createGeometry();
    };
    DeadlineProgress deadline(seconds);
    GmshProbe trial;
    try {
        trial = gmsh_probe(classify, &deadline);
    } catch (const Cancelled&) {
        if (!deadline.expired()) throw;
        throw GmshTimeout(ctx + ": Gmsh's split of the surface for its parametrization did not end within " +
                          format_number(seconds, 3) +
                          " s (it splits again and again where the triangles are poor: slivers, needles)");
    }
    if (trial.ran && !trial.returned && !trial.threw)
        throw BackendError(ctx + ": Gmsh's split of the surface for its parametrization " + how_it_failed(trial));
    classify();
}

/// Each Gmsh surface of the classified model → the old triangles it was made of.
std::map<int, std::vector<std::size_t>> old_triangles_by_surface() {
    std::map<int, std::vector<std::size_t>> old_of_surface;
    gmsh::vectorpair surfaces;
    gmsh::model::getEntities(surfaces, 2);
    for (const auto& [dim, tag] : surfaces) {
        std::vector<std::size_t> tags, nodes;  // Gmsh 4.8: output vectors must start empty
        gmsh::model::mesh::getElementsByType(2, tags, nodes, tag);
        for (std::size_t& t : tags) t -= 1;
        old_of_surface[tag] = std::move(tags);
    }
    return old_of_surface;
}

/// Gmsh's meshing of the classified surfaces, in a child process within \p seconds
/// (GmshTimeout past them), its mesh brought back: on a surface it cannot parametrize well
/// Gmsh can refine for ever or abort the process ("Unable to recover the edge", thrown out of
/// its OpenMP loop), either of which is this attempt's failure. Blossom may abort the process
/// on this surface: then Gmsh's simple recombination, within the same budget. Returns
/// RecombinationReport::blossom_failure.
std::string mesh_within(const std::string& ctx, bool quads, GmshOptionScope& options, double seconds) {
    const auto generate = [] { gmsh::model::mesh::generate(2); };
    DeadlineProgress mesh_deadline(seconds);
    try {
        return generate_surfaces_in_child(ctx, quads, options, generate, &mesh_deadline);
    } catch (const Cancelled&) {
        if (!mesh_deadline.expired()) throw;
        throw GmshTimeout(ctx + ": Gmsh's meshing of the surfaces did not end within " + format_number(seconds, 3) +
                          " s");
    }
}

/// The patch most of the old triangles \p olds come from.
Index majority_patch(const SurfaceMesh& in, const Triangles& tris, const std::vector<std::size_t>& olds) {
    std::map<Index, std::size_t> votes;
    for (std::size_t t : olds) ++votes[in.face_patch[tris.face[t]]];
    return std::max_element(votes.begin(), votes.end(), [](auto& x, auto& y) { return x.second < y.second; })->first;
}

/// The first layer's aspect ratio (RemeshParams::max_aspect_ratio) over the wall surfaces of
/// \p out's mesh, still in \p frame: those made mostly of a wall patch's old faces. Measured in
/// the frame, the sizes it asks for given back in the mesh's unit.
void measure_walls(const SurfaceMesh& in, const Triangles& tris,
                   const std::map<int, std::vector<std::size_t>>& old_of_surface, const std::vector<int>& face_surface,
                   const RemeshParams& p, const Frame& frame, const std::string& ctx, Attempt& out) {
    std::set<int> walls;
    for (const auto& [surface, olds] : old_of_surface) {
        if (olds.empty()) continue;
        const Index patch = majority_patch(in, tris, olds);
        if (in.patches[static_cast<std::size_t>(patch)].kind == PatchKind::Wall) walls.insert(surface);
    }
    const WallLimits limits{p.first_height / frame.scale, p.max_aspect_ratio, p.fan_angle_deg, p.wall_faces_budget};
    gmsh_call(ctx + ": measuring the first layer's aspect ratio over the walls",
              [&] { out.aspect = wall_aspect(out.mesh, face_surface, walls, limits); });
    for (auto& [c, need] : out.aspect.curve_need) need *= frame.scale;
    for (auto& [surface, a] : out.aspect.area) a *= frame.scale * frame.scale;
}

/// Gives the new faces \p faces of one Gmsh surface (made of the old triangles \p olds) the
/// patch of most of those, and orients them as those: a new face is folded where its normal
/// turns more than 90 degrees from the old face nearest its centroid (within its surface: no
/// feature lies between them, so their normals differ by less than the feature angle), or
/// without area (\p bad set for both).
void orient_surface(const SurfaceMesh& in, const Triangles& tris, const std::vector<std::size_t>& olds,
                    const std::vector<Index>& faces, double frame_scale, SurfaceMesh& m, std::vector<char>& bad) {
    std::vector<cgal::Triangle> prims;
    std::vector<Vec3> normals;
    for (std::size_t t : olds) {
        const auto& tri = tris.tri[t];
        const Vec3 &a = in.points[static_cast<std::size_t>(tri[0])], &b = in.points[static_cast<std::size_t>(tri[1])],
                   &c = in.points[static_cast<std::size_t>(tri[2])];
        prims.emplace_back(cgal::point(a), cgal::point(b), cgal::point(c));
        normals.push_back((b - a).cross(c - a));
    }
    const Index patch = majority_patch(in, tris, olds);
    const Tree tree(prims.begin(), prims.end());
    std::vector<char> along(faces.size(), 0);
    Index agree = 0;
    for (std::size_t i = 0; i < faces.size(); ++i) {
        const Index f = faces[i];
        m.face_patch[f] = patch;
        const Vec3 c = face_centroid(m, m.points, f), n = face_area_vector(m, f);
        const double scale = std::max((m.points[static_cast<std::size_t>(m.face_node(f, 0))] - c).norm(), 1e-300);
        if (!(n.norm() > 1e-12 * scale * scale) || !(n.norm() > 1e-24 * frame_scale * frame_scale)) {
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

/// Each new surface's patch and orientation from the old triangles it was made of (orient_surface),
/// and the count of faces folded or without area, with the first.
void orient_surfaces(const SurfaceMesh& in, const Triangles& tris,
                     const std::map<int, std::vector<std::size_t>>& old_of_surface,
                     const std::vector<int>& face_surface, double frame_scale, const std::string& ctx, Attempt& out) {
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
        orient_surface(in, tris, old->second, faces, frame_scale, m, bad);
    }
    for (Index f = 0; f < m.num_faces(); ++f)
        if (bad[static_cast<std::size_t>(f)]) {
            if (out.first_bad == kNone) out.first_bad = f;
            ++out.bad;
        }
}

/// One run of Gmsh's route at feature angle \p angle_deg, the result checked against \p in; \p budget:
/// the CPU seconds its classification (RemeshParams::classify_seconds) and its meshing may take.
Attempt remesh_once(const SurfaceMesh& in, const Triangles& tris, const std::vector<std::array<Index, 2>>& seams,
                    const RemeshParams& p, double size, double angle_deg, const Budget& budget,
                    const std::string& source, const WallCaps* caps = nullptr) {
    const std::string ctx = source + ": remeshing with Gmsh (feature angle " + format_number(angle_deg) + " degrees)";
    const Frame frame = frame_of(in);
    GmshSession session("strata_remesh");
    GmshOptionScope options;  // after the session: restored while Gmsh is still locked
    Attempt out;
    std::vector<int> face_surface;
    std::map<int, std::vector<std::size_t>> old_of_surface;  // Gmsh surface → its old triangles
    gmsh_call(ctx, [&] {
        set_remesh_options(options, p, size, frame.scale);
        add_old_surface(in, tris, seams, angle_deg, size, frame);
        classify_within(ctx, angle_deg, budget.classify);
        old_of_surface = old_triangles_by_surface();
        // The walls' sizes (RemeshParams::max_aspect_ratio), in the frame: the same input and angle
        // give the same entities, so the tags measured on the attempt before name them here.
        std::optional<SizeCallback> callback;
        if (caps) {
            WallCaps scaled = *caps;
            for (auto& [tag, s] : scaled.surface) s /= frame.scale;
            for (auto& [tag, s] : scaled.curve) s /= frame.scale;
            callback.emplace(entity_sizes(scaled), 1.0);
        }
        out.blossom_failure = mesh_within(ctx, p.quads, options, budget.mesh);
    });
    out.mesh = surface_from_gmsh_model("the remeshed " + source, NodeOrder::FirstUse, &face_surface);
    if (p.first_height > 0.0 && p.max_aspect_ratio > 0.0)
        measure_walls(in, tris, old_of_surface, face_surface, p, frame, ctx, out);
    for (Vec3& q : out.mesh.points) q = frame.centre + q * frame.scale;
    out.surfaces = static_cast<Index>(old_of_surface.size());
    orient_surfaces(in, tris, old_of_surface, face_surface, frame.scale, ctx, out);
    return out;
}

/// The input as triangles, each on its face's patch: what Gmsh is given.
SurfaceMesh as_triangles(const SurfaceMesh& mesh) {
    SurfaceMesh triangles;
    triangles.points = mesh.points;
    triangles.patches = mesh.patches;
    const Triangles t = triangles_of(mesh);
    for (std::size_t i = 0; i < t.tri.size(); ++i) triangles.add_face(t.tri[i].data(), 3, mesh.face_patch[t.face[i]]);
    return triangles;
}

/// The feature angles to try: the angle asked, then lower ones down to half of it (more edges
/// become curves, the surfaces Gmsh parametrizes get smaller and flatter: for a surface that
/// folded its faces), then higher ones up to 1.5 times it (fewer and simpler surfaces: for a
/// coarse tessellation where Gmsh's split of a surface for its parametrization leaves "wrong
/// topology of boundary mesh").
std::vector<double> feature_angles(double asked) {
    std::vector<double> angles{asked};
    while (angles.back() * 0.75 >= 0.5 * asked - 1e-9) angles.push_back(angles.back() * 0.75);
    for (const double up : {1.25, 1.5})
        if (asked * up < 90.0) angles.push_back(asked * up);
    return angles;
}

/// The triangles an attempt gives Gmsh, with their patch seams and the edges split to make them.
struct RemeshInput {
    const SurfaceMesh* mesh;
    Triangles tris;
    std::vector<std::array<Index, 2>> seams;
    Index split = 0;
};

/// The time budgets of the attempts.
struct Budgets {
    const RemeshParams& p;
    /// The classification's, by the input's triangles, bisected or not: it is there to end
    /// Gmsh's endless splitting, not to wait longer for more triangles.
    double classify = 0.0;
    double area = 0.0;  ///< the input's

    /// The budget at size \p h: the meshing's by the faces expected, and with the walls' sizes
    /// (refine_walls, \p walls_capped) by those the walls may take on top.
    Budget at(double h, bool walls_capped) const {
        const double faces = 4.0 * area / (h * h) + (walls_capped ? p.wall_faces_budget : 0.0);
        return Budget{classify, p.mesh_seconds > 0.0 ? p.mesh_seconds : kMeshSeconds + kMeshSecondsPerFace * faces};
    }
};

Budgets budgets_for(const RemeshParams& p, const SurfaceMesh& triangles) {
    Budgets b{p};
    b.classify = p.classify_seconds > 0.0
                     ? p.classify_seconds
                     : kClassifySeconds + kClassifySecondsPerTriangle * static_cast<double>(triangles.num_faces());
    for (Index f = 0; f < triangles.num_faces(); ++f) b.area += face_area_vector(triangles, f).norm();
    return b;
}

/// What the attempts so far failed with.
struct Failures {
    std::string text;
    int out_of_time = 0;  ///< attempts in a row whose classification or meshing ran out of its budget
    void add(const std::string& what) { text += std::string(text.empty() ? "" : "; ") + what; }
};

/// One attempt (remesh_once) on \p in at size \p h and feature angle \p angle, or none where
/// Gmsh failed or the new mesh has faces folded or without area (said in \p failures, with \p
/// at: where it was). Throws after two attempts in a row ran out of time.
std::optional<Attempt> try_attempt(const RemeshInput& in, const RemeshParams& params, double h, double angle,
                                   const Budget& budget, const std::string& source, const std::string& at,
                                   Failures& failures) {
    std::optional<Attempt> a;
    try {
        a = remesh_once(*in.mesh, in.tris, in.seams, params, h, angle, budget, source);
        failures.out_of_time = 0;
    } catch (const BackendError& e) {
        failures.add(at + " Gmsh failed (" + e.what() + ")");
        failures.out_of_time = dynamic_cast<const GmshTimeout*>(&e) ? failures.out_of_time + 1 : 0;
        if (failures.out_of_time == 2)
            throw BackendError(source + ": remeshing failed: " + failures.text +
                               ". Two attempts in a row ran out of time in Gmsh (its parametrization or "
                               "its meshing), so no more were made: the surface's triangles are too poor "
                               "for it (slivers, needles); export the surface finer, or mesh the CAD "
                               "model itself");
        return std::nullopt;
    }
    if (a->bad > 0) {
        failures.add(at + " " + std::to_string(a->bad) + " faces came out folded or without area, the first " +
                     describe_face(a->mesh, a->first_bad));
        return std::nullopt;
    }
    return a;
}

/// RemeshParams::max_aspect_ratio: the route of attempt \p a again with the walls' sizes, as
/// long as it succeeds; the last good mesh stands in \p a.
void refine_attempt(Attempt& a, const RemeshInput& in, const RemeshParams& params, double h, double angle,
                    const Budget& budget, const std::string& source, RemeshReport& rep) {
    const WallLimits limits{params.first_height, params.max_aspect_ratio, params.fan_angle_deg,
                            params.wall_faces_budget};
    refine_walls(limits, a.aspect, rep.walls, [&](const WallCaps& caps, WallAspect& measured) {
        std::optional<Attempt> b;
        try {
            b = remesh_once(*in.mesh, in.tris, in.seams, params, h, angle, budget, source, &caps);
        } catch (const BackendError&) {
            return false;
        }
        if (b->bad > 0) return false;
        measured = b->aspect;
        a = std::move(*b);
        return true;
    });
    rep.faces_after = a.mesh.num_faces();
    rep.surfaces = a.surfaces;
}

}  // namespace

SurfaceMesh remesh_surface(const SurfaceMesh& mesh, const RemeshParams& params, const std::string& source,
                           RemeshReport* report) {
    validate(params, source);
    if (mesh.num_faces() == 0) throw InputError(source + ": remeshing: the surface has no faces");
    const SurfaceMesh triangles = as_triangles(mesh);
    const double size = params.size > 0.0 ? params.size : median_edge_length(mesh);
    if (!(size > 0.0)) throw InputError(source + ": remeshing: the surface's edges have no length");

    RemeshReport rep;
    rep.faces_before = mesh.num_faces();
    rep.size = size;
    const NeedleReport before = needle_faces(mesh, kNeedleCornerDeg);
    rep.needles_before = before.needles;
    rep.sharpest_before_deg = before.sharpest_deg;
    const std::vector<double> angles = feature_angles(params.feature_angle_deg);
    rep.asked_feature_angle_deg = params.feature_angle_deg;
    // With the size left to Strata (the input's median edge), then half of it: a coarse
    // tessellation's median edge can be as large as a thin part's diameter (Gmsh then puts a face
    // across it at every angle).
    std::vector<double> sizes{size};
    if (!(params.size > 0.0)) sizes.push_back(0.5 * size);
    Failures failures;
    // The input's own triangles at every angle and size, then, where all of them failed, the
    // same triangles bisected to edges no longer than the size (split_long_edges: the same
    // surface): Gmsh can fold the new mesh where the triangles it is given are far longer than
    // it, but where the input's own triangles work they often give the better mesh.
    const RemeshInput whole{&triangles, triangles_of(triangles), patch_seams(triangles), 0};
    const Budgets budgets = budgets_for(params, triangles);
    for (int pass = 0; pass < 2; ++pass) {
        for (const double h : sizes) {
            SurfaceMesh fine;
            RemeshInput bisected{&fine, {}, {}, 0};
            if (pass == 1) {
                fine = split_long_edges(triangles, h,
                                        std::max<Index>(kSplitFacesMin, kSplitFacesPerFace * triangles.num_faces()),
                                        &bisected.split);
                if (bisected.split == 0) continue;  // nothing longer than the size: the attempts made
                bisected.tris = triangles_of(fine);
                bisected.seams = patch_seams(fine);
            }
            const RemeshInput& in = pass == 0 ? whole : bisected;
            for (double angle : angles) {
                ++rep.attempts;
                const std::string at =
                    "at " + format_number(angle) + " degrees" +
                    (sizes.size() > 1 ? " and size " + format_number(h) : std::string()) +
                    (pass == 1 ? " on the input's edges bisected to the size (" + std::to_string(in.split) + " splits)"
                               : std::string());
                std::optional<Attempt> a =
                    try_attempt(in, params, h, angle, budgets.at(h, false), source, at, failures);
                if (!a) continue;
                rep.size_halved = h != size;
                rep.split_edges = in.split;
                rep.size = h;
                rep.faces_after = a->mesh.num_faces();
                rep.surfaces = a->surfaces;
                rep.feature_angle_deg = angle;
                if (params.first_height > 0.0 && params.max_aspect_ratio > 0.0)
                    refine_attempt(*a, in, params, h, angle, budgets.at(h, true), source, rep);
                rep.recombination.blossom_failure = a->blossom_failure;
                const NeedleReport final_needles = needle_faces(a->mesh, kNeedleCornerDeg);
                rep.needles_after = final_needles.needles;
                rep.sharpest_after_deg = final_needles.sharpest_deg;
                if (report) *report = rep;
                return std::move(a->mesh);
            }
        }
    }
    throw BackendError(source + ": remeshing failed: " + failures.text +
                       ". Try another feature angle (RemeshParams::feature_angle_deg) or size, or repair the surface in a CAD tool");
}

}  // namespace strata
