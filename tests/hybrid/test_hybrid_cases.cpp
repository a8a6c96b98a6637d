// The real geometries the hybrid stage must mesh (the list): each gives a valid mesh
// with the expected cell types and patches, written as Cobalt60 and .msh, re-read and
// validated again.

#include <strata/geometry/prepare.h>
#include <strata/hybrid/hybrid_mesh.h>

#include <gtest/gtest.h>

#include "hybrid/reread_checks.h"
#include "test_support.h"

#include <algorithm>
#include <cstdio>
#include <string>

namespace strata {
namespace {

using test::example_data;

HybridParams params(int layers, double first_height, double growth = 1.2) {
    HybridParams p;
    p.layers.distribution.layers = layers;
    p.layers.distribution.first_height = first_height;
    p.layers.distribution.growth = growth;
    return p;
}

std::vector<std::string> names(const SurfaceMesh& s, const std::vector<Index>& patches) {
    std::vector<std::string> out;
    for (Index p : patches) out.push_back(s.patches[static_cast<std::size_t>(p)].name);
    return out;
}

/// The checks every case ends with; prints the figures for the record.
void expect_valid_case(const std::string& name, const VolumeMesh& m, const HybridReport& rep) {
    ASSERT_TRUE(rep.validation.ok()) << name << ": " << rep.validation.problems.front();
    EXPECT_GT(rep.validation.min_scaled_jacobian, 0.0) << name;
    std::printf(
        "%s: %zu hex, %zu prisms, %zu pyramids, %zu tets; min scaled Jacobian %.2e (layers %.2e)\n", name.c_str(),
        m.hexes.size(), m.prisms.size(), m.pyramids.size(), m.tets.size(), rep.validation.min_scaled_jacobian,
        std::min_element(rep.layer_stats.begin(), rep.layer_stats.end(), [](const LayerStats& a, const LayerStats& b) {
            return a.min_scaled_jacobian < b.min_scaled_jacobian;
        })->min_scaled_jacobian);
    test::ScratchDir dir("case_" + name);
    test::expect_rereads_valid(m, dir, name);
}

TEST(HybridCases, SphereStlInAGeneratedFarfield) {
    const SurfaceMesh s = prepare_surface(example_data("sphere.stl"), {});
    HybridReport rep;
    const VolumeMesh m = build_hybrid_mesh(s, params(10, 1e-3), nullptr, &rep);
    EXPECT_EQ(m.prisms.size(), 10u * static_cast<std::size_t>(s.num_faces()));
    expect_valid_case("sphere_stl", m, rep);
}

TEST(HybridCases, OneraM6FromStep) {
    PrepareParams pp;
    pp.cad.size = 60.0;  // mm; the wing's span is 1196
    const SurfaceMesh s = prepare_surface(example_data("onera_m6_sharp_te.stp"), pp);
    HybridReport rep;
    const VolumeMesh m = build_hybrid_mesh(s, params(10, 0.02), nullptr, &rep);
    EXPECT_GT(m.prisms.size(), 0u);
    EXPECT_GT(m.tets.size(), 0u);
    expect_valid_case("m6_step", m, rep);
}

TEST(HybridCases, HemisphereCylinderHalfDomainWithSymmetryAndOutflowPlanes) {
    PrepareParams pp;
    pp.cad.size = 10.0;
    pp.cad.curvature_points = 24;
    pp.cad.size_min = 0.05;
    pp.patch_kinds = {
        {"surface_1", PatchKind::Farfield}, {"surface_2", PatchKind::Symmetry}, {"surface_3", PatchKind::Other}};
    const SurfaceMesh s = prepare_surface(example_data("hemisphere_cylinder_halfdomain.stp"), pp);
    HybridReport rep;
    const VolumeMesh m = build_hybrid_mesh(s, params(15, 0.002), nullptr, &rep);
    // The symmetry plane (y = 0) and the outflow plane (x = 10) hold the layers' sides.
    EXPECT_EQ(names(s, rep.remeshed_patches), (std::vector<std::string>{"surface_2", "surface_3"}));
    for (Index f = 0; f < m.boundary.num_faces(); ++f) {
        const std::string& p = m.boundary.patches[static_cast<std::size_t>(m.boundary.face_patch[f])].name;
        for (const Index* v = m.boundary.face_begin(f); v != m.boundary.face_end(f); ++v) {
            if (p == "surface_2") {
                EXPECT_NEAR(m.points[*v].y(), 0.0, 1e-9);
            } else if (p == "surface_3") {
                EXPECT_NEAR(m.points[*v].x(), 10.0, 1e-9);
            }
        }
    }
    expect_valid_case("hemisphere_cylinder", m, rep);
}

TEST(HybridCases, BodyFinInABoxWhoseSidesAreFarfield) {
    PrepareParams pp;
    for (const char* n : {"surface_1", "surface_2", "surface_4", "surface_6"})
        pp.patch_kinds.emplace_back(n, PatchKind::Farfield);
    const SurfaceMesh s = prepare_surface(example_data("bl3d_5_body_fin_in_box.brep"), pp);
    HybridReport rep;
    const VolumeMesh m = build_hybrid_mesh(s, params(20, 5e-4, 1.15), nullptr, &rep);
    // The floor's and the ceiling's layers end on all four sides.
    EXPECT_EQ(names(s, rep.remeshed_patches),
              (std::vector<std::string>{"surface_1", "surface_2", "surface_4", "surface_6"}));
    expect_valid_case("body_fin_box", m, rep);
}

TEST(HybridCases, WingFuselageFusedFromTwoSolids) {
    PrepareParams pp;
    pp.cad.fuse = true;
    const SurfaceMesh s = prepare_surface(example_data("wing_fuselage.step"), pp);
    HybridReport rep;
    const VolumeMesh m = build_hybrid_mesh(s, params(5, 0.05), nullptr, &rep);
    EXPECT_GT(m.prisms.size(), 0u);
    expect_valid_case("wing_fuselage", m, rep);
}

TEST(HybridCases, MixedQuadTriangleOneraM6HasEveryCellType) {
    const SurfaceMesh s = prepare_surface(example_data("onera_m6_mixed_quadtri.msh"), {});
    HybridReport rep;
    const VolumeMesh m = build_hybrid_mesh(s, params(5, 0.01), nullptr, &rep);
    EXPECT_GT(m.hexes.size(), 0u);
    EXPECT_GT(m.prisms.size(), 0u);
    EXPECT_EQ(m.pyramids.size(), m.hexes.size() / 5);  // one per quad of the outermost layer
    EXPECT_GT(m.tets.size(), 0u);
    expect_valid_case("m6_mixed", m, rep);
}

}  // namespace
}  // namespace strata
