// Closed surfaces from formulas: the icosphere is closed, outward, on its sphere, 20·4^levels faces.

#include <strata/core/face_geometry.h>
#include <strata/geometry/primitives.h>
#include <strata/geometry/topology.h>

#include <gtest/gtest.h>

#include <cmath>

namespace strata {
namespace {

TEST(Icosphere, ClosedOutwardOnItsSphere) {
    const Vec3 c(1.0, -2.0, 0.5);
    for (int levels : {0, 1, 3}) {
        const SurfaceMesh s = icosphere(c, 2.5, levels, {"ball", PatchKind::Farfield});
        EXPECT_EQ(s.num_faces(), 20 * (1 << (2 * levels)));
        EXPECT_EQ(s.num_points(), 10 * (1 << (2 * levels)) + 2);  // Euler: V = F/2 + 2
        ASSERT_EQ(s.patches.size(), 1u);
        EXPECT_EQ(s.patches[0].name, "ball");
        EXPECT_EQ(s.patches[0].kind, PatchKind::Farfield);
        EXPECT_EQ(boundary_loops(s).rows(), 0);
        for (const Vec3& p : s.points) EXPECT_NEAR((p - c).norm(), 2.5, 1e-12);
        double volume = 0.0;
        for (Index f = 0; f < s.num_faces(); ++f) {
            const Vec3 a = face_area_vector(s, f);
            EXPECT_GT(a.dot(face_centroid(s, s.points, f) - c), 0.0) << "face " << f;
            volume += a.dot(face_centroid(s, s.points, f) - c) / 3.0;
        }
        EXPECT_LT(volume, 4.0 / 3.0 * M_PI * std::pow(2.5, 3));  // inscribed
        EXPECT_GT(volume, 0.6 * 4.0 / 3.0 * M_PI * std::pow(2.5, 3));
    }
}

}  // namespace
}  // namespace strata
