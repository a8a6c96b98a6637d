// Holes closed by triangles: fill_holes.h.

#include <strata/geometry/fill_holes.h>
#include <strata/geometry/topology.h>

#include <strata/geometry/cgal_kernel.h>

#include "cgal_mesh.h"

#include <CGAL/Polygon_mesh_processing/refine.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>

#include <algorithm>
#include <iterator>
#include <map>
#include <string>
#include <vector>

namespace strata {

namespace {

using CapMesh = cgal::TriangleMesh;

/// The patch most of loop \p v's (\p n nodes) edges' faces belong to (the lowest of equals).
Index loop_patch(const SurfaceMesh& mesh, const EdgeTable& edges, const Index* v, Index n) {
    std::map<Index, Index> votes;
    for (Index k = 0; k < n; ++k) {
        const Index e = find_edge(edges, v[k], v[(k + 1) % n]);
        if (e != kNone && edges.faces.row_size(e) > 0) ++votes[mesh.face_patch[edges.faces.row_begin(e)[0]]];
    }
    Index patch = 0, most = -1;
    for (const auto& [p, c] : votes)
        if (c > most) most = c, patch = p;
    return patch;
}

/// Loop \p v (\p n nodes, running as its faces do) closed into \p out: CGAL's triangulation of
/// its polygon (n - 2 triangles, each running against the loop), refined with nodes inside it
/// where \p refine. False where CGAL finds no triangulation.
bool close_loop(SurfaceMesh& out, const Index* v, Index n, Index patch, bool refine) {
    std::vector<cgal::Point> polyline;
    polyline.reserve(static_cast<std::size_t>(n));
    for (Index k = 0; k < n; ++k) polyline.push_back(cgal::point(out.points[static_cast<std::size_t>(v[k])]));
    std::vector<CGAL::Triple<int, int, int>> triangles;
    CGAL::Polygon_mesh_processing::triangulate_hole_polyline(polyline, std::back_inserter(triangles));
    if (static_cast<Index>(triangles.size()) != n - 2) return false;
    if (!refine) {
        // The loop runs as its faces do (boundary_loops), so a triangle closing it runs the
        // other way: (a, c, b) for the loop's order (a, b, c).
        for (const auto& t : triangles) out.add_face({v[t.first], v[t.third], v[t.second]}, patch);
        return true;
    }
    CapMesh cap;
    std::vector<CapMesh::Vertex_index> at;
    for (const cgal::Point& p : polyline) at.push_back(cap.add_vertex(p));
    for (const auto& t : triangles)
        cap.add_face(at[static_cast<std::size_t>(t.first)], at[static_cast<std::size_t>(t.third)],
                     at[static_cast<std::size_t>(t.second)]);
    std::vector<CapMesh::Face_index> made;
    std::vector<CapMesh::Vertex_index> added;
    CGAL::Polygon_mesh_processing::refine(cap, faces(cap), std::back_inserter(made), std::back_inserter(added));
    // The cap's nodes: the loop's first, then those refine added, appended to out in order.
    std::vector<Index> node(cap.number_of_vertices(), kNone);
    for (Index k = 0; k < n; ++k) node[static_cast<std::size_t>(at[static_cast<std::size_t>(k)])] = v[k];
    cgal::append_triangles(cap, node, out, patch);
    return true;
}

/// fill_holes, or with \p caps cap_holes.
SurfaceMesh close_holes(const SurfaceMesh& mesh, Index max_edges, HoleReport* report, bool caps) {
    HoleReport r;
    r.max_edges = max_edges;
    r.caps = caps;
    SurfaceMesh out = mesh;
    const Csr loops = boundary_loops(mesh);
    if (loops.rows() == 0 || max_edges < 3) {
        r.left = loops.rows();
        for (Index l = 0; l < loops.rows(); ++l) r.largest_left = std::max(r.largest_left, loops.row_size(l));
        if (report) *report = r;
        return out;
    }
    const EdgeTable edges = edge_table(mesh);
    for (Index l = 0; l < loops.rows(); ++l) {
        const Index n = loops.row_size(l);
        const Index* v = loops.row_begin(l);
        const auto leave = [&] {
            ++r.left;
            r.largest_left = std::max(r.largest_left, n);
        };
        if (n > max_edges) {
            leave();
            continue;
        }
        const Index patch = caps ? static_cast<Index>(out.patches.size()) : loop_patch(mesh, edges, v, n);
        if (caps) out.patches.push_back({"cap_" + std::to_string(r.holes + 1), PatchKind::Other});
        const Index faces_before = out.num_faces();
        if (!close_loop(out, v, n, patch, caps)) {
            if (caps) out.patches.pop_back();
            leave();
            continue;
        }
        ++r.holes;
        r.triangles += out.num_faces() - faces_before;
        if (n > r.largest) {
            r.largest = n;
            Vec3 c = Vec3::Zero();
            for (Index k = 0; k < n; ++k) c += mesh.points[static_cast<std::size_t>(v[k])];
            r.where = c / static_cast<double>(n);
        }
    }
    if (report) *report = r;
    return out;
}

}  // namespace

SurfaceMesh fill_holes(const SurfaceMesh& mesh, Index max_edges, HoleReport* report) {
    return close_holes(mesh, max_edges, report, false);
}

SurfaceMesh cap_holes(const SurfaceMesh& mesh, Index max_edges, HoleReport* report) {
    return close_holes(mesh, max_edges, report, true);
}

}  // namespace strata
