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

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace strata {
namespace {

/// The volume of two spheres of radii \p r1 and \p r2 whose centres are \p d apart (they
/// overlap): both less their lens.
double union_of_spheres_volume(double d, double r1, double r2) {
    const double lens = std::numbers::pi * std::pow(r1 + r2 - d, 2) *
                        (d * d + 2 * d * r2 - 3 * r2 * r2 + 2 * d * r1 + 6 * r1 * r2 - 3 * r1 * r1) / (12 * d);
    return 4.0 / 3.0 * std::numbers::pi * (r1 * r1 * r1 + r2 * r2 * r2) - lens;
}

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
    const double exact = union_of_spheres_volume((b - a).norm(), 1.0, 0.8);
    EXPECT_NEAR(test::enclosed_volume(u), exact, 0.02 * exact);
}

TEST(Fuse, ABodyTurnedInwardIsUnitedAsTheBodyItIs) {
    // orient_surface takes a body whose probe point lies inside another (a wing root inside a
    // fuselage) for a cavity and turns it inward; CGAL's "union" with an inward body is the
    // outside of their intersection, and an airliner STL of 12 parts came out as 30 triangles.
    // Each body is made outward first: the union is that of the two spheres.
    const Vec3 a(0, 0, 0), b(1.2, 0.1, 0);
    SurfaceMesh two =
        test::merged(icosphere(a, 1.0, 3, {"a", PatchKind::Wall}), icosphere(b, 0.8, 3, {"b", PatchKind::Wall}));
    for (Index f = 0; f < two.num_faces(); ++f)
        if (two.face_patch[f] == 1)
            std::reverse(two.face_nodes.begin() + two.face_offsets[f] + 1,
                         two.face_nodes.begin() + two.face_offsets[f + 1]);
    const SurfaceMesh u = orient_surface(fuse_components(two));
    const BoundingBox box = bounding_box(u.points);
    EXPECT_NEAR(box.min.x(), -1.0, 0.02);
    EXPECT_NEAR(box.max.x(), 2.0, 0.02);
    const double exact = union_of_spheres_volume((b - a).norm(), 1.0, 0.8);
    EXPECT_NEAR(test::enclosed_volume(u), exact, 0.02 * exact);
}

TEST(Topology, FlatTrianglesAreFlippedWithTheirNeighbour) {
    // A cap (apex 1e-9 off its longest edge) and the triangle across that edge become two
    // triangles through the apex and the far node, oriented as before; a fair pair stays.
    SurfaceMesh m;
    m.patches = {{"w", PatchKind::Wall}};
    m.points = {Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(1, 1e-9, 0), Vec3(1, -1, 0)};
    m.add_face({0, 1, 2}, 0);
    m.add_face({1, 0, 3}, 0);
    Index flipped = 0;
    const SurfaceMesh f = flip_flat_triangles(m, 1e-6, &flipped);
    EXPECT_EQ(flipped, 1);
    for (Index i = 0; i < 2; ++i) EXPECT_GT(face_area_vector(f, i).z(), 0.1) << i;  // fair, and up as before
    EXPECT_EQ(find_edge(edge_table(f), 0, 1), kNone);
    m.points[2] = Vec3(1, 0.5, 0);
    flip_flat_triangles(m, 1e-6, &flipped);
    EXPECT_EQ(flipped, 0);
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

/// A unit cube of triangles at \p offset, patch \p name, outward.
SurfaceMesh triangle_cube(const Vec3& offset, const std::string& name) {
    SurfaceMesh m = test::cube_corners(offset);
    m.patches[0].name = name;
    for (const auto& q : {std::array<Index, 4>{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2},
                          {1, 3, 7, 5}}) {
        m.add_face({q[0], q[1], q[2]}, 0);
        m.add_face({q[0], q[2], q[3]}, 0);
    }
    return m;
}

TEST(Fuse, PartsTouchingAlongAnEdgeOnlyAreATouchingPartsError) {
    // Two cubes sharing one edge and nothing else (fins whose roots sit on a body along a line):
    // their union would not bound a volume; the error says so by its type, for a caller that
    // joins them another way (prepare_mesh wraps them).
    const SurfaceMesh m = test::merged(triangle_cube(Vec3::Zero(), "a"), triangle_cube(Vec3(1, 1, 0), "b"));
    ASSERT_GT(test::enclosed_volume(m), 0.0);
    EXPECT_THROW(fuse_components(m), TouchingPartsError);
    test::expect_error<TopologyError>([&] { fuse_components(m); }, {"would not bound a volume", "touch along an edge"});
}

}  // namespace
}  // namespace strata
