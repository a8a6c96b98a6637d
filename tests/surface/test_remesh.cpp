// A surface mesh made again with Gmsh (surface/remesh.h): a box of needle triangles comes back
// as well-shaped faces on the same six planes with its edges kept; a sphere split into two
// patches keeps both, split where they were, and its outward orientation; the size asked is
// the size given; the same input gives the same mesh; bad parameters are refused.

#include <strata/core/error.h>
#include <strata/core/face_geometry.h>
#include <strata/core/solver_checks.h>
#include <strata/geometry/check.h>
#include <strata/geometry/primitives.h>
#include <strata/surface/prepare.h>
#include <strata/surface/remesh.h>

#include <gtest/gtest.h>

#include "test_support.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <tuple>

namespace strata {
namespace {

/// The box [0,1] × [0,ly] × [0,1] as triangles on a lattice of nx × ny × nz steps, closed and
/// pointing out. With ny ≫ nx, nz its x and z faces are strips of needles (aspect ratio ny).
SurfaceMesh lattice_box(int nx, int ny, int nz, double ly = 1.0) {
    SurfaceMesh m;
    m.patches.push_back({"box", PatchKind::Wall});
    std::map<std::tuple<int, int, int>, Index> id;
    auto node = [&](int i, int j, int k) {
        const auto [it, fresh] = id.emplace(std::tuple{i, j, k}, static_cast<Index>(m.points.size()));
        if (fresh) m.points.emplace_back(double(i) / nx, ly * j / ny, double(k) / nz);
        return it->second;
    };
    // One face of the box: the lattice over two axes at a fixed value of the third, split into
    // triangles along one diagonal.
    auto side = [&](int na, int nb, auto&& at) {
        for (int a = 0; a < na; ++a)
            for (int b = 0; b < nb; ++b) {
                const Index p = at(a, b), q = at(a + 1, b), r = at(a + 1, b + 1), s = at(a, b + 1);
                m.add_face({p, q, r}, 0);
                m.add_face({p, r, s}, 0);
            }
    };
    side(nx, ny, [&](int a, int b) { return node(a, b, 0); });
    side(nx, ny, [&](int a, int b) { return node(a, b, nz); });
    side(nx, nz, [&](int a, int b) { return node(a, 0, b); });
    side(nx, nz, [&](int a, int b) { return node(a, ny, b); });
    side(ny, nz, [&](int a, int b) { return node(0, a, b); });
    side(ny, nz, [&](int a, int b) { return node(nx, a, b); });
    return orient_surface(m);
}

TEST(Remesh, NeedleBoxComesBackWellShapedOnTheSamePlanes) {
    const SurfaceMesh box = lattice_box(1, 60, 1);
    ASSERT_GT(needle_faces(box, kNeedleCornerDeg).needles, 200);
    RemeshParams p;
    p.size = 0.1;
    RemeshReport rep;
    const SurfaceMesh m = remesh_surface(box, p, "box.stl", &rep);
    check_surface(m, "remeshed");
    EXPECT_TRUE(test::closed_manifold(m));
    EXPECT_EQ(rep.faces_before, box.num_faces());
    EXPECT_EQ(rep.faces_after, m.num_faces());
    EXPECT_EQ(rep.needles_before, needle_faces(box, kNeedleCornerDeg).needles);
    EXPECT_EQ(rep.needles_after, 0);
    EXPECT_EQ(needle_faces(m, kNeedleCornerDeg).needles, 0);
    EXPECT_GT(needle_faces(m, 0.0).sharpest_deg, 25.0);  // Frontal-Delaunay on planes: near-equilateral
    EXPECT_GE(rep.surfaces, 6);  // one per side at least (Gmsh splits a strip of needles further)
    EXPECT_EQ(rep.attempts, 1);
    EXPECT_DOUBLE_EQ(rep.feature_angle_deg, 40.0);
    // Every face lies in one of the six planes and points out of the box: the sharp edges are
    // kept and no face is turned.
    for (Index f = 0; f < m.num_faces(); ++f) {
        const Vec3 n = face_area_vector(m, f).normalized(), c = face_centroid(m, m.points, f);
        Index axis = 0;
        n.cwiseAbs().maxCoeff(&axis);
        EXPECT_GT(std::abs(n[axis]), 1.0 - 1e-9) << f;
        EXPECT_NEAR(c[axis], n[axis] > 0 ? 1.0 : 0.0, 1e-9) << f;
    }
    EXPECT_NEAR(test::enclosed_volume(m), 1.0, 1e-9);
    const BoundingBox bb = bounding_box(m.points);
    EXPECT_NEAR((bb.min - Vec3::Zero()).norm(), 0.0, 1e-12);
    EXPECT_NEAR((bb.max - Vec3::Ones()).norm(), 0.0, 1e-12);
    EXPECT_NEAR(median_edge_length(m), 0.1, 0.03);
}

TEST(Remesh, WhereEveryAttemptFoldsTheInputBisectedToTheSizeIsTried) {
    // A CAD tool's STL of a rocket (examples/sweep/rocket.geo, BRepMesh): each facet of its body
    // is one triangle pair 2 long and 0.05 wide, and the union with the fins cuts the bottom ones
    // into needles 0.002 wide along their whole length. On these triangles Gmsh's
    // parametrization folds the new mesh at every angle; bisected to edges no longer than the
    // size (the same surface), the first angle works.
    const std::string path = test::example_data("../sweep/rocket_brepmesh.stl");
    PrepareParams fused;
    fused.fuse = true;
    fused.collapse_ratio = 0.0;  // as remeshing has it
    const SurfaceMesh in = prepare_surface(path, fused);
    PrepareParams p = fused;
    p.remesh = true;
    p.remeshing.size = 0.0447;
    p.remeshing.feature_angle_deg = 80.0;  // angles 80, 60 and 45: three attempts on the input's triangles
    PrepareReport prep;
    const SurfaceMesh m = prepare_surface(path, p, &prep);
    ASSERT_TRUE(prep.remeshed);
    const RemeshReport& rep = prep.remesh;
    EXPECT_EQ(rep.attempts, 4);
    EXPECT_DOUBLE_EQ(rep.feature_angle_deg, 80.0);
    EXPECT_GT(rep.split_edges, 1000);
    EXPECT_TRUE(test::closed_manifold(m));
    // The same body, pointing out: its volume within what chords of 0.045 on a radius of 0.1 cut
    // off the facets (2 %).
    EXPECT_NEAR(test::enclosed_volume(m), test::enclosed_volume(in), 0.03 * test::enclosed_volume(in));
    EXPECT_GT(test::enclosed_volume(m), 0.0);
    EXPECT_LT(needle_faces(m, kNeedleCornerDeg).needles, needle_faces(in, kNeedleCornerDeg).needles / 10);
}

TEST(Remesh, AttemptsOutOfTimeInGmshsParametrizationEndTheRun) {
    // Gmsh's split of a surface for its parametrization can go on for ever on poor triangles (the
    // fused propeller STL: 12 minutes in one attempt). Each attempt tries it in a child process
    // under RemeshParams::classify_seconds; two attempts in a row out of time end the run (here
    // a budget no classification meets), with the reason, instead of eight more.
    const SurfaceMesh box = lattice_box(1, 6, 1);
    RemeshParams p;
    p.classify_seconds = 1e-6;
    RemeshReport rep;
    try {
        remesh_surface(box, p, "box.stl", &rep);
        FAIL() << "remeshed within a budget no classification meets";
    } catch (const BackendError& e) {
        const std::string m = e.what();
        test::expect_contains(m,
                              {"did not end within 1e-06 s",
                               "Two attempts in a row ran out of time in Gmsh (its parametrization or its meshing)"});
        EXPECT_EQ(m.find("at 22.5 degrees"), std::string::npos) << m;  // the third attempt was not made
    }
    p.classify_seconds = 0.0;  // the default budget: it remeshes
    EXPECT_GT(remesh_surface(box, p, "box.stl").num_faces(), 0);
}

TEST(Remesh, AttemptsOutOfTimeInGmshsMeshingEndTheRunToo) {
    // Gmsh's meshing of the new surfaces can refine for ever where it parametrizes them badly (a
    // helicopter's BRepMesh STL: past 20 minutes and 2 GB in one attempt). It runs in a child
    // process under RemeshParams::mesh_seconds, and runs out of it count as the classification's.
    const SurfaceMesh box = lattice_box(1, 6, 1);
    RemeshParams p;
    p.mesh_seconds = 1e-6;
    const std::string m = test::error_message<BackendError>([&] { remesh_surface(box, p, "box.stl"); });
    test::expect_contains(m, {"Gmsh's meshing of the surfaces did not end within 1e-06 s",
                              "Two attempts in a row ran out of time in Gmsh"});
    EXPECT_EQ(m.find("at 22.5 degrees"), std::string::npos) << m;
}

TEST(Remesh, SizeDefaultsToTheInputsMedianEdgeAndQuadsOnRequest) {
    // A box of 0.25 squares split in two: median edge 0.25 (the diagonals are the longer third).
    const SurfaceMesh box = lattice_box(4, 4, 4);
    RemeshReport rep;
    const SurfaceMesh tri = remesh_surface(box, {}, "box", &rep);
    EXPECT_DOUBLE_EQ(rep.size, 0.25);
    EXPECT_NEAR(median_edge_length(tri), 0.25, 0.05);
    RemeshParams q;
    q.quads = true;
    q.size = 0.1;
    const SurfaceMesh quads = remesh_surface(box, q, "box");
    EXPECT_TRUE(test::closed_manifold(quads));
    EXPECT_GT(quads.num_quads(), 4 * quads.num_triangles());
    EXPECT_NEAR(test::enclosed_volume(quads), 1.0, 1e-9);
}

TEST(Remesh, TwoPatchesKeepTheirNamesTheirSeamAndTheirOrientation) {
    // A sphere (radius 1) whose upper half is patch "top": the patches' boundary is a zigzag of
    // the old edges within one old edge length of the equator.
    SurfaceMesh s = icosphere(Vec3::Zero(), 1.0, 3, {"bottom", PatchKind::Wall});
    s.patches.push_back({"top", PatchKind::Symmetry});
    for (Index f = 0; f < s.num_faces(); ++f)
        if (face_centroid(s, s.points, f).z() > 0.0) s.face_patch[f] = 1;
    const double h = median_edge_length(s);
    RemeshParams p;
    p.size = 0.1;
    const SurfaceMesh m = remesh_surface(s, p, "sphere");
    check_surface(m, "remeshed");
    EXPECT_TRUE(test::closed_manifold(m));
    ASSERT_EQ(m.patches.size(), 2u);
    EXPECT_EQ(m.patches[0].name, "bottom");
    EXPECT_EQ(m.patches[1].name, "top");
    EXPECT_EQ(m.patches[1].kind, PatchKind::Symmetry);
    std::array<Index, 2> count{0, 0};
    for (Index f = 0; f < m.num_faces(); ++f) {
        const Index patch = m.face_patch[f];
        ++count[static_cast<std::size_t>(patch)];
        const double z = face_centroid(m, m.points, f).z();
        if (std::abs(z) > h) {
            EXPECT_EQ(patch, z > 0 ? 1 : 0) << f << " at z " << z;
        }
        // Out of the sphere, as the old faces were.
        EXPECT_GT(face_area_vector(m, f).dot(face_centroid(m, m.points, f)), 0.0) << f;
    }
    EXPECT_GT(count[0], 300);
    EXPECT_GT(count[1], 300);
    // Where the patches meet, an edge of the new faces lies on the old seam.
    for (Index f = 0; f < m.num_faces(); ++f)
        for (Index i = 0, k = m.face_size(f); i < k; ++i) {
            const Vec3& a = m.points[static_cast<std::size_t>(m.face_node(f, i))];
            EXPECT_NEAR(a.norm(), 1.0, 0.02);  // on the old facets: within their sag of the sphere
        }
    // The new faces are chords of the old facets: a little less volume, never more.
    EXPECT_LT(test::enclosed_volume(m), test::enclosed_volume(s));
    EXPECT_GT(test::enclosed_volume(m), 0.99 * test::enclosed_volume(s));
}

TEST(Remesh, SameInputSameMesh) {
    const SurfaceMesh box = lattice_box(1, 30, 2, 2.0);
    RemeshParams p;
    p.size = 0.15;
    const SurfaceMesh a = remesh_surface(box, p, "box"), b = remesh_surface(box, p, "box");
    EXPECT_EQ(a.points, b.points);
    EXPECT_EQ(a.face_nodes, b.face_nodes);
    EXPECT_EQ(a.face_patch, b.face_patch);
}

TEST(Remesh, LargeOrSmallCoordinatesMeshAlike) {
    // Gmsh's tolerances follow its model's size, which it does not compute for a model made
    // through its API: the same box in millimetres and in kilometres gives the same faces, to
    // the rounding of its coordinates.
    const SurfaceMesh box = lattice_box(1, 20, 1);
    RemeshParams p;
    p.size = 0.2;
    const SurfaceMesh unit = remesh_surface(box, p, "box");
    for (double scale : {1e-3, 1e3}) {
        SurfaceMesh big = box;
        for (Vec3& x : big.points) x *= scale;
        RemeshParams q = p;
        q.size = p.size * scale;
        const SurfaceMesh m = remesh_surface(big, q, "box");
        EXPECT_NEAR(m.num_faces(), unit.num_faces(), 0.02 * unit.num_faces()) << scale;
        EXPECT_EQ(needle_faces(m, kNeedleCornerDeg).needles, 0) << scale;
        EXPECT_NEAR(test::enclosed_volume(m), scale * scale * scale, 1e-9 * scale * scale * scale) << scale;
    }
}

TEST(Remesh, BadParametersAreRefused) {
    const SurfaceMesh box = lattice_box(2, 2, 2);
    auto with = [&](auto&& set) {
        RemeshParams p;
        set(p);
        return [&box, p] { remesh_surface(box, p, "part.stl"); };
    };
    test::expect_error<InputError>(with([](RemeshParams& p) { p.size = -1; }), {"part.stl", "size", "-1"});
    test::expect_error<InputError>(with([](RemeshParams& p) { p.size = std::nan(""); }), {"part.stl", "size"});
    test::expect_error<InputError>(with([](RemeshParams& p) {
                                       p.size = 0.1;
                                       p.size_min = 0.2;
                                   }),
                                   {"part.stl", "size_min", "0.2"});
    test::expect_error<InputError>(with([](RemeshParams& p) { p.feature_angle_deg = 0; }),
                                   {"part.stl", "feature angle", "between 0 and 180"});
    test::expect_error<InputError>(with([](RemeshParams& p) { p.feature_angle_deg = 180; }),
                                   {"part.stl", "feature angle"});
    test::expect_error<InputError>(with([](RemeshParams& p) { p.algorithm = 3; }), {"part.stl", "algorithm 3"});
    test::expect_error<InputError>(with([](RemeshParams& p) { p.curvature_points = -2; }),
                                   {"part.stl", "curvature_points"});
    test::expect_error<InputError>([] { remesh_surface(SurfaceMesh{}, {}, "empty.stl"); }, {"empty.stl", "no faces"});
}

}  // namespace
}  // namespace strata

namespace strata {
namespace {

TEST(Remesh, WallsTooCoarseForTheFirstLayerAreMeshedAgainFiner) {
    // The unit box remeshed at 0.25 under a first layer of 5e-5: prisms near 3000 (checkMesh
    // fails above 1000). The route is run again with the walls at 0.035: every face under 1000.
    const SurfaceMesh box = lattice_box(4, 4, 4);
    RemeshParams p;
    p.size = 0.25;
    const SurfaceMesh coarse = remesh_surface(box, p, "box");
    EXPECT_GT(test::worst_wall_aspect(coarse, 5e-5), 1000.0);
    p.first_height = 5e-5;
    RemeshReport rep;
    const SurfaceMesh fine = remesh_surface(box, p, "box", &rep);
    EXPECT_TRUE(test::closed_manifold(fine));
    EXPECT_NEAR(test::enclosed_volume(fine), 1.0, 1e-9);
    // The prediction is the right prism's where the columns stand square (test::worst_wall_aspect),
    // more where they lean over the box's edges (45 degrees there: at most sqrt(2) more).
    EXPECT_GE(rep.walls.worst_before, test::worst_wall_aspect(coarse, 5e-5));
    EXPECT_LE(rep.walls.worst_before, std::sqrt(2.0) * test::worst_wall_aspect(coarse, 5e-5));
    EXPECT_GE(rep.walls.worst_after, test::worst_wall_aspect(fine, 5e-5));
    EXPECT_LE(rep.walls.worst_after, std::sqrt(2.0) * test::worst_wall_aspect(fine, 5e-5));
    EXPECT_LE(rep.walls.worst_after, 1000.0);
    EXPECT_GE(rep.walls.surfaces, 6);
    EXPECT_NEAR(rep.walls.cap, 0.035, 1e-12);
    EXPECT_EQ(rep.faces_after, fine.num_faces());
    EXPECT_GT(fine.num_faces(), 20 * coarse.num_faces());
    // A symmetry patch is not a wall: nothing to size, nothing changes.
    SurfaceMesh plane = box;
    plane.patches[0].kind = PatchKind::Symmetry;
    const SurfaceMesh kept = remesh_surface(plane, p, "box", &rep);
    EXPECT_EQ(kept.points, coarse.points);
    EXPECT_EQ(rep.walls.worst_before, 0.0);
    // Over the budget: kept, and said.
    p.wall_faces_budget = 5000;
    const SurfaceMesh over = remesh_surface(box, p, "box", &rep);
    EXPECT_EQ(over.points, coarse.points);
    EXPECT_TRUE(rep.walls.over_budget);
    p = {};
    p.max_aspect_ratio = 3.0;
    EXPECT_THROW(remesh_surface(box, p, "box"), InputError);
}

}  // namespace
}  // namespace strata
