// fill_with_tets with Gmsh's HXT (hybrid/src/hxt_fill.cpp, hxt_library.cpp): the same checks as
// TetGen's fill (test_tetgen_fill.cpp), the cavities it leaves empty without hole points, its
// grading, the same bytes for the same thread count, its failures and cancellation.

#include <strata/core/error.h>
#include <strata/hybrid/tetgen_fill.h>

#include <gtest/gtest.h>

#include "box_surface.h"
#include "tet_fill_support.h"
#include "test_support.h"

#include <cmath>
#include <vector>

using namespace strata;
using namespace strata::test;

namespace {

TetFillParams hxt(int threads = 1, double growth = 0.3) {
    TetFillParams p;
    p.mesher = TetMesher::Hxt;
    p.threads = threads;
    p.growth = growth;
    return p;
}

/// \p b with every node moved by up to \p amount of the unit cube's size in each direction (a
/// fixed pseudo-random pattern): the boxes' regular grids are a degenerate Delaunay input (many
/// points on one sphere) on which HXT 4.8 stops (HxtFill.DegenerateGridIsBackendError); a
/// layer top is not such a grid.
SurfaceMesh jittered(SurfaceMesh b, double amount) {
    std::uint32_t seed = 12345;
    auto next = [&] {
        seed = seed * 1664525u + 1013904223u;
        return static_cast<double>(seed >> 8) / static_cast<double>(1u << 24) - 0.5;  // [-0.5, 0.5)
    };
    for (Vec3& x : b.points) x += amount * Vec3(next(), next(), next());
    return b;
}

/// The volume \p b encloses (divergence theorem).
double boundary_volume(const SurfaceMesh& b) {
    double v = 0.0;
    for (Index f = 0; f < b.num_faces(); ++f)
        v += b.points[b.face_node(f, 0)].dot(b.points[b.face_node(f, 1)].cross(b.points[b.face_node(f, 2)])) / 6.0;
    return v;
}

/// Mean edge length of the tets whose centroid lies at distance [lo, hi) from the unit cube, and
/// their mean distance.
std::array<double, 2> mean_edge_between(const TetFill& f, double lo, double hi) {
    double sum = 0.0, dist = 0.0;
    int n = 0;
    for (const auto& t : f.tets) {
        const Vec3 c = 0.25 * (f.points[t[0]] + f.points[t[1]] + f.points[t[2]] + f.points[t[3]]);
        const double d = (c - c.cwiseMax(Vec3::Zero()).cwiseMin(Vec3::Ones())).norm();
        if (d >= lo && d < hi) sum += mean_edge(f, t), dist += d, ++n;
    }
    return {n ? sum / n : 0.0, n ? dist / n : 0.0};
}

TEST(HxtFill, FillsBetweenTheBoxAndTheCubeWithoutHolePoints) {
    const SurfaceMesh b = cube_in_box(4, 2);
    const TetFill f = fill_with_tets(b, {}, hxt());
    expect_valid_fill(b, f, 124.0);
    EXPECT_GT(f.points.size(), b.points.size() + 50);  // refined
    for (std::size_t i = b.points.size(); i < f.points.size(); ++i) {
        const Vec3& x = f.points[i];
        EXPECT_FALSE((x.array() >= 0.0).all() && (x.array() <= 1.0).all()) << "HXT point " << i << " in the cube";
    }
    // The hole point TetGen needs changes nothing.
    const TetFill g = fill_with_tets(b, kCubeHole, hxt());
    EXPECT_EQ(f.tets, g.tets);
}

TEST(HxtFill, TwoCavities) {
    SurfaceMesh b = cube_in_box(3, 2);
    add_box(b, Vec3(-1.5, -1.5, -1.5), Vec3(-0.5, -0.5, -0.5), 2, 1, false);
    const TetFill f = fill_with_tets(b, {}, hxt());
    expect_valid_fill(b, f, 123.0);
}

TEST(HxtFill, NoRefinementIsBoundaryOnly) {
    const SurfaceMesh b = cube_in_box(3, 2);
    TetFillParams p = hxt();
    p.refine = false;
    const TetFill f = fill_with_tets(b, {}, p);
    expect_valid_fill(b, f, 124.0);
    EXPECT_LE(f.points.size(), b.points.size() + 10);
}

// The same boundary and thread count: the same points and tets, as many times as it runs.
TEST(HxtFill, SameTetsForTheSameThreadCount) {
    const SurfaceMesh b = jittered(cube_in_box(8, 3), 0.02);
    for (const int threads : {1, 2}) {
        const TetFill f1 = fill_with_tets(b, {}, hxt(threads, 0.2));
        const TetFill f2 = fill_with_tets(b, {}, hxt(threads, 0.2));
        ASSERT_GT(f1.tets.size(), 1000u);
        expect_valid_fill(b, f1, boundary_volume(b));
        EXPECT_EQ(f1.points, f2.points) << threads << " threads";
        EXPECT_EQ(f1.tets, f2.tets) << threads << " threads";
    }
}

// The grading of TetGen's fill (TetgenFill.SizeGradingFollowsGrowth): the mean edge within 30 % of
// h(d) = 0.1 + growth·d at each distance from the wall.
TEST(HxtFill, SizeGradingFollowsGrowth) {
    const double outer = 6.0, wall_edge = 0.1, growth = 0.2;
    const SurfaceMesh b = jittered(cube_in_box(10, 5, false, outer), 0.01);
    const TetFill f = fill_with_tets(b, {}, hxt(2, growth));
    expect_valid_fill(b, f, boundary_volume(b));
    for (int k = 0; k < 3; ++k) {
        const auto [e, d] = mean_edge_between(f, 1.0 + k, 1.5 + k);
        ASSERT_GT(e, 0.0) << "band " << k;
        const double h = wall_edge + growth * d;
        EXPECT_GT(e, 0.7 * h) << "band " << k << ": mean edge " << e << " at distance " << d << ", h = " << h;
        EXPECT_LT(e, 1.3 * h) << "band " << k << ": mean edge " << e << " at distance " << d << ", h = " << h;
    }
    const TetFill fast = fill_with_tets(b, {}, hxt(2, 2 * growth));
    EXPECT_LT(2 * fast.tets.size(), f.tets.size()) << fast.tets.size() << " vs " << f.tets.size();
}

// HXT 4.8 stops (its Delaunay's parallel loop ends its process) on the regular grids of two boxes
// refined finely: a BackendError here (it runs in a child process), and the hybrid mesh falls
// back to TetGen (HybridMesh.HxtFallsBackToTetGen).
TEST(HxtFill, DegenerateGridIsBackendError) {
    const SurfaceMesh b = cube_in_box(8, 3);
    test::expect_error<BackendError>([&] { fill_with_tets(b, {}, hxt(1, 0.2)); }, {"HXT", "--tets tetgen"});
}

TEST(HxtFill, SelfIntersectingBoundaryIsBackendErrorNamingTetGen) {
    SurfaceMesh b;
    b.patches.push_back({"wall", PatchKind::Wall});
    add_box(b, Vec3::Zero(), Vec3::Ones(), 2, 0, true);
    add_box(b, Vec3::Constant(0.3), Vec3::Constant(1.3), 2, 0, true);
    test::expect_error<BackendError>([&] { fill_with_tets(b, {}, hxt()); }, {"HXT", "--tets tetgen"});
}

TEST(HxtFill, BadInputIsInputErrorAsForTetGen) {
    SurfaceMesh inverted;
    inverted.patches.push_back({"farfield", PatchKind::Farfield});
    add_box(inverted, Vec3::Zero(), Vec3::Ones(), 1, 0, false);
    EXPECT_THROW(fill_with_tets(inverted, {}, hxt()), InputError);
}

struct CancelAfter : Progress {
    mutable int asked = 0;
    int allowed;
    explicit CancelAfter(int n) : allowed(n) {}
    void report(std::string_view, double) override {}
    bool cancelled() const override { return ++asked > allowed; }
};

// Cancelled before HXT starts, and while it runs (its child process is asked every 0.1 s).
TEST(HxtFill, CancelledBeforeAndDuringTheRun) {
    const SurfaceMesh b = jittered(cube_in_box(20, 5, false, 6.0), 0.005);
    CancelAfter now(0), later(1);
    EXPECT_THROW(fill_with_tets(b, {}, hxt(1, 0.05), &now), Cancelled);
    EXPECT_THROW(fill_with_tets(b, {}, hxt(1, 0.05), &later), Cancelled);
    EXPECT_GT(later.asked, 1);
}

TEST(HxtFill, TetGenAndHxtInOneProcess) {
    const SurfaceMesh b = cube_in_box(4, 2);
    const TetFill t1 = fill_with_tets(b, kCubeHole, TetFillParams{});
    const TetFill h1 = fill_with_tets(b, {}, hxt(2));
    const TetFill t2 = fill_with_tets(b, kCubeHole, TetFillParams{});
    const TetFill h2 = fill_with_tets(b, {}, hxt(2));
    EXPECT_EQ(t1.tets, t2.tets);
    EXPECT_EQ(h1.tets, h2.tets);
}

TEST(HxtFill, MesherNames) {
    EXPECT_EQ(parse_tet_mesher("hxt"), TetMesher::Hxt);
    EXPECT_EQ(parse_tet_mesher(to_string(TetMesher::TetGen)), TetMesher::TetGen);
    test::expect_error<InputError>([] { parse_tet_mesher("netgen"); }, {"netgen", "tetgen", "hxt"});
}

}  // namespace
