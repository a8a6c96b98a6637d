// Planar regions meshed through Gmsh (hybrid/plane_mesh.h): a square with a hole, and loops
// that bound no region refused with their place before Gmsh sees them (its 2D mesher throws
// from inside an OpenMP region on them, which would end the process).

#include <strata/core/error.h>
#include <strata/hybrid/plane_mesh.h>

#include <gtest/gtest.h>

#include "test_support.h"

#include <set>
#include <utility>

namespace strata {
namespace {

const Vec3 kOrigin = Vec3::Zero(), kNormal = Vec3::UnitZ();

double area(const std::vector<Vec3>& points, const PlaneMesh& m) {
    auto at = [&](Index i) {
        const auto k = static_cast<std::size_t>(i);
        return k < points.size() ? points[k] : m.new_points[k - points.size()];
    };
    double a = 0.0;
    for (const auto& t : m.triangles) a += 0.5 * (at(t[1]) - at(t[0])).cross(at(t[2]) - at(t[0])).z();
    return a;
}

TEST(PlaneMesh, SquareWithHoleKeepsEveryLoopPoint) {
    const std::vector<Vec3> p = {{0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0},
                                 {1, 1, 0}, {1, 3, 0}, {3, 3, 0}, {3, 1, 0}};
    const PlaneMesh m = mesh_plane_region(p, {{0, 1, 2, 3}, {4, 5, 6, 7}}, kOrigin, kNormal, "square");
    EXPECT_NEAR(area(p, m), 12.0, 1e-9);
    // Every loop segment is one triangle edge, in the loop's direction (region on its left).
    std::set<std::pair<Index, Index>> edges;
    for (const auto& t : m.triangles)
        for (std::size_t i = 0; i < 3; ++i) {
            ASSERT_LT(static_cast<std::size_t>(t[i]), p.size() + m.new_points.size());
            edges.insert({t[i], t[(i + 1) % 3]});
        }
    for (const std::vector<Index>& loop : {std::vector<Index>{0, 1, 2, 3}, std::vector<Index>{4, 5, 6, 7}})
        for (std::size_t i = 0; i < loop.size(); ++i)
            EXPECT_TRUE(edges.count({loop[i], loop[(i + 1) % loop.size()]})) << loop[i];
}

TEST(PlaneMesh, CrossingLoopIsRefusedWithItsPlace) {
    // A bow tie: the loop crosses itself at (1, 1, 0).
    const std::vector<Vec3> p = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {2, 2, 0}};
    test::expect_error<TopologyError>(
        [&] {
            mesh_plane_region(p, {{0, 1, 2, 3}}, kOrigin, kNormal, "bow tie");
        },
        {"bow tie", "crosses or overlaps itself at (1, 1, 0)"});
}

TEST(PlaneMesh, TJunctionAndTouchingLoopsAreRefused) {
    // A hole whose corner lies on the outer loop's edge (a T-junction).
    const std::vector<Vec3> t = {{0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0}, {2, 0, 0}, {3, 1, 0}, {1, 1, 0}};
    test::expect_error<TopologyError>(
        [&] {
            mesh_plane_region(t, {{0, 1, 2, 3}, {4, 6, 5}}, kOrigin, kNormal, "t");
        },
        {"at (2, 0, 0)"});
    // A hole touching the outer loop at a corner through a second point at the same place.
    const std::vector<Vec3> c = {{0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0}, {0, 0, 0}, {1, 2, 0}, {2, 1, 0}};
    test::expect_error<TopologyError>(
        [&] {
            mesh_plane_region(c, {{0, 1, 2, 3}, {4, 5, 6}}, kOrigin, kNormal, "c");
        },
        {"coincide at (0, 0, 0)"});
}

}  // namespace
}  // namespace strata
