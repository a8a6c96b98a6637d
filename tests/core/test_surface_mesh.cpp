// The surface-mesh container and single-face geometry.

#include <strata/core/face_geometry.h>
#include <strata/core/surface_mesh.h>

#include <gtest/gtest.h>

#include "test_support.h"

namespace strata {
namespace {

TEST(SurfaceMesh, MixedCsrAndCounts) {
    SurfaceMesh m;
    m.patches = {{"a", PatchKind::Wall}, {"b", PatchKind::Symmetry}};
    m.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0), Vec3(2, 0, 0)};
    m.add_face({0, 1, 2, 3}, 0);
    m.add_face({1, 4, 2}, 1);
    EXPECT_EQ(m.num_faces(), 2);
    EXPECT_EQ(m.num_quads(), 1);
    EXPECT_EQ(m.num_triangles(), 1);
    EXPECT_EQ(m.face_size(0), 4);
    EXPECT_EQ(m.face_node(1, 1), 4);
    EXPECT_EQ(m.face_offsets, (std::vector<Index>{0, 4, 7}));
    EXPECT_EQ(find_patch(m, "b"), 1);
    EXPECT_EQ(find_patch(m, "c"), kNone);
}

TEST(FaceGeometry, AreaVectorOfTriangleAndNonPlanarQuad) {
    SurfaceMesh m;
    m.points = {Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(2, 3, 0), Vec3(0, 3, 1)};
    m.add_face({0, 1, 2}, 0);
    m.add_face({0, 1, 2, 3}, 0);
    EXPECT_TRUE(face_area_vector(m, 0).isApprox(Vec3(0, 0, 3)));
    // Vector area of a closed loop = ½ d1 × d2 (exact, planar or not).
    const Vec3 expected = 0.5 * Vec3(2, 3, 0).cross(Vec3(-2, 3, 1));
    EXPECT_TRUE(face_area_vector(m, 1).isApprox(expected));
    EXPECT_TRUE(face_centroid(m, m.points, 1).isApprox(Vec3(1, 1.5, 0.25)));
}

TEST(FaceGeometry, QuadShorterDiagonal) {
    SurfaceMesh m;
    m.points = {{0, 0, 0}, {3, 0, 0}, {3, 1, 0}, {0, 1, 0}, {2, 0, 0}, {0, 3, 0}};
    m.add_face({0, 1, 2, 3}, 0);  // a rectangle: both diagonals equal, corner 0
    m.add_face({0, 4, 2, 5}, 0);  // 0–2 is sqrt(10), 4–5 sqrt(13): corner 0
    m.add_face({4, 2, 5, 0}, 0);  // the same quad from corner 4: 4–5 is its diagonal from corner 0
    EXPECT_EQ(quad_shorter_diagonal(m, 0), 0);
    EXPECT_EQ(quad_shorter_diagonal(m, 1), 0);
    EXPECT_EQ(quad_shorter_diagonal(m, 2), 1);
}

TEST(FaceGeometry, BoundingBox) {
    const SurfaceMesh g = test::quad_grid(3, 2, 0.5);
    const BoundingBox b = bounding_box(g.points);
    EXPECT_TRUE(b.min.isApprox(Vec3(0, 0, 0)));
    EXPECT_TRUE(b.max.isApprox(Vec3(1.5, 1.0, 0)));
    EXPECT_DOUBLE_EQ(bounding_box({}).diagonal(), 0.0);
}

TEST(FaceGeometry, MedianEdgeLength) {
    // Six quads of 0.5 (24 edges) and one long sliver beside them: the median ignores the sliver.
    SurfaceMesh g = test::quad_grid(3, 2, 0.5);
    EXPECT_DOUBLE_EQ(median_edge_length(g), 0.5);
    const Index far = static_cast<Index>(g.points.size());
    g.points.emplace_back(100.0, 0.0, 0.0);
    g.add_face({0, 1, far}, 0);
    EXPECT_DOUBLE_EQ(median_edge_length(g), 0.5);
    EXPECT_DOUBLE_EQ(median_edge_length(SurfaceMesh{}), 0.0);
}

TEST(FaceGeometry, WallsLengthIsTheWallsLargestExtent) {
    // A 1.5 x 1 grid of walls and a farfield face far off: only the walls count.
    SurfaceMesh g = test::quad_grid(3, 2, 0.5);
    EXPECT_DOUBLE_EQ(walls_length(g), 1.5);
    g.patches.push_back({"far", PatchKind::Farfield});
    const Index far = static_cast<Index>(g.points.size());
    g.points.insert(g.points.end(), {Vec3(0, 0, 40), Vec3(1, 0, 40), Vec3(0, 1, 40)});
    g.add_face({far, far + 1, far + 2}, 1);
    EXPECT_DOUBLE_EQ(walls_length(g), 1.5);
    g.patches[0].kind = PatchKind::Symmetry;  // no wall left
    EXPECT_DOUBLE_EQ(walls_length(g), 0.0);
    EXPECT_DOUBLE_EQ(walls_length(SurfaceMesh{}), 0.0);
}

}  // namespace
}  // namespace strata
