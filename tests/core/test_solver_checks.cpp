// OpenFOAM checkMesh's figures (solver_checks.h) on cells whose figures are worked out by hand
// from checkMesh's definitions; tests/openfoam/check_figures.sh compares them with checkMesh
// itself on a real mesh.

#include "box_mesh.h"

#include <strata/core/cell_faces.h>
#include <strata/core/cell_quality.h>
#include <strata/core/face_match.h>
#include <strata/core/solver_checks.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <random>
#include <string>

using namespace strata;
using strata::test::BoxMesh;
using strata::test::CubeSplit;

namespace {

SolverChecks checks(const VolumeMesh& m, int threads = 0) {
    const FaceMatch match = match_faces(m, threads);
    EXPECT_TRUE(match.ok());
    return solver_checks(m, match, threads);
}

/// Two unit cubes along x; the points of the far side (x = 2) moved by \p shift in y, so the
/// second cell is a parallelepiped leaning away from the first.
VolumeMesh leaning_pair(double shift) {
    VolumeMesh m = BoxMesh(2, 1, 1).build();
    for (Vec3& p : m.points)
        if (p.x() > 1.5) p.y() += shift;
    return m;
}

}  // namespace

TEST(SolverChecks, UnitCubesAreOrthogonalUnskewedAndOfAspectRatioOne) {
    const SolverChecks s = checks(BoxMesh(3, 2, 2).build());
    EXPECT_NEAR(s.max_non_orthogonality_deg, 0.0, 1e-6);
    EXPECT_NEAR(s.max_skewness, 0.0, 1e-9);
    EXPECT_NEAR(s.max_aspect_ratio, 1.0, 1e-9);
    EXPECT_EQ(s.severely_non_orthogonal + s.skew_faces + s.high_aspect_cells + s.negative_pyramids, 0);
    EXPECT_TRUE(s.ok());
}

TEST(SolverChecks, APointNoCellUsesFailsAsCheckMeshFailsIt) {
    // checkMesh fails a polyMesh with a point no face uses ("Unused points found in the mesh").
    VolumeMesh m = BoxMesh(2, 1, 1).build();
    EXPECT_EQ(checks(m).unused_points, 0);
    m.points.push_back(Vec3(0.5, 0.5, 0.5));
    const SolverChecks s = checks(m);
    EXPECT_EQ(s.unused_points, 1);
    EXPECT_FALSE(s.ok());
    ASSERT_EQ(s.failures().size(), 1u);
    EXPECT_NE(s.failures()[0].find("1 points used by no cell (the first node 12 at (0.5, 0.5, 0.5))"), std::string::npos)
        << s.failures()[0];
}

TEST(SolverChecks, LeaningCellHasTheFiguresWorkedOutByHand) {
    // Centres (0.5, 0.5, 0.5) and (1.5, 1.5, 0.5): d = (1, 1, 0) against the shared face's
    // normal x, 45°. d crosses the shared face at y = 1, 0.5 from its centre, over the face's
    // half-width 0.5 (more than 0.2 |d|): skewness 1. The far face's centre (2, 2.5) lies 1 off
    // the cell centre's projection (2, 1.5), over its half-width 0.5: boundary skewness 2, the
    // largest. Σ|S| of the leaning cell is (6, 2, 2): aspect ratio 3.
    const SolverChecks s = checks(leaning_pair(2.0));
    EXPECT_NEAR(s.max_non_orthogonality_deg, 45.0, 1e-9);
    EXPECT_NEAR(s.mean_non_orthogonality_deg, 45.0, 1e-9);
    EXPECT_NEAR(s.max_skewness, 2.0, 1e-9);
    EXPECT_NE(s.worst_skew.find("the face at (2, 2.5, 0.5) of hexahedron 1"), std::string::npos) << s.worst_skew;
    EXPECT_NEAR(s.max_aspect_ratio, 3.0, 1e-9);
    EXPECT_NE(s.worst_aspect.find("hexahedron 1"), std::string::npos) << s.worst_aspect;
    EXPECT_TRUE(s.ok());
}

TEST(SolverChecks, OneFacesSkewnessIsTheFigureWorkedOutByHand) {
    // The shared face and the far face of LeaningCellHasTheFiguresWorkedOutByHand, alone:
    // skewness 1 between the two centres, 2 as the leaning cell's boundary face.
    const std::vector<Vec3> p = {{1, 0, 0}, {1, 1, 0}, {1, 1, 1}, {1, 0, 1},
                                 {2, 2, 0}, {2, 3, 0}, {2, 3, 1}, {2, 2, 1}};
    const Index shared[4] = {0, 1, 2, 3}, far[4] = {4, 5, 6, 7};
    const Vec3 owner(0.5, 0.5, 0.5), neighbour(1.5, 1.5, 0.5);
    EXPECT_NEAR(face_skewness(p.data(), shared, 4, owner, &neighbour), 1.0, 1e-12);
    EXPECT_NEAR(face_skewness(p.data(), shared, 4, neighbour, &owner), 1.0, 1e-12);  // either side
    EXPECT_NEAR(face_skewness(p.data(), far, 4, neighbour, nullptr), 2.0, 1e-12);
    // Centres on the face's normal through its centre: none.
    const Vec3 square(1.5, 0.5, 0.5);
    EXPECT_NEAR(face_skewness(p.data(), shared, 4, owner, &square), 0.0, 1e-12);
}

TEST(SolverChecks, ACellsCentreIsItsCentroidAsOpenFoamComputesIt) {
    // A pyramid's centroid lies a quarter of its height up, not at its corners' mean (a fifth);
    // a prism's and a leaning hexahedron's at their corners' mean.
    const std::array<Vec3, 5> pyramid{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0), Vec3(0.5, 0.5, 1)};
    EXPECT_LT((foam_cell_centre(pyramid.data(), CellType::Pyramid) - Vec3(0.5, 0.5, 0.25)).norm(), 1e-12);
    const std::array<Vec3, 6> prism{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0),
                                    Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(0, 1, 1)};
    EXPECT_LT((foam_cell_centre(prism.data(), CellType::Prism) - Vec3(1.0 / 3, 1.0 / 3, 0.5)).norm(), 1e-12);
    const std::array<Vec3, 8> hex{Vec3(1, 0, 0), Vec3(2, 2, 0), Vec3(2, 3, 0), Vec3(1, 1, 0),
                                  Vec3(1, 0, 1), Vec3(2, 2, 1), Vec3(2, 3, 1), Vec3(1, 1, 1)};
    EXPECT_LT((foam_cell_centre(hex.data(), CellType::Hex) - Vec3(1.5, 1.5, 0.5)).norm(), 1e-12);
}

TEST(SolverChecks, StrongLeanIsSeverelyNonOrthogonalAndTooSkewForCheckMesh) {
    // Shift 10: d = (1, 5, 0), atan(5) = 78.7° (above 70); the far face's centre lies 5 off,
    // over its half-width 0.5: skewness 10, above checkMesh's 4.
    const SolverChecks s = checks(leaning_pair(10.0));
    EXPECT_NEAR(s.max_non_orthogonality_deg, std::atan(5.0) * 180.0 / std::numbers::pi, 1e-9);
    EXPECT_EQ(s.severely_non_orthogonal, 1);
    EXPECT_EQ(s.non_orthogonality_errors, 0);
    EXPECT_NEAR(s.max_skewness, 10.0, 1e-9);
    EXPECT_EQ(s.skew_faces, 1);
    ASSERT_FALSE(s.ok());
    ASSERT_EQ(s.failures().size(), 1u);
    EXPECT_NE(s.failures()[0].find("1 faces with a skewness above 4, the worst 10"), std::string::npos)
        << s.failures()[0];
}

TEST(SolverChecks, SkewedFacesAreListedByTheirSlots) {
    // The same strong lean: the one face above 4 (the far face, on the boundary) is listed by
    // its slot; with the lean of 2 (skewness 2) nothing is listed.
    const VolumeMesh m = leaning_pair(10.0);
    const FaceMatch match = match_faces(m);
    std::vector<std::uint64_t> skewed{7, 8, 9};  // cleared first
    const SolverChecks s = solver_checks(m, match, 0, &skewed);
    ASSERT_EQ(skewed.size(), 1u);
    EXPECT_EQ(static_cast<Index>(skewed.size()), s.skew_faces);
    EXPECT_LT(match.across[skewed[0]], 0);  // a boundary face
    Index v[4];
    ASSERT_EQ(match.slots.nodes(skewed[0], v), 4);
    const VolumeMesh calm = leaning_pair(2.0);
    solver_checks(calm, match_faces(calm), 0, &skewed);
    EXPECT_TRUE(skewed.empty());
}

TEST(SolverChecks, FlatCellsHaveTheRatioOfTheirSides) {
    // A 1 × 1 × h box: Σ|S| = (2h, 2h, 2), so the ratio of components is 1/h.
    VolumeMesh m = BoxMesh(2, 1, 1).build();
    for (Vec3& p : m.points) p.z() *= 1e-4;
    const SolverChecks s = checks(m);
    EXPECT_NEAR(s.max_aspect_ratio, 1e4, 1e-6);
    EXPECT_EQ(s.high_aspect_cells, 2);
    // Each listed, in cell order, with its centre and its longest edge (a diagonal: √(1 + 1 + h²)).
    ASSERT_EQ(s.high_aspect.size(), 2u);
    for (int c = 0; c < 2; ++c) {
        const HighAspectCell& h = s.high_aspect[static_cast<std::size_t>(c)];
        EXPECT_NEAR((h.centre - Vec3(0.5 + c, 0.5, 0.5e-4)).norm(), 0.0, 1e-12) << c;
        EXPECT_NEAR(h.aspect_ratio, 1e4, 1e-6) << c;
        EXPECT_NEAR(h.longest_edge, std::sqrt(2.0 + 1e-8), 1e-12) << c;
    }
    EXPECT_TRUE(checks(BoxMesh(2, 1, 1).build()).high_aspect.empty());
    ASSERT_EQ(s.failures().size(), 1u);
    EXPECT_NE(s.failures()[0].find("2 cells with an aspect ratio above 1000"), std::string::npos);
    EXPECT_NE(s.failures()[0].find("a finer surface or a thicker first layer"), std::string::npos);
}

TEST(SolverChecks, InvertedCellHasInvertedFacePyramids) {
    // A tetrahedron listed in the wrong order, with its (then inward) faces as the boundary.
    VolumeMesh m;
    m.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
    m.tets.push_back({0, 2, 1, 3});
    m.boundary.patches.push_back({"wall", PatchKind::Wall});
    const CellFaceTable& t = cell_faces(CellType::Tet);
    for (int f = 0; f < t.count; ++f) {
        Index v[3];
        for (int c = 0; c < 3; ++c) v[c] = m.tets[0][static_cast<std::size_t>(t.node[f][c])];
        m.boundary.add_face(v, 3, 0);
    }
    const SolverChecks s = checks(m);
    EXPECT_EQ(s.negative_pyramids, 4);
    ASSERT_FALSE(s.ok());
    EXPECT_NE(s.worst_pyramid.find("tetrahedron 0"), std::string::npos);
}

TEST(SolverChecks, FiguresAreTheSameForAnyThreadCount) {
    // 24³ cubes of six tetrahedra each (20 chunks of faces), the interior points jittered so
    // that no two faces tie.
    BoxMesh box(24, 24, 24);
    for (int k = 0; k < 24; ++k)
        for (int j = 0; j < 24; ++j)
            for (int i = 0; i < 24; ++i) box.set(i, j, k, CubeSplit::Kuhn);
    VolumeMesh m = box.build();
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> jitter(-0.15, 0.15);
    for (Vec3& p : m.points)
        if (p.minCoeff() > 0.5 && p.maxCoeff() < 23.5) p += Vec3(jitter(rng), jitter(rng), jitter(rng));
    const SolverChecks a = checks(m, 1);
    for (int threads : {2, 3}) {
        const SolverChecks b = checks(m, threads);
        EXPECT_GT(a.max_non_orthogonality_deg, 1.0);
        EXPECT_EQ(a.max_non_orthogonality_deg, b.max_non_orthogonality_deg);
        EXPECT_EQ(a.mean_non_orthogonality_deg, b.mean_non_orthogonality_deg);
        EXPECT_EQ(a.worst_non_orthogonal, b.worst_non_orthogonal);
        EXPECT_EQ(a.max_skewness, b.max_skewness);
        EXPECT_EQ(a.worst_skew, b.worst_skew);
        EXPECT_EQ(a.max_aspect_ratio, b.max_aspect_ratio);
        EXPECT_EQ(a.worst_aspect, b.worst_aspect);
        EXPECT_EQ(a.severely_non_orthogonal, b.severely_non_orthogonal);
        EXPECT_EQ(a.skew_faces, b.skew_faces);
    }
    // Per cell (the .vtu's fields): the same for any thread count, and their largest values are
    // the mesh's, exactly: each face's figures computed as solver_checks computes them.
    const FaceMatch match = match_faces(m);
    const CellSolverFigures one = cell_solver_figures(m, match, 1), three = cell_solver_figures(m, match, 3);
    EXPECT_EQ(one.non_orthogonality_deg, three.non_orthogonality_deg);
    EXPECT_EQ(one.skewness, three.skewness);
    EXPECT_EQ(one.aspect_ratio, three.aspect_ratio);
    ASSERT_EQ(one.skewness.size(), static_cast<std::size_t>(m.num_cells()));
    EXPECT_EQ(*std::max_element(one.non_orthogonality_deg.begin(), one.non_orthogonality_deg.end()),
              a.max_non_orthogonality_deg);
    EXPECT_EQ(*std::max_element(one.skewness.begin(), one.skewness.end()), a.max_skewness);
    EXPECT_EQ(*std::max_element(one.aspect_ratio.begin(), one.aspect_ratio.end()), a.max_aspect_ratio);
}

TEST(SolverChecks, PerCellFiguresAreTheLargestOfTheCellsFaces) {
    // The leaning pair: its one interior face's non-orthogonality is both cells'; the mesh's
    // worst skewness is one of the two cells'.
    const VolumeMesh m = leaning_pair(0.5);
    const SolverChecks s = checks(m);
    const CellSolverFigures c = cell_solver_figures(m, match_faces(m));
    ASSERT_EQ(c.non_orthogonality_deg.size(), static_cast<std::size_t>(m.num_cells()));
    EXPECT_GT(s.max_non_orthogonality_deg, 10.0);
    const std::size_t n = c.skewness.size();
    for (std::size_t g = 0; g < n; ++g) {
        EXPECT_EQ(c.non_orthogonality_deg[g], s.max_non_orthogonality_deg) << g;
        EXPECT_LE(c.skewness[g], s.max_skewness) << g;
    }
    EXPECT_EQ(std::max(c.skewness[0], c.skewness[n - 1]), s.max_skewness);
}

namespace {

/// One cell of \p type on \p points (in Strata's node order, the bottom either way round: it
/// is turned to give the cell a positive volume), its faces the boundary.
template <std::size_t N>
VolumeMesh one_cell(std::vector<Vec3> points, CellType type) {
    const Vec3 bottom = (points[1] - points[0]).cross(points[2] - points[0]);
    if constexpr (N == 4 || N == 5) {  // a tetrahedron's 0-1-2 and a pyramid's base face its apex
        if (bottom.dot(points[N - 1] - points[0]) < 0.0) std::swap(points[1], points[N - 2]);
    } else if (bottom.dot(points[N / 2] - points[0]) < 0.0) {  // Strata's bottom faces its top
        std::swap(points[1], points[N / 2 - 1]);
        std::swap(points[N / 2 + 1], points[N - 1]);
    }
    VolumeMesh m;
    m.points = std::move(points);
    std::array<Index, N> cell{};
    for (std::size_t i = 0; i < N; ++i) cell[i] = static_cast<Index>(i);
    if constexpr (N == 4) m.tets.push_back(cell);
    if constexpr (N == 5) m.pyramids.push_back(cell);
    if constexpr (N == 6) m.prisms.push_back(cell);
    if constexpr (N == 8) m.hexes.push_back(cell);
    m.boundary.patches.push_back({"wall", PatchKind::Wall});
    const CellFaceTable& t = cell_faces(type);
    for (int f = 0; f < t.count; ++f) {
        Index v[4];
        const int n = t.size[f];
        for (int c = 0; c < n; ++c) v[c] = cell[static_cast<std::size_t>(t.node[f][c])];
        m.boundary.add_face(v, n, 0);
    }
    return m;
}

}  // namespace

TEST(SolverChecks, RightPrismAspectRatioIsThatOfTheCellItPredicts) {
    // A triangle and a quad tilted against the axes (the Cartesian components are what count),
    // and the right prism and hexahedron of height h on them, measured as cells.
    const Vec3 u = Vec3(1.0, 0.3, 0.2).normalized(), w = Vec3(-0.2, 1.0, 0.4);
    const Vec3 n = u.cross(w).normalized(), v = n.cross(u);
    for (double h : {1e-4, 1e-2, 0.5}) {
        const std::array<Vec3, 3> tri{Vec3(0.1, 0.2, 0.3), Vec3(0.1, 0.2, 0.3) + 0.9 * u,
                                      Vec3(0.1, 0.2, 0.3) + 0.2 * u + 0.5 * v};
        std::vector<Vec3> p(tri.begin(), tri.end());
        for (const Vec3& x : tri) p.push_back(x + h * n);
        const double predicted = right_prism_aspect_ratio(tri.data(), 3, h);
        const SolverChecks s = checks(one_cell<6>(p, CellType::Prism));
        EXPECT_EQ(s.negative_pyramids, 0);
        EXPECT_NEAR(s.max_aspect_ratio, predicted, 1e-9 * predicted) << h;
        // The other orientation of the face: the same cell.
        const std::array<Vec3, 3> back{tri[0], tri[2], tri[1]};
        EXPECT_NEAR(right_prism_aspect_ratio(back.data(), 3, h), predicted, 1e-9 * predicted);

        const std::array<Vec3, 4> quad{Vec3::Zero(), 0.7 * u, 0.7 * u + 0.4 * v, 0.4 * v};
        std::vector<Vec3> q(quad.begin(), quad.end());
        for (const Vec3& x : quad) q.push_back(x + h * n);
        const double hex = right_prism_aspect_ratio(quad.data(), 4, h);
        EXPECT_NEAR(checks(one_cell<8>(q, CellType::Hex)).max_aspect_ratio, hex, 1e-9 * hex) << h;
    }
    // An axis-aligned unit square under 1e-4: Σ|S| = (2h, 2h, 2), the ratio 1 / h.
    const std::array<Vec3, 4> square{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)};
    EXPECT_NEAR(right_prism_aspect_ratio(square.data(), 4, 1e-4), 1e4, 1e-6);
    const std::array<Vec3, 3> flat{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0)};
    EXPECT_TRUE(std::isinf(right_prism_aspect_ratio(flat.data(), 3, 1e-4)));
}

TEST(SolverChecks, LeaningPrismAspectRatioIsThatOfTheCellItPredicts) {
    // The root face of a thin wing (0.5 by 0.03 in the plane y = 0), its columns leaning 45
    // degrees out over the 90-degree edges at its corners as a bisector does: the cell stands
    // 0.71 h off the face, and checkMesh's figure rises by about 1 / 0.71 over the right
    // prism's (a winglet STL remeshed: 955 predicted, 1192 made).
    const double h = 3e-4, r = std::sqrt(0.5);
    const std::array<Vec3, 3> tri{Vec3(1, 0, 0), Vec3(0.5, 0, -0.03), Vec3(1, 0, -0.03)};
    const std::array<Vec3, 3> lean{Vec3(r, -r, 0), Vec3(0, -r, -r),
                                   Vec3(r * r * std::sqrt(2.0), -r, -0.5 * std::sqrt(2.0) * r)};
    std::array<Vec3, 3> d;
    for (int i = 0; i < 3; ++i) d[static_cast<std::size_t>(i)] = lean[static_cast<std::size_t>(i)].normalized();
    // Strata's prism: bottom 0-1-2 with its normal towards the top.
    const bool up = (tri[1] - tri[0]).cross(tri[2] - tri[0]).dot(d[0]) > 0.0;
    const std::array<int, 3> order = up ? std::array<int, 3>{0, 1, 2} : std::array<int, 3>{0, 2, 1};
    std::vector<Vec3> p;
    for (int i : order) p.push_back(tri[static_cast<std::size_t>(i)]);
    for (int i : order) p.push_back(tri[static_cast<std::size_t>(i)] + h * d[static_cast<std::size_t>(i)]);
    const SolverChecks cell = checks(one_cell<6>(p, CellType::Prism));
    const double predicted = leaning_prism_aspect_ratio(tri.data(), d.data(), 3, h);
    EXPECT_EQ(cell.negative_pyramids, 0);
    EXPECT_NEAR(cell.max_aspect_ratio, predicted, 1e-6 * predicted);
    EXPECT_GT(predicted, 1.2 * right_prism_aspect_ratio(tri.data(), 3, h));
    // Every direction the face's normal: the right prism, either orientation of the face.
    const Vec3 n = (tri[1] - tri[0]).cross(tri[2] - tri[0]).normalized();
    const std::array<Vec3, 3> normal{n, n, n};
    const double right = right_prism_aspect_ratio(tri.data(), 3, h);
    EXPECT_NEAR(leaning_prism_aspect_ratio(tri.data(), normal.data(), 3, h), right, 1e-9 * right);
    const std::array<Vec3, 3> back{tri[0], tri[2], tri[1]};
    EXPECT_NEAR(leaning_prism_aspect_ratio(back.data(), normal.data(), 3, h), right, 1e-9 * right);
    const std::array<Vec3, 4> square{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)};
    const std::array<Vec3, 4> z{Vec3(0, 0, 1), Vec3(0, 0, 1), Vec3(0, 0, 1), Vec3(0, 0, 1)};
    EXPECT_NEAR(leaning_prism_aspect_ratio(square.data(), z.data(), 4, 1e-4), 1e4, 1e-6);
}

TEST(SolverChecks, LeaningPrismAspectRatioWithAColumnAtTheWallIsTheStepCells) {
    // A wall triangle (0.3 wide, tilted against the axes) whose first corner's column stops at
    // the wall (a sharp edge without a fan): the first-layer cell is the pyramid closing that
    // step, base the side face of the two moving columns, apex the corner; with two stopped,
    // the tetrahedron. Their figures are checkMesh's on those cells, and flatter than the
    // prism's: a step at the first layer spans the face at the layer's height.
    const double h = 1e-4;
    const Vec3 a(0.0, 0.0, 0.0), b(0.3, 0.05, 0.02), c(0.1, 0.28, -0.03);
    const Vec3 n = (b - a).cross(c - a).normalized();
    const Vec3 db = (n + 0.2 * Vec3(1, 0, 0)).normalized(), dc = (n - 0.1 * Vec3(0, 1, 0)).normalized();
    const std::array<Vec3, 3> tri{a, b, c};
    const std::array<Vec3, 3> one{Vec3::Zero(), db, dc}, two{Vec3::Zero(), Vec3::Zero(), dc};
    const double pyramid = leaning_prism_aspect_ratio(tri.data(), one.data(), 3, h);
    const double tet = leaning_prism_aspect_ratio(tri.data(), two.data(), 3, h);
    EXPECT_NEAR(checks(one_cell<5>({b, c, c + h * dc, b + h * db, a}, CellType::Pyramid)).max_aspect_ratio, pyramid,
                1e-6 * pyramid);
    EXPECT_NEAR(checks(one_cell<4>({a, b, c, c + h * dc}, CellType::Tet)).max_aspect_ratio, tet, 1e-6 * tet);
    const std::array<Vec3, 3> all{n, db, dc};
    const double prism = leaning_prism_aspect_ratio(tri.data(), all.data(), 3, h);
    EXPECT_GT(pyramid, 1.3 * prism);
    EXPECT_GT(tet, pyramid);
    // Every column at the wall: no cell.
    const std::array<Vec3, 3> none{Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
    EXPECT_FALSE(std::isfinite(leaning_prism_aspect_ratio(tri.data(), none.data(), 3, h)));
}

TEST(SolverChecks, FacePyramidsInvertedIsCheckMeshsTestOnOneCell) {
    // The first-layer prism lying on its side that closed a step over a quad Gmsh bent round
    // the slotted wing's leading edge (the sweep's slot.geo with --quads, 15 layers from
    // 7.5e-4): its two moving segments 0-2 and 3-5 are 9e-4 long, its stopped corners 1 and 4
    // the far side of a wall quad whose diagonals' midpoints lie 0.039 apart. Every corner is
    // positive, but the cell's centre lies outside the wall quad's side: checkMesh counted the
    // face as incorrectly oriented.
    const std::vector<Vec3> bent{Vec3(-0.41875205, 0.0335252, 0.17833375),   Vec3(-0.49170131, 0.0108862, 0.19718511),
                                 Vec3(-0.41911334, 0.03434486, 0.17830355),  Vec3(-0.47772075, 0.01812715, 0.11648235),
                                 Vec3(-0.47690067, -0.01802628, 0.15739478), Vec3(-0.47856202, 0.01829784, 0.11645318)};
    EXPECT_GT(min_scaled_jacobian(bent.data(), CellType::Prism), 0.0);
    EXPECT_TRUE(face_pyramids_inverted(bent.data(), CellType::Prism));
    EXPECT_GT(checks(one_cell<6>(bent, CellType::Prism)).negative_pyramids, 0);
    // A prism over a flat triangle, and a tetrahedron and pyramid of the same region: none.
    const std::vector<Vec3> flat{Vec3(0, 0, 0),     Vec3(1, 0, 0),     Vec3(0, 1, 0),
                                 Vec3(0, 0, 0.001), Vec3(1, 0, 0.001), Vec3(0, 1, 0.001)};
    EXPECT_FALSE(face_pyramids_inverted(flat.data(), CellType::Prism));
    EXPECT_EQ(checks(one_cell<6>(flat, CellType::Prism)).negative_pyramids, 0);
    const std::array<Vec3, 4> tet{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
    EXPECT_FALSE(face_pyramids_inverted(tet.data(), CellType::Tet));
    const std::array<Vec3, 5> pyramid{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0), Vec3(0.5, 0.5, 0.5)};
    EXPECT_FALSE(face_pyramids_inverted(pyramid.data(), CellType::Pyramid));
}

TEST(SolverChecks, FanWedgeAspectRatioIsThatOfTheCellItPredicts) {
    // A fan's first wedge on an edge along y (the worst case: its ends face y alone) and on a
    // skewed edge, 75 degrees between its directions (a 150-degree edge's two wedges).
    const double h = 1e-3, angle = 75.0 * std::numbers::pi / 180.0;
    for (const Vec3& along : {Vec3(0, 1, 0), Vec3(0.3, 1.0, -0.2).normalized()}) {
        const Vec3 d1 = along.cross(Vec3(0, 0, 1)).normalized(), side = along.cross(d1);
        const Vec3 d2 = std::cos(angle) * d1 + std::sin(angle) * side;
        const Vec3 a(0.5, -0.1, 0.2), b = a + 0.4 * along;
        const double predicted = fan_wedge_aspect_ratio(a, b, d1, d2, h);
        // Strata's prism order: bottom a, a + h d1, a + h d2; top the same at b.
        std::vector<Vec3> p{a, a + h * d1, a + h * d2, b, b + h * d1, b + h * d2};
        const SolverChecks s = checks(one_cell<6>(p, CellType::Prism));
        EXPECT_EQ(s.negative_pyramids, 0);
        EXPECT_NEAR(s.max_aspect_ratio, predicted, 1e-9 * predicted);
    }
    // Along y: about twice the edge's length over h sin(angle) (0.4 / 1e-3 / 0.966 ≈ 414).
    const double y = fan_wedge_aspect_ratio(Vec3::Zero(), Vec3(0, 0.4, 0), Vec3(1, 0, 0),
                                            Vec3(std::cos(angle), 0, std::sin(angle)), h);
    EXPECT_GT(y, 1.5 * 0.4 / h / std::sin(angle));
    EXPECT_LT(y, 2.5 * 0.4 / h / std::sin(angle));
}
