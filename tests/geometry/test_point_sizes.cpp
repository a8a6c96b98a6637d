// Sizes asked at points (geometry/point_sizes.h): the exact lower envelope of the points'
// cones against a brute-force minimum, a farther point of a smaller size winning over the
// nearest, bad input, and the faces estimate.

#include <strata/core/error.h>
#include <strata/geometry/point_sizes.h>

#include <gtest/gtest.h>

#include "test_support.h"

#include <cmath>
#include <limits>
#include <random>

namespace strata {
namespace {

double brute_force(const std::vector<SizePoint>& points, double growth, const Vec3& x) {
    double best = std::numeric_limits<double>::infinity();
    for (const SizePoint& p : points) best = std::min(best, p.size + growth * (x - p.at).norm());
    return best;
}

TEST(PointSizes, TheLowerEnvelopeOfEveryPointExactly) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1.0, 1.0), s(1e-4, 0.2);
    std::vector<SizePoint> points;
    for (int i = 0; i < 500; ++i) points.push_back({Vec3(u(rng), u(rng), 0.1 * u(rng)), s(rng)});
    for (const double growth : {0.05, 0.25, 2.0}) {
        const PointSizes sizes(points, growth);
        for (int q = 0; q < 400; ++q) {
            const Vec3 x(1.5 * u(rng), 1.5 * u(rng), u(rng));
            EXPECT_DOUBLE_EQ(sizes(x), brute_force(points, growth, x)) << "growth " << growth;
        }
    }
}

TEST(PointSizes, AFartherSmallerSizeWinsOverTheNearest) {
    // At x = 0: the point at 0.1 asks 1 (1.025 there), the one at 1 asks 0.001 (0.251 there).
    const PointSizes sizes({{Vec3(0.1, 0, 0), 1.0}, {Vec3(1.0, 0, 0), 0.001}}, 0.25);
    EXPECT_NEAR(sizes(Vec3::Zero()), 0.251, 1e-12);
    EXPECT_NEAR(sizes(Vec3(1.0, 0, 0)), 0.001, 1e-12);
}

TEST(PointSizes, NoPointsAskNothing) {
    const PointSizes sizes({}, 0.25);
    EXPECT_TRUE(sizes.empty());
    EXPECT_TRUE(std::isinf(sizes(Vec3::Zero())));
}

TEST(PointSizes, BadSizesAndGrowthAreInputErrors) {
    EXPECT_THROW(PointSizes({{Vec3::Zero(), 0.0}}, 0.25), InputError);
    EXPECT_THROW(PointSizes({{Vec3::Zero(), std::nan("")}}, 0.25), InputError);
    EXPECT_THROW(PointSizes({{Vec3(std::numeric_limits<double>::infinity(), 0, 0), 1.0}}, 0.25), InputError);
    EXPECT_THROW(PointSizes({{Vec3::Zero(), 1.0}}, 0.0), InputError);
    EXPECT_THROW(PointSizes({{Vec3::Zero(), 1.0}}, std::numeric_limits<double>::infinity()), InputError);
}

TEST(PointSizes, FacesEstimateCountsOnlyWhereTheSizesAreFiner) {
    // 10 x 10 unit quads: each counts as one unless asked finer at its centroid.
    const SurfaceMesh grid = test::quad_grid(10, 10);
    EXPECT_DOUBLE_EQ(faces_with_sizes(grid, PointSizes({}, 0.25)), 100.0);
    EXPECT_DOUBLE_EQ(faces_with_sizes(grid, PointSizes({{Vec3(5, 5, 0), 100.0}}, 0.25)), 100.0);
    // A size of 0.1 everywhere (growth tiny): each unit face is 1 / (0.433 · 0.01) triangles.
    const double each = 1.0 / (0.4330127 * 0.01);
    EXPECT_NEAR(faces_with_sizes(grid, PointSizes({{Vec3(5, 5, 0), 0.1}}, 1e-9)), 100.0 * each, 1e-3 * each);
}

}  // namespace
}  // namespace strata
