// The union of overlapping closed components (geometry/fuse.h): two spheres that overlap
// become one closed surface whose faces keep the patch of the sphere they lie on; components
// that do not overlap, and non-wall ones, are left as they are.

#include <strata/core/error.h>
#include <strata/core/face_geometry.h>
#include <strata/geometry/check.h>
#include <strata/geometry/fuse.h>
#include <strata/geometry/intersections.h>
#include <strata/geometry/primitives.h>
#include <strata/geometry/topology.h>

#include <gtest/gtest.h>

#include "test_support.h"

#include <array>
#include <cmath>
#include <numbers>

namespace strata {
namespace {

TEST(Fuse, TwoOverlappingSpheresBecomeOneKeepingTheirPatches) {
    const Vec3 a(0, 0, 0), b(1.2, 0.1, 0);
    const SurfaceMesh two = orient_surface(
        test::merged(icosphere(a, 1.0, 3, {"a", PatchKind::Wall}), icosphere(b, 0.8, 3, {"b", PatchKind::Wall})));
    ASSERT_FALSE(self_intersections(two, 1).empty());
    FuseReport rep;
    const SurfaceMesh u = orient_surface(fuse_components(two, &rep));
    EXPECT_EQ(rep.components, 2);
    EXPECT_EQ(rep.fused, 2);
    Index nc = 0;
    face_components(u, &nc);
    EXPECT_EQ(nc, 1);
    EXPECT_EQ(boundary_loops(u).rows(), 0);
    EXPECT_TRUE(self_intersections(u, 1).empty());
    // Each face lies on the sphere of its patch, outside the other.
    for (Index f = 0; f < u.num_faces(); ++f) {
        const Vec3 c = face_centroid(u, u.points, f);
        const bool on_a = u.face_patch[f] == 0;
        EXPECT_NEAR((c - (on_a ? a : b)).norm(), on_a ? 1.0 : 0.8, 0.02) << f;
        EXPECT_GT((c - (on_a ? b : a)).norm(), on_a ? 0.8 - 0.02 : 1.0 - 0.02) << f;
    }
    // The union's volume: both spheres less their lens (exact for spheres, faceting aside).
    const double d = (b - a).norm(), r1 = 1.0, r2 = 0.8;
    const double lens = std::numbers::pi * std::pow(r1 + r2 - d, 2) *
                        (d * d + 2 * d * r2 - 3 * r2 * r2 + 2 * d * r1 + 6 * r1 * r2 - 3 * r1 * r1) / (12 * d);
    const double exact = 4.0 / 3.0 * std::numbers::pi * (r1 * r1 * r1 + r2 * r2 * r2) - lens;
    EXPECT_NEAR(test::enclosed_volume(u), exact, 0.02 * exact);
}

TEST(Fuse, TheUnionIsOrderedByItsGeometryAlone) {
    // CGAL's corefinement orders what it makes in a way that followed heap addresses (the mesh of
    // the five missile parts changed with the length of the output path, the union's geometry
    // the same). So the union is put in an order of its geometry alone: nodes by coordinates,
    // each face from its lowest node, faces by their nodes.
    const SurfaceMesh two = orient_surface(test::merged(icosphere(Vec3(0, 0, 0), 1.0, 2, {"a", PatchKind::Wall}),
                                                        icosphere(Vec3(1.2, 0.1, 0), 0.8, 2, {"b", PatchKind::Wall})));
    const SurfaceMesh u = fuse_components(two);
    auto xyz = [&](Index i) {
        const Vec3& p = u.points[static_cast<std::size_t>(i)];
        return std::array<double, 3>{p.x(), p.y(), p.z()};
    };
    for (Index i = 1; i < u.num_points(); ++i) EXPECT_LT(xyz(i - 1), xyz(i)) << i;
    std::vector<Index> previous;
    for (Index f = 0; f < u.num_faces(); ++f) {
        const std::vector<Index> v(u.face_begin(f), u.face_end(f));
        EXPECT_EQ(std::min_element(v.begin(), v.end()), v.begin()) << f;
        EXPECT_LT(previous, v) << f;
        previous = v;
    }
}

TEST(Fuse, ApartOrNotWallsTheyStayAsTheyAre) {
    // Two spheres apart, and a farfield sphere around them: nothing to union.
    const SurfaceMesh m =
        orient_surface(test::merged(test::merged(icosphere(Vec3::Zero(), 1.0, 2, {"a", PatchKind::Wall}),
                                                 icosphere(Vec3(3, 0, 0), 1.0, 2, {"b", PatchKind::Wall})),
                                    icosphere(Vec3(1.5, 0, 0), 20.0, 2, {"farfield", PatchKind::Farfield})));
    FuseReport rep;
    const SurfaceMesh u = fuse_components(m, &rep);
    EXPECT_EQ(rep.components, 2);
    EXPECT_EQ(rep.fused, 0);
    EXPECT_EQ(u.num_faces(), m.num_faces());
    EXPECT_EQ(u.face_patch, m.face_patch);
}

}  // namespace
}  // namespace strata
