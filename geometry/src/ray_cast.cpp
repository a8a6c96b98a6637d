// First hits of rays from surface nodes: ray_cast.h.

#include <strata/geometry/cgal_kernel.h>

#include <strata/core/parallel.h>
#include <strata/geometry/intersections.h>
#include <strata/geometry/ray_cast.h>
#include <strata/geometry/topology.h>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace strata {

std::vector<RayHit> first_hits(const SurfaceMesh& surface, const std::vector<Index>& nodes,
                               const std::vector<Vec3>& origins, const std::vector<Vec3>& directions, int threads) {
    using Iterator = std::vector<cgal::Triangle>::const_iterator;
    using Tree =
        CGAL::AABB_tree<CGAL::AABB_traits<cgal::Kernel, CGAL::AABB_triangle_primitive<cgal::Kernel, Iterator>>>;
    std::vector<cgal::Triangle> tris;
    std::vector<Index> face_of;
    for (const SurfaceTriangle& t : surface_triangles(surface)) {
        tris.emplace_back(cgal::point(surface.points[t.v[0]]), cgal::point(surface.points[t.v[1]]),
                          cgal::point(surface.points[t.v[2]]));
        face_of.push_back(t.face);
    }
    const Csr node_faces = vertex_faces(surface);
    Tree tree(tris.cbegin(), tris.cend());
    tree.build();

    const auto n = static_cast<std::int64_t>(origins.size());
    std::vector<RayHit> hits(origins.size());
#pragma omp parallel for num_threads(thread_count(threads, n)) schedule(dynamic, 256)
    for (std::int64_t i = 0; i < n; ++i) {
        const Vec3& d = directions[static_cast<std::size_t>(i)];
        if (!(d.squaredNorm() > 0.0) || !d.allFinite()) continue;
        const Index node = nodes[static_cast<std::size_t>(i)];
        const Index* own_begin = node_faces.row_begin(node);
        const Index* own_end = node_faces.row_end(node);
        const Vec3& o = origins[static_cast<std::size_t>(i)];
        const cgal::Kernel::Ray_3 ray(cgal::point(o), cgal::Kernel::Vector_3(d.x(), d.y(), d.z()));
        auto skip = [&](Iterator it) {
            const auto k = static_cast<std::size_t>(it - tris.cbegin());
            if (std::find(own_begin, own_end, face_of[k]) != own_end) return true;
            const cgal::Kernel::Vector_3 nf = CGAL::normal(it->vertex(0), it->vertex(1), it->vertex(2));
            const Vec3 nv(nf.x(), nf.y(), nf.z());
            return std::abs(nv.dot(d)) <= 1e-9 * nv.norm() * d.norm();  // edge-on
        };
        const auto hit = tree.first_intersection(ray, skip);
        if (!hit) continue;
        const cgal::Point* p = boost::get<cgal::Point>(&hit->first);
        if (p == nullptr) continue;  // a segment: the ray runs in a face's plane (skipped above)
        RayHit& h = hits[static_cast<std::size_t>(i)];
        h.distance = (Vec3(p->x(), p->y(), p->z()) - o).norm();
        h.face = face_of[static_cast<std::size_t>(hit->second - tris.cbegin())];
    }
    return hits;
}

}  // namespace strata
