// The whole hybrid pipeline: generated farfields, then layers + pyramids + tetrahedra in one
// mesh, re-read from what was written (Cobalt60 through the test reader, .msh through Gmsh)
// and validated again.

#include <strata/core/error.h>
#include <strata/core/face_geometry.h>
#include <strata/core/validate.h>
#include <strata/geometry/primitives.h>
#include <strata/geometry/topology.h>
#include <strata/hybrid/hybrid_mesh.h>
#include <strata/io/write_volume.h>
#include <strata/surface/prepare.h>

#include <gtest/gtest.h>

#include "hybrid/box_surface.h"
#include "hybrid/reread_checks.h"
#include "test_support.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace strata {
namespace {

using test::closed_manifold;
using test::enclosed_volume;

using test::example_data;

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
    // Each cell's layer: the 606 prisms of each of the 8 layers, the tetrahedra (first) in none.
    ASSERT_EQ(m.cell_layers.size(), static_cast<std::size_t>(m.num_cells()));
    std::vector<std::size_t> per_layer(9, 0);
    for (std::size_t c = 0; c < m.cell_layers.size(); ++c) {
        const std::int32_t layer = m.cell_layers[c];
        ASSERT_TRUE(layer >= 0 && layer <= 8) << layer;
        ++per_layer[static_cast<std::size_t>(layer)];
        EXPECT_EQ(layer == 0, c < m.tets.size()) << "cell " << c;
    }
    EXPECT_EQ(per_layer[0], m.tets.size());
    for (int k = 1; k <= 8; ++k) EXPECT_EQ(per_layer[static_cast<std::size_t>(k)], 606u) << "layer " << k;
}

// --tets hxt where HXT 4.8 stops (the regular grids of a cube wall's layer top in a generated
// box: HxtFill.DegenerateGridIsBackendError): TetGen fills the domain instead, the same mesh as
// TetGen asked directly, and the report says why.
TEST(HybridMesh, HxtFallsBackToTetGen) {
    SurfaceMesh wall;
    wall.patches.push_back({"wall", PatchKind::Wall});
    test::add_box(wall, Vec3::Zero(), Vec3::Ones(), 8, 0, true);
    HybridParams p;
    p.layers.distribution.layers = 1;
    p.layers.distribution.first_height = 1e-3;
    p.farfield.shape = FarfieldShape::Box;
    p.farfield.size = 3.0;
    p.farfield.divisions = 3;
    p.tets.growth = 0.2;
    p.threads = 1;
    HybridReport tetgen_rep, hxt_rep;
    const VolumeMesh by_tetgen = build_hybrid_mesh(wall, p, nullptr, &tetgen_rep);
    p.tets.mesher = TetMesher::Hxt;
    const VolumeMesh by_hxt = build_hybrid_mesh(wall, p, nullptr, &hxt_rep);
    EXPECT_TRUE(tetgen_rep.tets_fallback.empty());
    test::expect_contains(hxt_rep.tets_fallback, {"HXT"});
    EXPECT_EQ(by_hxt.tets, by_tetgen.tets);
    EXPECT_TRUE(hxt_rep.validation.ok());
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

/// The upper half of a unit sphere as an open shell (its flat disk removed): a half model
/// whose open edge lies in the plane z = 0.
SurfaceMesh hemisphere_shell(const test::ScratchDir& dir) {
    const std::string geo = dir.file("hemisphere.geo");
    std::ofstream(geo)
        << "SetFactory(\"OpenCASCADE\");\nSphere(1) = {0, 0, 0, 1, 0, Pi/2, 2*Pi};\nMesh.MeshSizeMax = 0.15;\n";
    const SurfaceMesh solid = prepare_surface(geo, {});
    SurfaceMesh shell;
    shell.patches = solid.patches;
    std::vector<Index> id(static_cast<std::size_t>(solid.num_points()), kNone);
    for (Index f = 0; f < solid.num_faces(); ++f) {
        if (patch_plane(solid, solid.face_patch[f]).planar()) continue;  // the disk
        Index v[4];
        for (Index i = 0; i < solid.face_size(f); ++i) {
            Index& k = id[static_cast<std::size_t>(solid.face_node(f, i))];
            if (k == kNone) {
                k = shell.num_points();
                shell.points.push_back(solid.points[solid.face_node(f, i)]);
            }
            v[i] = k;
        }
        shell.add_face(v, solid.face_size(f), solid.face_patch[f]);
    }
    return shell;
}

TEST(HybridMesh, HalfModelGetsAHalfFarfieldAndASymmetryPlane) {
    test::ScratchDir dir("hybrid_half");
    const SurfaceMesh shell = hemisphere_shell(dir);
    ASSERT_EQ(boundary_loops(shell).rows(), 1);
    for (FarfieldShape shape : {FarfieldShape::Box, FarfieldShape::Sphere}) {
        HybridParams p = sphere_params();
        p.farfield.shape = shape;
        HybridReport rep;
        const VolumeMesh m = build_hybrid_mesh(shell, p, nullptr, &rep);
        ASSERT_TRUE(rep.validation.ok());
        EXPECT_TRUE(rep.closed_half_model);
        EXPECT_GT(rep.validation.min_scaled_jacobian, 0.0);
        // Patches: the shell's, then the generated symmetry plane and farfield.
        ASSERT_EQ(m.boundary.patches.size(), shell.patches.size() + 2);
        const Patch& sym = m.boundary.patches[shell.patches.size()];
        EXPECT_EQ(sym.name, "symmetry");
        EXPECT_EQ(sym.kind, PatchKind::Symmetry);
        EXPECT_EQ(m.boundary.patches.back().kind, PatchKind::Farfield);
        EXPECT_EQ(rep.remeshed_patches, std::vector<Index>{static_cast<Index>(shell.patches.size())});
        // Everything on the body's side of the plane, the symmetry faces in it, the farfield
        // at the right distance: a half box of half-width 10 × diagonal / 2 (the body and its
        // mirror image have a diagonal of 2√3, less a little for the facets), or a hemisphere
        // of that radius.
        const double h = 0.5 * p.farfield.size * 2.0 * std::sqrt(3.0);
        for (const Vec3& x : m.points) EXPECT_GE(x.z(), -1e-12);
        for (Index f = 0; f < m.boundary.num_faces(); ++f) {
            const Patch& pt = m.boundary.patches[static_cast<std::size_t>(m.boundary.face_patch[f])];
            for (const Index* v = m.boundary.face_begin(f); v != m.boundary.face_end(f); ++v) {
                const Vec3& x = m.points[*v];
                if (pt.kind == PatchKind::Symmetry) {
                    EXPECT_NEAR(x.z(), 0.0, 1e-12);
                } else if (pt.kind == PatchKind::Farfield && shape == FarfieldShape::Sphere) {
                    EXPECT_NEAR(x.norm(), h, 1e-2 * h);
                } else if (pt.kind == PatchKind::Farfield) {
                    EXPECT_NEAR(std::max({std::abs(x.x()), std::abs(x.y()), x.z()}), h, 1e-2 * h);
                }
            }
        }
        if (shape == FarfieldShape::Box) {  // the half box minus the half sphere (faceted: within 1 %)
            EXPECT_NEAR(rep.validation.cell_volume, 4.0 * h * h * h - 2.0 / 3.0 * std::numbers::pi,
                        0.03 * 4.0 * h * h * h);
            test::expect_rereads_valid(m, dir, "half");
        }
    }
}

TEST(HybridMesh, OpenSurfaceThatIsNotAHalfModelIsRefusedClearly) {
    SurfaceMesh bent;
    bent.patches.push_back({"sheet", PatchKind::Wall});
    bent.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 1), Vec3(0, 1, 0)};
    bent.add_face({0, 1, 2}, 0);
    bent.add_face({0, 2, 3}, 0);
    try {
        build_hybrid_mesh(bent, sphere_params());
        FAIL() << "an open wall that is not cut along one plane must not silently give a mesh";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("do not lie in one plane"), std::string::npos) << e.what();
    }
}

TEST(HybridMesh, AHoleOrACrackIsNotTakenForAHalfModel) {
    // A sphere missing one face: its open loop (a triangle) lies in a plane, as a half model's
    // cut does, but the body lies on both sides of it. Refused as a hole, with where. A node of
    // a face moved off by 1e-5 (its faces no longer meet) is a crack: the message names the gap
    // and the --merge-tolerance that welds it.
    const SurfaceMesh sphere = prepare_surface(example_data("sphere.stl"), {});
    SurfaceMesh holed = sphere;
    std::vector<char> drop(static_cast<std::size_t>(sphere.num_faces()), 0);
    drop[7] = 1;
    holed = remove_faces(sphere, drop);
    test::expect_error<InputError>(
        [&] { (void)build_hybrid_mesh(holed, sphere_params()); },
        {"1 open boundary loop: 3 edges around (", "not a half model", "a hole or a crack in the surface"});
    // The crack: face 7's first node replaced by a copy 1e-5 away.
    SurfaceMesh cracked = sphere;
    const Index v = cracked.face_node(7, 0);
    cracked.points.push_back(cracked.points[static_cast<std::size_t>(v)] + Vec3(1e-5, 0, 0));
    cracked.face_nodes[static_cast<std::size_t>(cracked.face_offsets[7])] = cracked.num_points() - 1;
    test::expect_error<InputError>([&] { (void)build_hybrid_mesh(cracked, sphere_params()); },
                                   {"two of their nodes are 1e-05 apart", "a crack: PrepareParams::merge_tolerance"});
}

TEST(HybridMesh, ANegativeThreadCountIsRefusedByName) {
    HybridParams p = sphere_params();
    p.threads = -1;
    const SurfaceMesh wall = prepare_surface(example_data("sphere.stl"), {});
    test::expect_error<InputError>([&] { (void)build_hybrid_mesh(wall, p); },
                                   {"HybridParams::threads is -1: give 0 (all cores) or a positive count"});
    test::expect_error<InputError>([&] { (void)step_plan(wall, p, 0.1, 1000.0); }, {"HybridParams::threads is -1"});
}

TEST(HybridMesh, LayersThickerThanTheGeneratedFarfieldAllowsAreRefusedWithTheNumbers) {
    // 10 layers from 0.5 at 1.2 make 12.98 around a unit sphere; a farfield 1.1 times its
    // diagonal (3.46) across leaves 0.8-0.9 (the divisions cut the sphere): refused before any layer (TetGen used to
    // say the boundary's normals pointed into the region), with the size that fits, which then does.
    const SurfaceMesh wall = prepare_surface(example_data("sphere.stl"), {});
    HybridParams p = sphere_params();
    p.layers.distribution.layers = 10;
    p.layers.distribution.first_height = 0.5;
    p.farfield.size = 1.1;
    std::string msg;
    try {
        build_hybrid_mesh(wall, p);
        FAIL() << "layers through the farfield must not give a mesh";
    } catch (const InputError& e) {
        msg = e.what();
    }
    for (const char* part :
         {"12.98 thick", "FarfieldParams::size 1.1", "leaves 0.8", "enlarge FarfieldParams::size to 9"})
        EXPECT_NE(msg.find(part), std::string::npos) << part << " not in: " << msg;
    p.farfield.size = 9.0;
    HybridReport rep;
    const VolumeMesh m = build_hybrid_mesh(wall, p, nullptr, &rep);
    EXPECT_GT(m.tets.size(), 0u);
    EXPECT_GT(rep.validation.min_scaled_jacobian, 0.0);
}

/// Two unit spheres (patches "a", "b"), the second at \p dx along x.
SurfaceMesh two_unit_spheres(double dx) {
    return test::merged(icosphere(Vec3::Zero(), 1.0, 3, {"a", PatchKind::Wall}),
                        icosphere(Vec3(dx, 0, 0), 1.0, 3, {"b", PatchKind::Wall}));
}

/// Ten layers of 0.02 (0.2 in all, as two_unit_spheres' gaps are measured against) in \p mode.
HybridParams ten_layers_of_0_02(ProximityMode mode) {
    HybridParams p;
    p.layers.distribution.layers = 10;
    p.layers.distribution.first_height = 0.02;
    p.layers.distribution.growth = 1.0;
    p.layers.proximity = mode;
    return p;
}

TEST(HybridMesh, LayersInANarrowGapAreThinnedUntilTheFrontIsClear) {
    // Two unit spheres 0.1 apart, 0.2 of layers asked on each: the proximity limit thins the
    // columns facing each other across the gap, the front check lowers the ones beside it
    // that still collide, and the mesh is valid; away from the gap the layers are whole.
    const SurfaceMesh s = two_unit_spheres(2.1);
    HybridParams p = ten_layers_of_0_02(ProximityMode::Scale);
    HybridReport r;
    const VolumeMesh m = build_hybrid_mesh(s, p, nullptr, &r);
    EXPECT_TRUE(validate_mesh(m).ok());
    EXPECT_GT(r.layers.thinned_nodes, 0);
    EXPECT_LT(r.layers.min_thickness_share, 0.25);          // 0.45 of the 0.1 gap is 0.045 of the 0.2 asked
    EXPECT_LT(r.layers.thinned_nodes, s.num_points() / 4);  // only around the gap
    // The coverage report: per sphere, most columns full, the short ones thinned by proximity
    // or lowered for the front, each listed once with its place.
    ASSERT_EQ(r.coverage.patches.size(), 2u);
    Index short_count = 0;
    for (const PatchCoverage& c : r.coverage.patches) {
        EXPECT_EQ(c.nodes, s.num_points() / 2);
        EXPECT_GT(c.full_nodes, c.nodes / 2);
        EXPECT_GT(c.short_nodes(Shortfall::Proximity), 0);
        EXPECT_EQ(c.full_nodes + c.short_nodes(Shortfall::Proximity) + c.short_nodes(Shortfall::Front) +
                      c.short_nodes(Shortfall::HeldBack) + c.short_nodes(Shortfall::Quality) +
                      c.short_nodes(Shortfall::Neighbours),
                  c.nodes);
        EXPECT_LT(c.min_share, 0.25);
        short_count += c.nodes - c.full_nodes;
    }
    EXPECT_EQ(static_cast<Index>(r.coverage.short_nodes.size()), short_count);
    for (const ShortNode& n : r.coverage.short_nodes) EXPECT_LT(std::abs(n.position.x() - 1.05), 1.0);
    // With proximity off, the front rounds alone resolve it.
    p.layers.proximity = ProximityMode::Off;
    HybridReport off;
    EXPECT_TRUE(validate_mesh(build_hybrid_mesh(s, p, nullptr, &off)).ok());
    EXPECT_GT(off.front_rounds, 0);
    EXPECT_GT(off.front_lowered_nodes, 0);
}

TEST(HybridMesh, AColumnWhoseFrontMeetsAnotherLosesItsTopLayerFirstAndHalfOnlyWhenItMeetsAgain) {
    // Two unit spheres, 10 layers of 0.02 on each, proximity off: only the front rounds act, and
    // their bounds scale the heights (mode off). A gap of 0.38: the fronts overlap by less than a
    // layer, taking the colliding columns' top layer off (0.9 of the thickness) clears them in
    // one round (halving them left 0.5). A gap of 0.3: one layer is not enough, and the columns
    // that meet again are halved.
    const HybridParams p = ten_layers_of_0_02(ProximityMode::Off);
    HybridReport r;
    EXPECT_TRUE(validate_mesh(build_hybrid_mesh(two_unit_spheres(2.38), p, nullptr, &r)).ok());
    EXPECT_EQ(r.front_rounds, 1);
    ASSERT_EQ(r.coverage.patches.size(), 2u);
    for (const PatchCoverage& c : r.coverage.patches) EXPECT_GT(c.min_share, 0.85);
    EXPECT_TRUE(validate_mesh(build_hybrid_mesh(two_unit_spheres(2.3), p, nullptr, &r)).ok());
    EXPECT_GE(r.front_rounds, 2);
    for (const PatchCoverage& c : r.coverage.patches) EXPECT_LT(c.min_share, 0.5);
}

TEST(HybridMesh, OverlappingBodiesAreRefusedBeforeTheLayers) {
    HybridParams p;
    p.layers.distribution.layers = 2;
    p.layers.distribution.first_height = 0.01;
    test::expect_error<InputError>([&] { build_hybrid_mesh(two_unit_spheres(1.5), p); },
                                   {"the surface intersects itself", "patch 'a'", "patch 'b'", "CadParams::fuse"});
}

/// Cancels once \p stop_stage has reported a fraction of at least \p stop_at; records every
/// report, and the reports that came after the cancellation.
class StopAt : public Progress {
public:
    StopAt(std::string stage, double at) : stage_(std::move(stage)), at_(at) {}
    void report(std::string_view stage, double fraction) override {
        if (stop_) ++after_;
        stages.emplace_back(stage);
        if (stage == stage_ && fraction >= at_) stop_ = true;
    }
    bool cancelled() const override { return stop_; }
    std::vector<std::string> stages;
    int reports_after_cancelling() const { return after_; }

private:
    std::string stage_;
    double at_;
    bool stop_ = false;
    int after_ = 0;
};

TEST(Cancellation, EveryStageStopsAtItsNextCheckAndNothingIsWritten) {
    // The whole pipeline (surface, layers on quads so that pyramids are built, tetrahedra,
    // validation, writing Cobalt60 and MSH), cancelled in each stage at its start and halfway:
    // Cancelled comes before any later stage reports, and no file (not even a temporary one).
    const std::string input = example_data("sphere_pyhyp_quads.msh");
    HybridParams p;
    p.layers.distribution.layers = 3;
    p.layers.distribution.first_height = 1e-3;
    for (const std::string stage : {"surface", "layers", "pyramids", "tetrahedra", "validation", "writing"})
        for (const double at : {0.0, 0.5})
            for (const char* out : {"mesh.cgr", "mesh.msh"}) {
                if (stage != "writing" && out == std::string("mesh.msh")) continue;  // the same up to writing
                test::ScratchDir dir("cancel_" + stage);
                StopAt progress(stage, at);
                bool cancelled = false;
                try {
                    const SurfaceMesh s = prepare_surface(input, {}, nullptr, &progress);
                    write_volume(build_hybrid_mesh(s, p, &progress), dir.file(out), 4.1, &progress);
                } catch (const Cancelled&) {
                    cancelled = true;
                }
                EXPECT_TRUE(cancelled) << stage << " " << at << " " << out;
                EXPECT_EQ(progress.reports_after_cancelling(), 0) << stage << " " << at;
                ASSERT_FALSE(progress.stages.empty());
                EXPECT_EQ(progress.stages.back(), stage) << at;
                EXPECT_TRUE(std::filesystem::is_empty(dir.path())) << stage << " " << at << " " << out;
            }
}

}  // namespace
}  // namespace strata
