// Proximity of the flow domain along each wall node's marching direction: proximity.h.

#include <strata/core/face_geometry.h>
#include <strata/geometry/ray_cast.h>
#include <strata/geometry/topology.h>
#include <strata/module/proximity.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <queue>
#include <utility>

namespace strata {

std::vector<ProximityHit> cast_proximity_rays(const SurfaceMesh& surface, const std::vector<Index>& surface_node,
                                              const std::vector<Vec3>& origins, const std::vector<Vec3>& directions,
                                              int threads) {
    const std::vector<RayHit> rays = first_hits(surface, surface_node, origins, directions, threads);
    std::vector<ProximityHit> hits(rays.size());
    for (std::size_t i = 0; i < rays.size(); ++i) {
        if (rays[i].face == kNone) continue;
        hits[i].distance = rays[i].distance;
        const Index patch = surface.face_patch[rays[i].face];
        hits[i].wall = surface.patches[static_cast<std::size_t>(patch)].kind == PatchKind::Wall;
        const Vec3 n = face_area_vector(surface, rays[i].face);
        const double len = n.norm() * directions[i].norm();
        hits[i].facing = len > 0.0 ? -n.dot(directions[i]) / len : 1.0;
    }
    return hits;
}

std::vector<double> thickness_limits(const SurfaceMesh& wall, const std::vector<ProximityHit>& hits,
                                     const ProximityParams& params, const std::vector<double>& extra) {
    const std::size_t n = static_cast<std::size_t>(wall.num_points());
    std::vector<double> limit(n, std::numeric_limits<double>::infinity());
    for (std::size_t i = 0; i < n; ++i)
        if (std::isfinite(hits[i].distance) && !(hits[i].facing < params.min_facing))
            limit[i] = (hits[i].wall ? params.facing_wall : params.other_patch) * hits[i].distance;
    if (!extra.empty())
        for (std::size_t i = 0; i < n; ++i) limit[i] = std::min(limit[i], extra[i]);
    // Lipschitz envelope: limit[i] = min_j (limit[j] + slope · path length from j to i), by a
    // Dijkstra sweep from every finite limit at once. Ties resolve by node id: deterministic.
    const EdgeTable edges = edge_table(wall);
    std::vector<std::vector<std::pair<Index, double>>> adjacent(n);
    for (Index e = 0; e < edges.faces.rows(); ++e) {
        const Index a = edges.nodes[e][0], b = edges.nodes[e][1];
        const double len = params.slope * (wall.points[a] - wall.points[b]).norm();
        adjacent[static_cast<std::size_t>(a)].emplace_back(b, len);
        adjacent[static_cast<std::size_t>(b)].emplace_back(a, len);
    }
    using Item = std::pair<double, Index>;
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
    for (std::size_t i = 0; i < n; ++i)
        if (std::isfinite(limit[i])) queue.emplace(limit[i], static_cast<Index>(i));
    while (!queue.empty()) {
        const auto [value, i] = queue.top();
        queue.pop();
        if (value > limit[static_cast<std::size_t>(i)]) continue;  // stale
        for (const auto& [j, len] : adjacent[static_cast<std::size_t>(i)]) {
            const double candidate = value + len;
            if (candidate < limit[static_cast<std::size_t>(j)]) {
                limit[static_cast<std::size_t>(j)] = candidate;
                queue.emplace(candidate, j);
            }
        }
    }
    return limit;
}

}  // namespace strata
