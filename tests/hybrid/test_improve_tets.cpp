// improve_tets: the 2-3 flip, edge removal, the moving of interior nodes, point insertion and the
// removal of a face checkMesh finds too skewed each on a configuration that needs it, and on a
// TetGen fill the invariants whatever was changed: the same region (volume), the same boundary
// triangles, conforming faces, every tetrahedron positive, the boundary's nodes where they were,
// the worst never worse, the same result twice.

#include <strata/core/cell_quality.h>
#include <strata/core/error.h>
#include <strata/core/solver_checks.h>
#include <strata/hybrid/improve_tets.h>
#include <strata/hybrid/tetgen_fill.h>

#include <gtest/gtest.h>

#include "box_surface.h"
#include "test_support.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <vector>

using namespace strata;

namespace {

using Tet = std::array<Index, 4>;
using Tri = std::array<Index, 3>;

double volume(const TetFill& f, const Tet& t) {
    const auto& p = f.points;
    return (p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]]).dot(p[t[3]] - p[t[0]]) / 6.0;
}

double worst(const TetFill& f) {
    double w = 1.0;
    for (const Tet& t : f.tets) w = std::min(w, tet_min_scaled_jacobian(f.points, t));
    return w;
}

/// Each face of the fill, sorted, with how many tetrahedra have it.
std::map<Tri, int> face_counts(const TetFill& f) {
    std::map<Tri, int> c;
    static constexpr int kFace[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};
    for (const Tet& t : f.tets)
        for (const auto& lf : kFace) {
            Tri k{t[lf[0]], t[lf[1]], t[lf[2]]};
            std::sort(k.begin(), k.end());
            ++c[k];
        }
    return c;
}

std::vector<Tri> boundary_faces(const TetFill& f) {
    std::vector<Tri> b;
    for (const auto& [k, n] : face_counts(f))
        if (n == 1) b.push_back(k);
    return b;
}

double total_volume(const TetFill& f) {
    double v = 0.0;
    for (const Tet& t : f.tets) v += volume(f, t);
    return v;
}

/// \p after fills what \p before filled: every tetrahedron positive, every face on one or two,
/// the same boundary triangles and volume, the first \p fixed points unmoved, and the worst
/// tetrahedron no worse.
void expect_same_region(const TetFill& before, const TetFill& after, Index fixed) {
    for (const Tet& t : after.tets) EXPECT_GT(volume(after, t), 0.0);
    for (const auto& [k, n] : face_counts(after)) EXPECT_LE(n, 2) << "face " << k[0] << " " << k[1] << " " << k[2];
    EXPECT_EQ(boundary_faces(after), boundary_faces(before));
    EXPECT_NEAR(total_volume(after), total_volume(before), 1e-12 * std::abs(total_volume(before)));
    ASSERT_EQ(after.points.size(), before.points.size());
    for (Index i = 0; i < fixed; ++i) EXPECT_EQ(after.points[i], before.points[i]) << "boundary node " << i;
    EXPECT_GE(worst(after), worst(before));
}

/// Two tetrahedra on the triangle p0 p1 p2 (radius 1 round the z axis), apexes u = (0, 0, h)
/// and v = (0, 0, -h); or, \p round_edge, the three round the edge u–v.
TetFill bipyramid(double h, bool round_edge) {
    TetFill f;
    for (int i = 0; i < 3; ++i) {
        const double a = 2.0 * M_PI * i / 3.0;
        f.points.emplace_back(std::cos(a), std::sin(a), 0.0);
    }
    f.points.emplace_back(0.0, 0.0, h);   // 3: u
    f.points.emplace_back(0.0, 0.0, -h);  // 4: v
    if (round_edge) {
        for (Index i = 0; i < 3; ++i) f.tets.push_back({3, 4, i, (i + 1) % 3});
    } else {
        f.tets = {{0, 1, 2, 3}, {1, 0, 2, 4}};
    }
    for (Tet& t : f.tets)
        if (volume(f, t) < 0.0) std::swap(t[0], t[1]);
    return f;
}

TEST(ImproveTets, RemovesAnEdgeWhoseRingIsWorseThanTwoTetrahedra) {
    const TetFill before = bipyramid(1.5, true);  // three round a long edge: 0.27; two would be 0.67
    TetFill f = before;
    const TetImproveReport r = improve_tets(f, 5, {.below = 0.5});
    EXPECT_EQ(r.edge_removals, 1);
    EXPECT_EQ(r.flips, 0);
    ASSERT_EQ(f.tets.size(), 2u);
    expect_same_region(before, f, 5);
    EXPECT_NEAR(r.min_before, worst(before), 1e-12);
    EXPECT_NEAR(r.min_after, worst(f), 1e-12);
    EXPECT_GT(worst(f), 0.6);
    EXPECT_LT(worst(before), 0.3);
}

TEST(ImproveTets, FlipsTwoFlatTetrahedraIntoThree) {
    const TetFill before = bipyramid(0.3, false);  // two on a wide face: 0.249; three round u–v: 0.275
    TetFill f = before;
    const TetImproveReport r = improve_tets(f, 5, {.below = 0.5});
    EXPECT_EQ(r.flips, 1);
    ASSERT_EQ(f.tets.size(), 3u);
    expect_same_region(before, f, 5);
    EXPECT_GT(worst(f), 0.27);
    EXPECT_LT(worst(before), 0.25);
}

TEST(ImproveTets, LeavesAConfigurationAlreadyAtItsBest) {
    const TetFill before = bipyramid(1.0, false);  // two: 0.61, better than the three round u–v
    TetFill f = before;
    const TetImproveReport r = improve_tets(f, 5, {.below = 0.9});
    EXPECT_EQ(r.flips + r.edge_removals + r.moved_nodes, 0);
    EXPECT_EQ(f.tets, before.tets);
    EXPECT_EQ(f.points, before.points);
}

/// The unit cube's 8 corners (the boundary, 12 triangles) and one interior point \p c joined
/// to every boundary triangle.
TetFill cube_star(const Vec3& c) {
    TetFill f;
    for (int i = 0; i < 8; ++i) f.points.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
    f.points.push_back(c);
    const std::array<std::array<Index, 4>, 6> sides{
        {{0, 1, 3, 2}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 3, 7, 5}}};
    for (const auto& s : sides)
        for (const Tri& t : {Tri{s[0], s[1], s[2]}, Tri{s[0], s[2], s[3]}}) {
            Tet tet{t[0], t[1], t[2], 8};
            if (volume(f, tet) < 0.0) std::swap(tet[0], tet[1]);
            f.tets.push_back(tet);
        }
    return f;
}

TEST(ImproveTets, MovesAnInteriorNodeAwayFromTheBoundary) {
    const TetFill before = cube_star({0.5, 0.45, 0.03});  // near the bottom: flat tetrahedra there
    TetFill f = before;
    const TetImproveReport r = improve_tets(f, 8);
    EXPECT_GT(r.moved_nodes, 0);
    expect_same_region(before, f, 8);
    EXPECT_LT(worst(before), 0.1);
    EXPECT_GT(worst(f), 0.3);
    EXPECT_GT(f.points[8].z(), 0.3);
    EXPECT_EQ(r.inserted_nodes, 0);  // only where every corner is fixed
}

TEST(ImproveTets, AnInsertedPointsCavityNeverSwallowsANode) {
    // The same cube with its point fixed: the flat tetrahedra at the bottom have four fixed
    // corners and no flip helps them; the only cavity whose new point would lift them is the
    // whole star of the cube's point, which would then be in no tetrahedron (a point the mesh
    // carries and checkMesh fails: "Unused points"). So nothing is inserted and every node stays
    // in a tetrahedron. (Points are inserted where a cavity keeps its nodes: the notched box of
    // Cli.TetrahedraAreImprovedAfterTetGen.)
    const TetFill before = cube_star({0.5, 0.45, 0.03});
    TetFill f = before;
    const TetImproveReport r = improve_tets(f, 9);
    EXPECT_EQ(r.moved_nodes, 0);
    EXPECT_EQ(r.inserted_nodes, 0);
    ASSERT_EQ(f.points.size(), before.points.size());
    std::vector<char> used(f.points.size(), 0);
    for (const Tet& t : f.tets)
        for (const Index v : t) used[static_cast<std::size_t>(v)] = 1;
    EXPECT_EQ(std::count(used.begin(), used.end(), 1), static_cast<std::ptrdiff_t>(f.points.size()));
    for (const Tet& t : f.tets) EXPECT_GT(volume(f, t), 0.0);
    EXPECT_EQ(boundary_faces(f), boundary_faces(before));
    EXPECT_NEAR(total_volume(f), 1.0, 1e-12);
}

TEST(ImproveTets, KeepsTheRegionOfATetGenFillAndRaisesItsWorst) {
    // A box with a cubic cavity (the walls finer than the farfield), as TetGen fills it: 240
    // of its tetrahedra below 0.2, the worst 0.045.
    SurfaceMesh b;
    b.patches.push_back({"farfield", PatchKind::Farfield});
    b.patches.push_back({"wall", PatchKind::Wall});
    test::add_box(b, Vec3(-2, -2, -2), Vec3(3, 3, 3), 3, 0, true);
    test::add_box(b, Vec3(0, 0, 0), Vec3(1, 1, 1), 4, 1, false);
    const TetFill before = fill_with_tets(b, {Vec3(0.5, 0.5, 0.5)}, TetFillParams{});
    TetFill f = before;
    const TetImproveReport r = improve_tets(f, b.num_points());
    expect_same_region(before, f, b.num_points());
    EXPECT_GT(r.flips + r.edge_removals, 10);
    EXPECT_GT(r.moved_nodes, 10);
    EXPECT_GT(r.below_before, 100);
    EXPECT_LT(r.below_after, r.below_before / 10);
    EXPECT_GT(r.min_after, 2.0 * r.min_before);
    EXPECT_NEAR(r.min_after, worst(f), 1e-12);
    EXPECT_FALSE(r.budget_reached);
    TetFill again = before;
    improve_tets(again, b.num_points());
    EXPECT_EQ(again.tets, f.tets);
    EXPECT_EQ(again.points, f.points);
    // With work for 3 qualities per tetrahedron: it stops early, what it did is sound.
    TetFill brief = before;
    const TetImproveReport rb =
        improve_tets(brief, b.num_points(), {.evaluations_per_tet = 3.0, .evaluations_floor = 0.0});
    EXPECT_TRUE(rb.budget_reached);
    expect_same_region(before, brief, b.num_points());
    EXPECT_LT(rb.edge_removals + rb.flips + rb.moved_nodes, r.edge_removals + r.flips + r.moved_nodes);
    EXPECT_GT(rb.below_after, r.below_after);
}

/// The largest checkMesh skewness over the faces two tetrahedra of \p f share.
double worst_interior_skewness(const TetFill& f) {
    static constexpr int kFace[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};
    auto centre = [&](const Tet& t) {
        return Vec3(0.25 * (f.points[t[0]] + f.points[t[1]] + f.points[t[2]] + f.points[t[3]]));
    };
    double w = 0.0;
    for (std::size_t i = 0; i < f.tets.size(); ++i)
        for (std::size_t j = i + 1; j < f.tets.size(); ++j)
            for (const auto& lf : kFace) {
                const Index v[3] = {f.tets[i][lf[0]], f.tets[i][lf[1]], f.tets[i][lf[2]]};
                const Tet& o = f.tets[j];
                if (std::count_if(std::begin(v), std::end(v),
                                  [&](Index x) { return std::find(o.begin(), o.end(), x) != o.end(); }) != 3)
                    continue;
                const Vec3 cn = centre(o);
                w = std::max(w, face_skewness(f.points.data(), v, 3, centre(f.tets[i]), &cn));
            }
    return w;
}

TEST(ImproveTets, RemovesAnEdgeWhoseFacesAreTooSkewedForCheckMesh) {
    // Three tetrahedra round the edge a–b (the z axis from -1 to 1), the ring c = (1, 0, 0) and
    // d, e twelve units the other way: the face a b c between (a, b, c, d) and (a, b, e, c) has
    // the line of their centres (parallel to d–e) meet its plane twelve units off, skewness
    // 4.6; two tetrahedra on c d e have none above 1. The scaled Jacobian bound is set below
    // all of them (the worst 0.003), so only the skewness pass acts.
    TetFill before;
    before.points = {{0, 0, -1}, {0, 0, 1}, {1, 0, 0}, {-12, 3, 0}, {-12, -3, 0}};
    before.tets = {{0, 1, 2, 3}, {0, 1, 3, 4}, {0, 1, 4, 2}};
    for (Tet& t : before.tets)
        if (volume(before, t) < 0.0) std::swap(t[0], t[1]);
    ASSERT_GT(worst_interior_skewness(before), kFoamSkewness);
    TetFill f = before;
    const TetImproveReport r = improve_tets(f, 5, {.below = 1e-9});
    EXPECT_EQ(r.flips + r.edge_removals + r.moved_nodes, 0);
    EXPECT_EQ(r.skew_changes, 1);
    EXPECT_EQ(r.skewed_before, 1);
    EXPECT_EQ(r.skewed_after, 0);
    ASSERT_EQ(f.tets.size(), 2u);
    expect_same_region(before, f, 5);
    EXPECT_LT(worst_interior_skewness(f), 1.0);
}

TEST(ImproveTets, LeavesASkewedFaceThatNoFlipCanRemove) {
    // The same without (a, b, d, e): the ring round a–b is open (a–b on the boundary), the
    // segment d–e passes outside the face a b c (no 2-3 flip), and the rings round a–c and
    // b–c are open too. The skewed face stays, counted, and the fill is as it was.
    TetFill before;
    before.points = {{0, 0, -1}, {0, 0, 1}, {1, 0, 0}, {-12, 3, 0}, {-12, -3, 0}};
    before.tets = {{0, 1, 2, 3}, {0, 1, 4, 2}};
    for (Tet& t : before.tets)
        if (volume(before, t) < 0.0) std::swap(t[0], t[1]);
    ASSERT_GT(worst_interior_skewness(before), kFoamSkewness);
    TetFill f = before;
    const TetImproveReport r = improve_tets(f, 5, {.below = 1e-9});
    EXPECT_EQ(r.skew_changes, 0);
    EXPECT_EQ(f.tets, before.tets);
    EXPECT_EQ(r.skewed_before, 1);
    EXPECT_EQ(r.skewed_after, 1);
}

TEST(ImproveTets, OffLeavesTheFillAsItIs) {
    const TetFill before = bipyramid(1.5, true);
    TetFill f = before;
    const TetImproveReport r = improve_tets(f, 5, {.below = 0.0, .max_passes = 10});
    EXPECT_EQ(f.tets, before.tets);
    EXPECT_EQ(r.edge_removals, 0);
}

TEST(ImproveTets, RefusesBadParameters) {
    TetFill f = bipyramid(1.5, true);
    test::expect_error<InputError>([&] { improve_tets(f, 5, {.below = 1.0}); }, {"below = 1", "[0, 1)"});
    test::expect_error<InputError>([&] { improve_tets(f, 5, {.below = -0.1}); }, {"below"});
    test::expect_error<InputError>([&] { improve_tets(f, 5, {.below = std::nan("")}); }, {"below"});
    test::expect_error<InputError>([&] { improve_tets(f, 5, {.below = 0.2, .max_passes = 0}); }, {"max_passes"});
    test::expect_error<InputError>([&] { improve_tets(f, 5, {.evaluations_per_tet = 0.0}); }, {"evaluations_per_tet"});
    test::expect_error<InputError>([&] { improve_tets(f, 6); }, {"num_fixed = 6"});
}

}  // namespace
