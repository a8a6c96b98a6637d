// fill_with_tets (TetGen's libtet, loaded privately) and the platform check that TetGen and
// Gmsh's own 3D meshers work in one process (PLATFORM.md; why libtet is not linked: the file
// comment of hybrid/src/tetgen_fill.cpp).

#include <strata/core/cell_quality.h>
#include <strata/core/error.h>
#include <strata/core/validate.h>
#include <strata/hybrid/tetgen_fill.h>
#include <strata/io/gmsh_session.h>

#include <gtest/gtest.h>

#include "box_surface.h"
#include "tet_fill_support.h"
#include "test_support.h"

#include <dlfcn.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <vector>

using namespace strata;

namespace {

using namespace strata::test;

// ---------------------------------------------------------------------------------------

TEST(TetgenFill, UnitCubeTwelveTriangles) {
    const SurfaceMesh b = unit_cube();
    ASSERT_EQ(b.num_faces(), 12);
    const TetFill f = fill_with_tets(b, {}, TetFillParams{});
    expect_valid_fill(b, f, 1.0);
    for (std::size_t i = b.points.size(); i < f.points.size(); ++i)
        for (int k = 0; k < 3; ++k) {
            EXPECT_GT(f.points[i][k], 1e-9) << "Steiner point " << i;
            EXPECT_LT(f.points[i][k], 1.0 - 1e-9) << "Steiner point " << i;
        }
}

// A cube whose bottom side holds an edge of 5e-9 (a needle of a remeshed surface carried up to
// the layers' top): TetGen's default tolerance takes its ends for one point and renumbered the
// rest; with the tolerance fill_with_tets passes, every boundary node stays.
TEST(TetgenFill, KeepsPointsCloserThanTetGensTolerance) {
    SurfaceMesh b;
    b.patches.push_back({"farfield", PatchKind::Farfield});
    SurfaceMesh cube = unit_cube();
    b.points = cube.points;
    for (Index f = 0; f < cube.num_faces(); ++f) {
        bool bottom = true;
        for (int c = 0; c < 3; ++c) bottom &= cube.points[cube.face_node(f, c)].z() == 0.0;
        if (!bottom) b.add_face({cube.face_node(f, 0), cube.face_node(f, 1), cube.face_node(f, 2)}, 0);
    }
    auto corner = [&](double x, double y) {
        for (Index i = 0; i < b.num_points(); ++i)
            if (b.points[i] == Vec3(x, y, 0.0)) return i;
        return kNone;
    };
    const Index a = corner(0, 0), c1 = corner(1, 0), c2 = corner(1, 1), d = corner(0, 1);
    const Index p = b.num_points(), q = p + 1;
    b.points.emplace_back(0.5, 0.5, 0.0);
    b.points.emplace_back(0.5 + 5e-9, 0.5, 0.0);
    // The bottom (normal −z, out of the cube) around the short edge p-q.
    for (const auto& t :
         {std::array<Index, 3>{a, q, c1}, std::array<Index, 3>{c1, q, c2}, std::array<Index, 3>{c2, q, p},
          std::array<Index, 3>{c2, p, d}, std::array<Index, 3>{d, p, a}, std::array<Index, 3>{a, p, q}}) {
        const Vec3 n = (b.points[t[1]] - b.points[t[0]]).cross(b.points[t[2]] - b.points[t[0]]);
        ASSERT_LT(n.z(), 0.0);
        b.add_face({t[0], t[1], t[2]}, 0);
    }
    for (const bool refine : {false, true}) {
        TetFillParams params;
        params.refine = refine;
        const TetFill f = fill_with_tets(b, {}, params);
        expect_valid_fill(b, f, 1.0);
    }
}

// A volume bound far below what the boundary triangles allow: without -Y TetGen would split
// the boundary triangles; with it every Steiner point stays strictly inside the cube.
TEST(TetgenFill, VolumeBoundAddsSteinerPointsOnlyInside) {
    const SurfaceMesh b = unit_cube(6);
    TetFillParams p;
    p.max_volume = 1e-4;
    const TetFill f = fill_with_tets(b, {}, p);
    expect_valid_fill(b, f, 1.0);
    EXPECT_GT(f.points.size(), b.points.size() + 1000);
    for (std::size_t i = b.points.size(); i < f.points.size(); ++i)
        for (int k = 0; k < 3; ++k) {
            EXPECT_GT(f.points[i][k], 1e-9) << "Steiner point " << i;
            EXPECT_LT(f.points[i][k], 1.0 - 1e-9) << "Steiner point " << i;
        }
    // Most tets respect the bound (some at the boundary cannot: it may not be split).
    std::size_t within = 0;
    for (const auto& t : f.tets)
        within += (f.points[t[1]] - f.points[t[0]])
                          .cross(f.points[t[2]] - f.points[t[0]])
                          .dot(f.points[t[3]] - f.points[t[0]]) /
                      6.0 <=
                  1e-4;
    EXPECT_GT(within, f.tets.size() * 3 / 4);
}

// Without refinement: the boundary's own points, plus at most a few Steiner points TetGen may
// need inside to recover the boundary.
TEST(TetgenFill, NoRefinementIsBoundaryOnly) {
    const SurfaceMesh b = cube_in_box(3, 2);
    TetFillParams p;
    p.refine = false;
    p.max_volume = 1e-2;  // ignored without refinement
    p.growth = 0.2;       // likewise
    const TetFill f = fill_with_tets(b, kCubeHole, p);
    expect_valid_fill(b, f, 125.0 - 1.0);
    EXPECT_LT(f.points.size(), b.points.size() + 10);
    p.refine = true;  // the same bounds with refinement: many interior points
    EXPECT_GT(fill_with_tets(b, kCubeHole, p).points.size(), b.points.size() + 1000);
}

TEST(TetgenFill, CubeWithCavityValidates) {
    const SurfaceMesh b = cube_in_box(4, 2);
    const TetFill f = fill_with_tets(b, kCubeHole, TetFillParams{});
    expect_valid_fill(b, f, 125.0 - 1.0);
    // No tet inside the cavity.
    for (const auto& t : f.tets) {
        const Vec3 c = 0.25 * (f.points[t[0]] + f.points[t[1]] + f.points[t[2]] + f.points[t[3]]);
        EXPECT_FALSE((c.array() > 0.0).all() && (c.array() < 1.0).all()) << "tet in the cavity at " << c.transpose();
    }
    const ValidationReport r = validate_mesh(as_volume_mesh(b, f));
    std::string problems;
    for (const auto& s : r.problems) problems += "\n" + s;
    EXPECT_TRUE(r.ok()) << problems;
    EXPECT_GT(r.min_scaled_jacobian, 0.0);
    EXPECT_EQ(r.boundary_faces, b.num_faces());
    EXPECT_NEAR(r.cell_volume, 124.0, 1e-9);
}

TEST(TetgenFill, Deterministic) {
    const SurfaceMesh b = cube_in_box(4, 2);
    TetFillParams p;
    p.growth = 0.3;
    const TetFill f1 = fill_with_tets(b, kCubeHole, p);
    const TetFill f2 = fill_with_tets(b, kCubeHole, p);
    EXPECT_EQ(f1.points, f2.points);
    EXPECT_EQ(f1.tets, f2.tets);
}

/// The "tetrahedra" fractions a run reports.
class PhaseRecorder : public Progress {
public:
    std::vector<double> heard;
    void report(std::string_view stage, double fraction) override {
        if (stage == "tetrahedra") heard.push_back(fraction);
    }
};

TEST(TetgenFill, ProgressHearsTetGensPhasesInOrderAndTheMeshIsTheSame) {
    // A cube of 10,800 wall triangles graded out to a box 13 wide: a run of a second or more, so
    // that the parent, which looks every 0.1 s, hears TetGen's refinement at least (its share of
    // the main run, after the background mesh's 20 %), and nothing past the end of the run.
    const SurfaceMesh b = cube_in_box(30, 5, false, 6.0);
    TetFillParams p;
    p.growth = 0.1;
    PhaseRecorder r;
    const TetFill heard = fill_with_tets(b, kCubeHole, p, &r);
    const TetFill quiet = fill_with_tets(b, kCubeHole, p);
    EXPECT_EQ(heard.points, quiet.points);  // announcing its phases changes nothing TetGen makes
    EXPECT_EQ(heard.tets, quiet.tets);
    ASSERT_FALSE(r.heard.empty());
    EXPECT_TRUE(std::is_sorted(r.heard.begin(), r.heard.end()));
    EXPECT_GE(r.heard.back(), 0.2 + 0.2 * 0.8 - 1e-12) << "the refinement was not heard";
    EXPECT_LT(r.heard.back(), 1.0);
}

// Fine wall (edge 0.1) in a coarse farfield (edge 2.6): with growth > 0 the tets grade from the
// wall's size out, following h(d) = 0.1 + growth·d (TetFillParams::growth).
TEST(TetgenFill, SizeGradingFollowsGrowth) {
    const double outer = 6.0, wall_edge = 0.1;
    const SurfaceMesh b = cube_in_box(10, 5, false, outer);
    const double volume = std::pow(1.0 + 2 * outer, 3) - 1.0;
    auto run = [&](double growth) {
        TetFillParams p;
        p.growth = growth;
        TetFill f = fill_with_tets(b, kCubeHole, p);
        expect_valid_fill(b, f, volume);
        return f;
    };
    const double growth = 0.2;
    const TetFill f = run(growth);

    // Tets touching the wall vs tets touching the farfield.
    std::vector<char> on_wall(b.points.size(), 0), on_far(b.points.size(), 0);
    for (Index i = 0; i < b.num_faces(); ++i)
        for (int k = 0; k < 3; ++k) (b.face_patch[i] == 1 ? on_wall : on_far)[b.face_node(i, k)] = 1;
    auto touches = [&](const std::array<Index, 4>& t, const std::vector<char>& flag) {
        return std::any_of(t.begin(), t.end(), [&](Index v) { return v < static_cast<Index>(flag.size()) && flag[v]; });
    };
    double wall_sum = 0, far_sum = 0;
    int wall_n = 0, far_n = 0;
    // Mean edge per distance band from the cube: d in [1, 1.5), [2, 2.5), [3, 3.5).
    std::array<double, 3> band_sum{}, band_d{};
    std::array<int, 3> band_n{};
    for (const auto& t : f.tets) {
        const double e = mean_edge(f, t);
        if (touches(t, on_wall)) wall_sum += e, ++wall_n;
        if (touches(t, on_far)) far_sum += e, ++far_n;
        const Vec3 c = 0.25 * (f.points[t[0]] + f.points[t[1]] + f.points[t[2]] + f.points[t[3]]);
        const double d = (c - c.cwiseMax(Vec3::Zero()).cwiseMin(Vec3::Ones())).norm();  // distance to the cube
        for (int k = 0; k < 3; ++k)
            if (d >= 1.0 + k && d < 1.5 + k) band_sum[k] += e, band_d[k] += d, ++band_n[k];
    }
    ASSERT_GT(wall_n, 0);
    ASSERT_GT(far_n, 0);
    EXPECT_LT(10.0 * wall_sum / wall_n, far_sum / far_n)
        << "mean edge at the wall " << wall_sum / wall_n << ", at the farfield " << far_sum / far_n;
    for (int k = 0; k < 3; ++k) {
        ASSERT_GT(band_n[k], 0) << "band " << k;
        const double e = band_sum[k] / band_n[k], d = band_d[k] / band_n[k];
        const double h = wall_edge + growth * d;
        EXPECT_GT(e, 0.7 * h) << "band " << k << ": mean edge " << e << " at distance " << d << ", h = " << h;
        EXPECT_LT(e, 1.3 * h) << "band " << k << ": mean edge " << e << " at distance " << d << ", h = " << h;
    }

    // Twice the growth rate: far fewer tets; no sizing at all (growth 0): fewer still.
    const TetFill fast = run(2 * growth);
    EXPECT_LT(2 * fast.tets.size(), f.tets.size()) << fast.tets.size() << " vs " << f.tets.size();
    const TetFill none = run(0.0);
    EXPECT_LT(none.tets.size(), fast.tets.size());
}

// Also the check that TetGen's failures reach Strata as exceptions: Debian's libtet 1.5.0 frees
// its mesh twice when it fails (SIGSEGV) unless tetgen_fill.cpp's terminatetetgen replacement
// is in place.
TEST(TetgenFill, SelfIntersectingBoundaryIsBackendError) {
    SurfaceMesh b;
    b.patches.push_back({"wall", PatchKind::Wall});
    add_box(b, Vec3::Zero(), Vec3::Ones(), 2, 0, true);
    add_box(b, Vec3::Constant(0.3), Vec3::Constant(1.3), 2, 0, true);  // no shared nodes
    // The message says what intersects and what to do (about the layers).
    test::expect_error<BackendError>([&] { fill_with_tets(b, {}, TetFillParams{}); }, {"intersect", "layer"});
}

TEST(TetgenFill, MissingHolePointIsBackendError) {
    const SurfaceMesh b = cube_in_box(2, 2);
    test::expect_error<BackendError>([&] { fill_with_tets(b, {}, TetFillParams{}); }, {"hole", "patch 'wall'"});
}

TEST(TetgenFill, CavityOrientedOutOfTheCavityIsInputError) {
    const SurfaceMesh b = cube_in_box(2, 2, /*inner_outward=*/true);
    test::expect_error<InputError>([&] { fill_with_tets(b, kCubeHole, TetFillParams{}); },
                                   {"points into the region", "patch 'wall'"});
}

TEST(TetgenFill, BadInputIsInputError) {
    SurfaceMesh inverted;
    inverted.patches.push_back({"farfield", PatchKind::Farfield});
    add_box(inverted, Vec3::Zero(), Vec3::Ones(), 1, 0, false);
    EXPECT_THROW(fill_with_tets(inverted, {}, TetFillParams{}), InputError);

    SurfaceMesh twice = unit_cube();
    twice.add_face({twice.face_node(3, 0), twice.face_node(3, 2), twice.face_node(3, 1)}, 0);
    add_box(twice, Vec3::Constant(2.0), Vec3::Constant(3.0), 1, 0, true);  // keeps the volume positive
    try {
        fill_with_tets(twice, {}, TetFillParams{});
        ADD_FAILURE() << "no exception for a repeated triangle";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("same nodes as boundary triangle 3"), std::string::npos) << e.what();
    }

    SurfaceMesh quads = unit_cube();
    quads.add_face({0, 1, 2, 3}, 0);
    EXPECT_THROW(fill_with_tets(quads, {}, TetFillParams{}), InputError);

    TetFillParams p;
    p.radius_edge = 0.9;
    EXPECT_THROW(fill_with_tets(unit_cube(), {}, p), InputError);
    p = TetFillParams{};
    p.growth = -1.0;
    EXPECT_THROW(fill_with_tets(unit_cube(), {}, p), InputError);
    for (const double bad : {45.0, 180.0, -1.0}) {
        p = TetFillParams{};
        p.max_dihedral = bad;
        strata::test::expect_error<InputError>([&] { fill_with_tets(unit_cube(), {}, p); }, {"max_dihedral"});
    }
    EXPECT_THROW(fill_with_tets(SurfaceMesh{}, {}, TetFillParams{}), InputError);
}

// ---------------------------------------------------------------------------------------
// The platform check (PLATFORM.md). Debian's libgmsh exports its own modified TetGen under the
// same symbol names as libtet; in one symbol scope one of them binds to the other's copy and
// crashes whatever the link order (-lgmsh -ltet: TetGen; -ltet -lgmsh: Gmsh's HXT mesher).
// fill_with_tets therefore dlopen()s libtet with RTLD_LOCAL | RTLD_DEEPBIND instead of
// linking it. These tests guard that: libtet stays out of the global scope, and TetGen and
// Gmsh's Delaunay and HXT 3D meshers all work in this one process, in both orders.

constexpr const char* kTetrahedralizeSymbol = "_Z14tetrahedralizePcP8tetgenioS1_S1_S1_";
constexpr const char* kInittablesSymbol = "_ZN10tetgenmesh10inittablesEv";  // defined by both libraries

/// The shared object that defines \p address ("" if none).
std::string object_of(const void* address) {
    Dl_info info{};
    return address != nullptr && dladdr(address, &info) != 0 && info.dli_fname ? info.dli_fname : "";
}

TEST(TetgenPlatform, LibtetStaysOutOfTheGlobalSymbolScope) {
    // Before and after TetGen has run: the global scope (what libgmsh's calls bind to) has no
    // libtet, and the TetGen class symbols both libraries define resolve to libgmsh.
    for (int pass = 0; pass < 2; ++pass) {
        EXPECT_EQ(dlsym(RTLD_DEFAULT, kTetrahedralizeSymbol), nullptr) << "libtet is linked (pass " << pass << ")";
        const std::string shared = object_of(dlsym(RTLD_DEFAULT, kInittablesSymbol));
        EXPECT_NE(shared.find("libgmsh"), std::string::npos) << "tetgenmesh::inittables() from " << shared;
        if (pass == 0) fill_with_tets(unit_cube(), {}, TetFillParams{});
    }
    // libtet is loaded privately, and its tetrahedralize is its own.
    void* tet = dlopen("libtet.so.1.5", RTLD_NOW | RTLD_NOLOAD);
    ASSERT_NE(tet, nullptr) << "libtet not loaded after fill_with_tets";
    EXPECT_NE(object_of(dlsym(tet, kTetrahedralizeSymbol)).find("libtet"), std::string::npos);
    dlclose(tet);
}

/// Mesh the unit sphere with Gmsh's own 3D mesher (algorithm 1 = Delaunay, 10 = HXT).
struct GmshSphere {
    std::size_t tets = 0;
    double volume = 0.0;      ///< Σ tet volumes
    double min_volume = 0.0;  ///< smallest signed tet volume
};
GmshSphere gmsh_sphere(int algorithm) {
    GmshSession session("tet_platform");
    GmshOptionScope options;
    options.set("Mesh.Algorithm3D", algorithm);
    options.set("Mesh.MeshSizeMax", 0.25);
    gmsh::model::occ::addSphere(0, 0, 0, 1);
    gmsh::model::occ::synchronize();
    gmsh::model::mesh::generate(3);
    std::vector<std::size_t> tags, nodes, node_tags;
    std::vector<double> coords, param;
    gmsh::model::mesh::getElementsByType(4, tags, nodes);
    gmsh::model::mesh::getNodes(node_tags, coords, param);
    std::map<std::size_t, Vec3> x;
    for (std::size_t i = 0; i < node_tags.size(); ++i)
        x[node_tags[i]] = Vec3(coords[3 * i], coords[3 * i + 1], coords[3 * i + 2]);
    GmshSphere r;
    r.tets = tags.size();
    r.min_volume = std::numeric_limits<double>::infinity();
    for (std::size_t t = 0; t < tags.size(); ++t) {
        const Vec3 &a = x[nodes[4 * t]], &b = x[nodes[4 * t + 1]], &c = x[nodes[4 * t + 2]], &d = x[nodes[4 * t + 3]];
        const double v = (b - a).cross(c - a).dot(d - a) / 6.0;
        r.volume += v;
        r.min_volume = std::min(r.min_volume, v);
    }
    return r;
}

/// Gmsh's mesh of the sphere is sound: tets, all positive, filling the (faceted) sphere.
void expect_sound(const GmshSphere& g, int algorithm) {
    EXPECT_GT(g.tets, 500u) << "algorithm " << algorithm;
    EXPECT_GT(g.min_volume, 0.0) << "algorithm " << algorithm;
    EXPECT_NEAR(g.volume, 4.0 / 3.0 * M_PI, 0.05 * 4.0 / 3.0 * M_PI) << "algorithm " << algorithm;
}

std::size_t tetgen_cavity_tets() {
    const SurfaceMesh b = cube_in_box(4, 2);
    const TetFill f = fill_with_tets(b, kCubeHole, TetFillParams{});
    expect_valid_fill(b, f, 124.0);
    return f.tets.size();
}

// Gmsh's Delaunay mesher is deterministic: the same tets before and after TetGen ran. HXT's
// count varies between calls in one process even without libtet (1502, 1477, 1476 seen), so
// it is checked for soundness only.
TEST(TetgenPlatform, GmshThenTetgenThenGmsh) {
    const GmshSphere d1 = gmsh_sphere(1);
    expect_sound(d1, 1);
    expect_sound(gmsh_sphere(10), 10);
    const std::size_t t1 = tetgen_cavity_tets();
    const GmshSphere d2 = gmsh_sphere(1);
    expect_sound(d2, 1);
    EXPECT_EQ(d1.tets, d2.tets);
    expect_sound(gmsh_sphere(10), 10);
    EXPECT_EQ(t1, tetgen_cavity_tets());
}

TEST(TetgenPlatform, TetgenThenGmsh) {
    const std::size_t t1 = tetgen_cavity_tets();
    expect_sound(gmsh_sphere(10), 10);
    expect_sound(gmsh_sphere(1), 1);
    EXPECT_EQ(t1, tetgen_cavity_tets());
}

}  // namespace
