#include <strata/core/cell_quality.h>

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <vector>

using namespace strata;

namespace {

const double kHalfSqrt2 = std::sqrt(2.0) / 2.0;
const double kHalfSqrt3 = std::sqrt(3.0) / 2.0;

std::vector<Vec3> unit_cube() {
    return {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
}

/// A rigid motion far from the origin: scaled Jacobians must not change.
std::vector<Vec3> moved(std::vector<Vec3> p) {
    const Eigen::Matrix3d r = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
    for (Vec3& x : p) x = r * x + Vec3(1e3, -2e3, 5e2);
    return p;
}

}  // namespace

TEST(CornerScaledJacobian, RightAngledCornerIsOneAndMirroredIsMinusOne) {
    const Vec3 o(0, 0, 0), x(2, 0, 0), y(0, 3, 0), z(0, 0, 0.5);
    EXPECT_DOUBLE_EQ(corner_scaled_jacobian(o, x, y, z), 1.0);
    EXPECT_DOUBLE_EQ(corner_scaled_jacobian(o, y, x, z), -1.0);
    // 45° between e1 and e2: sin 45°.
    EXPECT_NEAR(corner_scaled_jacobian(o, x, Vec3(1, 1, 0), z), kHalfSqrt2, 1e-15);
    // A collapsed edge counts as degenerate, not as NaN.
    EXPECT_EQ(corner_scaled_jacobian(o, o, y, z), 0.0);
}

TEST(TetScaledJacobian, CornerTetHasOneAtTheRightAngleAndHalfElsewhere) {
    const std::vector<Vec3> p{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    EXPECT_DOUBLE_EQ(corner_scaled_jacobian(p[0], p[1], p[2], p[3]), 1.0);
    // At (1,0,0): det = 1, edge lengths √2 · 1 · √2.
    EXPECT_NEAR(tet_min_scaled_jacobian(p, {0, 1, 2, 3}), 0.5, 1e-15);
    // Every corner of a positive tet is positive, whichever node comes first.
    EXPECT_NEAR(tet_min_scaled_jacobian(p, {1, 2, 0, 3}), 0.5, 1e-15);
    EXPECT_NEAR(tet_min_scaled_jacobian(moved(p), {0, 1, 2, 3}), 0.5, 1e-12);
}

TEST(TetScaledJacobian, RegularTetIsHalfSqrt2AndFlippedIsNegative) {
    // Regular tetrahedron on alternate corners of the unit cube, positively ordered.
    const std::vector<Vec3> p{{0, 0, 0}, {1, 0, 1}, {1, 1, 0}, {0, 1, 1}};
    EXPECT_NEAR(tet_min_scaled_jacobian(p, {0, 1, 2, 3}), kHalfSqrt2, 1e-15);
    EXPECT_NEAR(tet_min_scaled_jacobian(p, {0, 2, 1, 3}), -kHalfSqrt2, 1e-15);  // two nodes swapped
}

TEST(HexScaledJacobian, UnitAndStretchedHexAreOne) {
    const auto p = unit_cube();
    EXPECT_DOUBLE_EQ(hex_min_scaled_jacobian(p, {0, 1, 2, 3, 4, 5, 6, 7}), 1.0);
    std::vector<Vec3> box = p;
    for (Vec3& x : box) x = x.cwiseProduct(Vec3(2.0, 0.01, 7.0));  // aspect ratio does not count
    EXPECT_DOUBLE_EQ(hex_min_scaled_jacobian(box, {0, 1, 2, 3, 4, 5, 6, 7}), 1.0);
    EXPECT_NEAR(hex_min_scaled_jacobian(moved(p), {0, 1, 2, 3, 4, 5, 6, 7}), 1.0, 1e-12);
    // The same cube started from another bottom corner is still the same cube.
    EXPECT_DOUBLE_EQ(hex_min_scaled_jacobian(p, {1, 2, 3, 0, 5, 6, 7, 4}), 1.0);
}

TEST(HexScaledJacobian, ShearedHexIsCosineOfTheShear) {
    auto p = unit_cube();
    const double s = 0.75;
    for (int i = 4; i < 8; ++i) p[i].x() += s;  // top shifted along x
    EXPECT_NEAR(hex_min_scaled_jacobian(p, {0, 1, 2, 3, 4, 5, 6, 7}), 1.0 / std::sqrt(1.0 + s * s), 1e-15);
}

TEST(HexScaledJacobian, FlippedHexIsNegative) {
    const auto p = unit_cube();
    EXPECT_LT(hex_min_scaled_jacobian(p, {1, 0, 2, 3, 4, 5, 6, 7}), 0.0);          // two nodes swapped
    EXPECT_DOUBLE_EQ(hex_min_scaled_jacobian(p, {4, 5, 6, 7, 0, 1, 2, 3}), -1.0);  // mirrored
    EXPECT_DOUBLE_EQ(hex_min_scaled_jacobian(p, {0, 3, 2, 1, 4, 7, 6, 5}), -1.0);  // mirrored
}

TEST(PrismScaledJacobian, RightPrismIsOneAtTheRightAngleAndEquilateralIsHalfSqrt3) {
    const std::vector<Vec3> p{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 2}, {1, 0, 2}, {0, 1, 2}};
    EXPECT_DOUBLE_EQ(corner_scaled_jacobian(p[0], p[1], p[2], p[3]), 1.0);
    EXPECT_DOUBLE_EQ(corner_scaled_jacobian(p[3], p[5], p[4], p[0]), 1.0);
    // 45° corners at nodes 1, 2, 4, 5.
    EXPECT_NEAR(prism_min_scaled_jacobian(p, {0, 1, 2, 3, 4, 5}), kHalfSqrt2, 1e-15);

    const std::vector<Vec3> q{{0, 0, 0},   {1, 0, 0},   {0.5, kHalfSqrt3, 0},
                              {0, 0, 0.3}, {1, 0, 0.3}, {0.5, kHalfSqrt3, 0.3}};
    EXPECT_NEAR(prism_min_scaled_jacobian(q, {0, 1, 2, 3, 4, 5}), kHalfSqrt3, 1e-15);
    EXPECT_NEAR(prism_min_scaled_jacobian(moved(q), {0, 1, 2, 3, 4, 5}), kHalfSqrt3, 1e-12);
}

TEST(PrismScaledJacobian, FlippedPrismIsNegative) {
    const std::vector<Vec3> p{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {0, 1, 1}};
    EXPECT_LT(prism_min_scaled_jacobian(p, {0, 2, 1, 3, 5, 4}), 0.0);  // mirrored
    EXPECT_LT(prism_min_scaled_jacobian(p, {3, 4, 5, 0, 1, 2}), 0.0);  // top and bottom swapped
    EXPECT_LT(prism_min_scaled_jacobian(p, {1, 0, 2, 3, 4, 5}), 0.0);  // two nodes swapped
}

TEST(PyramidScaledJacobian, IdealPyramidIsHalfSqrt2AtEveryCorner) {
    // Unit square base, all edges 1 (apex height 1/√2): every corner, apex included, is √2/2.
    const std::vector<Vec3> p{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 0.5, kHalfSqrt2}};
    EXPECT_NEAR(pyramid_min_scaled_jacobian(p, {0, 1, 2, 3, 4}), kHalfSqrt2, 1e-15);
    EXPECT_NEAR(pyramid_min_scaled_jacobian(moved(p), {0, 1, 2, 3, 4}), kHalfSqrt2, 1e-12);
    // Apex above node 0: that corner is right-angled.
    const std::vector<Vec3> q{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}};
    EXPECT_DOUBLE_EQ(corner_scaled_jacobian(q[0], q[1], q[3], q[4]), 1.0);
    EXPECT_GT(pyramid_min_scaled_jacobian(q, {0, 1, 2, 3, 4}), 0.0);
}

TEST(PyramidScaledJacobian, FlippedPyramidIsNegative) {
    const std::vector<Vec3> p{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 0.5, 0.5}};
    EXPECT_GT(pyramid_min_scaled_jacobian(p, {0, 1, 2, 3, 4}), 0.0);
    EXPECT_LT(pyramid_min_scaled_jacobian(p, {0, 3, 2, 1, 4}), 0.0);  // base reversed
    EXPECT_LT(pyramid_min_scaled_jacobian(p, {1, 0, 2, 3, 4}), 0.0);  // two nodes swapped
    // Apex in the base plane: degenerate.
    std::vector<Vec3> flat = p;
    flat[4].z() = 0.0;
    EXPECT_LE(pyramid_min_scaled_jacobian(flat, {0, 1, 2, 3, 4}), 0.0);
}

TEST(ScaledJacobian, ACornerThatCannotBeComputedMakesTheCellNaN) {
    // A prism whose top triangle has edges of 1e160: at its top corners |e1| |e2| |e3| overflows
    // and the corner's value is NaN, while the bottom corners are fine. The cell is then NaN
    // (never better than its worst corner), not the minimum of the corners that could be
    // computed, so every caller sees that its quality is unknown.
    const double h = 1e160;
    const std::vector<Vec3> p{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, h}, {h, 0, h}, {0, h, h}};
    EXPECT_TRUE(std::isnan(corner_scaled_jacobian(p[3], p[5], p[4], p[0])));
    EXPECT_TRUE(std::isnan(prism_min_scaled_jacobian(p, {0, 1, 2, 3, 4, 5})));
    EXPECT_TRUE(std::isnan(min_scaled_jacobian(p, std::array<Index, 6>{0, 1, 2, 3, 4, 5}.data(), CellType::Prism)));
}

TEST(ScaledJacobian, CellGivenByItsCornersMeasuresAsByIds) {
    // A sheared hexahedron, its corners picked out of a larger array in an order of their own.
    const std::vector<Vec3> p{{9, 9, 9}, {0, 0, 0},   {1, 0, 0},   {1.2, 1, 0}, {0.1, 1, 0},
                              {0, 0, 1}, {1, 0.1, 1}, {1, 1, 1.3}, {0, 1, 1}};
    const std::array<Index, 8> ids{1, 2, 3, 4, 5, 6, 7, 8};
    std::array<Vec3, 8> corners;
    for (std::size_t i = 0; i < 8; ++i) corners[i] = p[static_cast<std::size_t>(ids[i])];
    for (const CellType t : kCellTypes)
        EXPECT_EQ(min_scaled_jacobian(corners.data(), t), min_scaled_jacobian(p, ids.data(), t)) << to_string(t);
    EXPECT_LT(min_scaled_jacobian(corners.data(), CellType::Hex), 1.0);
    EXPECT_GT(min_scaled_jacobian(corners.data(), CellType::Hex), 0.0);
}
