// Proximity rays and thickness limits (module/proximity.h): facing plates at a known gap,
// what is hit and what is skipped, the Lipschitz envelope, and thread-count independence.

#include <strata/core/surface_mesh.h>
#include <strata/geometry/primitives.h>
#include <strata/module/proximity.h>

#include <gtest/gtest.h>

#include "test_support.h"

#include <cmath>

namespace strata {
namespace {

/// A 10 × 10 plate at z = 0 facing +z (patch "a", a wall) and one at z = \p gap facing down
/// (patch "b", of \p kind), 0.5 larger on each side.
SurfaceMesh facing_plates(double gap, PatchKind kind) {
    SurfaceMesh m = test::quad_grid(10, 10);
    m.patches[0] = Patch{std::string("a"), PatchKind::Wall};
    SurfaceMesh top = test::quad_grid(11, 11);
    const Index n = m.num_points();
    m.patches.push_back({"b", kind});
    for (const Vec3& x : top.points) m.points.push_back(x + Vec3(-0.5, -0.5, gap));
    for (Index f = 0; f < top.num_faces(); ++f) {
        const Index* v = top.face_begin(f);
        m.add_face({v[0] + n, v[3] + n, v[2] + n, v[1] + n}, 1);  // reversed: facing down
    }
    return m;
}

std::vector<ProximityHit> rays_up(const SurfaceMesh& m, Index count, int threads = 0) {
    std::vector<Index> node(static_cast<std::size_t>(count));
    std::vector<Vec3> origin, dir(static_cast<std::size_t>(count), Vec3::UnitZ());
    for (Index i = 0; i < count; ++i) node[static_cast<std::size_t>(i)] = i, origin.push_back(m.points[i]);
    return cast_proximity_rays(m, node, origin, dir, threads);
}

TEST(Proximity, FacingPlateAtItsDistanceAndKind) {
    for (const PatchKind kind : {PatchKind::Wall, PatchKind::Symmetry}) {
        const SurfaceMesh m = facing_plates(0.3, kind);
        const std::vector<ProximityHit> hits = rays_up(m, 121);
        for (const ProximityHit& h : hits) {
            EXPECT_NEAR(h.distance, 0.3, 1e-12);
            EXPECT_EQ(h.wall, kind == PatchKind::Wall);
        }
        // Limits on the lower plate: 0.45 of the gap against a wall, 0.9 against a symmetry plane.
        SurfaceMesh lower = test::quad_grid(10, 10);
        const std::vector<double> limit = thickness_limits(lower, hits, {});
        for (double l : limit) EXPECT_NEAR(l, kind == PatchKind::Wall ? 0.135 : 0.27, 1e-12);
    }
}

TEST(Proximity, ObliqueHitsAtConcaveCornersDoNotLimit) {
    // The upper plate tilted by 70° about the x axis (a concave corner, like the Apollo base
    // and nozzle): the rays meet it at cos 70° = 0.34 and the layers merge there instead of
    // colliding: no limit. Tilted by 30° (a wedge-shaped gap): cos 30° = 0.87, limited.
    for (const auto& [deg, limited] : {std::pair{70.0, false}, std::pair{30.0, true}}) {
        SurfaceMesh m = facing_plates(2.0, PatchKind::Wall);
        const double a = deg * std::acos(-1.0) / 180.0;
        for (Index i = 121; i < m.num_points(); ++i) {  // the upper plate's nodes, turned about y = 5, z = 2
            Vec3& x = m.points[static_cast<std::size_t>(i)];
            const double y = x.y() - 5.0, z = x.z() - 2.0;
            x = Vec3(x.x(), 5.0 + std::cos(a) * y - std::sin(a) * z, 2.0 + std::sin(a) * y + std::cos(a) * z);
        }
        const std::vector<ProximityHit> hits = rays_up(m, 121);
        const ProximityHit& centre = hits[60];  // (5, 5, 0): meets the plate at (5, 5, 2)
        ASSERT_TRUE(std::isfinite(centre.distance)) << deg;
        EXPECT_NEAR(centre.distance, 2.0, 1e-9) << deg;
        EXPECT_NEAR(centre.facing, std::cos(a), 1e-9) << deg;
        const std::vector<double> limit = thickness_limits(test::quad_grid(10, 10), hits, {});
        EXPECT_EQ(std::isfinite(limit[60]), limited) << deg;
        if (limited) {
            EXPECT_LE(limit[60], 0.45 * 2.0 + 1e-12);
        }
    }
}

TEST(Proximity, OwnFacesAndEdgeOnFacesAreSkipped) {
    // Outward rays from a closed sphere meet nothing; its own incident faces are not hits.
    const SurfaceMesh s = icosphere(Vec3::Zero(), 1.0, 2, {"s", PatchKind::Wall});
    std::vector<Index> node;
    std::vector<Vec3> origin, dir;
    for (Index i = 0; i < s.num_points(); ++i)
        node.push_back(i), origin.push_back(s.points[i]), dir.push_back(s.points[i]);
    for (const ProximityHit& h : cast_proximity_rays(s, node, origin, dir, 0)) EXPECT_TRUE(std::isinf(h.distance));
    // Inward rays cross the sphere: the far side, at the diameter.
    for (Vec3& d : dir) d = -d;
    for (const ProximityHit& h : cast_proximity_rays(s, node, origin, dir, 0)) EXPECT_NEAR(h.distance, 2.0, 1e-9);
    // A ray along the lower plate (in its plane) meets neither it edge-on nor anything else.
    const SurfaceMesh m = facing_plates(0.3, PatchKind::Wall);
    const std::vector<ProximityHit> along =
        cast_proximity_rays(m, {0}, {m.points[0] + Vec3(-1, 0.5, 0)}, {Vec3::UnitX()}, 0);
    EXPECT_TRUE(std::isinf(along[0].distance));
}

TEST(Proximity, LimitsRiseAtMostBySlopeAlongTheWall) {
    // One node limited to 0.1, the rest free: the envelope is 0.1 + slope × path length.
    const SurfaceMesh line = test::quad_grid(20, 1);
    std::vector<ProximityHit> hits(line.points.size());
    hits[0] = {0.1 / 0.45, true};
    ProximityParams p;
    p.slope = 0.25;
    const std::vector<double> limit = thickness_limits(line, hits, p);
    EXPECT_NEAR(limit[0], 0.1, 1e-12);
    for (int i = 0; i <= 20; ++i) EXPECT_NEAR(limit[static_cast<std::size_t>(i)], 0.1 + 0.25 * i, 1e-12) << i;
    // An extra bound per node counts as well.
    std::vector<double> extra(line.points.size(), std::numeric_limits<double>::infinity());
    extra[20] = 0.05;
    EXPECT_NEAR(thickness_limits(line, hits, p, extra)[19], 0.3, 1e-12);
    EXPECT_NEAR(thickness_limits(line, hits, p, extra)[20], 0.05, 1e-12);
}

TEST(Proximity, SameHitsForAnyThreadCount) {
    const SurfaceMesh m = facing_plates(0.7, PatchKind::Wall);
    const std::vector<ProximityHit> a = rays_up(m, 121, 1), b = rays_up(m, 121, 2);
    for (std::size_t i = 0; i < a.size(); ++i) {
        EXPECT_EQ(a[i].distance, b[i].distance);
        EXPECT_EQ(a[i].wall, b[i].wall);
    }
}

}  // namespace
}  // namespace strata
