// The alpha wrap (geometry/wrap.h): a surface nothing repairs in place (two bodies through each
// other, a hole, a face given twice, a fin on one edge, so non-manifold) becomes one closed,
// manifold, non-self-intersecting surface whose faces keep the patch of the input they lie on,
// with its distance from the input measured both ways.

#include <strata/core/error.h>
#include <strata/core/face_geometry.h>
#include <strata/geometry/check.h>
#include <strata/geometry/intersections.h>
#include <strata/geometry/primitives.h>
#include <strata/geometry/topology.h>
#include <strata/geometry/wrap.h>

#include <gtest/gtest.h>

#include "test_support.h"

#include <cmath>
#include <limits>
#include <numbers>

namespace strata {
namespace {

/// Sphere "a" (radius 1 at the origin) through sphere "b" (radius 0.8 at x = 1.2), with three
/// of a's faces gone (a hole), one of b's written twice and a fin on one of a's edges: every
/// defect of a dirty STL at once.
SurfaceMesh dirty_soup() {
    SurfaceMesh a = icosphere(Vec3::Zero(), 1.0, 3, {"a", PatchKind::Wall});
    const SurfaceMesh b = icosphere(Vec3(1.2, 0.1, 0), 0.8, 3, {"b", PatchKind::Wall});
    std::vector<char> drop(static_cast<std::size_t>(a.num_faces()), 0);
    drop[0] = drop[1] = drop[2] = 1;
    SurfaceMesh soup = test::merged(remove_faces(a, drop), b);
    const Index last = soup.num_faces() - 1;
    soup.add_face(soup.face_begin(last), 3, soup.face_patch[last]);  // b's last face again
    const Index* e = soup.face_begin(100);                            // a fin on an edge of a
    soup.points.push_back(0.5 * (soup.points[e[0]] + soup.points[e[1]]) * 1.05);
    const std::array<Index, 3> fin{e[0], e[1], static_cast<Index>(soup.points.size() - 1)};
    soup.add_face(fin.data(), 3, 0);
    return soup;
}

TEST(Wrap, ADirtySoupBecomesOneClosedManifoldSurface) {
    const SurfaceMesh soup = dirty_soup();
    EXPECT_THROW(check_surface(soup, "soup"), TopologyError);
    WrapReport r;
    const SurfaceMesh w = wrap_surface(soup, {.alpha = 0.1}, &r);
    EXPECT_TRUE(test::closed_manifold(w));
    EXPECT_NO_THROW(check_surface(w, "wrap"));
    EXPECT_TRUE(self_intersections(w, 1).empty());
    Index components = 0;
    face_components(w, &components);
    EXPECT_EQ(components, 1);
    EXPECT_EQ(r.alpha, 0.1);
    EXPECT_DOUBLE_EQ(r.offset, 0.1 / 30.0);
    EXPECT_EQ(r.faces, w.num_faces());
    EXPECT_EQ(r.input_faces, soup.num_faces());

    // The wrap lies outside the input by about the offset, never farther than α; its nodes are
    // on the offset surface.
    EXPECT_GE(r.wrap_to_input, 0.9 * r.offset);
    EXPECT_LT(r.wrap_to_input, r.alpha);
    // The input's farthest point from the wrap: one of the faces inside the union (a's within
    // b, b's within a), up to about half a radius deep; the hole is closed over at the offset.
    EXPECT_GT(r.input_to_wrap, 0.3);
    EXPECT_LT(r.input_to_wrap, 0.8);
    EXPECT_LT((r.input_to_wrap_at - Vec3(1.2, 0.1, 0)).norm(), 0.8);  // inside b
    EXPECT_EQ(r.hausdorff(), std::max(r.wrap_to_input, r.input_to_wrap));

    // The volume of the union of the balls, and a shell of about the offset round it.
    const double d = Vec3(1.2, 0.1, 0).norm(), r1 = 1.0, r2 = 0.8;
    const double lens = std::numbers::pi * std::pow(r1 + r2 - d, 2) *
                        (d * d + 2 * d * r2 - 3 * r2 * r2 + 2 * d * r1 + 6 * r1 * r2 - 3 * r1 * r1) / (12 * d);
    const double exact = 4.0 / 3.0 * std::numbers::pi * (r1 * r1 * r1 + r2 * r2 * r2) - lens;
    EXPECT_NEAR(test::enclosed_volume(w), exact, 0.05 * exact);
}

TEST(Wrap, FacesKeepThePatchOfTheInputTheyLieOn) {
    const SurfaceMesh w = wrap_surface(dirty_soup(), {.alpha = 0.1});
    ASSERT_EQ(w.patches.size(), 2u);
    EXPECT_EQ(w.patches[0].name, "a");
    EXPECT_EQ(w.patches[1].name, "b");
    Index wrong = 0, on_b = 0;
    for (Index f = 0; f < w.num_faces(); ++f) {
        const Vec3 c = face_centroid(w, w.points, f);
        const double to_a = std::abs(c.norm() - 1.0), to_b = std::abs((c - Vec3(1.2, 0.1, 0)).norm() - 0.8);
        const Index nearest = to_a < to_b ? 0 : 1;
        // Where both spheres are within a facet's depth (their crossing) either will do.
        if (std::abs(to_a - to_b) > 0.02 && w.face_patch[f] != nearest) ++wrong;
        on_b += w.face_patch[f] == 1;
    }
    EXPECT_EQ(wrong, 0);
    EXPECT_GT(on_b, w.num_faces() / 5);
}

TEST(Wrap, TheSameSoupGivesTheSameBytes) {
    const SurfaceMesh soup = dirty_soup();
    const SurfaceMesh one = wrap_surface(soup, {.alpha = 0.15, .threads = 1});
    const SurfaceMesh two = wrap_surface(soup, {.alpha = 0.15, .threads = 2});
    EXPECT_EQ(one.points, two.points);
    EXPECT_EQ(one.face_nodes, two.face_nodes);
    EXPECT_EQ(one.face_patch, two.face_patch);
}

TEST(Wrap, DefaultsFollowTheModelsSize) {
    const SurfaceMesh sphere = icosphere(Vec3::Zero(), 2.0, 3, {"s", PatchKind::Wall});
    WrapReport r;
    const SurfaceMesh w = wrap_surface(sphere, {}, &r);
    EXPECT_NEAR(r.alpha, std::sqrt(3.0) * 4.0 / 100.0, 1e-3);  // a hundredth of the diagonal
    EXPECT_DOUBLE_EQ(r.offset, r.alpha / 30.0);
    EXPECT_TRUE(test::closed_manifold(w));
    EXPECT_LT(r.hausdorff(), r.alpha);  // a clean sphere: nothing inside, nothing far
}

TEST(Wrap, BadInputIsRefusedByName) {
    test::expect_error<InputError>([] { wrap_surface(SurfaceMesh{}, {}); }, {"no faces"});
    const SurfaceMesh sphere = icosphere(Vec3::Zero(), 1.0, 1, {"s", PatchKind::Wall});
    test::expect_error<InputError>([&] { wrap_surface(sphere, {.alpha = -1.0}); }, {"WrapParams::alpha", "-1"});
    test::expect_error<InputError>([&] { wrap_surface(sphere, {.offset = std::numeric_limits<double>::infinity()}); },
                       {"WrapParams::offset"});
    test::expect_error<InputError>([&] { wrap_surface(sphere, {.threads = -2}); }, {"WrapParams::threads"});
    SurfaceMesh nan = sphere;
    nan.points[3].x() = std::numeric_limits<double>::quiet_NaN();
    test::expect_error<InputError>([&] { wrap_surface(nan, {}); }, {"not a finite number"});
}

}  // namespace
}  // namespace strata
