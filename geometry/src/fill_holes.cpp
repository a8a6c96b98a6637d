// Holes closed by triangles: fill_holes.h.

#include <strata/geometry/fill_holes.h>
#include <strata/geometry/topology.h>

#include <strata/geometry/cgal_kernel.h>

#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>

#include <algorithm>
#include <iterator>
#include <map>
#include <vector>

namespace strata {

SurfaceMesh fill_holes(const SurfaceMesh& mesh, Index max_edges, HoleReport* report) {
    HoleReport r;
    r.max_edges = max_edges;
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
        if (n > max_edges) {
            ++r.left;
            r.largest_left = std::max(r.largest_left, n);
            continue;
        }
        // The patch most of the loop's faces belong to (the lowest of equals).
        std::map<Index, Index> votes;
        for (Index k = 0; k < n; ++k) {
            const Index e = find_edge(edges, v[k], v[(k + 1) % n]);
            if (e != kNone && edges.faces.row_size(e) > 0) ++votes[mesh.face_patch[edges.faces.row_begin(e)[0]]];
        }
        Index patch = 0, most = -1;
        for (const auto& [p, c] : votes)
            if (c > most) most = c, patch = p;
        std::vector<cgal::Point> polyline;
        polyline.reserve(static_cast<std::size_t>(n));
        for (Index k = 0; k < n; ++k) polyline.push_back(cgal::point(mesh.points[static_cast<std::size_t>(v[k])]));
        std::vector<CGAL::Triple<int, int, int>> triangles;
        CGAL::Polygon_mesh_processing::triangulate_hole_polyline(polyline, std::back_inserter(triangles));
        if (static_cast<Index>(triangles.size()) != n - 2) {
            ++r.left;
            r.largest_left = std::max(r.largest_left, n);
            continue;
        }
        // The loop runs as its faces do (boundary_loops), so a triangle closing it runs the
        // other way: (a, c, b) for the loop's order (a, b, c).
        for (const auto& t : triangles) out.add_face({v[t.first], v[t.third], v[t.second]}, patch);
        ++r.holes;
        r.triangles += n - 2;
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

}  // namespace strata
