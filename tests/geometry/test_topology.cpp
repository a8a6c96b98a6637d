#include <gtest/gtest.h>

#include <strata/core/error.h>
#include <strata/core/face_geometry.h>
#include <strata/geometry/topology.h>

#include "test_support.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <set>
#include <string>
#include <vector>

namespace strata {
namespace {

using test::closed_manifold;
using test::enclosed_volume;
using test::quad_grid;

constexpr double kPi = std::numbers::pi;

// ---------------------------------------------------------------- helpers

std::vector<Index> row(const Csr& c, Index i) {
    return {c.row_begin(i), c.row_end(i)};
}

/// The faces of \p m in a random order, each face's node list rotated by a random amount
/// (orientation kept), so nothing can depend on the order faces were built in.
SurfaceMesh shuffled(const SurfaceMesh& m, unsigned seed) {
    std::mt19937 rng(seed);
    std::vector<Index> order(static_cast<std::size_t>(m.num_faces()));
    for (Index f = 0; f < m.num_faces(); ++f) order[f] = f;
    std::shuffle(order.begin(), order.end(), rng);
    SurfaceMesh out;
    out.points = m.points;
    out.patches = m.patches;
    for (Index f : order) {
        std::vector<Index> v(m.face_begin(f), m.face_end(f));
        std::rotate(v.begin(), v.begin() + static_cast<long>(rng() % v.size()), v.end());
        out.add_face(v.data(), static_cast<Index>(v.size()), m.face_patch[f]);
    }
    return out;
}

/// Every face's node order reversed.
SurfaceMesh reversed(const SurfaceMesh& m) {
    SurfaceMesh out = m;
    for (Index f = 0; f < m.num_faces(); ++f)
        std::reverse(out.face_nodes.begin() + out.face_offsets[f], out.face_nodes.begin() + out.face_offsets[f + 1]);
    return out;
}

/// Rotation r such that got[(k + r) % M] == want[k] for all k, or -1.
int cyclic_shift(const std::vector<Index>& got, const std::vector<Index>& want) {
    if (got.size() != want.size()) return -1;
    const std::size_t m = got.size();
    for (std::size_t r = 0; r < m; ++r) {
        bool ok = true;
        for (std::size_t k = 0; k < m && ok; ++k) ok = got[(k + r) % m] == want[k];
        if (ok) return static_cast<int>(r);
    }
    return -1;
}

bool face_has(const SurfaceMesh& m, Index f, Index v) {
    return std::find(m.face_begin(f), m.face_end(f), v) != m.face_end(f);
}

enum class FanKind { Triangles, Quads, Mixed };

/// A planar closed fan in z = 0 around centre node 0: neighbours 1..M on the unit circle at
/// angles 2πk/M (so 1..M is counter-clockwise seen from +z), sector k spans neighbours k+1
/// and k+2 (cyclic). A quad sector has an extra outer corner; diag[k] is it (or kNone).
struct Fan {
    SurfaceMesh mesh;
    std::vector<Index> diag;  ///< per sector
};
Fan make_fan(int M, FanKind kind) {
    Fan fan;
    SurfaceMesh& m = fan.mesh;
    m.patches.push_back({"wall", PatchKind::Wall});
    m.points.emplace_back(0.0, 0.0, 0.0);
    for (int k = 0; k < M; ++k) {
        const double t = 2.0 * kPi * k / M;
        m.points.emplace_back(std::cos(t), std::sin(t), 0.0);
    }
    for (int k = 0; k < M; ++k) {
        const Index a = k + 1, b = (k + 1) % M + 1;
        const bool quad = kind == FanKind::Quads || (kind == FanKind::Mixed && k % 2 == 0);
        if (quad) {
            const double t = 2.0 * kPi * (k + 0.5) / M;
            const Index d = m.num_points();
            m.points.emplace_back(1.5 * std::cos(t), 1.5 * std::sin(t), 0.0);
            m.add_face({0, a, d, b}, 0);
            fan.diag.push_back(d);
        } else {
            m.add_face({0, a, b}, 0);
            fan.diag.push_back(kNone);
        }
    }
    return fan;
}

// ---------------------------------------------------------------- node rings

struct RingCase {
    int valence;
    FanKind kind;
};
class RingOrder : public ::testing::TestWithParam<RingCase> {};

TEST_P(RingOrder, CentreRingIsCounterClockwiseWithDiagonalsInTheirSectors) {
    const auto [M, kind] = GetParam();
    const Fan fan = make_fan(M, kind);
    std::vector<Index> ccw;
    for (Index k = 1; k <= M; ++k) ccw.push_back(k);

    for (unsigned seed : {1u, 2u, 3u, 4u, 5u}) {
        const SurfaceMesh m = shuffled(fan.mesh, seed);
        const NodeRings r = node_rings(m);
        ASSERT_EQ(r.neighbours.rows(), m.num_points());
        EXPECT_EQ(r.closed[0], 1);
        const std::vector<Index> nb = row(r.neighbours, 0);
        ASSERT_EQ(static_cast<int>(nb.size()), M);
        const int shift = cyclic_shift(nb, ccw);
        ASSERT_GE(shift, 0) << "seed " << seed;
        const Index off = r.neighbours.offsets[0];
        for (int k = 0; k < M; ++k) {
            // Ring slot j spans nb[j] → nb[j+1]: original sector k sits at slot (k + shift) % M.
            const Index j = off + (k + shift) % M;
            const Index f = r.faces[j];
            ASSERT_NE(f, kNone);
            EXPECT_TRUE(face_has(m, f, 0) && face_has(m, f, k + 1) && face_has(m, f, (k + 1) % M + 1))
                << "sector " << k;
            EXPECT_EQ(r.diagonals[j], fan.diag[k]) << "sector " << k << " seed " << seed;
        }

        // Reversing every face reverses the ring (and moves each diagonal with its sector).
        const NodeRings rr = node_rings(reversed(m));
        EXPECT_EQ(rr.closed[0], 1);
        std::vector<Index> cw(ccw.rbegin(), ccw.rend());
        const std::vector<Index> nbr = row(rr.neighbours, 0);
        const int rshift = cyclic_shift(nbr, cw);
        ASSERT_GE(rshift, 0);
        for (int k = 0; k < M; ++k) {
            // Clockwise list cw[i] = M - i; sector k spans cw[M-1-k] → cw[M-2-k] reversed, i.e. slot
            // i = (M - 2 - k) mod M spans cw[i] = k+2 → cw[i+1] = k+1.
            const int i = ((M - 2 - k) % M + M) % M;
            EXPECT_EQ(rr.diagonals[rr.neighbours.offsets[0] + (i + rshift) % M], fan.diag[k]) << "sector " << k;
        }
    }
}

INSTANTIATE_TEST_SUITE_P(
    Valences, RingOrder,
    ::testing::Values(RingCase{3, FanKind::Triangles}, RingCase{4, FanKind::Triangles}, RingCase{5, FanKind::Triangles},
                      RingCase{6, FanKind::Triangles}, RingCase{20, FanKind::Triangles}, RingCase{3, FanKind::Quads},
                      RingCase{4, FanKind::Quads}, RingCase{5, FanKind::Quads}, RingCase{6, FanKind::Quads},
                      RingCase{20, FanKind::Quads}, RingCase{3, FanKind::Mixed}, RingCase{4, FanKind::Mixed},
                      RingCase{5, FanKind::Mixed}, RingCase{6, FanKind::Mixed}, RingCase{20, FanKind::Mixed}));

/// Unit cube [0,1]³ of 6 outward quads; node id = x + 2y + 4z.
SurfaceMesh unit_cube() {
    SurfaceMesh m = test::cube_corners();
    m.add_face({0, 2, 3, 1}, 0);  // z = 0, normal -z
    m.add_face({4, 5, 7, 6}, 0);  // z = 1, +z
    m.add_face({0, 1, 5, 4}, 0);  // y = 0, -y
    m.add_face({2, 6, 7, 3}, 0);  // y = 1, +y
    m.add_face({0, 4, 6, 2}, 0);  // x = 0, -x
    m.add_face({1, 3, 7, 5}, 0);  // x = 1, +x
    return m;
}

TEST(NodeRings, CubeCornerIsValenceThreeCounterClockwiseFromOutside) {
    const SurfaceMesh base = unit_cube();
    for (Index f = 0; f < base.num_faces(); ++f)  // the builder itself is outward
        EXPECT_GT(face_area_vector(base, f).dot(face_centroid(base, base.points, f) - Vec3(0.5, 0.5, 0.5)), 0.0);
    const SurfaceMesh m = shuffled(base, 7);
    const NodeRings r = node_rings(m);
    const Vec3 centre(0.5, 0.5, 0.5);
    for (Index o = 0; o < 8; ++o) {
        ASSERT_EQ(r.neighbours.row_size(o), 3);
        EXPECT_EQ(r.closed[o], 1);
        const Vec3 x = m.points[o];
        const Vec3 out = x - centre;
        const Index off = r.neighbours.offsets[o];
        for (Index k = 0; k < 3; ++k) {
            const Index a = r.neighbours.values[off + k], b = r.neighbours.values[off + (k + 1) % 3];
            EXPECT_DOUBLE_EQ((m.points[a] - x).norm(), 1.0);  // edge neighbours
            EXPECT_GT((m.points[a] - x).cross(m.points[b] - x).dot(out), 0.0) << "node " << o;
            // The diagonal closes the unit square spanned by the two edge neighbours.
            const Index d = r.diagonals[off + k];
            ASSERT_NE(d, kNone);
            EXPECT_TRUE(m.points[d].isApprox(m.points[a] + m.points[b] - x));
            EXPECT_TRUE(face_has(m, r.faces[off + k], d));
        }
    }
}

/// A spherical cap: pole node 0 at (0,0,1), ring A of 20 nodes (1..20) at polar angle 0.3,
/// ring B (21..40) at 0.6; triangles pole–A, quads A–B, all normals outward.
SurfaceMesh polar_cap() {
    SurfaceMesh m;
    m.patches.push_back({"wall", PatchKind::Wall});
    m.points.emplace_back(0.0, 0.0, 1.0);
    for (double polar : {0.3, 0.6})
        for (int k = 0; k < 20; ++k) {
            const double t = 2.0 * kPi * k / 20;
            m.points.emplace_back(std::sin(polar) * std::cos(t), std::sin(polar) * std::sin(t), std::cos(polar));
        }
    for (Index k = 0; k < 20; ++k) {
        const Index a = 1 + k, b = 1 + (k + 1) % 20;
        m.add_face({0, a, b}, 0);
        m.add_face({a, a + 20, b + 20, b}, 0);
    }
    return m;
}

TEST(NodeRings, TwentyValentPoleOfACapIsCounterClockwiseFromOutside) {
    const SurfaceMesh base = polar_cap();
    for (Index f = 0; f < base.num_faces(); ++f)
        ASSERT_GT(face_area_vector(base, f).dot(face_centroid(base, base.points, f)), 0.0) << "builder outward";
    const SurfaceMesh m = shuffled(base, 11);
    const NodeRings r = node_rings(m);

    std::vector<Index> ccw;
    for (Index k = 1; k <= 20; ++k) ccw.push_back(k);
    EXPECT_EQ(r.closed[0], 1);
    ASSERT_GE(cyclic_shift(row(r.neighbours, 0), ccw), 0);
    const Vec3 o = m.points[0];
    for (Index k = 0; k < 20; ++k) {
        const Index j = r.neighbours.offsets[0] + k;
        const Index a = r.neighbours.values[j], b = r.neighbours.values[r.neighbours.offsets[0] + (k + 1) % 20];
        EXPECT_GT((m.points[a] - o).cross(m.points[b] - o).dot(o), 0.0);
        EXPECT_EQ(r.diagonals[j], kNone);  // all triangles
    }
    // Ring A nodes: closed, M = 4 (pole, both A neighbours, one B node), two triangle and two
    // quad sectors, counter-clockwise seen from outside.
    for (Index v = 1; v <= 20; ++v) {
        EXPECT_EQ(r.closed[v], 1);
        ASSERT_EQ(r.neighbours.row_size(v), 4);
        const Index off = r.neighbours.offsets[v];
        Index triangles = 0;
        for (Index k = 0; k < 4; ++k) {
            const Index a = r.neighbours.values[off + k], b = r.neighbours.values[off + (k + 1) % 4];
            EXPECT_GT((m.points[a] - m.points[v]).cross(m.points[b] - m.points[v]).dot(m.points[v]), 0.0);
            triangles += r.diagonals[off + k] == kNone;
        }
        EXPECT_EQ(triangles, 2);
    }
    // Ring B nodes lie on the cap's rim: open rings.
    for (Index v = 21; v <= 40; ++v) {
        EXPECT_EQ(r.closed[v], 0);
        ASSERT_EQ(r.neighbours.row_size(v), 3);
        const Index last = r.neighbours.offsets[v + 1] - 1;
        EXPECT_EQ(r.faces[last], kNone);
        EXPECT_EQ(r.diagonals[last], kNone);
    }
}

TEST(NodeRings, OpenRingsOnTheBoundaryOfAGrid) {
    // quad_grid(3,3): node (i,j) = 4j + i; face (i,j) = 3j + i = (n, n+1, n+5, n+4).
    const SurfaceMesh m = quad_grid(3, 3);
    const NodeRings r = node_rings(m);
    ASSERT_EQ(r.neighbours.rows(), 16);
    ASSERT_EQ(r.faces.size(), r.neighbours.values.size());
    ASSERT_EQ(r.diagonals.size(), r.neighbours.values.size());

    // Corner node 0: M = 2, from the boundary neighbour 1 counter-clockwise to 4.
    EXPECT_EQ(r.closed[0], 0);
    EXPECT_EQ(row(r.neighbours, 0), (std::vector<Index>{1, 4}));
    Index off = r.neighbours.offsets[0];
    EXPECT_EQ(r.faces[off], 0);
    EXPECT_EQ(r.diagonals[off], 5);
    EXPECT_EQ(r.faces[off + 1], kNone);
    EXPECT_EQ(r.diagonals[off + 1], kNone);

    // Edge node 1 on the bottom side: M = 3.
    EXPECT_EQ(r.closed[1], 0);
    EXPECT_EQ(row(r.neighbours, 1), (std::vector<Index>{2, 5, 0}));
    off = r.neighbours.offsets[1];
    EXPECT_EQ((std::vector<Index>{r.faces[off], r.faces[off + 1], r.faces[off + 2]}),
              (std::vector<Index>{1, 0, kNone}));
    EXPECT_EQ((std::vector<Index>{r.diagonals[off], r.diagonals[off + 1], r.diagonals[off + 2]}),
              (std::vector<Index>{6, 4, kNone}));

    // Interior node 5: closed, 4 neighbours counter-clockwise, diagonals are the grid diagonals.
    EXPECT_EQ(r.closed[5], 1);
    ASSERT_GE(cyclic_shift(row(r.neighbours, 5), {6, 9, 4, 1}), 0);
    std::set<Index> diagonals;
    for (Index k = r.neighbours.offsets[5]; k < r.neighbours.offsets[6]; ++k) diagonals.insert(r.diagonals[k]);
    EXPECT_EQ(diagonals, (std::set<Index>{0, 2, 8, 10}));

    // Every boundary node is open with its last sector empty; interior nodes closed.
    for (Index v = 0; v < 16; ++v) {
        const Index i = v % 4, j = v / 4;
        const bool boundary = i == 0 || i == 3 || j == 0 || j == 3;
        EXPECT_EQ(r.closed[v], boundary ? 0 : 1) << "node " << v;
        if (boundary) {
            EXPECT_EQ(r.faces[r.neighbours.offsets[v + 1] - 1], kNone);
        }
    }
}

TEST(NodeRings, LargeGridIsLinearAndCorrect) {
    // 100k nodes: a quadratic ring builder would not finish in the test timeout.
    const SurfaceMesh m = quad_grid(316, 316);
    const NodeRings r = node_rings(m);
    ASSERT_EQ(r.neighbours.rows(), m.num_points());
    Index closed = 0;
    for (Index v = 0; v < m.num_points(); ++v) closed += r.closed[v];
    EXPECT_EQ(closed, 315 * 315);
    const Index centre = 158 * 317 + 158;
    EXPECT_GE(cyclic_shift(row(r.neighbours, centre), {centre + 1, centre + 317, centre - 1, centre - 317}), 0);
}

TEST(NodeRings, NonManifoldVertexIsReportedWithItsNode) {
    // Two open triangle fans touching at node 0 (a bow tie).
    SurfaceMesh m;
    m.patches.push_back({"wall", PatchKind::Wall});
    m.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(-1, 0, 0), Vec3(-1, -1, 0)};
    m.add_face({0, 1, 2}, 0);
    m.add_face({0, 3, 4}, 0);
    try {
        node_rings(m);
        FAIL() << "expected TopologyError";
    } catch (const TopologyError& e) {
        EXPECT_NE(std::string(e.what()).find("node 0 "), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("non-manifold"), std::string::npos) << e.what();
    }

    // Two closed tetrahedra sharing one vertex: two closed fans at node 0.
    SurfaceMesh t;
    t.patches.push_back({"wall", PatchKind::Wall});
    t.points = {Vec3(0, 0, 0),  Vec3(1, 0, 0),  Vec3(0, 1, 0), Vec3(0, 0, 1),
                Vec3(-1, 0, 0), Vec3(0, -1, 0), Vec3(0, 0, -1)};
    for (Index base : {Index{0}, Index{3}}) {
        const Index a = base == 0 ? 1 : 4, b = a + 1, c = a + 2;
        t.add_face({0, b, a}, 0);
        t.add_face({0, a, c}, 0);
        t.add_face({0, c, b}, 0);
        t.add_face({a, b, c}, 0);
    }
    EXPECT_THROW(node_rings(t), TopologyError);
}

TEST(NodeRings, InconsistentOrientationIsReported) {
    SurfaceMesh m = quad_grid(2, 1);
    std::reverse(m.face_nodes.begin() + 4, m.face_nodes.end());
    EXPECT_THROW(node_rings(m), TopologyError);
}

// ---------------------------------------------------------------- merge

/// Every face gets its own copies of its nodes (as an STL file stores them).
SurfaceMesh exploded(const SurfaceMesh& m) {
    SurfaceMesh out;
    out.patches = m.patches;
    for (Index f = 0; f < m.num_faces(); ++f) {
        std::vector<Index> v;
        for (const Index* p = m.face_begin(f); p != m.face_end(f); ++p) {
            v.push_back(out.num_points());
            out.points.push_back(m.points[*p]);
        }
        out.add_face(v.data(), static_cast<Index>(v.size()), m.face_patch[f]);
    }
    return out;
}

TEST(Merge, ExplodedGridAndCubeMergeBack) {
    const SurfaceMesh grid = quad_grid(3, 2);
    const SurfaceMesh e = exploded(grid);
    ASSERT_EQ(e.num_points(), 24);
    const SurfaceMesh g = merge_coincident_nodes(e);
    EXPECT_EQ(g.num_points(), 12);
    ASSERT_EQ(g.num_faces(), grid.num_faces());
    for (Index f = 0; f < g.num_faces(); ++f)
        for (Index i = 0; i < 4; ++i) EXPECT_EQ(g.points[g.face_node(f, i)], grid.points[grid.face_node(f, i)]);
    EXPECT_EQ(edge_table(g).nodes.size(), 17u);

    // STL-like cube: 12 triangles, 36 nodes → 8.
    const SurfaceMesh cube = unit_cube();
    const SurfaceMesh tri = test::split_into_triangles(cube, false);
    const SurfaceMesh stl = exploded(tri);
    ASSERT_EQ(stl.num_points(), 36);
    const SurfaceMesh c = merge_coincident_nodes(stl);
    EXPECT_EQ(c.num_points(), 8);
    const EdgeTable t = edge_table(c);
    EXPECT_EQ(t.nodes.size(), 18u);
    for (Index k = 0; k < t.faces.rows(); ++k) EXPECT_EQ(t.faces.row_size(k), 2);
}

TEST(Merge, IdsAreDeterministicLowestOldIdSurvivesOrderKept) {
    SurfaceMesh m;
    m.patches.push_back({"wall", PatchKind::Wall});
    const Vec3 A(0, 0, 0), B(1, 0, 0), C(0, 1, 0), D(5, 5, 5);
    m.points = {D, A, B, A, C, B};  // node 0 unused, dropped
    m.add_face({1, 2, 4}, 0);
    m.add_face({3, 4, 5}, 0);  // collapses: 3 ≡ 1, 5 ≡ 2 → kept with its corners (0, 2, 1)
    const SurfaceMesh g = merge_coincident_nodes(m);
    ASSERT_EQ(g.num_points(), 3);
    EXPECT_EQ(g.points[0], A);
    EXPECT_EQ(g.points[1], B);
    EXPECT_EQ(g.points[2], C);
    EXPECT_EQ(g.face_nodes, (std::vector<Index>{0, 1, 2, 0, 2, 1}));
    EXPECT_EQ(g.face_patch, m.face_patch);
    EXPECT_EQ(g.patches.size(), 1u);

    // The collapsed-face case: two corners of one face become equal, the face stays.
    SurfaceMesh s;
    s.patches.push_back({"wall", PatchKind::Wall});
    s.points = {A, B, B + Vec3(1e-12, 0, 0), C};
    s.add_face({0, 1, 2}, 0);
    s.add_face({0, 1, 3}, 0);
    const SurfaceMesh sg = merge_coincident_nodes(s);
    EXPECT_EQ(sg.num_points(), 3);
    EXPECT_EQ(sg.face_nodes, (std::vector<Index>{0, 1, 1, 0, 1, 2}));
}

TEST(CollapsedFaces, RemovedOrMadeTrianglesAndTheCubeStaysClosed) {
    // The unit cube (quads) with, on its edge 0-1, a collapsed triangle (0, 0, 1) and a quad
    // (1, 0, 1, 0) whose repeats are opposite: both go. A quad (a, a, b, c) becomes (a, b, c).
    SurfaceMesh m = unit_cube();
    const Index quads = m.num_faces();
    m.add_face({0, 0, 1}, 0);
    m.add_face({1, 0, 1, 0}, 0);
    Index changed = -1;
    SurfaceMesh r = remove_collapsed_faces(m, &changed);
    EXPECT_EQ(changed, 2);
    EXPECT_EQ(r.num_faces(), quads);
    EXPECT_TRUE(test::closed_manifold(r));
    EXPECT_EQ(r.points, m.points);

    SurfaceMesh q;
    q.patches.push_back({"wall", PatchKind::Wall});
    q.points = {Vec3(9, 9, 9), Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};  // node 0 unused
    q.add_face({1, 1, 2, 3}, 0);
    r = remove_collapsed_faces(q, &changed);
    EXPECT_EQ(changed, 1);
    ASSERT_EQ(r.num_faces(), 1);
    EXPECT_EQ(r.face_size(0), 3);
    EXPECT_EQ(r.points, (std::vector<Vec3>{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}));
    EXPECT_EQ(r.face_nodes, (std::vector<Index>{0, 1, 2}));

    // Nothing collapsed: the mesh as it was, unused nodes and all.
    r = remove_collapsed_faces(unit_cube(), &changed);
    EXPECT_EQ(changed, 0);
    EXPECT_EQ(r.face_nodes, unit_cube().face_nodes);
}

TEST(DuplicateFaces, ACopyGoesTheOtherWayRoundStays) {
    // The unit cube's six quads, then its first quad again from another corner and its second
    // twice more: those three copies go, the cube is closed again. The first quad the other way
    // round (a body back to back with it) stays: touching.h's case, not a copy.
    SurfaceMesh m = unit_cube();
    const Index quads = m.num_faces();
    const std::vector<Index> q0(m.face_begin(0), m.face_end(0)), q1(m.face_begin(1), m.face_end(1));
    m.add_face({q0[2], q0[3], q0[0], q0[1]}, 0);
    m.add_face(q1.data(), 4, 0);
    m.add_face(q1.data(), 4, 0);
    EXPECT_FALSE(test::closed_manifold(m));
    Index removed = -1;
    SurfaceMesh r = remove_duplicate_faces(m, &removed);
    EXPECT_EQ(removed, 3);
    EXPECT_EQ(r.num_faces(), quads);
    EXPECT_EQ(r.face_nodes, unit_cube().face_nodes);
    EXPECT_EQ(r.points, m.points);
    EXPECT_TRUE(test::closed_manifold(r));
    m = unit_cube();
    m.add_face({q0[3], q0[2], q0[1], q0[0]}, 0);
    r = remove_duplicate_faces(m, &removed);
    EXPECT_EQ(removed, 0);
    EXPECT_EQ(r.num_faces(), quads + 1);
}

/// The unit cube in triangles, the side y = 0 meshed with a node of its own on its top edge,
/// \p lift above it (a curved edge's sagitta), and the top face left out if \p open.
SurfaceMesh cube_with_a_crack(double lift, bool open) {
    SurfaceMesh m = test::cube_corners();
    m.points.emplace_back(0.5, 0.0, 1.0 + lift);  // node 8, by edge 4-5
    const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& q : quads) {
        if (open && q[0] == 4) continue;
        if (q[0] == 0 && q[1] == 1) {
            m.add_face({0, 1, 5}, 0);
            m.add_face({0, 5, 8}, 0);
            m.add_face({0, 8, 4}, 0);
            continue;
        }
        m.add_face({q[0], q[1], q[2]}, 0);
        m.add_face({q[0], q[2], q[3]}, 0);
    }
    return m;
}

TEST(TJunctions, ATriangleIsSplitWhereTheFacesBesideItHaveANodeOnItsEdge) {
    // The unit cube in triangles, one of its side's two triangles replaced by two meeting at the
    // midpoint m of the edge it shares with the top (an exporter that meshed that edge twice): the
    // top's triangle on that edge has m inside its open edge. Split there, the cube is closed.
    const SurfaceMesh m = cube_with_a_crack(0.0, false);  // node 8 on edge 4-5
    EXPECT_FALSE(test::closed_manifold(m));
    Index split = -1;
    const SurfaceMesh r = split_t_junctions(m, &split);
    EXPECT_EQ(split, 1);
    EXPECT_EQ(r.num_faces(), m.num_faces() + 1);
    EXPECT_TRUE(test::closed_manifold(r));
    EXPECT_NEAR(test::enclosed_volume(r), 1.0, 1e-12);
    // An open sheet's boundary has no node inside another's edge: nothing changes.
    const SurfaceMesh sheet = quad_grid(3, 2);
    const SurfaceMesh same = split_t_junctions(sheet, &split);
    EXPECT_EQ(split, 0);
    EXPECT_EQ(same.face_nodes, sheet.face_nodes);
}

TEST(StitchCracks, ANodeOffTheEdgeBesideItClosesTheSurfaceAndNothingElseChanges) {
    // The side's node 0.02 above the top's edge (2 % of it): no T-junction, a crack. Stitched,
    // the top's triangle is split at it and every edge bounds two faces.
    const SurfaceMesh m = cube_with_a_crack(0.02, false);
    Index split = -1;
    EXPECT_EQ(split_t_junctions(m, &split).face_nodes, m.face_nodes);
    EXPECT_EQ(split, 0);
    Stitching r;
    const SurfaceMesh c = stitch_cracks(m, 0.1, &r);
    EXPECT_EQ(r.split, 1);
    EXPECT_NEAR(r.widest, 0.02, 1e-12);
    EXPECT_EQ(r.at, Vec3(0.5, 0.0, 1.02));
    EXPECT_TRUE(test::closed_manifold(c));
    // Farther than the share, or a surface the stitch would leave open: the input as it was.
    for (const SurfaceMesh& left : {cube_with_a_crack(0.2, false), cube_with_a_crack(0.02, true)}) {
        const SurfaceMesh same = stitch_cracks(left, 0.1, &r);
        EXPECT_EQ(same.face_nodes, left.face_nodes);
        EXPECT_EQ(r.split, 0);
    }
}

/// The unit cube in triangles (outward), without its top's second triangle if \p hole.
SurfaceMesh cube_triangles(bool hole = false) {
    SurfaceMesh m = test::cube_corners();
    const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& q : quads) {
        m.add_face({q[0], q[1], q[2]}, 0);
        if (!(hole && q[0] == 4)) m.add_face({q[0], q[2], q[3]}, 0);
    }
    return m;
}

TEST(HangingSheets, AFlapOnAnEdgeGoesAndTheBodyItHangsOnStays) {
    // A flap of two triangles on the cube's edge 0-1, sticking out below it.
    SurfaceMesh m = cube_triangles();
    m.points.emplace_back(0.0, 0.0, -1.0);  // 8
    m.points.emplace_back(1.0, 0.0, -1.0);  // 9
    m.add_face({0, 1, 9}, 0);
    m.add_face({0, 9, 8}, 0);
    HangingSheets r;
    const SurfaceMesh c = remove_hanging_sheets(m, &r);
    EXPECT_EQ(r.sheets, 1);
    EXPECT_EQ(r.faces, 2);
    EXPECT_NEAR(r.at.z(), -1.0 / 3.0, 1e-12);
    EXPECT_TRUE(test::closed_manifold(c));
    EXPECT_EQ(c.num_points(), 8);
    // The body open too (a hole in its top): the flap, the smaller, still goes, the body stays.
    SurfaceMesh open = cube_triangles(true);
    open.points = m.points;
    open.add_face({0, 1, 9}, 0);
    open.add_face({0, 9, 8}, 0);
    const SurfaceMesh left = remove_hanging_sheets(open, &r);
    EXPECT_EQ(r.faces, 2);
    EXPECT_EQ(left.num_faces(), 11);
    // Two cubes sharing an edge (four faces on it) have no free edge: nothing hangs, nothing goes.
    const SurfaceMesh two = test::merged(cube_triangles(), [] {
        SurfaceMesh b = cube_triangles();
        for (Vec3& p : b.points) p += Vec3(1.0, 1.0, 0.0);
        return b;
    }());
    const SurfaceMesh same = remove_hanging_sheets(merge_coincident_nodes(two), &r);
    EXPECT_EQ(r.faces, 0);
    EXPECT_EQ(same.num_faces(), 24);
    // A collapsed triangle (0, 0, 9) on the flap, whose edge 0-0 no edge table has (the fuzzer's
    // find: that edge was looked up past the table): a sheet of its own, hanging on the flap's
    // edge 0-9, it goes; the flap, whose edge 0-9 it made one of four, stays for the later steps.
    SurfaceMesh collapsed = m;
    collapsed.add_face({0, 0, 9}, 0);
    const SurfaceMesh without = remove_hanging_sheets(collapsed, &r);
    EXPECT_EQ(r.sheets, 1);
    EXPECT_EQ(r.faces, 1);
    EXPECT_EQ(without.num_faces(), 14);
}

TEST(CollapsedFaces, FacePatchWithoutAnEntryPerFaceIsAnInputError) {
    // Faces are copied with their patch entry, which must exist (a fuzzer's find: it was read
    // past the end of face_patch).
    SurfaceMesh m = quad_grid(2, 1);
    m.face_patch.pop_back();
    test::expect_error<InputError>([&] { remove_collapsed_faces(m); },
                                   {"remove_collapsed_faces: face patches: 1 entries for 2 faces"});
}

TEST(Merge, RespectsTheRelativeTolerance) {
    // Bounding box diagonal of the unit cube is √3; with rel_tol 1e-3 the tolerance is 1.73e-3.
    const SurfaceMesh cube = unit_cube();
    const double tol = 1e-3 * std::sqrt(3.0);
    SurfaceMesh m = cube;
    const Index near = m.num_points(), far = near + 1;
    m.points.push_back(cube.points[7] + Vec3(0.4 * tol, -0.3 * tol, 0.5 * tol));  // within
    m.points.push_back(cube.points[6] + Vec3(1.1 * tol, 0.0, 0.0));               // beyond
    m.add_face({near, far, 5}, 0);
    const SurfaceMesh g = merge_coincident_nodes(m, 1e-3);
    EXPECT_EQ(g.num_points(), 9);
    EXPECT_EQ(g.face_node(6, 0), 7);  // merged onto the lower old id
    EXPECT_EQ(g.face_node(6, 1), 8);  // kept, renumbered after the survivors before it

    // Jitter of each copy ≤ 0.43 tolerance (so copies are < 0.87 tolerance apart), placed at random
    // across hash-cell boundaries: everything still merges.
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-0.25, 0.25);
    SurfaceMesh e = exploded(quad_grid(10, 10, 0.1));
    const double diag = bounding_box(e.points).diagonal();
    for (Vec3& p : e.points) p += 1e-6 * diag * Vec3(u(rng), u(rng), u(rng));
    const SurfaceMesh eg = merge_coincident_nodes(e, 1e-6);
    EXPECT_EQ(eg.num_points(), 121);
}

TEST(Merge, NonFiniteNodesAreKeptForTheCheck) {
    SurfaceMesh m = quad_grid(1, 1);
    m.points[2] = Vec3(std::nan(""), 0, 0);
    const SurfaceMesh g = merge_coincident_nodes(m);
    EXPECT_EQ(g.num_points(), 4);
    EXPECT_TRUE(std::isnan(g.points[2].x()));
}

TEST(Merge, SpanBeyondTheDoublesIsATopologyError) {
    // Nodes at ±1.7e308 span more than a double holds: the tolerance and cells were infinite and
    // turned into integers (undefined; a fuzzer's find). The span names the box; below 1e100
    // merging works as ever, and an absurd tolerance merges every node.
    SurfaceMesh m = quad_grid(1, 1);
    m.points[0].x() = -1.7e308;
    m.points[2].x() = 1.7e308;
    test::expect_error<TopologyError>(
        [&] { merge_coincident_nodes(m); },
        {"merge_coincident_nodes: the nodes span from (-1.7e+308", "1.7e+308", "beyond the 1e+100", "wrong unit"});
    EXPECT_THROW(merge_coincident_nodes(quad_grid(1, 1, 1e100)), TopologyError);
    EXPECT_EQ(merge_coincident_nodes(quad_grid(1, 1, 1e99)).num_points(), 4);
    EXPECT_EQ(merge_coincident_nodes(quad_grid(1, 1), 1e308).num_points(), 1);
}

// ---------------------------------------------------------------- adjacency

TEST(VertexFaces, GridRowsAreSortedIncidentFaces) {
    const SurfaceMesh m = quad_grid(3, 2);  // face (i,j) = 3j + i
    const Csr vf = vertex_faces(m);
    ASSERT_EQ(vf.rows(), 12);
    EXPECT_EQ(row(vf, 0), (std::vector<Index>{0}));
    EXPECT_EQ(row(vf, 5), (std::vector<Index>{0, 1, 3, 4}));
    EXPECT_EQ(row(vf, 11), (std::vector<Index>{5}));
}

TEST(EdgeTable, GridEdgesSortedWithBoundaryAndInteriorFaces) {
    const int nx = 3, ny = 2;
    const SurfaceMesh m = quad_grid(nx, ny);
    const EdgeTable t = edge_table(m);
    ASSERT_EQ(t.nodes.size(), static_cast<std::size_t>(nx * (ny + 1) + ny * (nx + 1)));
    ASSERT_EQ(t.faces.rows(), static_cast<Index>(t.nodes.size()));
    Index boundary = 0;
    for (std::size_t e = 0; e < t.nodes.size(); ++e) {
        EXPECT_LT(t.nodes[e][0], t.nodes[e][1]);
        if (e > 0) {
            EXPECT_LT(t.nodes[e - 1], t.nodes[e]);
        }
        const Index k = t.faces.row_size(static_cast<Index>(e));
        ASSERT_TRUE(k == 1 || k == 2);
        boundary += k == 1;
        if (k == 2) {
            EXPECT_LT(t.faces.row_begin(static_cast<Index>(e))[0], t.faces.row_begin(static_cast<Index>(e))[1]);
        }
    }
    EXPECT_EQ(boundary, 2 * (nx + ny));
    // Edge 5–6 (node (1,1)–(2,1)) lies between face 1 (below) and face 4 (above).
    const auto it = std::find(t.nodes.begin(), t.nodes.end(), std::array<Index, 2>{5, 6});
    ASSERT_NE(it, t.nodes.end());
    EXPECT_EQ(row(t.faces, static_cast<Index>(it - t.nodes.begin())), (std::vector<Index>{1, 4}));
}

/// Shoelace area of a loop in the z = 0 plane: > 0 counter-clockwise seen from +z.
double loop_area(const SurfaceMesh& m, const std::vector<Index>& loop) {
    double a = 0.0;
    for (std::size_t k = 0; k < loop.size(); ++k) {
        const Vec3 &p = m.points[loop[k]], &q = m.points[loop[(k + 1) % loop.size()]];
        a += p.x() * q.y() - q.x() * p.y();
    }
    return 0.5 * a;
}

/// Does some face traverse a → b?
bool directed_edge_in_faces(const SurfaceMesh& m, Index a, Index b) {
    for (Index f = 0; f < m.num_faces(); ++f)
        for (Index i = 0; i < m.face_size(f); ++i)
            if (m.face_node(f, i) == a && m.face_node(f, (i + 1) % m.face_size(f)) == b) return true;
    return false;
}

TEST(BoundaryLoops, GridHasOneLoopInTheFacesDirection) {
    const int nx = 4, ny = 3;
    const SurfaceMesh m = quad_grid(nx, ny);
    const Csr loops = boundary_loops(m);
    ASSERT_EQ(loops.rows(), 1);
    const std::vector<Index> loop = row(loops, 0);
    ASSERT_EQ(static_cast<int>(loop.size()), 2 * (nx + ny));
    EXPECT_EQ(loop[0], 0);                          // starts at its lowest node
    EXPECT_DOUBLE_EQ(loop_area(m, loop), nx * ny);  // counter-clockwise like the +z faces
    for (std::size_t k = 0; k < loop.size(); ++k)
        EXPECT_TRUE(directed_edge_in_faces(m, loop[k], loop[(k + 1) % loop.size()]));

    // Reversed faces reverse the loop.
    const Csr rl = boundary_loops(reversed(m));
    ASSERT_EQ(rl.rows(), 1);
    EXPECT_DOUBLE_EQ(loop_area(m, row(rl, 0)), -nx * ny);
}

TEST(BoundaryLoops, ClosedCubeHasNone) {
    EXPECT_EQ(boundary_loops(unit_cube()).rows(), 0);
    EXPECT_EQ(boundary_loops(shuffled(polar_cap(), 1)).rows(), 1);
}

TEST(BoundaryLoops, GridWithAHoleHasTwoLoops) {
    const SurfaceMesh full = quad_grid(5, 5);
    SurfaceMesh m;
    m.points = full.points;
    m.patches = full.patches;
    for (Index f = 0; f < full.num_faces(); ++f)
        if (f != 12) m.add_face(full.face_begin(f), 4, 0);  // face (2,2) removed
    const Csr loops = boundary_loops(m);
    ASSERT_EQ(loops.rows(), 2);
    std::vector<Index> sizes{loops.row_size(0), loops.row_size(1)};
    std::sort(sizes.begin(), sizes.end());
    EXPECT_EQ(sizes, (std::vector<Index>{4, 20}));
    for (Index l = 0; l < 2; ++l) {
        const double a = loop_area(m, row(loops, l));
        // Outer loop counter-clockwise, the hole's clockwise (both follow the faces).
        EXPECT_DOUBLE_EQ(a, loops.row_size(l) == 20 ? 25.0 : -1.0);
    }
}

TEST(BoundaryLoops, TouchingLoopsThrow) {
    SurfaceMesh m;
    m.patches.push_back({"wall", PatchKind::Wall});
    m.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0),
                Vec3(2, 1, 0), Vec3(2, 2, 0), Vec3(1, 2, 0)};
    m.add_face({0, 1, 2, 3}, 0);
    m.add_face({2, 4, 5, 6}, 0);  // shares only node 2
    try {
        boundary_loops(m);
        FAIL() << "expected TopologyError";
    } catch (const TopologyError& e) {
        EXPECT_NE(std::string(e.what()).find("node 2 "), std::string::npos) << e.what();
    }
}

TEST(FaceComponents, SeparatedByEdgesNotVertices) {
    SurfaceMesh m;
    m.patches.push_back({"wall", PatchKind::Wall});
    m.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0),
                Vec3(2, 1, 0), Vec3(2, 2, 0), Vec3(1, 2, 0), Vec3(2, 0, 0)};
    m.add_face({2, 4, 5, 6}, 0);  // component 0 (lowest face 0), touches face 1 at node 2 only
    m.add_face({0, 1, 2, 3}, 0);  // component 1
    m.add_face({1, 7, 2}, 0);     // shares edge 1–2 with face 1
    Index n = 0;
    const std::vector<Index> c = face_components(m, &n);
    EXPECT_EQ(n, 2);
    EXPECT_EQ(c, (std::vector<Index>{0, 1, 1}));

    Index ng = 0;
    const std::vector<Index> g = face_components(quad_grid(4, 4), &ng);
    EXPECT_EQ(ng, 1);
    EXPECT_EQ(g, std::vector<Index>(16, 0));
}

// ---------------------------------------------------------------- split_long_edges

/// A closed cylinder as a CAD tool's coarse export writes it: \p n facets round, each one
/// triangle pair as long as the cylinder (2 long, radius 0.1), the two ends fans to a centre;
/// side patch 0, ends patch 1, normals out.
SurfaceMesh strip_cylinder(int n) {
    SurfaceMesh m;
    m.patches = {{"side", PatchKind::Wall}, {"ends", PatchKind::Wall}};
    for (int end = 0; end < 2; ++end)
        for (int i = 0; i < n; ++i) {
            const double t = 2.0 * kPi * i / n;
            m.points.push_back(Vec3(2.0 * end, 0.1 * std::cos(t), 0.1 * std::sin(t)));
        }
    m.points.push_back(Vec3(0, 0, 0));
    m.points.push_back(Vec3(2, 0, 0));
    for (Index i = 0; i < n; ++i) {
        const Index j = (i + 1) % n;
        m.add_face({i, n + j, n + i}, 0);
        m.add_face({i, j, n + j}, 0);
        m.add_face({2 * n, j, i}, 1);
        m.add_face({2 * n + 1, n + i, n + j}, 1);
    }
    return m;
}

double sharpest_corner_deg(const SurfaceMesh& m) {
    double worst = 180.0;
    for (Index f = 0; f < m.num_faces(); ++f)
        for (Index i = 0, k = m.face_size(f); i < k; ++i) {
            const Vec3 &o = m.points[m.face_node(f, i)], &a = m.points[m.face_node(f, (i + 1) % k)],
                       &b = m.points[m.face_node(f, (i + k - 1) % k)];
            const double c = (a - o).normalized().dot((b - o).normalized());
            worst = std::min(worst, std::acos(std::clamp(c, -1.0, 1.0)) * 180.0 / kPi);
        }
    return worst;
}

double longest_edge(const SurfaceMesh& m) {
    double l = 0.0;
    for (Index f = 0; f < m.num_faces(); ++f)
        for (Index i = 0, k = m.face_size(f); i < k; ++i)
            l = std::max(l, (m.points[m.face_node(f, (i + 1) % k)] - m.points[m.face_node(f, i)]).norm());
    return l;
}

TEST(SplitLongEdges, ALongStripExportBecomesShortEdgesOnTheSameSurface) {
    const SurfaceMesh in = strip_cylinder(12);
    ASSERT_GT(longest_edge(in), 1.9);
    Index splits = 0;
    const SurfaceMesh out = split_long_edges(in, 0.05, 1000000, &splits);
    EXPECT_GT(splits, 0);
    EXPECT_LE(longest_edge(out), 0.05);
    EXPECT_TRUE(closed_manifold(out));
    // Midpoints only: the same polyhedron, so the same volume; the old nodes first, unmoved.
    EXPECT_NEAR(enclosed_volume(out), enclosed_volume(in), 1e-12);
    EXPECT_GT(enclosed_volume(out), 0.0);  // orientation kept
    for (Index i = 0; i < in.num_points(); ++i) EXPECT_EQ(out.points[i], in.points[i]);
    EXPECT_EQ(out.num_points(), in.num_points() + splits);
    // Rivara's bound: no corner sharper than half the sharpest there was.
    EXPECT_GE(sharpest_corner_deg(out), 0.5 * sharpest_corner_deg(in) - 1e-9);
    // Each new face on its parent's patch: the side's area stays the side's.
    const auto area_of = [](const SurfaceMesh& m, Index patch) {
        double a = 0.0;
        for (Index f = 0; f < m.num_faces(); ++f)
            if (m.face_patch[f] == patch) a += face_area_vector(m, f).norm();
        return a;
    };
    EXPECT_NEAR(area_of(out, 0), area_of(in, 0), 1e-12);
    EXPECT_NEAR(area_of(out, 1), area_of(in, 1), 1e-12);
    // Deterministic.
    const SurfaceMesh again = split_long_edges(in, 0.05, 1000000);
    EXPECT_EQ(again.points, out.points);
    EXPECT_EQ(again.face_nodes, out.face_nodes);
}

TEST(SplitLongEdges, ShortEdgesQuadsAndTheFaceCapAreLeft) {
    const SurfaceMesh in = strip_cylinder(12);
    Index splits = -1;
    const SurfaceMesh same = split_long_edges(in, 3.0, 1000000, &splits);
    EXPECT_EQ(splits, 0);
    EXPECT_EQ(same.face_nodes, in.face_nodes);
    EXPECT_EQ(same.points, in.points);

    // A quad keeps its edges, and the triangle beside it cannot split along the shared one.
    SurfaceMesh q = quad_grid(1, 1, 1.0);
    q.points.push_back(Vec3(0.5, -3.0, 0.0));
    q.add_face({0, static_cast<Index>(q.points.size() - 1), 1}, 0);
    const SurfaceMesh qs = split_long_edges(q, 0.4, 1000000);
    EXPECT_EQ(qs.face_size(0), 4);
    EXPECT_EQ(std::vector<Index>(qs.face_begin(0), qs.face_end(0)), std::vector<Index>(q.face_begin(0), q.face_end(0)));
    for (Index f = 1; f < qs.num_faces(); ++f) EXPECT_EQ(qs.face_size(f), 3);
    EXPECT_GT(qs.num_faces(), 2);

    // At the cap the faces stop growing, and what was split is still conforming.
    const SurfaceMesh capped = split_long_edges(in, 0.01, in.num_faces() + 40, &splits);
    EXPECT_GE(capped.num_faces(), in.num_faces() + 40);
    EXPECT_LE(capped.num_faces(), in.num_faces() + 42);  // one edge splits at most two faces
    EXPECT_TRUE(closed_manifold(capped));
    EXPECT_NEAR(enclosed_volume(capped), enclosed_volume(in), 1e-12);

    EXPECT_THROW(split_long_edges(in, 0.0, 100), InputError);
    EXPECT_THROW(split_long_edges(in, std::nan(""), 100), InputError);
}

}  // namespace
}  // namespace strata
