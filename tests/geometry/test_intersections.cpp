// Self-intersections with exact predicates (geometry/intersections.h): each way two
// triangles can share nodes, crossing and touching, and whole surfaces.

#include <strata/geometry/intersections.h>
#include <strata/geometry/primitives.h>

#include <gtest/gtest.h>

#include "test_support.h"

namespace strata {
namespace {

/// One patch "p", the given points, triangles.
SurfaceMesh soup(std::vector<Vec3> points, const std::vector<std::array<Index, 3>>& tris) {
    SurfaceMesh m;
    m.patches.push_back({"p", PatchKind::Wall});
    m.points = std::move(points);
    for (const auto& t : tris) m.add_face({t[0], t[1], t[2]}, 0);
    return m;
}

/// Two spheres of radius 1, the second at \p dx along x; patches "a" and "b".
SurfaceMesh two_spheres(double dx) {
    return test::merged(icosphere(Vec3::Zero(), 1.0, 2, {"a", PatchKind::Wall}),
                        icosphere(Vec3(dx, 0, 0), 1.0, 2, {"b", PatchKind::Wall}));
}

TEST(SelfIntersections, ClosedSurfaceHasNone) {
    EXPECT_TRUE(self_intersections(icosphere(Vec3::Zero(), 1.0, 3, {"s", PatchKind::Wall})).empty());
    EXPECT_TRUE(self_intersections(two_spheres(2.5)).empty());
}

TEST(SelfIntersections, OverlappingSpheresPairOneFaceOfEach) {
    const SurfaceMesh m = two_spheres(1.5);
    const std::vector<FacePair> pairs = self_intersections(m);
    ASSERT_FALSE(pairs.empty());
    const Index half = m.num_faces() / 2;
    for (const FacePair& p : pairs) {
        EXPECT_LT(p.a, half);
        EXPECT_GE(p.b, half);
    }
    EXPECT_TRUE(std::is_sorted(pairs.begin(), pairs.end(), [](const FacePair& x, const FacePair& y) {
        return x.a != y.a ? x.a < y.a : x.b < y.b;
    }));
    EXPECT_EQ(self_intersections(m, 3).size(), 3u);
    EXPECT_EQ(self_intersections(m, 3), std::vector<FacePair>(pairs.begin(), pairs.begin() + 3));
}

TEST(SelfIntersections, NoSharedNode) {
    // A vertical triangle whose corner touches the horizontal one inside: touching counts.
    const std::vector<Vec3> x = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0.5, 0.5, 0}, {0.5, 0.5, 1}, {1.5, 0.5, 1}};
    EXPECT_EQ(self_intersections(soup(x, {{0, 1, 2}, {3, 4, 5}})), (std::vector<FacePair>{{0, 1}}));
    // A hair above: apart.
    std::vector<Vec3> y = x;
    y[3].z() = 1e-12;
    EXPECT_TRUE(self_intersections(soup(y, {{0, 1, 2}, {3, 4, 5}})).empty());
}

TEST(SelfIntersections, SharedEdge) {
    // Folded at an edge (a dihedral angle): fine; folded flat onto itself: intersecting; flat
    // and continuing on the other side: fine.
    const Vec3 a(0, 0, 0), b(1, 0, 0), c(0.5, 1, 0);
    EXPECT_TRUE(self_intersections(soup({a, b, c, {0.5, -1, 0.5}}, {{0, 1, 2}, {1, 0, 3}})).empty());
    EXPECT_EQ(self_intersections(soup({a, b, c, {0.3, 0.5, 0}}, {{0, 1, 2}, {1, 0, 3}})).size(), 1u);
    EXPECT_TRUE(self_intersections(soup({a, b, c, {0.5, -1, 0}}, {{0, 1, 2}, {1, 0, 3}})).empty());
}

TEST(SelfIntersections, SharedNode) {
    const Vec3 o(0, 0, 0), a(2, 0, 0), b(0, 2, 0);
    // Apart except at the node.
    EXPECT_TRUE(self_intersections(soup({o, a, b, {-1, 0, 1}, {-1, -1, 1}}, {{0, 1, 2}, {0, 3, 4}})).empty());
    // The second pierces the first away from the node.
    EXPECT_EQ(self_intersections(soup({o, a, b, {1, 0.5, -1}, {0.5, 1, 1}}, {{0, 1, 2}, {0, 3, 4}})).size(), 1u);
    // The second stands on the first's edge o-a (in the plane y = 0, through it): they share
    // the segment from o to (1, 0, 0) although neither opposite edge crosses the interior.
    EXPECT_EQ(self_intersections(soup({o, a, b, {1, 0, 1}, {1, 0, -1}}, {{0, 1, 2}, {0, 3, 4}})).size(), 1u);
    // Coplanar, the second inside the first's corner.
    EXPECT_EQ(self_intersections(soup({o, a, b, {0.5, 0.2, 0}, {0.2, 0.5, 0}}, {{0, 1, 2}, {0, 3, 4}})).size(), 1u);
}

TEST(SelfIntersections, RepeatedFaceAndQuads) {
    const std::vector<Vec3> x = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    EXPECT_EQ(self_intersections(soup(x, {{0, 1, 2}, {0, 2, 1}})).size(), 1u);
    // A quad crossed by a triangle through its second half (a c d): found, named by the quad.
    SurfaceMesh m =
        soup({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.2, 0.6, -1}, {0.3, 0.7, 1}, {0.1, 0.9, 1}}, {});
    m.add_face({0, 1, 2, 3}, 0);
    m.add_face({4, 5, 6}, 0);
    EXPECT_EQ(self_intersections(m), (std::vector<FacePair>{{0, 1}}));
    // A degenerate triangle (collinear corners) is skipped, not a crash.
    EXPECT_TRUE(self_intersections(soup({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 1}}, {{0, 1, 2}, {0, 1, 3}})).empty());
}

TEST(SelfIntersections, DescribeFace) {
    const SurfaceMesh m = soup({{0, 0, 0}, {3, 0, 0}, {0, 3, 0}}, {{0, 1, 2}});
    EXPECT_EQ(describe_face(m, 0), "face 0 (patch 'p') at (1, 1, 0)");
}

}  // namespace
}  // namespace strata
