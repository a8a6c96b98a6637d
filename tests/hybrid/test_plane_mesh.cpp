// Planar regions meshed through Gmsh (hybrid/plane_mesh.h): a square with a hole, and loops
// that bound no region refused with their place before Gmsh sees them (its 2D mesher throws
// from inside an OpenMP region on them, which would end the process).

#include <strata/core/error.h>
#include <strata/hybrid/plane_mesh.h>

#include <gtest/gtest.h>

#include "test_support.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
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

/// Over the triangles of \p m within 25 of the origin with no corner among the first \p outer
/// points (the outer loop, whose own spacing the mesher keeps), sorted: the ratios of the longest
/// edge to the size the growth rule allows at the centroid, 0.1 (the hole's spacing) + \p growth
/// x the distance to the hole (radius 1 about the origin). \p at_hole: the longest edge of a
/// triangle touching the hole.
std::vector<double> grading(const std::vector<Vec3>& p, const PlaneMesh& m, double growth, std::size_t outer,
                            double& at_hole) {
    auto at = [&](Index i) {
        const auto k = static_cast<std::size_t>(i);
        return k < p.size() ? p[k] : m.new_points[k - p.size()];
    };
    std::vector<double> ratio;
    at_hole = 0.0;
    for (const auto& t : m.triangles) {
        double longest = 0.0;
        bool on_outer = false, on_hole = false;
        for (std::size_t i = 0; i < 3; ++i) {
            longest = std::max(longest, (at(t[i]) - at(t[(i + 1) % 3])).norm());
            on_outer |= static_cast<std::size_t>(t[i]) < outer;
            on_hole |= static_cast<std::size_t>(t[i]) >= outer && static_cast<std::size_t>(t[i]) < p.size();
        }
        if (on_hole) at_hole = std::max(at_hole, longest);
        const Vec3 c = (at(t[0]) + at(t[1]) + at(t[2])) / 3.0;
        if (on_outer || c.norm() > 25.0) continue;  // next to the outer loop its 100-long edges rule
        ratio.push_back(longest / (0.1 + growth * std::max(0.0, c.norm() - 1.0)));
    }
    std::sort(ratio.begin(), ratio.end());
    return ratio;
}

TEST(PlaneMesh, GrowthGradesTheSizeFromTheLoops) {
    // A hole of radius 1 with a spacing of 0.1 (a body's layer top cut by a symmetry plane) in a
    // square of side 100 with only its corners (a farfield side). Gmsh's frontal mesher alone
    // joins the hole to the corners with no point between; with growth 0.3 the triangles grow
    // from the hole as the tetrahedra do, so those standing on them need not be needles.
    std::vector<Vec3> p = {{-50, -50, 0}, {50, -50, 0}, {50, 50, 0}, {-50, 50, 0}};
    std::vector<Index> hole;
    const int n = 63;  // spacing 2 pi / 63 = 0.0997
    for (int i = 0; i < n; ++i) {
        const double a = -2.0 * std::numbers::pi * i / n;  // clockwise: a hole
        hole.push_back(static_cast<Index>(p.size()));
        p.emplace_back(std::cos(a), std::sin(a), 0.0);
    }
    std::vector<char> from_hole(p.size(), 1);
    std::fill(from_hole.begin(), from_hole.begin() + 4, 0);
    const PlaneMesh graded = mesh_plane_region(p, {{0, 1, 2, 3}, hole}, kOrigin, kNormal, "graded", 0.3, from_hole);
    const PlaneMesh plain = mesh_plane_region(p, {{0, 1, 2, 3}, hole}, kOrigin, kNormal, "plain");
    const double expected = 1e4 - 0.5 * n * std::sin(2.0 * std::numbers::pi / n);
    EXPECT_NEAR(area(p, graded), expected, 1e-6 * expected);
    EXPECT_NEAR(area(p, plain), expected, 1e-6 * expected);
    double g_hole = 0.0, f_hole = 0.0;
    const std::vector<double> g = grading(p, graded, 0.3, 4, g_hole);
    grading(p, plain, 0.3, 4, f_hole);
    ASSERT_GT(g.size(), 100u);
    const double median = g[g.size() / 2], p90 = g[g.size() * 9 / 10];
    std::printf(
        "longest edge over 0.1 + 0.3 d, graded: median %.2f, 90 %% %.2f, max %.2f; at the hole: graded %.3g, "
        "Gmsh alone %.3g; %zu and %zu triangles\n",
        median, p90, g.back(), g_hole, f_hole, graded.triangles.size(), plain.triangles.size());
    EXPECT_GT(median, 0.7);  // graded, not uniformly fine
    EXPECT_LT(p90, 1.5);
    EXPECT_LT(g.back(), 4.0);
    EXPECT_LT(g_hole, 0.3);
    EXPECT_GT(f_hole, 10.0);
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
