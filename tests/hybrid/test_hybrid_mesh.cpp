// The whole hybrid pipeline: generated farfields, then layers + pyramids + tetrahedra in one
// mesh, re-read from what was written (Cobalt60 through the test reader, .msh through Gmsh)
// and validated again.

#include <strata/error.h>
#include <strata/geometry/face_geometry.h>
#include <strata/geometry/prepare.h>
#include <strata/geometry/topology.h>
#include <strata/hybrid/hybrid_mesh.h>

#include <gtest/gtest.h>

#include "hybrid/reread_checks.h"
#include "test_support.h"

#include <cmath>
#include <numbers>

namespace strata {
namespace {

using test::example_data;

double enclosed_volume(const SurfaceMesh& m) {
    double v = 0.0;
    for (Index f = 0; f < m.num_faces(); ++f) v += face_centroid(m, m.points, f).dot(face_area_vector(m, f)) / 3.0;
    return v;
}

bool closed_manifold(const SurfaceMesh& m) {
    const EdgeTable e = edge_table(m);
    for (Index i = 0; i < e.faces.rows(); ++i)
        if (e.faces.row_size(i) != 2) return false;
    return true;
}

TEST(Farfield, BoxAndSphereAreClosedOutwardAndSized) {
    const std::vector<Vec3> body = {Vec3(0, 0, 0), Vec3(2, 1, 0.5)};
    const double diag = Vec3(2, 1, 0.5).norm();
    FarfieldParams p;
    p.size = 10.0;
    p.shape = FarfieldShape::Box;
    const SurfaceMesh box = make_farfield(body, p);
    EXPECT_TRUE(closed_manifold(box));
    EXPECT_NEAR(enclosed_volume(box), std::pow(10.0 * diag, 3), 1e-9 * std::pow(10.0 * diag, 3));  // > 0: outward
    EXPECT_EQ(box.patches.at(0).kind, PatchKind::Farfield);
    p.shape = FarfieldShape::Sphere;
    const SurfaceMesh sph = make_farfield(body, p);
    EXPECT_TRUE(closed_manifold(sph));
    const double r = 5.0 * diag, exact = 4.0 / 3.0 * std::numbers::pi * r * r * r;
    EXPECT_GT(enclosed_volume(sph), 0.97 * exact);
    EXPECT_LT(enclosed_volume(sph), exact);
    for (const Vec3& x : sph.points) EXPECT_NEAR((x - Vec3(1, 0.5, 0.25)).norm(), r, 1e-9 * r);
    p.size = 0.5;
    EXPECT_THROW(make_farfield(body, p), InputError);
    EXPECT_THROW(parse_farfield_shape("cylinder"), InputError);
}

HybridParams sphere_params() {
    HybridParams p;
    p.layers.distribution.layers = 8;
    p.layers.distribution.first_height = 2e-3;
    p.layers.distribution.growth = 1.2;
    p.farfield.size = 10.0;
    p.farfield.divisions = 8;
    return p;
}

TEST(HybridMesh, SpherePrismsPyramidsFreeTetsValid) {
    const SurfaceMesh wall = prepare_surface(example_data("sphere.stl"), {});
    HybridReport rep;
    const VolumeMesh m = build_hybrid_mesh(wall, sphere_params(), nullptr, &rep);
    EXPECT_EQ(m.prisms.size(), 8u * 606u);
    // One generated farfield patch, holding every outer face.
    Index farfield_patches = 0;
    for (const Patch& p : m.boundary.patches) farfield_patches += p.kind == PatchKind::Farfield;
    EXPECT_EQ(farfield_patches, 1);
    EXPECT_TRUE(m.pyramids.empty());
    EXPECT_GT(m.tets.size(), 1000u);
    EXPECT_TRUE(rep.validation.ok());
    EXPECT_GT(rep.validation.min_scaled_jacobian, 0.0);
}

TEST(HybridMesh, QuadSphereHasEveryCellTypeButTetsAndItWritesAndRereads) {
    const SurfaceMesh wall = prepare_surface(example_data("sphere_pyhyp_quads.msh"), {});
    HybridReport rep;
    const VolumeMesh m = build_hybrid_mesh(wall, sphere_params(), nullptr, &rep);
    EXPECT_EQ(m.hexes.size(), 8u * 1536u);
    EXPECT_EQ(m.pyramids.size(), 1536u);
    EXPECT_GT(m.tets.size(), 1000u);
    ASSERT_TRUE(rep.validation.ok());

    test::ScratchDir dir("hybrid_rw");
    test::expect_rereads_valid(m, dir, "sphere");
}

TEST(HybridMesh, HalfModelIsRefusedClearly) {
    SurfaceMesh wall = prepare_surface(example_data("onera_m6_pyhyp_quads.msh"), {});
    try {
        build_hybrid_mesh(wall, sphere_params());
        FAIL() << "an open wall without a symmetry patch must not silently give a mesh";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("open"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace strata
