// CAD input and surface meshing (cad.h) on the real geometries of examples/data and small
// files of tests/data. Closedness is computed here from edge use counts, independently of
// topology.h, so these tests do not lean on another unit's code.
#include <strata/core/error.h>
#include <strata/core/face_geometry.h>
#include <strata/core/solver_checks.h>
#include <strata/geometry/intersections.h>
#include <strata/geometry/topology.h>
#include <strata/io/gmsh_session.h>
#include <strata/surface/cad.h>
#include <strata/surface/prepare.h>

#include "test_support.h"

#include <gtest/gtest.h>

#include <sys/stat.h>
#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <numeric>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace strata {
namespace {

using test::example_data;
using test::ScratchDir;
using test::test_data;

// Undirected edge → number of faces using it.
std::map<std::pair<Index, Index>, int> edge_uses(const SurfaceMesh& m) {
    std::map<std::pair<Index, Index>, int> uses;
    for (Index f = 0; f < m.num_faces(); ++f) {
        const Index n = m.face_size(f);
        for (Index k = 0; k < n; ++k) {
            const Index a = m.face_node(f, k);
            const Index b = m.face_node(f, (k + 1) % n);
            ++uses[{std::min(a, b), std::max(a, b)}];
        }
    }
    return uses;
}

// Every undirected edge used by exactly two faces: a closed, conforming surface.
::testing::AssertionResult closed(const SurfaceMesh& m) {
    if (m.num_faces() == 0) return ::testing::AssertionFailure() << "no faces";
    int bad = 0;
    std::pair<Index, Index> first{};
    int first_count = 0;
    for (const auto& [edge, n] : edge_uses(m))
        if (n != 2 && bad++ == 0) {
            first = edge;
            first_count = n;
        }
    if (bad == 0) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << bad << " edges not used exactly twice, e.g. (" << first.first << ", "
                                         << first.second << ") used " << first_count << " times";
}

// Connected components of faces joined through shared nodes.
int components(const SurfaceMesh& m) {
    std::vector<Index> parent(m.points.size());
    std::iota(parent.begin(), parent.end(), 0);
    auto find = [&](Index i) {
        while (parent[i] != i) i = parent[i] = parent[parent[i]];
        return i;
    };
    std::vector<bool> used(m.points.size(), false);
    for (Index f = 0; f < m.num_faces(); ++f) {
        used[m.face_node(f, 0)] = true;
        for (Index k = 1; k < m.face_size(f); ++k) {
            used[m.face_node(f, k)] = true;
            parent[find(m.face_node(f, k))] = find(m.face_node(f, 0));
        }
    }
    int n = 0;
    for (Index i = 0; i < m.num_points(); ++i) n += used[i] && find(i) == i;
    return n;
}

struct Box3 {
    Vec3 lo, hi;
};
Box3 bounds(const SurfaceMesh& m) {
    Box3 b{m.points.at(0), m.points.at(0)};
    for (const Vec3& p : m.points) {
        b.lo = b.lo.cwiseMin(p);
        b.hi = b.hi.cwiseMax(p);
    }
    return b;
}

// Faces per patch, split into triangles and quads.
std::vector<std::array<int, 2>> tri_quad_per_patch(const SurfaceMesh& m) {
    std::vector<std::array<int, 2>> n(m.patches.size(), {0, 0});
    for (Index f = 0; f < m.num_faces(); ++f) ++n.at(m.face_patch[f])[m.face_size(f) == 4 ? 1 : 0];
    return n;
}

// Basic invariants every extracted mesh must have, whatever the input.
void expect_well_formed(const SurfaceMesh& m) {
    ASSERT_GT(m.num_faces(), 0);
    ASSERT_EQ(m.face_patch.size(), static_cast<std::size_t>(m.num_faces()));
    std::vector<bool> used(m.points.size(), false);
    for (Index f = 0; f < m.num_faces(); ++f) {
        ASSERT_TRUE(m.face_size(f) == 3 || m.face_size(f) == 4) << "face " << f;
        ASSERT_GE(m.face_patch[f], 0);
        ASSERT_LT(m.face_patch[f], static_cast<Index>(m.patches.size()));
        std::set<Index> distinct(m.face_begin(f), m.face_end(f));
        ASSERT_EQ(distinct.size(), static_cast<std::size_t>(m.face_size(f))) << "face " << f;
        for (const Index* v = m.face_begin(f); v != m.face_end(f); ++v) {
            ASSERT_GE(*v, 0);
            ASSERT_LT(*v, m.num_points());
            used[*v] = true;
        }
    }
    // No orphan nodes, and nodes shared between surfaces appear once.
    EXPECT_TRUE(std::all_of(used.begin(), used.end(), [](bool b) { return b; }));
    std::set<std::array<double, 3>> coords;
    for (const Vec3& p : m.points) coords.insert({p.x(), p.y(), p.z()});
    EXPECT_EQ(coords.size(), m.points.size()) << "duplicate node coordinates";
    for (const Patch& p : m.patches) EXPECT_EQ(p.kind, PatchKind::Wall) << p.name;
}

std::string write_file(const ScratchDir& dir, const std::string& name, const std::string& text) {
    const std::string path = dir.file(name);
    std::ofstream(path) << text;
    return path;
}

template <class F>
std::string error_text(F&& f) {
    try {
        f();
    } catch (const std::exception& e) {
        return e.what();
    }
    return "<no exception>";
}

// ---------------------------------------------------------------------------------------

TEST(CadFile, RecognisesExtensionsCaseInsensitively) {
    for (const char* p :
         {"a.step", "a.stp", "b/A.STEP", "a.Stp", "a.iges", "a.IGS", "a.brep", "a.BRP", "x/y.geo", "y.GEO"})
        EXPECT_TRUE(is_cad_file(p)) << p;
    for (const char* p : {"a.stl", "a.msh", "step", "a.step.txt", "a", "a.geo_unrolled", ""})
        EXPECT_FALSE(is_cad_file(p)) << p;
}

TEST(MeshCad, OneraM6TrianglesAreClosedWithOnePatchPerFace) {
    const SurfaceMesh m = mesh_cad(example_data("onera_m6_sharp_te.stp"), {});
    expect_well_formed(m);
    EXPECT_EQ(m.num_triangles(), m.num_faces());
    ASSERT_EQ(m.patches.size(), 11u);
    for (int s = 1; s <= 11; ++s) EXPECT_NE(find_patch(m, "surface_" + std::to_string(s)), kNone) << s;
    for (const auto& [tri, quad] : tri_quad_per_patch(m)) EXPECT_GT(tri + quad, 0);
    EXPECT_TRUE(closed(m));
    EXPECT_EQ(components(m), 1);
    // The wing in millimetres: root chord 806 at y = 0, span 1196 plus the rounded tip,
    // maximum thickness 78 mm (the STEP declares mm; OpenCASCADE keeps it).
    const Box3 b = bounds(m);
    EXPECT_NEAR(b.lo.x(), 0.0, 1e-3);
    EXPECT_NEAR(b.hi.x(), 1146.57, 0.1);
    EXPECT_NEAR(b.lo.y(), 0.0, 1e-3);
    EXPECT_NEAR(b.hi.y(), 1218.4, 1.0);
    EXPECT_NEAR(b.lo.z(), -39.4, 0.5);
    EXPECT_NEAR(b.hi.z(), 39.4, 0.5);
}

TEST(MeshCad, OneraM6QuadsAreMostlyQuads) {
    CadParams p;
    p.size = 40.0;
    p.elements = SurfaceElements::Quads;
    RecombinationReport r;
    const SurfaceMesh m = mesh_cad(example_data("onera_m6_sharp_te.stp"), p, nullptr, nullptr, nullptr, &r);
    expect_well_formed(m);
    EXPECT_GT(m.num_quads(), 0.8 * m.num_faces()) << m.num_quads() << " of " << m.num_faces();
    EXPECT_TRUE(closed(m));
    EXPECT_EQ(r.blossom_failure, "");  // Blossom did it
}

TEST(MeshCad, SimpleRecombinationPairsFewerTriangles) {
    // CadParams::simple_recombination: Gmsh's simple algorithm instead of Blossom, over a
    // script's own choice too (the M6 has none; a .geo saying Blossom is below).
    CadParams p;
    p.size = 40.0;
    p.elements = SurfaceElements::Quads;
    const SurfaceMesh blossom = mesh_cad(example_data("onera_m6_sharp_te.stp"), p);
    p.simple_recombination = true;
    const SurfaceMesh simple = mesh_cad(example_data("onera_m6_sharp_te.stp"), p);
    expect_well_formed(simple);
    EXPECT_TRUE(closed(simple));
    EXPECT_GT(simple.num_quads(), simple.num_faces() / 2);
    EXPECT_GT(simple.num_triangles(), blossom.num_triangles());
    ScratchDir dir("cad_simple_recombination");
    const std::string geo = dir.file("blossom.geo");
    std::ofstream(geo) << "SetFactory(\"OpenCASCADE\");\nBox(1) = {0, 0, 0, 1, 1, 1};\n"
                          "Mesh.RecombinationAlgorithm = 1;\nMesh.RecombineAll = 1;\n";
    CadParams q;
    q.size = 0.13;
    const SurfaceMesh box_blossom = mesh_cad(geo, q);
    q.simple_recombination = true;
    const SurfaceMesh box_simple = mesh_cad(geo, q);
    EXPECT_GT(box_blossom.num_quads(), 0);
    EXPECT_GT(box_simple.num_quads(), 0);
    EXPECT_NE(box_simple.num_triangles(), box_blossom.num_triangles());
}

TEST(MeshCad, GmshAbortsAreErrorsAndItsMeshingCanBeStopped) {
    // Gmsh meshes the surfaces in a child process whose mesh is brought back
    // (generate_in_child). tests/data/cli_gmsh_aborts.geo makes Gmsh throw out of its OpenMP
    // loop, which ended this test program (and a Python or FreeCAD session); now it is an error
    // naming Gmsh's message.
    CadParams p;
    test::expect_error<BackendError>(
        [&] { mesh_cad(test_data("cli_gmsh_aborts.geo"), p); },
        {"cli_gmsh_aborts.geo", "Gmsh aborts (The 1D mesh seems not to be forming a closed loop)",
         "nothing else is lost"});
    // Gmsh's meshing can be stopped, where in this process it could not: the child is killed.
    struct Stop : Progress {
        void report(std::string_view, double) override {}
        bool cancelled() const override { return true; }
    } stop;
    EXPECT_THROW(mesh_cad(example_data("onera_m6_sharp_te.stp"), p, nullptr, nullptr, nullptr, nullptr, &stop),
                 Cancelled);
}

/// \p path fused and meshed in quads at the default size, where Gmsh's Blossom would end the
/// process: found in a child first, the surfaces are recombined with Gmsh's simple algorithm,
/// and the report says how Blossom failed (\p failure in its text).
void expect_simple_quads_where_blossom_fails(const std::string& path, const std::string& failure) {
    CadParams p;
    p.fuse = true;
    p.elements = SurfaceElements::Quads;
    RecombinationReport r;
    const SurfaceMesh m = mesh_cad(path, p, nullptr, nullptr, nullptr, &r);
    EXPECT_NE(r.blossom_failure.find(failure), std::string::npos) << r.blossom_failure;
    expect_well_formed(m);
    EXPECT_GT(m.num_quads(), m.num_faces() / 2) << m.num_quads() << " of " << m.num_faces();
    EXPECT_TRUE(closed(m));
}

TEST(MeshCad, QuadsWhereBlossomWouldAbortTheProcess) {
    // The sphere with three cones fused (examples/sweep/spiky.geo): Gmsh's Blossom finds no
    // perfect matching on a cone and throws out of Gmsh's OpenMP loop, which ended the process
    // (this test program with it).
    expect_simple_quads_where_blossom_fails(example_data("../sweep/spiky.geo"), "Perfect Match failed");
}

TEST(MeshCad, QuadsWhereBlossomWouldCrashTheProcess) {
    // A body with a mirror on a thin stalk: Gmsh 4.8's Blossom crashes (a segmentation fault, no
    // words of its own), which ended the process.
    expect_simple_quads_where_blossom_fails(test_data("cad_mirror_on_stalk.geo"), "crashes (signal 11)");
}

TEST(MeshCad, MixedPutsQuadsOnTheChosenSurfaceOnly) {
    CadParams p;
    p.elements = SurfaceElements::Mixed;
    p.quad_surfaces = {10};  // one of the two large wing skins
    const SurfaceMesh m = mesh_cad(example_data("onera_m6_sharp_te.stp"), p);
    expect_well_formed(m);
    const Index chosen = find_patch(m, "surface_10");
    ASSERT_NE(chosen, kNone);
    const auto counts = tri_quad_per_patch(m);
    for (std::size_t i = 0; i < counts.size(); ++i) {
        if (static_cast<Index>(i) == chosen) {
            EXPECT_GT(counts[i][1], 4 * counts[i][0]) << "quads on surface_10";
        } else {
            EXPECT_EQ(counts[i][1], 0) << m.patches[i].name;
        }
    }
    EXPECT_TRUE(closed(m));  // quads and triangles conform along the skin's edges
}

TEST(MeshCad, UnknownQuadSurfaceListsTheValidTags) {
    CadParams p;
    p.elements = SurfaceElements::Mixed;
    p.quad_surfaces = {3, 99};
    const std::string path = example_data("onera_m6_sharp_te.stp");
    EXPECT_THROW(mesh_cad(path, p), InputError);
    const std::string what = error_text([&] { mesh_cad(path, p); });
    test::expect_contains(what, {"99", "1-11", "onera_m6_sharp_te.stp"});
}

TEST(MeshCad, WingFuselageFusedIsOneClosedSurface) {
    CadParams p;
    p.fuse = true;
    const SurfaceMesh fused = mesh_cad(example_data("wing_fuselage.step"), p);
    expect_well_formed(fused);
    EXPECT_TRUE(closed(fused));
    EXPECT_EQ(components(fused), 1);

    // Unfused: the two solids are meshed as they are, two closed surfaces crossing each other
    // (no shared node), with the wing's root and the fuselage inside each other.
    const SurfaceMesh apart = mesh_cad(example_data("wing_fuselage.step"), {});
    expect_well_formed(apart);
    EXPECT_TRUE(closed(apart));
    EXPECT_EQ(components(apart), 2);
    EXPECT_EQ(apart.patches.size(), 16u);
    EXPECT_LT(fused.patches.size(), apart.patches.size());  // the Boolean removed and merged faces
    EXPECT_LT(fused.num_faces(), apart.num_faces());        // the internal parts are gone

    // The union spans both bodies; the STEP is in metres and stays in metres (OpenCASCADE
    // alone gives mm: it came out 1000 times larger).
    const Box3 b = bounds(fused);
    EXPECT_NEAR(b.lo.y(), -0.4, 5e-4);
    EXPECT_NEAR(b.hi.y(), 0.4, 5e-4);
    EXPECT_NEAR(b.lo.x(), -0.13785, 5e-4);
}

TEST(MeshCad, FusedOnSeveralThreadsIsTheSameSurface) {
    // OpenCASCADE's Boolean union runs in parallel above one thread (Geometry.OCCParallel): the
    // rocket's body, fins and nozzle fused give the same nodes and faces, bit for bit.
    CadParams p;
    p.fuse = true;
    p.size = 0.05;
    p.threads = 1;
    const SurfaceMesh one = mesh_cad(example_data("../sweep/rocket.geo"), p);
    p.threads = 2;
    const SurfaceMesh two = mesh_cad(example_data("../sweep/rocket.geo"), p);
    expect_well_formed(two);
    EXPECT_TRUE(closed(two));
    EXPECT_EQ(one.points, two.points);
    EXPECT_EQ(one.face_offsets, two.face_offsets);
    EXPECT_EQ(one.face_nodes, two.face_nodes);
    EXPECT_EQ(one.face_patch, two.face_patch);
    p.threads = -1;
    EXPECT_THROW(mesh_cad(example_data("../sweep/rocket.geo"), p), InputError);
}

TEST(MeshCad, StepAndIgesAreReadInTheUnitTheyDeclareOrTheOneAsked) {
    // wing_fuselage.step declares metres, onera_m6_sharp_te.stp millimetres, the IGES box mm.
    CadUnits u;
    CadParams p;
    // Gmsh integrates a size that varies along a curve to an absolute precision, so the narrow
    // faces' sizes (CadParams::narrow_face_ratio) do not scale exactly: compared without them.
    p.narrow_face_ratio = 0.0;
    const SurfaceMesh m = mesh_cad(example_data("wing_fuselage.step"), p, &u);
    EXPECT_EQ(u.unit, "m");
    EXPECT_EQ(u.declared, "m");
    EXPECT_NEAR(bounds(m).hi.y(), 0.4, 5e-4);
    p.units = "mm";
    const SurfaceMesh mm = mesh_cad(example_data("wing_fuselage.step"), p, &u);
    EXPECT_EQ(u.unit, "mm");
    EXPECT_EQ(u.declared, "m");
    EXPECT_NEAR(bounds(mm).hi.y(), 400.0, 0.5);
    // The same model 1000 times larger, meshed alike (the default size is a share of the
    // model's diagonal): as many faces, 10^6 times the area.
    EXPECT_EQ(mm.num_faces(), m.num_faces());
    double area_m = 0.0, area_mm = 0.0;
    for (Index f = 0; f < m.num_faces(); ++f) area_m += face_area_vector(m, f).norm();
    for (Index f = 0; f < mm.num_faces(); ++f) area_mm += face_area_vector(mm, f).norm();
    EXPECT_NEAR(area_mm / area_m, 1e6, 1e3);
    p.units = "in";
    const SurfaceMesh in = mesh_cad(example_data("wing_fuselage.step"), p, &u);
    EXPECT_NEAR(bounds(in).hi.y(), 400.0 / 25.4, 0.5 / 25.4);
    mesh_cad(example_data("onera_m6_sharp_te.stp"), {}, &u);
    EXPECT_EQ(u.unit, "mm");
    EXPECT_EQ(u.declared, "mm");
    const SurfaceMesh box = mesh_cad(test::test_data("cad_box_with_hole.igs"), {}, &u);
    EXPECT_EQ(u.declared, "mm");
    EXPECT_NEAR(bounds(box).hi.x(), 2.0, 1e-6);
    p.units = "cm";
    EXPECT_NEAR(bounds(mesh_cad(test::test_data("cad_box_with_hole.igs"), p, &u)).hi.x(), 0.2, 1e-7);
    // No unit to convert from: refused, naming the file; an unknown unit: refused.
    p.units = "m";
    const std::string brep = error_text([&] { mesh_cad(example_data("bl3d_4_box_notch_concave_corner.brep"), p); });
    test::expect_contains(brep, {"declares no length unit", "bl3d_4_box_notch_concave_corner.brep"});
    p.units = "parsec";
    const std::string unknown = error_text([&] { mesh_cad(example_data("wing_fuselage.step"), p); });
    test::expect_contains(unknown, {"parsec", "mm, cm, m"});
}

/// A closed, well-formed surface with \p patches patches; its bounding box.
Box3 expect_closed_with_patches(const SurfaceMesh& m, std::size_t patches) {
    expect_well_formed(m);
    EXPECT_EQ(m.patches.size(), patches);
    EXPECT_TRUE(closed(m));
    return bounds(m);
}

TEST(MeshCad, BrepBenchmarksMeshClosed) {
    const SurfaceMesh notch = mesh_cad(example_data("bl3d_4_box_notch_concave_corner.brep"), {});
    const Box3 b = expect_closed_with_patches(notch, 11);
    EXPECT_NEAR(b.lo.x(), -0.5, 1e-9);
    EXPECT_NEAR(b.hi.z(), 1.0, 1e-9);

    expect_closed_with_patches(mesh_cad(example_data("bl3d_5_body_fin_in_box.brep"), {}), 13);
}

TEST(MeshCad, ExtensionCaseAndBrpAreAccepted) {
    ScratchDir dir("cad_ext");
    const std::string upper = dir.file("NOTCH.BRP");
    std::filesystem::copy_file(example_data("bl3d_4_box_notch_concave_corner.brep"), upper);
    const SurfaceMesh a = mesh_cad(upper, {});
    const SurfaceMesh b = mesh_cad(example_data("bl3d_4_box_notch_concave_corner.brep"), {});
    EXPECT_EQ(a.num_faces(), b.num_faces());
    EXPECT_EQ(a.num_points(), b.num_points());
}

TEST(MeshCad, PartsCloserThanTheDefaultSizeAreMeshedFinerUntilNoFacesCross) {
    // The sweep's airliner: the default size (0.777) left its thin parts' sides on one chord,
    // and at half of it (0.388) the faces of a nacelle and its pylon crossed, which the layers
    // refuse ("the surface intersects itself"). Unasked, the size is halved again (0.194).
    // With its narrow faces meshed at their width (the default), halving once is enough.
    const std::string path = example_data("../sweep/airliner.geo");
    CadParams p;
    p.fuse = true;
    p.narrow_face_ratio = 0.0;
    WallSizeReport walls;
    const SurfaceMesh m = mesh_cad(path, p, nullptr, &walls);
    EXPECT_TRUE(self_intersections(m).empty());
    EXPECT_NEAR(walls.thin_size, walls.default_size / 4.0, 1e-12);
    p.narrow_face_ratio = CadParams{}.narrow_face_ratio;
    WallSizeReport narrow;
    EXPECT_TRUE(self_intersections(mesh_cad(path, p, nullptr, &narrow)).empty());
    EXPECT_GT(narrow.narrow_faces, 0);
    EXPECT_NEAR(narrow.thin_size, narrow.default_size / 2.0, 1e-12);
}

TEST(MeshCad, AThinPartUnderTheDefaultSizeIsMeshedFiner) {
    // The sweep's propeller: at the default size (a twentieth of the diagonal, 0.127) Gmsh meshed
    // both sides of the blades' thin outer parts through the same nodes, one chord across (edges
    // of four faces), and the run stopped on a non-manifold edge. Unasked, the size is halved
    // until no edge has more than two faces; asked, it is the user's. (Without the narrow faces'
    // sizes: with them, the blades' narrow tip faces are meshed at their width and no edge has
    // more than two faces at the default size.)
    auto most_faces_on_an_edge = [](const SurfaceMesh& m) {
        const EdgeTable et = edge_table(m);
        Index most = 0;
        for (Index e = 0; e < et.faces.rows(); ++e) most = std::max(most, et.faces.row_size(e));
        return most;
    };
    const std::string path = example_data("../sweep/propeller.geo");
    CadParams p;
    p.fuse = true;
    WallSizeReport narrow;
    EXPECT_EQ(most_faces_on_an_edge(mesh_cad(path, p, nullptr, &narrow)), 2);
    EXPECT_GT(narrow.narrow_faces, 0);
    EXPECT_EQ(narrow.thin_size, 0.0);
    p.narrow_face_ratio = 0.0;
    WallSizeReport walls;
    const SurfaceMesh m = mesh_cad(path, p, nullptr, &walls);
    EXPECT_EQ(most_faces_on_an_edge(m), 2);
    EXPECT_NEAR(walls.default_size, 0.1266, 1e-3);
    EXPECT_NEAR(walls.thin_size, walls.default_size / 2.0, 1e-12);
    p.size = walls.default_size;
    WallSizeReport asked;
    EXPECT_GT(most_faces_on_an_edge(mesh_cad(path, p, nullptr, &asked)), 2);
    EXPECT_EQ(asked.thin_size, 0.0);
    // Where no size mends it (two boxes sharing a face: three faces to an edge round it), the
    // default size and its mesh stay, not one 64 times finer.
    ScratchDir dir("cad_thin_part");
    const std::string shared = dir.file("shared_face.geo");
    std::ofstream(shared) << "SetFactory(\"OpenCASCADE\");\nBox(1) = {0, 0, 0, 1, 1, 1};\nBox(2) = {1, 0, 0, 1, 1, "
                             "1};\nBooleanFragments{ Volume{1}; Delete; }{ Volume{2}; Delete; }\n";
    WallSizeReport none;
    const SurfaceMesh boxes = mesh_cad(shared, {}, nullptr, &none);
    EXPECT_EQ(most_faces_on_an_edge(boxes), 3);
    EXPECT_EQ(none.thin_size, 0.0);
    CadParams at_default;
    at_default.size = std::sqrt(6.0) / 20.0;                                     // a twentieth of the diagonal, asked
    EXPECT_LT(boxes.num_faces(), 2 * mesh_cad(shared, at_default).num_faces());  // halved once: 4 times
}

/// The mean longest edge of the faces of \p m on the patches named \p names.
double mean_longest_edge(const SurfaceMesh& m, const std::vector<std::string>& names) {
    std::set<Index> on;
    for (const std::string& n : names) on.insert(find_patch(m, n));
    double sum = 0.0;
    Index count = 0;
    for (Index f = 0; f < m.num_faces(); ++f) {
        if (!on.count(m.face_patch[static_cast<std::size_t>(f)])) continue;
        double longest = 0.0;
        const Index n = m.face_size(f);
        for (Index i = 0; i < n; ++i)
            longest = std::max(longest, (m.points[m.face_node(f, i)] - m.points[m.face_node(f, (i + 1) % n)]).norm());
        sum += longest;
        ++count;
    }
    return count > 0 ? sum / static_cast<double>(count) : 0.0;
}

TEST(MeshCad, NarrowFacesGetTrianglesAboutTheirWidthNotSlivers) {
    // The ONERA M6 STEP closes its sharp trailing edge with two strips 3.47 mm wide along the
    // span (surfaces 5 and 8). At size 30 each is one row of triangles 30 long; meshed at 4
    // times their width they are about 14 long.
    const std::string path = example_data("onera_m6_sharp_te.stp");
    CadParams p;
    p.size = 30.0;
    WallSizeReport r;
    const SurfaceMesh on = mesh_cad(path, p, nullptr, &r);
    EXPECT_EQ(r.narrow_faces, 2);
    EXPECT_NEAR(r.narrowest, 3.47, 0.01);
    EXPECT_NEAR(r.narrow_size, 4.0 * r.narrowest, 1e-9);
    EXPECT_FALSE(r.narrow_over_budget);
    CadParams off_params = p;
    off_params.narrow_face_ratio = 0.0;
    WallSizeReport off_report;
    const SurfaceMesh off = mesh_cad(path, off_params, nullptr, &off_report);
    EXPECT_EQ(off_report.narrow_faces, 0);
    const std::vector<std::string> strips{"surface_5", "surface_8"};
    EXPECT_LT(mean_longest_edge(on, strips), 20.0);
    EXPECT_GT(mean_longest_edge(off, strips), 25.0);
    expect_well_formed(on);
    EXPECT_TRUE(closed(on));
    // Over the faces budget the strips are meshed at the size, and the report says why.
    CadParams tight = p;
    tight.wall_faces_budget = 100.0;
    WallSizeReport over;
    EXPECT_EQ(mesh_cad(path, tight, nullptr, &over).num_faces(), off.num_faces());
    EXPECT_TRUE(over.narrow_over_budget);
    EXPECT_GT(over.narrow_faces_estimate, 100.0);
    p.narrow_face_ratio = 0.5;
    EXPECT_THROW(mesh_cad(path, p), InputError);
}

TEST(MeshCad, APlateEdgeTooThinForTheSmallestSizeIsNotRefined) {
    // The sweep's thin fin: a plate 1 mm thick whose edge faces would need triangles of 4 mm
    // where the smallest size is an eighth of 0.157: refined, they would stay slivers, only
    // more of them. A thin tube is narrow along its circumference, not across: not refined
    // either (a cylinder's seam is not an edge of it).
    const std::string path = example_data("../sweep/thinfin.geo");
    WallSizeReport r;
    const SurfaceMesh m = mesh_cad(path, {}, nullptr, &r);
    EXPECT_EQ(r.narrow_faces, 0);
    CadParams off;
    off.narrow_face_ratio = 0.0;
    EXPECT_EQ(m.num_faces(), mesh_cad(path, off).num_faces());
    ScratchDir dir("cad_thin_tube");
    const std::string tube = dir.file("tube.geo");
    std::ofstream(tube) << "SetFactory(\"OpenCASCADE\");\nCylinder(1) = {0, 0, 0, 1, 0, 0, 0.002};\n"
                           "Mesh.MeshSizeMax = 0.1;\n";
    WallSizeReport t;
    mesh_cad(tube, {}, nullptr, &t);
    EXPECT_EQ(t.narrow_faces, 0);
}

TEST(MeshCad, GeoSphereNodesLieOnTheSphere) {
    CadParams p;
    p.size = 0.05;
    const SurfaceMesh m = mesh_cad(test_data("cad_unit_sphere.geo"), p);
    expect_well_formed(m);
    ASSERT_EQ(m.patches.size(), 1u);
    EXPECT_EQ(m.patches[0].name, "surface_1");
    EXPECT_GT(m.num_faces(), 5000);  // 4π / (0.05² √3/4) ≈ 11,600 triangles
    for (Index i = 0; i < m.num_points(); ++i) ASSERT_NEAR(m.points[i].norm(), 1.0, 1e-6) << "node " << i;
    EXPECT_TRUE(closed(m));  // across the sphere's seam and poles too
}

TEST(MeshCad, BuiltInKernelGeoMeshes) {
    const SurfaceMesh m = mesh_cad(example_data("naca0012_wing_between_walls.geo"), {});
    expect_well_formed(m);
    EXPECT_EQ(m.patches.size(), 12u);
    EXPECT_NE(find_patch(m, "surface_14"), kNone);    // the wing's tip cap
    EXPECT_NE(find_patch(m, "surface_1100"), kNone);  // a wall
    EXPECT_TRUE(closed(m));
    const Box3 b = bounds(m);
    EXPECT_NEAR(b.lo.x(), -10.0, 1e-9);
    EXPECT_NEAR(b.hi.y(), 10.0, 1e-9);
    // The script's point size lc = 0.1 on the airfoil (root at y = 0, tip cap at y = 1) is
    // respected under the default cap (1/20 of the diagonal, 1.5): edges near the leading
    // edge are about 0.1 long, not 1.5.
    double shortest_le = 1e9;
    for (const auto& [e, n] : edge_uses(m)) {
        const Vec3& a = m.points[e.first];
        const Vec3& c = m.points[e.second];
        if (a.x() < 0.05 && c.x() < 0.05 && std::abs(a.z()) < 0.1 && a.y() > 0.1 && a.y() < 0.9)
            shortest_le = std::min(shortest_le, (a - c).norm());
    }
    EXPECT_LT(shortest_le, 0.2);
}

TEST(MeshCad, GeoPhysicalGroupsBecomePatches) {
    const SurfaceMesh m = mesh_cad(test_data("cad_box_groups.geo"), {});
    expect_well_formed(m);
    ASSERT_EQ(m.patches.size(), 5u);
    EXPECT_EQ(m.patches[0].name, "inlet");
    EXPECT_EQ(m.patches[1].name, "walls");
    EXPECT_EQ(m.patches[2].name, "physical_7");
    EXPECT_EQ(m.patches[3].name, "surface_2");
    EXPECT_EQ(m.patches[4].name, "surface_6");
    const auto counts = tri_quad_per_patch(m);
    for (std::size_t i = 0; i < counts.size(); ++i) EXPECT_GT(counts[i][0], 0) << m.patches[i].name;
    // "walls" holds two unit faces, the others one: about twice as many triangles.
    EXPECT_GT(counts[1][0], 1.5 * counts[0][0]);
    EXPECT_TRUE(closed(m));
}

TEST(MeshCad, NodesAreNumberedInOrderOfFirstUse) {
    // Gmsh numbers a fresh mesh's nodes points, curves, then surfaces; the CAD import renumbers
    // them as the faces use them (NodeOrder::FirstUse), so each surface's nodes are together.
    const SurfaceMesh m = mesh_cad(test_data("cad_box_groups.geo"), {});
    Index next = 0;
    std::vector<char> seen(static_cast<std::size_t>(m.num_points()), 0);
    for (Index v : m.face_nodes) {
        if (seen[static_cast<std::size_t>(v)]) continue;
        seen[static_cast<std::size_t>(v)] = 1;
        ASSERT_EQ(v, next) << "node " << v << " first used after node " << next - 1;
        ++next;
    }
    EXPECT_EQ(next, m.num_points());
}

TEST(MeshCad, IgesMeshes) {
    const SurfaceMesh m = mesh_cad(test_data("cad_box_with_hole.igs"), {});
    const Box3 b = expect_closed_with_patches(m, 7);
    EXPECT_NEAR(b.lo.x(), 0.0, 1e-6);
    EXPECT_NEAR(b.hi.x(), 2.0, 1e-6);
    EXPECT_NEAR(b.hi.y(), 1.0, 1e-6);
    EXPECT_NEAR(b.hi.z(), 0.5, 1e-6);
    // Nodes on the hole's wall are at radius 0.25 from its axis.
    int on_hole = 0;
    for (const Vec3& p : m.points) {
        const double r = std::hypot(p.x() - 1.0, p.y() - 0.5);
        if (r < 0.3) {
            EXPECT_NEAR(r, 0.25, 1e-6);
            ++on_hole;
        }
    }
    EXPECT_GT(on_hole, 10);
}

/// The unit sphere (.geo) meshed at maximum size \p size and \p curvature_points per 2π.
SurfaceMesh unit_sphere(double size, int curvature_points = 0) {
    CadParams p;
    p.size = size;
    p.curvature_points = curvature_points;
    return mesh_cad(test_data("cad_unit_sphere.geo"), p);
}

TEST(MeshCad, CurvatureRefinementAddsFaces) {
    const SurfaceMesh plain = unit_sphere(0.4), curved = unit_sphere(0.4, 40);
    EXPECT_TRUE(closed(curved));
    // 40 elements per 2π on a unit radius: size 0.157 instead of 0.4.
    EXPECT_GT(curved.num_faces(), 2 * plain.num_faces()) << curved.num_faces() << " vs " << plain.num_faces();
}

TEST(MeshCad, HalvingTheSizeRoughlyQuadruplesTheFaces) {
    const SurfaceMesh coarse = unit_sphere(0.2), fine = unit_sphere(0.1);
    const double ratio = static_cast<double>(fine.num_faces()) / coarse.num_faces();
    EXPECT_GT(ratio, 3.0);
    EXPECT_LT(ratio, 5.5);
}

TEST(MeshCad, DefaultSizeIsATwentiethOfTheDiagonal) {
    // Unit sphere: diagonal 2√3, size 0.173; the same as asking for that size.
    const SurfaceMesh automatic = mesh_cad(test_data("cad_unit_sphere.geo"), {});
    CadParams p;
    p.size = 2.0 * std::sqrt(3.0) / 20.0;
    const SurfaceMesh explicit_size = mesh_cad(test_data("cad_unit_sphere.geo"), p);
    EXPECT_EQ(automatic.num_faces(), explicit_size.num_faces());
}

TEST(MeshCad, GeoScriptSizesStandUnlessTheCallerGivesOne) {
    ScratchDir dir("cad_script_size");
    const std::string sphere = "SetFactory(\"OpenCASCADE\");\nSphere(1) = {0,0,0,1};\n";
    const std::string coarse = write_file(dir, "coarse.geo", sphere + "Mesh.MeshSizeMax = 0.5;\n");
    const SurfaceMesh script = mesh_cad(coarse, {});
    const SurfaceMesh plain = mesh_cad(test_data("cad_unit_sphere.geo"), {});
    EXPECT_LT(2 * script.num_faces(), plain.num_faces());  // 0.5 rather than 0.173

    CadParams p;
    p.size = 0.1;
    const SurfaceMesh caller = mesh_cad(coarse, p);
    const SurfaceMesh reference = mesh_cad(test_data("cad_unit_sphere.geo"), p);
    EXPECT_EQ(caller.num_faces(), reference.num_faces());

    // A script that meshes itself is meshed again, curves included, with the caller's size.
    const std::string meshed = write_file(dir, "meshed.geo", sphere + "Mesh.MeshSizeMax = 0.5;\nMesh 2;\n");
    EXPECT_EQ(mesh_cad(meshed, p).num_faces(), reference.num_faces());

    // High-order requests are ignored: Strata needs linear faces.
    const std::string order2 = write_file(dir, "order2.geo", sphere + "Mesh.ElementOrder = 2;\n");
    const SurfaceMesh linear = mesh_cad(order2, {});
    EXPECT_EQ(linear.num_triangles(), linear.num_faces());
    EXPECT_EQ(linear.num_faces(), plain.num_faces());
}

TEST(MeshCad, OptionsDoNotLeakIntoAnOpenGmshSession) {
    ScratchDir dir("cad_leak");
    // An outer session keeps Gmsh initialised across the calls, as a front end would.
    GmshSession outer("outer");
    double before = 0.0;
    gmsh::option::getNumber("Mesh.MeshSizeMax", before);
    const SurfaceMesh first = mesh_cad(test_data("cad_unit_sphere.geo"), {});
    const std::string coarse =
        write_file(dir, "coarse.geo",
                   "SetFactory(\"OpenCASCADE\");\nSphere(1) = {0,0,0,1};\n"
                   "Mesh.MeshSizeMax = 0.5;\nMesh.RecombineAll = 1;\nMesh.MeshSizeFactor = 3;\n");
    const SurfaceMesh script = mesh_cad(coarse, {});
    EXPECT_GT(script.num_quads(), 0);  // the script's recombination stood
    const SurfaceMesh again = mesh_cad(test_data("cad_unit_sphere.geo"), {});
    EXPECT_EQ(again.num_faces(), first.num_faces());
    EXPECT_EQ(again.num_quads(), 0);
    double after = 0.0;
    gmsh::option::getNumber("Mesh.MeshSizeMax", after);
    EXPECT_EQ(after, before);
}

TEST(MeshCad, SameInputGivesTheSameMesh) {
    CadParams p;
    p.elements = SurfaceElements::Mixed;
    p.quad_surfaces = {10, 11};
    const SurfaceMesh a = mesh_cad(example_data("onera_m6_sharp_te.stp"), p);
    const SurfaceMesh b = mesh_cad(example_data("onera_m6_sharp_te.stp"), p);
    ASSERT_EQ(a.points.size(), b.points.size());
    for (std::size_t i = 0; i < a.points.size(); ++i) ASSERT_EQ(a.points[i], b.points[i]) << i;
    EXPECT_EQ(a.face_offsets, b.face_offsets);
    EXPECT_EQ(a.face_nodes, b.face_nodes);
    EXPECT_EQ(a.face_patch, b.face_patch);
    ASSERT_EQ(a.patches.size(), b.patches.size());
    for (std::size_t i = 0; i < a.patches.size(); ++i) EXPECT_EQ(a.patches[i].name, b.patches[i].name);
}

// --- errors ------------------------------------------------------------------------------

TEST(MeshCadErrors, MissingFileNamesThePath) {
    const std::string path = "/nonexistent/strata/wing.step";
    EXPECT_THROW(mesh_cad(path, {}), InputError);
    EXPECT_NE(error_text([&] { mesh_cad(path, {}); }).find(path), std::string::npos);
    const std::string geo = "/nonexistent/strata/wing.geo";  // Gmsh would make an empty model
    EXPECT_THROW(mesh_cad(geo, {}), InputError);
    EXPECT_NE(error_text([&] { mesh_cad(geo, {}); }).find(geo), std::string::npos);
}

TEST(MeshCadErrors, DirectoryAndUnknownExtensionAreInputErrors) {
    ScratchDir dir("cad_dirs");
    std::filesystem::create_directories(dir.file("folder.step"));
    EXPECT_THROW(mesh_cad(dir.file("folder.step"), {}), InputError);
    const std::string stl = write_file(dir, "x.stl", "solid x\nendsolid x\n");
    EXPECT_THROW(mesh_cad(stl, {}), InputError);
}

TEST(MeshCadErrors, CorruptStepNamesTheFile) {
    ScratchDir dir("cad_corrupt");
    const std::string path = write_file(dir, "corrupt_wing.step", "garbage\n");
    EXPECT_THROW(mesh_cad(path, {}), InputError);
    const std::string what = error_text([&] { mesh_cad(path, {}); });
    test::expect_contains(what, {"corrupt_wing.step", "STEP"});
}

TEST(MeshCadErrors, BrokenGeoScriptNamesTheFile) {
    ScratchDir dir("cad_badgeo");
    const std::string path = write_file(dir, "broken.geo", "Sphere(1) = {0,0,0,1};\nfoo bar;\n");
    EXPECT_THROW(mesh_cad(path, {}), InputError);
    EXPECT_NE(error_text([&] { mesh_cad(path, {}); }).find("broken.geo"), std::string::npos);
}

TEST(MeshCadErrors, ModelWithoutSurfaces) {
    ScratchDir dir("cad_nosurf");
    const std::string path =
        write_file(dir, "curves.geo", "Point(1) = {0,0,0};\nPoint(2) = {1,0,0};\nLine(1) = {1,2};\n");
    EXPECT_THROW(mesh_cad(path, {}), InputError);
    const std::string what = error_text([&] { mesh_cad(path, {}); });
    EXPECT_NE(what.find("curves.geo: no surfaces in the model"), std::string::npos) << what;
    EXPECT_THROW(mesh_cad(write_file(dir, "empty.geo", ""), {}), InputError);
}

TEST(MeshCadErrors, WrongContentAndPipesAreRefusedBeforeGmshReads) {
    ScratchDir dir("cad_wrong_content");
    // A PNG named .iges gave "no surfaces in the model"; a STEP named .brep, Gmsh's parse error.
    const std::string png = write_file(dir, "wing.iges", std::string("\x89PNG\r\n\x1a\n\0\0\0\rIHDR", 16));
    test::expect_error<InputError>([&] { mesh_cad(png, {}); },
                                   {"wing.iges' is not an IGES file: it looks like a PNG image"});
    std::ofstream(dir.file("wing.brep"), std::ios::binary) << test::slurp(example_data("wing_fuselage.step"));
    test::expect_error<InputError>(
        [&] { mesh_cad(dir.file("wing.brep"), {}); },
        {"wing.brep' is not a BREP file: it looks like a STEP file", "give the file the extension of its format"});
    // A pipe: refused at once (opening it would wait for a writer; Gmsh reads files by name).
    ASSERT_EQ(::mkfifo(dir.file("pipe.step").c_str(), 0600), 0);
    test::expect_error<InputError>([&] { mesh_cad(dir.file("pipe.step"), {}); },
                                   {"pipe.step' is a pipe, not a file: Gmsh reads it by name"});
}

TEST(MeshCadErrors, BadParametersAreRefusedBeforeReading) {
    const std::string path = test_data("cad_unit_sphere.geo");
    CadParams p;
    p.size = -1.0;
    EXPECT_THROW(mesh_cad(path, p), InputError);
    p = {};
    p.size = 1.0;
    p.size_min = 2.0;
    EXPECT_THROW(mesh_cad(path, p), InputError);
    p = {};
    p.curvature_points = -3;
    EXPECT_THROW(mesh_cad(path, p), InputError);
    for (int algorithm : {0, 3, 7, 8, 42}) {
        p = {};
        p.algorithm = algorithm;
        EXPECT_THROW(mesh_cad(path, p), InputError) << algorithm;
    }
    p = {};
    p.algorithm = 5;
    EXPECT_TRUE(closed(mesh_cad(path, p)));
}

TEST(MeshCadErrors, FuseNeedsOpenCascadeSolids) {
    ScratchDir dir("cad_fuse_geo");
    // Two built-in kernel cubes: fuse cannot apply, and says how to fix it.
    const std::string path = write_file(dir, "builtin.geo",
                                        "Point(1) = {0,0,0,0.5};\n"
                                        "l[] = Extrude {1,0,0} { Point{1}; };\n"
                                        "s[] = Extrude {0,1,0} { Line{l[1]}; };\n"
                                        "v[] = Extrude {0,0,1} { Surface{s[1]}; };\n"
                                        "Point(101) = {2,0,0,0.5};\n"
                                        "m[] = Extrude {1,0,0} { Point{101}; };\n"
                                        "t[] = Extrude {0,1,0} { Line{m[1]}; };\n"
                                        "w[] = Extrude {0,0,1} { Surface{t[1]}; };\n");
    CadParams p;
    p.fuse = true;
    EXPECT_THROW(mesh_cad(path, p), InputError);
    EXPECT_NE(error_text([&] { mesh_cad(path, p); }).find("OpenCASCADE"), std::string::npos);
    // Without fuse the two cubes mesh as two closed surfaces.
    const SurfaceMesh m = mesh_cad(path, {});
    EXPECT_TRUE(closed(m));
    EXPECT_EQ(components(m), 2);
}

}  // namespace
}  // namespace strata

namespace strata {
namespace {

TEST(MeshCadWalls, WallsTooCoarseForTheFirstLayerAreMeshedAgainFiner) {
    // The unit box (Gmsh meshes its edges in sevenths) under a first layer of 5e-5: prisms near
    // 1900, above checkMesh's 1000. Meshed again, every wall face stays under the limit.
    CadParams p;
    p.size = 0.5;
    const SurfaceMesh coarse = mesh_cad(test_data("cad_box_groups.geo"), p);
    EXPECT_GT(test::worst_wall_aspect(coarse, 5e-5), 1000.0);
    p.first_height = 5e-5;
    WallSizeReport r;
    const SurfaceMesh fine = mesh_cad(test_data("cad_box_groups.geo"), p, nullptr, &r);
    expect_well_formed(fine);
    EXPECT_TRUE(closed(fine));
    EXPECT_EQ(r.max_aspect_ratio, 1000.0);
    // The prediction is the right prism's where the columns stand square (test::worst_wall_aspect),
    // more where they lean over the box's edges (45 degrees there: at most sqrt(2) more).
    EXPECT_GE(r.worst_before, test::worst_wall_aspect(coarse, 5e-5));
    EXPECT_LE(r.worst_before, std::sqrt(2.0) * test::worst_wall_aspect(coarse, 5e-5));
    EXPECT_GE(r.worst_after, test::worst_wall_aspect(fine, 5e-5));
    EXPECT_LE(r.worst_after, std::sqrt(2.0) * test::worst_wall_aspect(fine, 5e-5));
    EXPECT_LE(r.worst_after, 1000.0);
    EXPECT_EQ(r.surfaces, 6);  // every face is a wall
    EXPECT_EQ(r.curves, 0);    // a box has no fan edge (and no fan angle was given)
    EXPECT_NEAR(r.cap, 0.035, 1e-12);
    EXPECT_FALSE(r.over_budget);
    EXPECT_GT(fine.num_faces(), 10 * coarse.num_faces());
    EXPECT_LT(fine.num_faces(), 2.0 * r.faces_estimate);
    EXPECT_GT(fine.num_faces(), 0.5 * r.faces_estimate);

    // A patch that is not a wall is not capped (the inlet named a farfield; Gmsh still grades it
    // from its curves, which it shares with the walls, so here it is as fine).
    p.wall_patch_kinds = {{"inlet", PatchKind::Farfield}};
    const SurfaceMesh five = mesh_cad(test_data("cad_box_groups.geo"), p, nullptr, &r);
    EXPECT_EQ(r.surfaces, 5);
    EXPECT_LE(r.worst_after, 1000.0);

    // The same settings give the same mesh.
    const SurfaceMesh again = mesh_cad(test_data("cad_box_groups.geo"), p);
    EXPECT_EQ(again.points, five.points);
    EXPECT_EQ(again.face_nodes, five.face_nodes);
}

TEST(MeshCadWalls, NothingChangesWhereTheFirstLayerIsFineOrTheLimitIsOff) {
    CadParams p;
    p.size = 0.5;
    const SurfaceMesh plain = mesh_cad(test_data("cad_box_groups.geo"), p);
    WallSizeReport r;
    p.first_height = 0.01;  // prisms near 10
    SurfaceMesh m = mesh_cad(test_data("cad_box_groups.geo"), p, nullptr, &r);
    EXPECT_EQ(m.points, plain.points);
    EXPECT_EQ(r.surfaces + r.curves, 0);
    EXPECT_LT(r.worst_before, 1000.0);
    EXPECT_EQ(r.worst_after, r.worst_before);
    p.first_height = 5e-5;
    p.max_aspect_ratio = 0.0;
    m = mesh_cad(test_data("cad_box_groups.geo"), p, nullptr, &r);
    EXPECT_EQ(m.points, plain.points);
    EXPECT_EQ(r.worst_before, 0.0);
}

TEST(MeshCadWalls, OverTheFaceBudgetTheSizeIsKeptAndTheReportSaysWhy) {
    CadParams p;
    p.size = 0.5;
    const SurfaceMesh plain = mesh_cad(test_data("cad_box_groups.geo"), p);
    p.first_height = 5e-5;
    p.wall_faces_budget = 5000;  // the box would need about 6 / (0.433 * 0.035^2) = 11,300
    WallSizeReport r;
    const SurfaceMesh m = mesh_cad(test_data("cad_box_groups.geo"), p, nullptr, &r);
    EXPECT_EQ(m.points, plain.points);
    EXPECT_TRUE(r.over_budget);
    EXPECT_EQ(r.surfaces, 0);
    EXPECT_GT(r.faces_estimate, 10000.0);
    EXPECT_LT(r.faces_estimate, 13000.0);
    EXPECT_NEAR(r.cap, 0.035, 1e-12);
    EXPECT_GT(r.worst_after, 1000.0);
}

TEST(MeshCadWalls, TheBudgetCountsASurfaceWhoseBoundaryTheCapsFill) {
    // The hemisphere-cylinder's half domain with every patch a wall, first layer 0.003: the two
    // half-disc planes (and the body's cylinder) are over the limit and capped at 2.1; the
    // quarter-sphere between the planes is not, but its whole boundary is theirs, and Gmsh
    // carries those sizes into it: 37,076 faces where the caps alone count 16,900. The
    // estimate now counts it (about 33,000), so a budget of 25,000 keeps the mesh as it was.
    CadParams p;
    p.first_height = 0.003;
    WallSizeReport r;
    const SurfaceMesh fine = mesh_cad(example_data("hemisphere_cylinder_halfdomain.stp"), p, nullptr, &r);
    EXPECT_FALSE(r.over_budget);
    EXPECT_EQ(r.surfaces, 3);
    EXPECT_GT(r.faces_estimate, 0.8 * static_cast<double>(fine.num_faces()));
    EXPECT_LT(r.faces_estimate, 1.2 * static_cast<double>(fine.num_faces()));
    p.wall_faces_budget = 25000;
    const SurfaceMesh kept = mesh_cad(example_data("hemisphere_cylinder_halfdomain.stp"), p, nullptr, &r);
    EXPECT_TRUE(r.over_budget);
    EXPECT_EQ(r.surfaces, 0);
    EXPECT_LT(kept.num_faces(), 2000);
}

/// A blade 1 long and 1 wide in y, its 20-degree edge along y at x = 0 (its faces turn by 160
/// degrees there), as a .geo in \p dir.
std::string write_blade(const ScratchDir& dir) {
    return write_file(dir, "blade.geo",
                      "SetFactory(\"OpenCASCADE\");\n"
                      "Point(1) = {0, 0, 0};\nPoint(2) = {1, 0, 0.1763};\nPoint(3) = {1, 0, -0.1763};\n"
                      "Line(1) = {1, 2};\nLine(2) = {2, 3};\nLine(3) = {3, 1};\n"
                      "Curve Loop(1) = {1, 2, 3};\nPlane Surface(1) = {1};\n"
                      "Extrude {0, 1, 0} { Surface{1}; }\n");
}

/// \p geo meshed by mesh_cad at size 0.15 with the first height \p first_height and the fan angle
/// \p fan_angle_deg (0: no fans), the walls' report in \p r.
SurfaceMesh mesh_blade(const std::string& geo, double first_height, double fan_angle_deg, WallSizeReport& r) {
    CadParams p;
    p.size = 0.15;
    p.first_height = first_height;
    p.fan_angle_deg = fan_angle_deg;
    return mesh_cad(geo, p, nullptr, &r);
}

/// \p m is a closed surface whose worst forecast wall cell, above \p before, was brought to 1000.
void expect_walls_refined(const SurfaceMesh& m, const WallSizeReport& r, double before) {
    expect_well_formed(m);
    EXPECT_TRUE(closed(m));
    EXPECT_GT(r.worst_before, before);
    EXPECT_LE(r.worst_after, 1000.0);
}

TEST(MeshCadWalls, FanEdgesAreMeshedFinerAlongTheirCurve) {
    // A blade with a 20-degree edge along y (its faces turn by 160 degrees: a fan at the default
    // 150) at size 0.15: the fan's first wedge is about twice the edge over h, 2 * 0.14 / 1.5e-4
    // = 1900, while a prism on a face is near 500. Only the edge's curve is refined.
    const ScratchDir dir("mesh_cad_fan");
    const std::string geo = write_blade(dir);
    WallSizeReport r;
    SurfaceMesh m = mesh_blade(geo, 1.5e-4, 0.0, r);
    EXPECT_EQ(r.surfaces + r.curves, 0);  // no fan angle given: no fan is predicted
    m = mesh_blade(geo, 1.5e-4, 150.0, r);
    expect_walls_refined(m, r, 1500.0);
    EXPECT_EQ(r.surfaces, 0);
    EXPECT_EQ(r.curves, 1);
    // The edge at x = 0 is now in segments of at most about r.cap.
    double longest = 0.0;
    for (Index f = 0; f < m.num_faces(); ++f)
        for (Index i = 0, n = m.face_size(f); i < n; ++i) {
            const Vec3& a = m.points[static_cast<std::size_t>(m.face_node(f, i))];
            const Vec3& b = m.points[static_cast<std::size_t>(m.face_node(f, (i + 1) % n))];
            if (std::abs(a.x()) < 1e-9 && std::abs(b.x()) < 1e-9) longest = std::max(longest, (a - b).norm());
        }
    EXPECT_GT(longest, 0.0);
    EXPECT_LE(longest, 1.5 * r.cap);
    EXPECT_LT(r.cap, 0.1);
}

TEST(MeshCadWalls, StepCellsAtASharpEdgeWithoutAFanAreMeshedFinerToo) {
    // The blade of the test above without fans: the columns on its 20-degree edge lean 80
    // degrees off each face and stop at the wall, so the first-layer cells beside the edge are
    // the tetrahedra and pyramids closing those steps, as flat as the faces are wide (checkMesh
    // 1172 under 1.2e-4 at size 0.15, where the prisms stay under 1000). They are forecast too,
    // and the surfaces beside the edge meshed finer for them.
    const ScratchDir dir("mesh_cad_steps");
    const std::string geo = write_blade(dir);
    WallSizeReport r;
    const SurfaceMesh m = mesh_blade(geo, 1.2e-4, 0.0, r);
    expect_walls_refined(m, r, 1100.0);
    EXPECT_GE(r.surfaces, 2);
    // A first layer the faces allow: nothing to do.
    (void)mesh_blade(geo, 2e-4, 0.0, r);
    EXPECT_LT(r.worst_before, 1000.0);
    EXPECT_EQ(r.surfaces + r.curves, 0);
}

TEST(MeshCadWalls, AFanEdgeEndingOnAConcaveJunctionIsNotMeshedFinerForAFan) {
    // The blade of FanEdgesAreMeshedFinerAlongTheirCurve standing on a plate (fused), its 20-degree edge now vertical:
    // at its foot it meets only the blade's root, concave, and a fan's chain cannot end there
    // (the layers build none: fans.cpp), so its curve is not meshed finer for one. Its chain
    // met the root's curves at that point and counted as closed (r.curves was 1).
    const ScratchDir dir("mesh_cad_fan_on_plate");
    const std::string geo = write_file(dir, "blade_on_plate.geo",
                                       "SetFactory(\"OpenCASCADE\");\n"
                                       "Box(1) = {-1, -1.5, -0.2, 3, 3, 0.2};\n"
                                       "Point(101) = {0, 0, 0};\nPoint(102) = {1, 0.1763, 0};\n"
                                       "Point(103) = {1, -0.1763, 0};\n"
                                       "Line(101) = {101, 102};\nLine(102) = {102, 103};\nLine(103) = {103, 101};\n"
                                       "Curve Loop(101) = {101, 102, 103};\nPlane Surface(101) = {101};\n"
                                       "v() = Extrude {0, 0, 1} { Surface{101}; };\n"
                                       "BooleanUnion{ Volume{1}; Delete; }{ Volume{v(1)}; Delete; }\n");
    WallSizeReport r;
    const SurfaceMesh m = mesh_blade(geo, 1.5e-4, 150.0, r);
    expect_well_formed(m);
    EXPECT_TRUE(closed(m));
    EXPECT_EQ(r.curves, 0);
}

TEST(MeshCadWalls, BadLimitsAreInputErrors) {
    const std::string path = test_data("cad_unit_sphere.geo");
    CadParams p;
    p.max_aspect_ratio = 5.0;
    EXPECT_NE(error_text([&] { mesh_cad(path, p); }).find("CadParams::max_aspect_ratio = 5"), std::string::npos);
    p = {};
    p.first_height = -1.0;
    EXPECT_THROW(mesh_cad(path, p), InputError);
    p = {};
    p.wall_faces_budget = 0.0;
    EXPECT_THROW(mesh_cad(path, p), InputError);
}

// Sewing (CadParams::sew_tolerance): surface models whose faces each have their own edges.

/// The mean of the face centroids of the patch named \p name.
Vec3 patch_centre(const SurfaceMesh& m, const std::string& name) {
    Vec3 sum = Vec3::Zero();
    int n = 0;
    for (Index f = 0; f < m.num_faces(); ++f)
        if (m.patches[static_cast<std::size_t>(m.face_patch[f])].name == name) {
            sum += face_centroid(m, m.points, f);
            ++n;
        }
    return n > 0 ? Vec3(sum / n) : Vec3::Constant(std::nan(""));
}

/// Sewing made one closed solid of \p faces faces: no free edge left, \p m closed.
void expect_one_closed_solid(const SurfaceMesh& m, const SewReport& r, Index faces) {
    EXPECT_EQ(r.faces, faces);
    EXPECT_EQ(r.free_after, 0);
    EXPECT_EQ(r.solids, 1);
    EXPECT_TRUE(closed(m));
}

TEST(CadSewing, LooseFacesThatMissEachOtherAreSewnIntoOneClosedSolid) {
    // Six faces of a box whose corners miss by up to 1e-7 (cad_box_loose_faces.py): meshed one
    // by one the surface is open along every edge; sewn it is one closed solid, each patch still
    // named after the face the file numbers so.
    const std::string path = test_data("cad_box_loose_faces_1e-7.brep");
    SewReport r;
    const SurfaceMesh m = mesh_cad(path, {}, nullptr, nullptr, &r);
    expect_one_closed_solid(m, r, 6);
    EXPECT_EQ(r.free_before, 24);
    EXPECT_EQ(r.cracks, 0);
    EXPECT_FALSE(r.rejected);
    EXPECT_GT(r.gap_before, 1e-8);
    EXPECT_LT(r.gap_before, 1e-6);
    EXPECT_EQ(components(m), 1);
    const std::array<Vec3, 6> centre{Vec3(0.5, 0.25, 0),   Vec3(0.5, 0.25, 0.3), Vec3(0.5, 0, 0.15),
                                     Vec3(0.5, 0.5, 0.15), Vec3(0, 0.25, 0.15),  Vec3(1, 0.25, 0.15)};
    for (std::size_t k = 0; k < centre.size(); ++k)
        EXPECT_LT((patch_centre(m, "surface_" + std::to_string(k + 1)) - centre[k]).norm(), 0.03) << "face " << k + 1;

    CadParams unsewn;
    unsewn.sew_tolerance = 0.0;
    SewReport none;
    const SurfaceMesh open = mesh_cad(path, unsewn, nullptr, nullptr, &none);
    EXPECT_EQ(none.faces, 0);
    PrepareParams pp;
    pp.cad = unsewn;
    PrepareReport rep;
    const SurfaceMesh merged = prepare_surface(path, pp, &rep);
    EXPECT_FALSE(closed(merged));  // the faces' nodes miss each other: merging cannot close it
    EXPECT_EQ(rep.orient.closed_components, 0);
}

TEST(CadSewing, GapsWiderThanTheToleranceAreMeasuredAndTheSuggestionSewsThem) {
    // Corners missing by up to 3e-5 (gaps up to 4e-5 of a diagonal of 1.16): over the 1e-5 of
    // the diagonal sewing goes to unasked, so the edges stay apart, and the report says by how
    // much and what tolerance sews them; that tolerance does.
    const std::string path = test_data("cad_box_loose_faces_3e-5.brep");
    SewReport r;
    (void)mesh_cad(path, {}, nullptr, nullptr, &r);
    EXPECT_EQ(r.faces, 6);
    // 1e-5 of the diagonal of OpenCASCADE's bounding box (which its filling surfaces enlarge).
    EXPECT_GE(r.tolerance, 1e-5 * std::hypot(1.0, 0.5, 0.3));
    EXPECT_LE(r.tolerance, 1.2e-5 * std::hypot(1.0, 0.5, 0.3));
    EXPECT_GT(r.free_after, 0);
    EXPECT_EQ(r.cracks, r.free_after);
    EXPECT_GT(r.widest_gap, 1e-5);
    EXPECT_LT(r.widest_gap, 1e-4);
    EXPECT_GT(r.suggested_tolerance, 1e-5);
    EXPECT_LE(r.suggested_tolerance, 1e-4);
    CadParams p;
    p.sew_tolerance = r.suggested_tolerance;
    SewReport again;
    const SurfaceMesh m = mesh_cad(path, p, nullptr, nullptr, &again);
    expect_one_closed_solid(m, again, 6);
}

TEST(CadSewing, AnIgesOfTrimmedFacesWithAPoleIsSewnWithItsSmallEdgesFixed) {
    // A half body with a quarter-sphere nose as IGES trimmed faces (cad_nose_trimmed_faces.geo):
    // sewn alone its nose keeps a degenerate edge and Gmsh aborts on it; with the small edges
    // fixed it is one closed solid whose faces did not move.
    SewReport r;
    const SurfaceMesh m = mesh_cad(test_data("cad_nose_trimmed_faces.igs"), {}, nullptr, nullptr, &r);
    expect_one_closed_solid(m, r, 5);
    EXPECT_FALSE(r.rejected);
    EXPECT_LT(r.moved, 1e-9);
}

TEST(CadSewing, HealingThatMovesAFaceIsRefusedAndTheFacesMeshedAsTheyAre) {
    // A capsule as IGES trimmed faces (cad_capsule_trimmed_faces.geo): healing its faces cuts its
    // spherical ends to 40 % of their area. The sewn model is refused and the file meshed
    // unsewn, its coincident edges merged into a closed surface of the capsule's whole area.
    const std::string path = test_data("cad_capsule_trimmed_faces.igs");
    SewReport r;
    (void)mesh_cad(path, {}, nullptr, nullptr, &r);
    EXPECT_EQ(r.faces, 4);
    EXPECT_TRUE(r.rejected);
    EXPECT_GT(r.moved, 1e-2);
    PrepareReport rep;
    const SurfaceMesh m = prepare_surface(path, {}, &rep);
    EXPECT_TRUE(rep.sew.rejected);
    EXPECT_TRUE(closed(m));
    double area = 0.0;
    for (Index f = 0; f < m.num_faces(); ++f) area += face_area_vector(m, f).norm();
    const double pi = std::acos(-1.0);
    EXPECT_NEAR(area, 2.0 * pi * 0.2 * 1.0 + 4.0 * pi * 0.04, 0.02);
}

TEST(CadSewing, SolidsAndClosedFacesAreLeftAlone) {
    // Faces that bound solids are never sewn, nor a face that closes on itself (a sphere's, whose
    // seam bounds it twice and whose poles are degenerate edges): sewing it, Gmsh could not mesh
    // the periodic face again and aborted.
    SewReport solid, sphere;
    EXPECT_TRUE(closed(mesh_cad(test_data("cad_box_with_hole.igs"), {}, nullptr, nullptr, &solid)));
    EXPECT_EQ(solid.faces, 0);
    EXPECT_TRUE(closed(mesh_cad(test_data("cad_sphere_face_only.brep"), {}, nullptr, nullptr, &sphere)));
    EXPECT_EQ(sphere.faces, 0);
    CadParams p;
    p.sew_tolerance = 0.01;
    EXPECT_THROW(mesh_cad(test_data("cad_box_with_hole.igs"), p), InputError);
}

TEST(CadSewing, ALooseFaceBesideASolidIsSetAsideAndSaidAndFreeCurvesIgnored) {
    // A cube, a square beside it and a free line in one file (cad_solid_and_loose_face.brep):
    // the square bounds no solid and is open where it lies (a construction profile left in the
    // file), so no layer could grow on it and the surface would be refused as open: it is set
    // aside, counted and located; the line, bounding nothing, is left out.
    SewReport r;
    const SurfaceMesh m = mesh_cad(test_data("cad_solid_and_loose_face.brep"), {}, nullptr, nullptr, &r);
    EXPECT_EQ(m.patches.size(), 6u);
    EXPECT_EQ(r.faces, 0);
    EXPECT_EQ(r.ignored, 1);
    EXPECT_LT((r.ignored_at - Vec3(2.5, 0.5, 0.0)).norm(), 0.6) << r.ignored_at.transpose();
    double far = 0.0;
    for (const Vec3& x : m.points) far = std::max(far, x.x());
    EXPECT_NEAR(far, 1.0, 1e-9);
    EXPECT_TRUE(closed(m));
    for (Index f = 0; f < m.num_faces(); ++f) EXPECT_GT(face_area_vector(m, f).norm(), 0.0);
}

TEST(CadSewing, ARevolvesProfileIsSetAsideButLooseFacesClosedRoundASolidStay) {
    // A STEP of a cylinder and the rectangle it was revolved from, beside it: meshed, the
    // rectangle left the surface open ("a hole or a crack"); set aside, the cylinder meshes.
    SewReport r;
    const SurfaceMesh m = mesh_cad(test_data("cad_cylinder_and_profile.step"), {}, nullptr, nullptr, &r);
    EXPECT_EQ(r.ignored, 1);
    EXPECT_EQ(m.patches.size(), 3u);
    EXPECT_TRUE(closed(m));
    // A sphere solid inside six loose faces of a box: sewn, they close round it, and stay.
    SewReport boxed;
    const SurfaceMesh both = mesh_cad(test_data("cad_sphere_in_box_faces.brep"), {}, nullptr, nullptr, &boxed);
    EXPECT_EQ(boxed.ignored, 0);
    EXPECT_EQ(both.patches.size(), 7u);
    EXPECT_TRUE(closed(both));
    // Without a solid, loose faces are sewn as before (cad_box_loose_faces_1e-7.brep).
    SewReport box;
    EXPECT_TRUE(closed(mesh_cad(test_data("cad_box_loose_faces_1e-7.brep"), {}, nullptr, nullptr, &box)));
    EXPECT_EQ(box.ignored, 0);
    EXPECT_EQ(box.faces, 6);
}

TEST(CadSewing, AFaceWrittenTwiceIsRemovedBeforeSewing) {
    // The six faces of a box, the first written twice (cad_box_face_written_twice.brep): sewn
    // with both copies, Gmsh meshed each on the same edges with its own interior, three faces
    // on each edge round it; the copy goes first, and the box is closed.
    SewReport r;
    const SurfaceMesh m = mesh_cad(test_data("cad_box_face_written_twice.brep"), {}, nullptr, nullptr, &r);
    EXPECT_EQ(r.written_twice, 1);
    expect_one_closed_solid(m, r, 6);
    EXPECT_EQ(m.patches.size(), 6u);
}

TEST(CadSewing, ANoseFaceHeldTwiceWithGeometryOfItsOwnIsMeshedOnce) {
    // A half model in its box whose flat nose face is held twice, the copy a B-spline filling
    // on the same edges (cad_half_model_nose_twice.py): meshed both, three faces met on each edge
    // round the nose ("non-manifold edge ... shared by 3 faces"). The copy is not meshed, whether
    // the solid's shell lists it (it goes, the solid with it) or it lies beside the solid.
    for (const char* file : {"cad_half_model_nose_twice_shell.brep", "cad_half_model_nose_twice_loose.brep"}) {
        SCOPED_TRACE(file);
        SewReport r;
        const SurfaceMesh m = mesh_cad(test_data(file), {}, nullptr, nullptr, &r);
        EXPECT_EQ(r.coincident, 1);
        EXPECT_EQ(r.coincident_surface, 11);  // the filling, read last
        EXPECT_EQ(r.ignored, 0);
        EXPECT_LT(r.coincident_distance, 1e-9);
        EXPECT_NEAR(r.coincident_at.x(), -0.5, 1e-9);
        EXPECT_EQ(m.patches.size(), 10u);
        EXPECT_TRUE(closed(m));
        const EdgeTable et = edge_table(m);
        for (Index e = 0; e < et.faces.rows(); ++e) ASSERT_EQ(et.faces.row_size(e), 2) << "edge " << e;
    }
}

TEST(CadSewing, FacesLyingOnEachOtherThatAreNotCopiesStay) {
    // Nothing repeats in a box of six loose faces; two bodies touching along a face hold it
    // twice, once each, lying on each other on the same edges once sewn: not a copy.
    SewReport r;
    (void)mesh_cad(test_data("cad_box_loose_faces_1e-7.brep"), {}, nullptr, nullptr, &r);
    EXPECT_EQ(r.coincident, 0);
    (void)mesh_cad(test_data("cad_two_boxes_trimmed_faces.igs"), {}, nullptr, nullptr, &r);
    EXPECT_EQ(r.coincident, 0);  // each copy bounds a solid of its own: both stay
}

TEST(CadSewing, TwoBodiesTouchingAlongAFaceGetNoFanWhereTheirCopiesOfItMeet) {
    // Two boxes touching along y = 0.5 as IGES trimmed faces (cad_two_boxes_trimmed_faces.geo):
    // sewn, the two copies of the face between them lie back to back, whose common edges turn
    // 180 degrees; they are not a sharp edge of the wall, so the wall sizing for the first layer
    // puts no fan on them (it did: 12 curves meshed finer, and on a wing and fuselage written
    // so, a first-layer aspect ratio of 4e32 from the fan's undefined plane).
    CadParams p;
    p.first_height = 1e-4;
    p.fan_angle_deg = 150.0;
    WallSizeReport w;
    SewReport r;
    (void)mesh_cad(test_data("cad_two_boxes_trimmed_faces.igs"), p, nullptr, &w, &r);
    EXPECT_EQ(r.free_after, 0);
    EXPECT_EQ(r.written_twice, 0);  // the two copies face opposite ways: not written twice
    EXPECT_FALSE(r.renumbered);     // each copy matched to one of the file's two
    EXPECT_EQ(w.curves, 0);
    EXPECT_LT(w.worst_before, 1e4);
}

}  // namespace
}  // namespace strata
