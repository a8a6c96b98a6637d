// The tetrahedra's size field and switches (hybrid/src/tetgen_sizing.h): h(x) = min(h_wall +
// growth · d, h_far) with the nearest wall node found by a k-d tree, checked against a brute
// force search, including exact ties.

#include "tetgen_sizing.h"

#include <strata/core/face_geometry.h>
#include <strata/geometry/primitives.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <random>

namespace strata {
namespace {

/// h(x) by brute force: the nearest wall node (of equally near ones the smallest size, then
/// the lowest number), capped at \p cap.
double brute_force_h(const SurfaceMesh& b, const tetgen::SizeField& h, double growth, double cap, const Vec3& x) {
    Index best = kNone;
    double best_d2 = std::numeric_limits<double>::infinity();
    for (Index i = 0; i < b.num_points(); ++i) {
        const double d2 = (x - b.points[i]).squaredNorm();
        if (d2 < best_d2 || (d2 == best_d2 && h.boundary_size(i) < h.boundary_size(best))) best_d2 = d2, best = i;
    }
    return std::min(h.boundary_size(best) + growth * (x - b.points[best]).norm(), cap);
}

/// A unit wall sphere (patch 0) inside a farfield sphere of radius 10 (patch 1), given in \p far.
SurfaceMesh wall_in_far_sphere(SurfaceMesh& far) {
    SurfaceMesh b = icosphere(Vec3::Zero(), 1.0, 2, {"wall", PatchKind::Wall});
    far = icosphere(Vec3::Zero(), 10.0, 1, {"far", PatchKind::Farfield});
    const Index n = b.num_points();
    b.patches.push_back(far.patches[0]);
    b.points.insert(b.points.end(), far.points.begin(), far.points.end());
    for (Index f = 0; f < far.num_faces(); ++f)
        b.add_face({far.face_node(f, 0) + n, far.face_node(f, 1) + n, far.face_node(f, 2) + n}, 1);
    return b;
}

TEST(TetgenSizing, NearestWallNodeAsByBruteForce) {
    // An ellipsoid (node sizes differ from node to node), no farfield: capped at the diagonal.
    SurfaceMesh b = icosphere(Vec3::Zero(), 1.0, 3, {"wall", PatchKind::Wall});
    for (Vec3& p : b.points) p = p.cwiseProduct(Vec3(2.0, 1.0, 0.5));
    const double growth = 0.3, cap = bounding_box(b.points).diagonal();
    const tetgen::SizeField h(b, growth, 0.0);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-3.0, 3.0);
    for (int k = 0; k < 3000; ++k) {
        const Vec3 x(u(rng), u(rng), u(rng));
        ASSERT_EQ(h(x), brute_force_h(b, h, growth, cap, x)) << k;
    }
    // On the axes (symmetric: many exact ties) too.
    for (int k = -30; k <= 30; ++k)
        for (int axis = 0; axis < 3; ++axis) {
            Vec3 x = Vec3::Zero();
            x[axis] = 0.1 * k;
            ASSERT_EQ(h(x), brute_force_h(b, h, growth, cap, x)) << axis << " " << k;
        }
}

TEST(TetgenSizing, ExactTieTakesTheSmallerSize) {
    // Two triangles mirrored about x = 0, the right one twice the size and numbered first: the
    // origin is exactly as far from (1,0,0) as from (-1,0,0); h there is the smaller size + d.
    SurfaceMesh b;
    b.patches.push_back({"wall", PatchKind::Wall});
    b.points = {{1, 0, 0}, {3, 2, 0}, {3, -2, 0}, {-1, 0, 0}, {-2, 1, 0}, {-2, -1, 0}};
    b.add_face({0, 1, 2}, 0);
    b.add_face({3, 5, 4}, 0);
    const tetgen::SizeField h(b, 0.5, 0.0);
    ASSERT_LT(h.boundary_size(3), h.boundary_size(0));
    EXPECT_DOUBLE_EQ(h(Vec3::Zero()), h.boundary_size(3) + 0.5 * 1.0);
    EXPECT_DOUBLE_EQ(h(Vec3(0, 0, 7)), h.boundary_size(3) + 0.5 * std::sqrt(50.0));
}

TEST(TetgenSizing, FarfieldCapsAndVolumeBound) {
    SurfaceMesh far;
    SurfaceMesh b = wall_in_far_sphere(far);
    const Index n = b.num_points() - far.num_points();
    const tetgen::SizeField h(b, 1.0, 0.0);
    // The far sphere's mean edge caps h (8.5 from the wall); near the wall h is the wall's edge.
    double far_edge = 0.0;
    for (Index f = 0; f < far.num_faces(); ++f)
        for (int i = 0; i < 3; ++i)
            far_edge += (far.points[far.face_node(f, i)] - far.points[far.face_node(f, (i + 1) % 3)]).norm();
    far_edge /= 3.0 * static_cast<double>(far.num_faces());
    EXPECT_NEAR(h(Vec3(9.5, 0, 0)), far_edge, 1e-12 * far_edge);
    EXPECT_LT(h(Vec3(1.01, 0, 0)), 2.0 * h.boundary_size(0));
    // max_volume caps h at the regular tetrahedron's edge of that volume.
    const double v = 1e-3, edge = std::cbrt(6.0 * std::sqrt(2.0) * v);
    const tetgen::SizeField hv(b, 0.3, v);
    EXPECT_DOUBLE_EQ(hv(Vec3(5, 0, 0)), edge);
    EXPECT_LE(hv.boundary_size(n), edge * (1 + 1e-12));
}

TEST(TetgenSizing, BackgroundHullLiesOutsideEveryPoint) {
    // Internal flow: the walls are the outer boundary, no farfield. The background's boundary is
    // the walls unchanged and, after their nodes, 8 loose corners of a box outside them.
    const SurfaceMesh walls = icosphere(Vec3::Zero(), 1.0, 2, {"duct", PatchKind::Wall});
    const SurfaceMesh bg = tetgen::background_boundary(walls);
    ASSERT_EQ(bg.num_points(), walls.num_points() + 8);
    EXPECT_EQ(bg.face_nodes, walls.face_nodes);
    EXPECT_EQ(bg.face_offsets, walls.face_offsets);
    for (Index i = 0; i < walls.num_points(); ++i) EXPECT_EQ(bg.points[i], walls.points[i]);
    const BoundingBox box = bounding_box(walls.points);
    for (Index k = walls.num_points(); k < bg.num_points(); ++k)
        for (int a = 0; a < 3; ++a)
            EXPECT_TRUE(bg.points[k][a] < box.min[a] || bg.points[k][a] > box.max[a])
                << "corner " << k << " axis " << a;

    // A separate farfield is pushed out by 1 % instead; no point is added.
    SurfaceMesh far;
    SurfaceMesh b = wall_in_far_sphere(far);
    const Index n = b.num_points() - far.num_points();
    const SurfaceMesh pushed = tetgen::background_boundary(b);
    ASSERT_EQ(pushed.num_points(), b.num_points());
    for (Index i = n; i < b.num_points(); ++i) EXPECT_NEAR(pushed.points[i].norm(), 10.1, 1e-9);

    // A farfield sharing nodes with another patch (a half model's symmetry plane): the corners.
    b.patches.push_back({"symmetry", PatchKind::Symmetry});
    b.face_patch[static_cast<std::size_t>(b.num_faces() - 1)] = 2;
    EXPECT_EQ(tetgen::background_boundary(b).num_points(), b.num_points() + 8);
}

TEST(TetgenSizing, Switches) {
    TetFillParams p;
    p.min_dihedral = 12.0;
    p.max_volume = 0.5;
    EXPECT_EQ(tetgen::switches(p, true, false), "pYzQq1.5/12a0.5mo/150");
    EXPECT_EQ(tetgen::switches(p, false, false), "pYzQq1.5/12a0.5o/150");
    p.max_dihedral = 0.0;
    EXPECT_EQ(tetgen::switches(p, true, false), "pYzQq1.5/12a0.5m");
    EXPECT_EQ(tetgen::switches(p, true, true), "pYzQcq2");
    EXPECT_EQ(tetgen::switches(p, true, true, 2.5e-12), "pYzQT2.5e-12cq2");
    EXPECT_EQ(tetgen::switches(p, true, false, 0.0), "pYzQq1.5/12a0.5m");  // 0: TetGen's default
    p.refine = false;
    EXPECT_EQ(tetgen::switches(p, true, false), "pYzQ");
}

TEST(TetgenSizing, ToleranceKeepsPointsCloserThanTetGensOwn) {
    // The unit cube's corners: nothing near, TetGen's default.
    std::vector<Vec3> pts;
    for (int i = 0; i < 8; ++i) pts.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
    EXPECT_EQ(tetgen::tolerance_keeping_points(pts), 0.0);
    // Two points 1e-9 apart (TetGen's default merges points within 1e-8 × the diagonal, √3):
    // a hundredth of their distance over the diagonal.
    pts.emplace_back(0.5, 0.5, 0.0);
    pts.emplace_back(0.5, 0.5 + 1e-9, 0.0);
    EXPECT_NEAR(tetgen::tolerance_keeping_points(pts), 0.01 * 1e-9 / std::sqrt(3.0), 1e-6 * 1e-11);
    // Ten times TetGen's own tolerance is the bound: 1e-6 apart is far enough.
    pts.back() = Vec3(0.5, 0.5 + 1e-6, 0.0);
    EXPECT_EQ(tetgen::tolerance_keeping_points(pts), 0.0);
    // Equal points are not asked about (no tolerance keeps both: the caller's error).
    pts.back() = pts[pts.size() - 2];
    EXPECT_EQ(tetgen::tolerance_keeping_points(pts), 0.0);
}

}  // namespace
}  // namespace strata
