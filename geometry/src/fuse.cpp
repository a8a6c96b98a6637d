// The union of overlapping closed components: fuse.h. CGAL's corefinement works on its own
// Surface_mesh; a face property carries each face's patch through the cuts and copies.

#include <strata/geometry/cgal_kernel.h>

#include <strata/core/error.h>
#include <strata/core/face_geometry.h>
#include <strata/core/union_find.h>
#include <strata/geometry/fuse.h>
#include <strata/geometry/intersections.h>
#include <strata/geometry/topology.h>

#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <array>
#include <map>
#include <vector>

namespace strata {
namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
using Mesh = CGAL::Surface_mesh<cgal::Point>;
using FaceD = Mesh::Face_index;
using PatchMap = Mesh::Property_map<FaceD, Index>;

PatchMap patch_map(Mesh& m) {
    return m.add_property_map<FaceD, Index>("f:patch", kNone).first;
}

/// Carries the patch of every face through corefinement: a face cut into subfaces gives them
/// its patch; a face copied into the result keeps it.
struct PatchVisitor : PMP::Corefinement::Default_visitor<Mesh> {
    Index pending = kNone;
    void before_subface_creations(FaceD f, Mesh& tm) { pending = patch_map(tm)[f]; }
    void after_subface_created(FaceD f, Mesh& tm) { patch_map(tm)[f] = pending; }
    void after_face_copy(FaceD src, const Mesh& tm_src, FaceD tgt, Mesh& tm_tgt) {
        const auto [from, found] = tm_src.property_map<FaceD, Index>("f:patch");
        patch_map(tm_tgt)[tgt] = found ? from[src] : kNone;
    }
};

/// Component \p faces of \p mesh as a CGAL triangle mesh (quads split along their first
/// diagonal), each face with its patch.
Mesh to_cgal(const SurfaceMesh& mesh, const std::vector<Index>& faces) {
    Mesh out;
    PatchMap patch = patch_map(out);
    std::map<Index, Mesh::Vertex_index> vertex;
    auto v = [&](Index i) {
        auto it = vertex.find(i);
        if (it == vertex.end()) it = vertex.emplace(i, out.add_vertex(cgal::point(mesh.points[i]))).first;
        return it->second;
    };
    for (const Index f : faces) {
        const Index* n = mesh.face_begin(f);
        const Index p = mesh.face_patch[f];
        auto add = [&](Index a, Index b, Index c) {
            const FaceD g = out.add_face(v(a), v(b), v(c));
            if (g == Mesh::null_face())
                throw TopologyError("fuse: " + describe_face(mesh, f) +
                                    " cannot join its component's other faces (a non-manifold edge or a face "
                                    "repeated); repair the surface first");
            patch[g] = p;
        };
        add(n[0], n[1], n[2]);
        if (mesh.face_size(f) == 4) add(n[0], n[2], n[3]);
    }
    return out;
}

/// The components of \p mesh: each face's, and each component's faces in order.
struct Components {
    Index count = 0;
    std::vector<Index> of_face;
    std::vector<std::vector<Index>> faces;
    const std::vector<Index>& faces_of(Index c) const { return faces[static_cast<std::size_t>(c)]; }
};

Components components_of(const SurfaceMesh& mesh) {
    Components c;
    c.of_face = face_components(mesh, &c.count);
    c.faces.resize(static_cast<std::size_t>(c.count));
    for (Index f = 0; f < mesh.num_faces(); ++f)
        c.faces[static_cast<std::size_t>(c.of_face[static_cast<std::size_t>(f)])].push_back(f);
    return c;
}

/// 1 for each closed component of walls (a candidate for the union), 0 for the others.
std::vector<char> closed_wall_components(const SurfaceMesh& mesh, const Components& comps) {
    const Index nc = comps.count;
    // A node's component is its faces'.
    std::vector<Index> node_comp(mesh.points.size(), kNone);
    for (Index f = 0; f < mesh.num_faces(); ++f)
        for (const Index* n = mesh.face_begin(f); n != mesh.face_end(f); ++n)
            node_comp[static_cast<std::size_t>(*n)] = comps.of_face[static_cast<std::size_t>(f)];
    std::vector<char> open(static_cast<std::size_t>(nc), 0);
    for (const Index v : boundary_loops(mesh).values)
        open[static_cast<std::size_t>(node_comp[static_cast<std::size_t>(v)])] = 1;
    std::vector<char> candidate(static_cast<std::size_t>(nc), 0);
    for (Index c = 0; c < nc; ++c) {
        bool walls = !open[static_cast<std::size_t>(c)];
        for (const Index f : comps.faces_of(c))
            walls &= mesh.patches[static_cast<std::size_t>(mesh.face_patch[f])].kind == PatchKind::Wall;
        candidate[static_cast<std::size_t>(c)] = walls ? 1 : 0;
    }
    return candidate;
}

/// The candidates that meet (the surface's own intersections between two of them), grouped:
/// each group's root → its components, in order. A candidate alone is a group of one.
std::map<Index, std::vector<Index>> overlapping_groups(const SurfaceMesh& mesh, const Components& comps,
                                                       const std::vector<char>& candidate) {
    const Index nc = comps.count;
    UnionFind group(static_cast<std::size_t>(nc));
    for (const FacePair& p : self_intersections(mesh)) {
        const Index a = comps.of_face[static_cast<std::size_t>(p.a)], b = comps.of_face[static_cast<std::size_t>(p.b)];
        if (candidate[static_cast<std::size_t>(a)] && candidate[static_cast<std::size_t>(b)]) group.unite(a, b);
    }
    std::map<Index, std::vector<Index>> groups;
    for (Index c = 0; c < nc; ++c)
        if (candidate[static_cast<std::size_t>(c)]) groups[group.find(c)].push_back(c);
    return groups;
}

/// The union of the components \p members of \p mesh, each made outward first.
Mesh union_of(const SurfaceMesh& mesh, const Components& comps, const std::vector<Index>& members) {
    Mesh result;
    for (std::size_t k = 0; k < members.size(); ++k) {
        const Index c = members[k];
        Mesh part = to_cgal(mesh, comps.faces_of(c));
        const Index first = comps.faces_of(c).front();
        if (PMP::does_self_intersect(part))
            throw TopologyError("fuse: the component of " + describe_face(mesh, first) +
                                " intersects itself, so it cannot be unioned with the others it overlaps; "
                                "repair it first (remesh it)");
        // Each body outward: orient_surface takes a body whose probe point lies inside another
        // (a wing root inside a fuselage) for a cavity and turns it inward, and the "union"
        // of an inward body is the outside of the intersection (an airliner of 12 parts came
        // out as 30 triangles).
        if (!PMP::is_outward_oriented(part)) PMP::reverse_face_orientations(part);
        if (k == 0) {
            result = std::move(part);
            continue;
        }
        Mesh united;
        patch_map(united);
        PatchVisitor visitor;
        bool ok = false;
        try {
            ok = PMP::corefine_and_compute_union(result, part, united, CGAL::parameters::visitor(visitor));
        } catch (const std::exception& e) {
            throw TopologyError("fuse: CGAL could not union the component of " + describe_face(mesh, first) +
                                " with the others (" + e.what() + "); check that each is closed and outward");
        }
        if (!ok)
            throw TouchingPartsError("fuse: the union of the component of " + describe_face(mesh, first) +
                                " with the others would not bound a volume (they touch along an edge or a "
                                "point only, or one is not closed); move them apart or overlap them more");
        result = std::move(united);
    }
    return result;
}

/// TopologyError unless \p result, the union of the components \p members (\p root the
/// group's), spans what they span: anything else is not their union.
void check_union_span(const SurfaceMesh& mesh, const Components& comps, const std::vector<Index>& members, Index root,
                      const Mesh& result) {
    BoundingBox span;
    bool first_point = true;
    for (const Index c : members)
        for (const Index f : comps.faces_of(c))
            for (const Index* v = mesh.face_begin(f); v != mesh.face_end(f); ++v) {
                const Vec3& x = mesh.points[*v];
                span.min = first_point ? x : Vec3(span.min.cwiseMin(x));
                span.max = first_point ? x : Vec3(span.max.cwiseMax(x));
                first_point = false;
            }
    BoundingBox got;
    got.min = got.max = span.min;
    first_point = true;
    for (const auto v : result.vertices()) {
        const auto& q = result.point(v);
        const Vec3 x(CGAL::to_double(q.x()), CGAL::to_double(q.y()), CGAL::to_double(q.z()));
        got.min = first_point ? x : Vec3(got.min.cwiseMin(x));
        got.max = first_point ? x : Vec3(got.max.cwiseMax(x));
        first_point = false;
    }
    const double tol = 1e-6 * (span.max - span.min).norm();
    if (first_point || (got.min - span.min).cwiseAbs().maxCoeff() > tol ||
        (got.max - span.max).cwiseAbs().maxCoeff() > tol)
        throw TopologyError(
            "fuse: the union of the " + std::to_string(members.size()) + " bodies overlapping the component of " +
            describe_face(mesh, comps.faces_of(root).front()) +
            " does not span what they span (CGAL's corefinement gave " + std::to_string(result.number_of_faces()) +
            " faces); check that each body is closed and its faces consistent, or mesh the "
            "CAD model with CadParams::fuse instead of its STL");
}

/// Appends \p result to \p out in an order of the geometry alone: CGAL's corefinement visits the
/// intersecting faces in an order that depends on heap addresses (its boxes' ids are their
/// addresses), so its vertex and face order changed with, e.g., the length of the output path.
/// Vertices sorted by coordinates, faces by their nodes from the lowest; a face without a patch
/// gets \p fallback_patch.
void append_sorted(const Mesh& result, Index fallback_patch, SurfaceMesh& out) {
    const auto [patch, has_patch] = result.property_map<FaceD, Index>("f:patch");
    std::vector<Mesh::Vertex_index> verts(result.vertices().begin(), result.vertices().end());
    auto coords = [&](Mesh::Vertex_index v) {
        const auto& p = result.point(v);
        return std::array<double, 3>{p.x(), p.y(), p.z()};
    };
    std::sort(verts.begin(), verts.end(), [&](auto a, auto b) { return coords(a) < coords(b); });
    std::map<Mesh::Vertex_index, Index> index;
    for (const auto v : verts) {
        const auto c = coords(v);
        index[v] = static_cast<Index>(out.points.size());
        out.points.emplace_back(c[0], c[1], c[2]);
    }
    std::vector<std::pair<std::vector<Index>, Index>> united_faces;  // nodes from the lowest, patch
    for (const auto f : result.faces()) {
        std::vector<Index> n;
        for (const auto v : CGAL::vertices_around_face(result.halfedge(f), result)) n.push_back(index.at(v));
        std::rotate(n.begin(), std::min_element(n.begin(), n.end()), n.end());
        const Index p = has_patch ? patch[f] : kNone;
        united_faces.emplace_back(std::move(n), p == kNone ? fallback_patch : p);
    }
    std::sort(united_faces.begin(), united_faces.end());
    for (const auto& [n, p] : united_faces) out.add_face(n.data(), static_cast<Index>(n.size()), p);
}

}  // namespace

SurfaceMesh fuse_components(const SurfaceMesh& mesh, FuseReport* report) {
    FuseReport rep;
    const Components comps = components_of(mesh);
    const Index nc = comps.count;
    const std::vector<char> candidate = closed_wall_components(mesh, comps);
    for (Index c = 0; c < nc; ++c) rep.components += candidate[static_cast<std::size_t>(c)] ? 1 : 0;
    const std::map<Index, std::vector<Index>> groups = overlapping_groups(mesh, comps, candidate);
    std::vector<Index> root(static_cast<std::size_t>(nc), kNone);
    for (const auto& [r, members] : groups)
        for (const Index c : members) root[static_cast<std::size_t>(c)] = r;
    SurfaceMesh out;
    out.patches = mesh.patches;
    std::vector<Index> kept(mesh.points.size(), kNone);
    auto keep_face = [&](Index f) {
        std::vector<Index> n;
        for (const Index* v = mesh.face_begin(f); v != mesh.face_end(f); ++v) {
            Index& k = kept[static_cast<std::size_t>(*v)];
            if (k == kNone) k = static_cast<Index>(out.points.size()), out.points.push_back(mesh.points[*v]);
            n.push_back(k);
        }
        out.add_face(n.data(), static_cast<Index>(n.size()), mesh.face_patch[f]);
    };
    for (Index c = 0; c < nc; ++c) {
        const bool alone =
            !candidate[static_cast<std::size_t>(c)] || groups.at(root[static_cast<std::size_t>(c)]).size() == 1;
        if (alone)
            for (const Index f : comps.faces_of(c)) keep_face(f);
    }
    for (const auto& [r, members] : groups) {
        if (members.size() < 2) continue;
        const Mesh result = union_of(mesh, comps, members);
        rep.fused += static_cast<Index>(members.size());
        check_union_span(mesh, comps, members, r, result);
        append_sorted(result, mesh.face_patch[comps.faces_of(r).front()], out);
    }
    if (report) *report = rep;
    return out;
}

}  // namespace strata
