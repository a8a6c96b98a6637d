// Faces where closed bodies touch back to back (geometry/touching.h): two boxes sharing a
// side, each closed by its own triangulation of it, become one closed box once those faces
// go (remove_faces); bodies apart, overlapping or merely duplicated keep every face.

#include <strata/core/error.h>
#include <strata/geometry/check.h>
#include <strata/geometry/fuse.h>
#include <strata/geometry/topology.h>
#include <strata/geometry/touching.h>

#include <gtest/gtest.h>

#include "test_support.h"

namespace strata {
namespace {

/// The box [x0, x0 + 1] × [0, 1] × [0, 1] as 12 triangles, normals out; its sides x = x0 and
/// x = x0 + 1 split along the diagonal (y, z) = (0, 0)-(1, 1) if \p diagonal is 0, along
/// (0, 1)-(1, 0) if 1.
SurfaceMesh box(double x0, int diagonal, const std::string& name) {
    SurfaceMesh m;
    m.patches.push_back({name, PatchKind::Wall});
    for (int k = 0; k < 8; ++k) m.points.emplace_back(x0 + (k & 1), (k >> 1) & 1, (k >> 2) & 1);
    auto quad = [&](Index a, Index b, Index c, Index d, bool flip) {
        if (!flip) {
            m.add_face({a, b, c}, 0);
            m.add_face({a, c, d}, 0);
        } else {
            m.add_face({b, c, d}, 0);
            m.add_face({b, d, a}, 0);
        }
    };
    quad(0, 2, 3, 1, false);          // z = 0
    quad(4, 5, 7, 6, false);          // z = 1
    quad(0, 1, 5, 4, false);          // y = 0
    quad(2, 6, 7, 3, false);          // y = 1
    quad(0, 4, 6, 2, diagonal == 1);  // x = x0
    quad(1, 3, 7, 5, diagonal == 1);  // x = x0 + 1
    return m;
}

TEST(Touching, TwoBoxesSideBySideLoseTheSideTheyShare) {
    // [-1, 0] and [0, 1]: the left one's side x = 0 (two triangles along one diagonal) lies on
    // the right one's side x = 0 (along the other diagonal, its normal the other way).
    const SurfaceMesh two = merge_coincident_nodes(test::merged(box(-1.0, 0, "left"), box(0.0, 1, "right")));
    EXPECT_FALSE(test::closed_manifold(two));
    // The left box's side x = 0 is its faces 10 and 11; the right one's, its faces 8 and 9
    // (20 and 21 of the two).
    const std::vector<Index> t = touching_faces(two);
    EXPECT_EQ(t, (std::vector<Index>{10, 11, 20, 21}));
    std::vector<char> drop(static_cast<std::size_t>(two.num_faces()), 0);
    for (const Index f : t) drop[static_cast<std::size_t>(f)] = 1;
    const SurfaceMesh one = remove_faces(two, drop);
    EXPECT_EQ(one.num_faces(), 20);
    EXPECT_EQ(one.num_points(), 12);
    EXPECT_TRUE(test::closed_manifold(one));
    EXPECT_NEAR(test::enclosed_volume(one), 2.0, 1e-12);
    EXPECT_NO_THROW(check_surface(one, "two boxes"));
}

TEST(Touching, BoxesApartOverlappingOrDuplicatedKeepEveryFace) {
    // A gap of 1e-3 (far beyond the tolerance of 1e-6 of the diagonal).
    EXPECT_TRUE(touching_faces(test::merged(box(-1.001, 0, "l"), box(0.0, 1, "r"))).empty());
    // Overlapping by half: no face lies on another.
    EXPECT_TRUE(touching_faces(test::merged(box(-0.5, 0, "l"), box(0.0, 1, "r"))).empty());
    // The same box twice: every face lies on its copy, facing the same way: not back to back.
    EXPECT_TRUE(touching_faces(test::merged(box(0.0, 0, "a"), box(0.0, 0, "b"))).empty());
    // Just within the tolerance, the rims welded at it: still touching. Not welded, taking the
    // sides away would leave both rims open: they stay.
    const SurfaceMesh near = test::merged(box(-1.0 - 1e-7, 0, "l"), box(0.0, 1, "r"));
    EXPECT_EQ(touching_faces(merge_coincident_nodes(near, 1e-6)).size(), 4u);
    EXPECT_TRUE(touching_faces(near).empty());
}

TEST(Touching, ABodyOnPartOfAnothersFaceIsLeftForTheUnion) {
    // A half-size box standing on the middle of the unit box's side x = 1 (a car's cabin on its
    // body): its side x = 1 lies on the big one's, facing it, but covers only part of it. Taking
    // the small side away would leave its rim open, and the big side cannot go: neither goes
    // (fuse.h's union joins them there), where they used to both go and open the surface.
    SurfaceMesh small = box(0.0, 0, "cabin");
    for (Vec3& p : small.points) p = Vec3(1.0 + 0.5 * p.x(), 0.25 + 0.5 * p.y(), 0.25 + 0.5 * p.z());
    const SurfaceMesh two = test::merged(box(0.0, 1, "body"), small);
    EXPECT_TRUE(touching_faces(two).empty());
    FuseReport rep;
    const SurfaceMesh u = fuse_components(orient_surface(two), &rep);
    EXPECT_EQ(rep.fused, 2);
    EXPECT_TRUE(test::closed_manifold(u));
    EXPECT_NEAR(test::enclosed_volume(u), 1.125, 1e-12);
    EXPECT_NO_THROW(check_surface(u, "box and cabin"));
    // The same pair, the small box as large as the big one's side: back to back over all of
    // it, both sides go as before.
    EXPECT_EQ(touching_faces(merge_coincident_nodes(test::merged(box(0.0, 1, "body"), box(1.0, 0, "r")))).size(), 4u);
}

TEST(Touching, RemoveFacesKeepsTheRestInOrderAndChecksItsFlags) {
    const SurfaceMesh b = box(0.0, 0, "b");
    std::vector<char> drop(12, 0);
    drop[0] = drop[1] = 1;  // the bottom: nodes 0..3 stay (the sides use them)
    const SurfaceMesh open = remove_faces(b, drop);
    EXPECT_EQ(open.num_faces(), 10);
    EXPECT_EQ(open.num_points(), 8);
    EXPECT_EQ(open.face_node(0, 0), b.face_node(2, 0));
    drop.assign(12, 1);
    drop[2] = 0;  // one face left: its three nodes
    EXPECT_EQ(remove_faces(b, drop).num_points(), 3);
    EXPECT_THROW(remove_faces(b, std::vector<char>(3, 0)), InputError);
}

}  // namespace
}  // namespace strata
