#pragma once
// Private to strata_geometry: a CGAL Surface_mesh of triangles brought back into a SurfaceMesh.

#include <strata/core/surface_mesh.h>
#include <strata/geometry/cgal_kernel.h>

#include <CGAL/Surface_mesh.h>

#include <array>
#include <vector>

namespace strata::cgal {

using TriangleMesh = CGAL::Surface_mesh<Point>;

/// \p mesh's triangles appended to \p out in patch \p patch: \p node maps each of \p mesh's
/// vertex indices to a node of \p out, kNone for those to append (in \p mesh's vertex order);
/// it is resized to cover every vertex index and filled in.
inline void append_triangles(const TriangleMesh& mesh, std::vector<Index>& node, SurfaceMesh& out, Index patch) {
    node.resize(mesh.number_of_vertices() + mesh.number_of_removed_vertices(), kNone);
    for (const TriangleMesh::Vertex_index v : mesh.vertices()) {
        Index& to = node[static_cast<std::size_t>(v)];
        if (to != kNone) continue;
        const Point& p = mesh.point(v);
        to = static_cast<Index>(out.points.size());
        out.points.emplace_back(p.x(), p.y(), p.z());
    }
    for (const TriangleMesh::Face_index f : mesh.faces()) {
        std::array<Index, 3> tri{};
        std::size_t k = 0;
        for (const TriangleMesh::Vertex_index v : CGAL::vertices_around_face(mesh.halfedge(f), mesh))
            if (k < 3) tri[k++] = node[static_cast<std::size_t>(v)];
        out.add_face(tri.data(), 3, patch);
    }
}

}  // namespace strata::cgal
