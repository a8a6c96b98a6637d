#include <gtest/gtest.h>

#include <strata/geometry/topology.h>
#include <strata/module/stencil.h>

#include "test_support.h"

#include <array>
#include <cmath>
#include <functional>
#include <numbers>
#include <random>
#include <string>
#include <vector>

namespace strata {
namespace {

using test::quad_grid;

constexpr double kPi = std::numbers::pi;
using D5 = std::array<double, 5>;
using Field = std::function<double(const Vec3&)>;
const std::vector<MirrorPlane> kNoPlanes;

// ---------------------------------------------------------------- helpers

Vec3 point_position(const SurfaceMesh& m, const std::vector<MirrorPlane>& planes, StencilPoint p) {
    const Vec3& x = m.points[static_cast<std::size_t>(p.node)];
    return p.mirror == kNone ? x : planes[static_cast<std::size_t>(p.mirror)].reflect(x);
}

std::size_t sz(Index i) {
    return static_cast<std::size_t>(i);
}

/// The five derivatives at node o of the field f evaluated at every stencil point's position
/// (ghost points at their mirrored position).
D5 apply(const Stencils& s, const SurfaceMesh& m, const std::vector<MirrorPlane>& planes, Index o, const Field& f) {
    D5 out{};
    const double fo = f(m.points[sz(o)]);
    for (int d = 0; d < 5; ++d) out[sz(d)] = s.centre[sz(o)][sz(d)] * fo;
    for (Index j = s.offsets[sz(o)]; j < s.offsets[sz(o) + 1]; ++j) {
        const double fj = f(point_position(m, planes, s.points[sz(j)]));
        for (int d = 0; d < 5; ++d) out[sz(d)] += s.weights[sz(j)][sz(d)] * fj;
    }
    return out;
}

/// The same with per-node values (a ghost point takes its node's value, as a field even in
/// the mirror plane does).
D5 apply_values(const Stencils& s, Index o, const std::vector<double>& v) {
    D5 out{};
    for (int d = 0; d < 5; ++d) out[sz(d)] = s.centre[sz(o)][sz(d)] * v[sz(o)];
    for (Index j = s.offsets[sz(o)]; j < s.offsets[sz(o) + 1]; ++j)
        for (int d = 0; d < 5; ++d) out[sz(d)] += s.weights[sz(j)][sz(d)] * v[sz(s.points[sz(j)].node)];
    return out;
}

Stencils stencils_of(const SurfaceMesh& m, const std::vector<Index>& node_plane = {},
                     const std::vector<MirrorPlane>& planes = kNoPlanes) {
    return build_stencils(m, node_rings(m), node_plane, planes);
}

std::vector<StencilPoint> row(const Stencils& s, Index o) {
    return {s.points.begin() + s.offsets[sz(o)], s.points.begin() + s.offsets[sz(o) + 1]};
}

void check_layout(const Stencils& s, const SurfaceMesh& m);

/// Node 0's stencil points, after checking the stencils' layout and that node 0 has one
/// (empty, with a failure, otherwise).
std::vector<StencilPoint> checked_row_of_node_0(const Stencils& s, const SurfaceMesh& m) {
    check_layout(s, m);
    EXPECT_TRUE(s.valid[0]);
    if (!s.valid[0]) return {};
    return row(s, 0);
}

/// \p m's node rings, its stencils (no planes, no mirrors) and node 0's row (checked_row_of_node_0).
struct NodeZeroStencil {
    NodeRings rings;
    Stencils s;
    std::vector<StencilPoint> pts;
};
NodeZeroStencil node_0_stencil(const SurfaceMesh& m) {
    NodeZeroStencil z{node_rings(m), {}, {}};
    z.s = build_stencils(m, z.rings, {}, {});
    z.pts = checked_row_of_node_0(z.s, m);
    return z;
}

/// Array sizes, and for every valid node: the weights annihilate constants (the centre
/// weights are minus the sum of the others). Invalid nodes have empty rows.
void check_layout(const Stencils& s, const SurfaceMesh& m) {
    const std::size_t n = sz(m.num_points());
    ASSERT_EQ(s.offsets.size(), n + 1);
    ASSERT_EQ(s.centre.size(), n);
    ASSERT_EQ(s.valid.size(), n);
    ASSERT_EQ(s.weights.size(), s.points.size());
    ASSERT_EQ(s.direction.size(), s.points.size());
    ASSERT_EQ(sz(s.offsets.back()), s.points.size());
    for (std::size_t o = 0; o < n; ++o) {
        ASSERT_LE(s.offsets[o], s.offsets[o + 1]);
        if (!s.valid[o]) {
            EXPECT_EQ(s.offsets[o], s.offsets[o + 1]) << "invalid node " << o << " has stencil points";
            continue;
        }
        for (int d = 0; d < 5; ++d) {
            double sum = s.centre[o][sz(d)];
            for (Index j = s.offsets[o]; j < s.offsets[o + 1]; ++j) {
                sum += s.weights[sz(j)][sz(d)];
                ASSERT_GE(s.points[sz(j)].node, 0);
                ASSERT_LT(s.points[sz(j)].node, m.num_points());
            }
            EXPECT_NEAR(sum, 0.0, 1e-14) << "node " << o << " derivative " << d << " does not annihilate constants";
        }
    }
}

/// Node o's local logical frame: ξ towards its stencil's first point (edge neighbour 0, at
/// logical (1, 0)), η = normal × ξ. Unit spacing is assumed (|neighbour 0 − o| = 1).
struct Frame {
    Vec3 o, ex, ey;
    double xi(const Vec3& p) const { return (p - o).dot(ex); }
    double eta(const Vec3& p) const { return (p - o).dot(ey); }
};
Frame frame_of(const Stencils& s, const SurfaceMesh& m, const std::vector<MirrorPlane>& planes, Index o,
               const Vec3& normal = Vec3::UnitZ()) {
    Frame fr;
    fr.o = m.points[sz(o)];
    fr.ex = point_position(m, planes, s.points[sz(s.offsets[sz(o)])]) - fr.o;
    EXPECT_NEAR(fr.ex.norm(), 1.0, 1e-14);
    fr.ey = normal.cross(fr.ex);
    return fr;
}

/// A quadratic in the logical coordinates: a + b ξ + c η + d ξ² + e ξη + g η².
struct Quadratic {
    double a, b, c, d, e, g;
    double operator()(double x, double y) const { return a + b * x + c * y + d * x * x + e * x * y + g * y * y; }
    /// (f_ξ, f_η, f_ξξ, f_ξη, f_ηη) at the origin.
    D5 derivatives() const { return {b, c, 2 * d, e, 2 * g}; }
};
Quadratic random_quadratic(std::mt19937& rng) {
    std::uniform_real_distribution<double> u(-2.0, 2.0);
    return {u(rng), u(rng), u(rng), u(rng), u(rng), u(rng)};
}

void expect_d5(const D5& got, const D5& want, double tol, const std::string& what) {
    static const char* names[5] = {"xi", "eta", "xixi", "xieta", "etaeta"};
    for (int d = 0; d < 5; ++d) EXPECT_NEAR(got[sz(d)], want[sz(d)], tol) << what << ": f_" << names[d];
}

/// Node o's stencil differentiates quadratics in its logical frame exactly.
void expect_quadratics_exact(const Stencils& s, const SurfaceMesh& m, const std::vector<MirrorPlane>& planes, Index o,
                             double tol, const std::string& what, const Vec3& normal = Vec3::UnitZ()) {
    ASSERT_TRUE(s.valid[sz(o)]) << what;
    const Frame fr = frame_of(s, m, planes, o, normal);
    std::mt19937 rng(12345u + static_cast<unsigned>(o));
    for (int trial = 0; trial < 6; ++trial) {
        const Quadratic q = random_quadratic(rng);
        const D5 got = apply(s, m, planes, o, [&](const Vec3& p) { return q(fr.xi(p), fr.eta(p)); });
        expect_d5(got, q.derivatives(), tol, what + " trial " + std::to_string(trial));
    }
    // Each monomial on its own, so a wrong weight cannot hide behind a lucky combination.
    for (int k = 0; k < 6; ++k) {
        auto one = [k](int i) { return i == k ? 1.0 : 0.0; };
        const Quadratic q{one(0), one(1), one(2), one(3), one(4), one(5)};
        const D5 got = apply(s, m, planes, o, [&](const Vec3& p) { return q(fr.xi(p), fr.eta(p)); });
        expect_d5(got, q.derivatives(), tol, what + " monomial " + std::to_string(k));
    }
}

Vec3 on_circle(double angle, double radius = 1.0, const Vec3& centre = Vec3::Zero()) {
    return centre + radius * Vec3(std::cos(angle), std::sin(angle), 0.0);
}

/// Fan of M triangles around node 0 at \p centre, edge neighbours 1..M on the unit circle at
/// angles rot + 2πm/M, plus an outer triangle across every outer edge (far vertex M+1+m at
/// rot + (2m+1)π/M, radius 1.7). The centre's triangles are added starting with sector
/// \p first, so its ring starts at neighbour 1 + first.
SurfaceMesh triangle_fan(int M, int first, double rot, const Vec3& centre) {
    SurfaceMesh m;
    m.patches.push_back({"wall", PatchKind::Wall});
    m.points.push_back(centre);
    for (int k = 0; k < M; ++k) m.points.push_back(on_circle(rot + 2 * kPi * k / M, 1.0, centre));
    for (int k = 0; k < M; ++k) m.points.push_back(on_circle(rot + (2 * k + 1) * kPi / M, 1.7, centre));
    auto n = [M](int k) { return static_cast<Index>(1 + (k % M + M) % M); };
    auto x = [M](int k) { return static_cast<Index>(1 + M + (k % M + M) % M); };
    for (int s = 0; s < M; ++s) m.add_face({0, n(first + s), n(first + s + 1)}, 0);
    for (int k = 0; k < M; ++k) m.add_face({n(k + 1), n(k), x(k)}, 0);
    return m;
}

// ---------------------------------------------------------------- structured grid, M = 4

TEST(Stencil, StructuredGridGivesCentralDifferences) {
    const int nx = 6, ny = 6;
    const SurfaceMesh m = quad_grid(nx, ny);
    const NodeRings rings = node_rings(m);
    const Stencils s = build_stencils(m, rings, {}, {});
    check_layout(s, m);
    auto id = [nx](int i, int j) { return static_cast<Index>(j * (nx + 1) + i); };

    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::vector<double> f(sz(m.num_points()));
    for (double& v : f) v = u(rng);

    for (int j = 0; j <= ny; ++j)
        for (int i = 0; i <= nx; ++i) {
            const Index o = id(i, j);
            const bool interior = i > 0 && j > 0 && i < nx && j < ny;
            EXPECT_EQ(s.valid[sz(o)] != 0, interior) << "node (" << i << "," << j << ")";
            if (!interior) continue;
            // Grid offsets of neighbours 0 (ξ = +1) and 1 (η = +1).
            const Index n0 = rings.neighbours.values[sz(rings.neighbours.offsets[sz(o)])];
            const Index n1 = rings.neighbours.values[sz(rings.neighbours.offsets[sz(o)]) + 1];
            const int ai = static_cast<int>(n0) % (nx + 1) - i, aj = static_cast<int>(n0) / (nx + 1) - j;
            const int bi = static_cast<int>(n1) % (nx + 1) - i, bj = static_cast<int>(n1) / (nx + 1) - j;
            ASSERT_EQ(std::abs(ai) + std::abs(aj), 1);
            ASSERT_EQ(bi, -aj) << "neighbour 1 is not neighbour 0 turned 90° counter-clockwise";
            ASSERT_EQ(bj, ai);
            auto F = [&](int p, int q) { return f[sz(id(i + p * ai + q * bi, j + p * aj + q * bj))]; };
            const D5 want{(F(1, 0) - F(-1, 0)) / 2, (F(0, 1) - F(0, -1)) / 2, F(1, 0) - 2 * F(0, 0) + F(-1, 0),
                          (F(1, 1) - F(-1, 1) - F(1, -1) + F(-1, -1)) / 4, F(0, 1) - 2 * F(0, 0) + F(0, -1)};
            expect_d5(apply_values(s, o, f), want, 1e-14, "node (" + std::to_string(i) + "," + std::to_string(j) + ")");

            // 4 edge neighbours (the ring, in order) then the 4 quad diagonals (sectors in order).
            const auto pts = row(s, o);
            ASSERT_EQ(pts.size(), 8u);
            for (std::size_t k = 0; k < 4; ++k) {
                EXPECT_EQ(pts[k].node, rings.neighbours.values[sz(rings.neighbours.offsets[sz(o)]) + k]);
                EXPECT_EQ(pts[4 + k].node, rings.diagonals[sz(rings.neighbours.offsets[sz(o)]) + k]);
                EXPECT_EQ(pts[k].mirror, kNone);
                const auto dir = s.direction[sz(s.offsets[sz(o)]) + k];
                EXPECT_EQ(dir[0], std::round(std::cos(kPi / 2 * static_cast<double>(k))));
                EXPECT_EQ(dir[1], std::round(std::sin(kPi / 2 * static_cast<double>(k))));
                const auto ddir = s.direction[sz(s.offsets[sz(o)]) + 4 + k];
                EXPECT_EQ(ddir[0], 0.0);
                EXPECT_EQ(ddir[1], 0.0);
            }
        }
}

TEST(Stencil, StructuredGridExactForQuadraticsInPhysicalSpace) {
    // On a unit grid the logical frame is the physical one turned by a multiple of 90°.
    const SurfaceMesh m = quad_grid(5, 4);
    const Stencils s = stencils_of(m);
    for (Index o = 0; o < m.num_points(); ++o)
        if (s.valid[sz(o)]) expect_quadratics_exact(s, m, kNoPlanes, o, 1e-12, "grid node " + std::to_string(o));
}

TEST(Stencil, M4WeightsAreExactlyTheCentralDifferenceWeights) {
    const SurfaceMesh m = quad_grid(2, 2);
    const Stencils s = stencils_of(m);
    const Index o = 4;  // the one interior node
    ASSERT_TRUE(s.valid[sz(o)]);
    const std::size_t b = sz(s.offsets[sz(o)]);
    ASSERT_EQ(s.offsets[sz(o) + 1] - s.offsets[sz(o)], 8);
    // Edge neighbours at θ = 0, 90, 180, 270°; diagonals at 45, 135, 225, 315°.
    const std::array<D5, 8> want{D5{0.5, 0, 1, 0, 0},  D5{0, 0.5, 0, 0, 1},  D5{-0.5, 0, 1, 0, 0},
                                 D5{0, -0.5, 0, 0, 1}, D5{0, 0, 0, 0.25, 0}, D5{0, 0, 0, -0.25, 0},
                                 D5{0, 0, 0, 0.25, 0}, D5{0, 0, 0, -0.25, 0}};
    for (std::size_t k = 0; k < 8; ++k)
        for (std::size_t d = 0; d < 5; ++d)
            EXPECT_EQ(s.weights[b + k][d], want[k][d]) << "point " << k << " derivative " << d;
    const D5 centre{0, 0, -2, 0, -2};
    for (std::size_t d = 0; d < 5; ++d) EXPECT_EQ(s.centre[sz(o)][d], centre[d]) << "derivative " << d;
}

// ---------------------------------------------------------------- M ≥ 5, Eq. 8

class TriangleFan : public ::testing::TestWithParam<int> {};

TEST_P(TriangleFan, ExactForQuadratics) {
    const int M = GetParam();
    const int first = M / 3;  // the ring starts at neighbour 1 + first, not at node 1
    const double rot = 0.37;
    const SurfaceMesh m = triangle_fan(M, first, rot, Vec3(0.3, -1.2, 0.5));
    const NodeRings rings = node_rings(m);
    ASSERT_TRUE(rings.closed[0]);
    ASSERT_EQ(rings.neighbours.row_size(0), M);
    const Stencils s = build_stencils(m, rings, {}, {});
    check_layout(s, m);
    ASSERT_TRUE(s.valid[0]);
    const auto pts = row(s, 0);
    ASSERT_EQ(pts.size(), static_cast<std::size_t>(M)) << "Eq. 8 uses the edge neighbours only";
    EXPECT_EQ(pts[0].node, 1 + first);
    const Frame fr = frame_of(s, m, kNoPlanes, 0);
    for (int k = 0; k < M; ++k) {
        EXPECT_EQ(pts[sz(k)].node, rings.neighbours.values[sz(k)]);
        // The premise of the exactness test: neighbour k sits at logical (cos θ_k, sin θ_k).
        const Vec3 p = m.points[sz(pts[sz(k)].node)];
        const double th = 2 * kPi * k / M;
        EXPECT_NEAR(fr.xi(p), std::cos(th), 1e-13);
        EXPECT_NEAR(fr.eta(p), std::sin(th), 1e-13);
        EXPECT_NEAR(s.direction[sz(k)][0], std::cos(th), 1e-15);
        EXPECT_NEAR(s.direction[sz(k)][1], std::sin(th), 1e-15);
    }
    expect_quadratics_exact(s, m, kNoPlanes, 0, 1e-12, "M = " + std::to_string(M));
    // The rim nodes are on the open boundary and have no plane.
    for (Index o = 1; o < m.num_points(); ++o) EXPECT_FALSE(s.valid[sz(o)]);
}

INSTANTIATE_TEST_SUITE_P(Valence, TriangleFan, ::testing::Values(5, 6, 7, 8, 9, 10, 11, 12, 20), [](const auto& p) {
    std::string name = "M";
    name += std::to_string(p.param);
    return name;
});

TEST(Stencil, Eq8WeightsAreTheFormula) {
    // Compare the weights themselves with ALGORITHM.md Eq. 8 for M = 7.
    const int M = 7;
    const SurfaceMesh m = triangle_fan(M, 0, 0.0, Vec3::Zero());
    const Stencils s = stencils_of(m);
    ASSERT_TRUE(s.valid[0]);
    for (int k = 0; k < M; ++k) {
        const double th = 2 * kPi * k / M, c = std::cos(th), sn = std::sin(th), w = 2.0 / M;
        const D5 want{w * c, w * sn, w * (4 * c * c - 1), 4 * w * c * sn, w * (4 * sn * sn - 1)};
        expect_d5(s.weights[sz(k)], want, 1e-15, "weight " + std::to_string(k));
    }
    const D5 centre = s.centre[0];
    EXPECT_NEAR(centre[Stencils::XiXi], -2.0, 1e-14);
    EXPECT_NEAR(centre[Stencils::EtaEta], -2.0, 1e-14);
    EXPECT_NEAR(centre[Stencils::Xi], 0.0, 1e-14);
    EXPECT_NEAR(centre[Stencils::Eta], 0.0, 1e-14);
    EXPECT_NEAR(centre[Stencils::XiEta], 0.0, 1e-14);
}

// ---------------------------------------------------------------- M = 3

TEST(Stencil, ThreeQuadsAt120DegreesUseInterleavedM6) {
    // Node 0 at the origin; edge neighbours n_k (1..3) at 120k°, quad corners d_k (4..6) at
    // 120k + 60°, all on the unit circle: the interleaved ring is the regular M = 6 ring.
    SurfaceMesh m;
    m.patches.push_back({"wall", PatchKind::Wall});
    m.points.push_back(Vec3::Zero());
    for (int k = 0; k < 3; ++k) m.points.push_back(on_circle(2 * kPi * k / 3));
    for (int k = 0; k < 3; ++k) m.points.push_back(on_circle(2 * kPi * k / 3 + kPi / 3));
    for (int k = 0; k < 3; ++k)
        m.add_face({0, static_cast<Index>(1 + k), static_cast<Index>(4 + k), static_cast<Index>(1 + (k + 1) % 3)}, 0);
    const NodeRings rings = node_rings(m);
    ASSERT_TRUE(rings.closed[0]);
    ASSERT_EQ(rings.neighbours.row_size(0), 3);
    const Stencils s = build_stencils(m, rings, {}, {});
    check_layout(s, m);
    ASSERT_TRUE(s.valid[0]);
    const auto pts = row(s, 0);
    ASSERT_EQ(pts.size(), 6u);
    for (std::size_t k = 0; k < 3; ++k) {
        EXPECT_EQ(pts[2 * k].node, rings.neighbours.values[k]) << "edge neighbour " << k;
        EXPECT_EQ(pts[2 * k + 1].node, rings.diagonals[k]) << "diagonal of sector " << k;
        EXPECT_EQ(rings.diagonals[k], 4 + (pts[2 * k].node - 1)) << "the quad's corner opposite node 0";
    }
    // Eq. 8 with M = 6: direction of point j is 60 j°.
    for (std::size_t j = 0; j < 6; ++j) {
        EXPECT_NEAR(s.direction[j][0], std::cos(kPi / 3 * static_cast<double>(j)), 1e-15);
        EXPECT_NEAR(s.direction[j][1], std::sin(kPi / 3 * static_cast<double>(j)), 1e-15);
    }
    expect_quadratics_exact(s, m, kNoPlanes, 0, 1e-12, "M = 3, quads");
}

TEST(Stencil, CubeCornersAreValidWithQuadDiagonalsInterleaved) {
    SurfaceMesh m;
    m.patches.push_back({"wall", PatchKind::Wall});
    for (int v = 0; v < 8; ++v) m.points.emplace_back(double(v & 1), double((v >> 1) & 1), double((v >> 2) & 1));
    m.add_face({0, 2, 3, 1}, 0);  // z = 0, normal −z
    m.add_face({4, 5, 7, 6}, 0);  // z = 1
    m.add_face({0, 1, 5, 4}, 0);  // y = 0
    m.add_face({2, 6, 7, 3}, 0);  // y = 1
    m.add_face({0, 4, 6, 2}, 0);  // x = 0
    m.add_face({1, 3, 7, 5}, 0);  // x = 1
    const NodeRings rings = node_rings(m);
    const Stencils s = build_stencils(m, rings, {}, {});
    check_layout(s, m);
    for (Index o = 0; o < 8; ++o) {
        ASSERT_TRUE(s.valid[sz(o)]) << "cube corner " << o;
        ASSERT_EQ(rings.neighbours.row_size(o), 3);
        const auto pts = row(s, o);
        ASSERT_EQ(pts.size(), 6u);
        const std::size_t b = sz(rings.neighbours.offsets[sz(o)]);
        for (std::size_t k = 0; k < 3; ++k) {
            EXPECT_EQ(pts[2 * k].node, rings.neighbours.values[b + k]);
            EXPECT_EQ(pts[2 * k + 1].node, rings.diagonals[b + k]);
            const Vec3 p = m.points[sz(o)];
            EXPECT_NEAR((m.points[sz(pts[2 * k].node)] - p).norm(), 1.0, 1e-15);
            EXPECT_NEAR((m.points[sz(pts[2 * k + 1].node)] - p).norm(), std::sqrt(2.0), 1e-15);
        }
        // The M = 6 weights of Eq. 8.
        for (std::size_t j = 0; j < 6; ++j) {
            const double th = kPi / 3 * static_cast<double>(j), c = std::cos(th), sn = std::sin(th);
            const D5 want{c / 3, sn / 3, (4 * c * c - 1) / 3, 4 * c * sn / 3, (4 * sn * sn - 1) / 3};
            expect_d5(s.weights[sz(s.offsets[sz(o)]) + j], want, 1e-14, "corner " + std::to_string(o));
        }
    }
}

/// Node 0 with three triangles; edge neighbours 1..3 at 120k°; outer triangles across the
/// outer edges with far vertices 4..6 at 120k + 60° (unit circle) if \p outer.
SurfaceMesh three_triangles(bool outer) {
    SurfaceMesh m;
    m.patches.push_back({"wall", PatchKind::Wall});
    m.points.push_back(Vec3::Zero());
    for (int k = 0; k < 3; ++k) m.points.push_back(on_circle(2 * kPi * k / 3));
    for (int k = 0; k < 3; ++k) m.points.push_back(on_circle(2 * kPi * k / 3 + kPi / 3));
    auto n = [](int k) { return static_cast<Index>(1 + k % 3); };
    for (int k = 0; k < 3; ++k) m.add_face({0, n(k), n(k + 1)}, 0);
    if (outer)
        for (int k = 0; k < 3; ++k) m.add_face({n(k + 1), n(k), static_cast<Index>(4 + k)}, 0);
    return m;
}

TEST(Stencil, ThreeTrianglesTakeFarVerticesAsDiagonals) {
    const SurfaceMesh m = three_triangles(true);
    const auto [rings, s, pts] = node_0_stencil(m);
    ASSERT_EQ(pts.size(), 6u);
    for (std::size_t k = 0; k < 3; ++k) {
        const Index a = rings.neighbours.values[k];
        const Index c = rings.neighbours.values[(k + 1) % 3];
        EXPECT_EQ(rings.diagonals[k], kNone);
        EXPECT_EQ(pts[2 * k].node, a);
        // The far vertex of the triangle across the outer edge (a, c) is 4 + (a − 1).
        EXPECT_EQ(pts[2 * k + 1].node, 4 + (a - 1)) << "sector " << a << "-" << c;
        EXPECT_EQ(pts[2 * k + 1].mirror, kNone);
    }
    expect_quadratics_exact(s, m, kNoPlanes, 0, 1e-12, "M = 3, triangles");
}

TEST(Stencil, ThreeTrianglesWithoutFarVerticesAreInvalid) {
    const SurfaceMesh m = three_triangles(false);
    const Stencils s = stencils_of(m);
    check_layout(s, m);
    EXPECT_FALSE(s.valid[0]) << "M = 3 needs diagonals; the outer edges are boundary edges";
}

// ---------------------------------------------------------------- M = 4 with triangles

/// Node 0 at the origin with edge neighbours E, N, W, S (1..4) and far corners NE, NW, SW, SE
/// (5..8). Sector k (between neighbours k and k+1) is a quad when quad[k], else a triangle
/// with an outer triangle across its outer edge to corner 5 + k (if outer[k]).
SurfaceMesh plus_ring(std::array<bool, 4> quad, std::array<bool, 4> outer) {
    SurfaceMesh m;
    m.patches.push_back({"wall", PatchKind::Wall});
    m.points.push_back(Vec3::Zero());
    for (int k = 0; k < 4; ++k) m.points.push_back(on_circle(kPi / 2 * k));
    for (int k = 0; k < 4; ++k) m.points.push_back(std::sqrt(2.0) * on_circle(kPi / 4 + kPi / 2 * k));
    for (Vec3& p : m.points) p = p.unaryExpr([](double v) { return std::round(v); });  // exact grid
    auto n = [](int k) { return static_cast<Index>(1 + k % 4); };
    for (int k = 0; k < 4; ++k) {
        if (quad[sz(k)])
            m.add_face({0, n(k), static_cast<Index>(5 + k), n(k + 1)}, 0);
        else
            m.add_face({0, n(k), n(k + 1)}, 0);
    }
    for (int k = 0; k < 4; ++k)
        if (!quad[sz(k)] && outer[sz(k)]) m.add_face({n(k + 1), n(k), static_cast<Index>(5 + k)}, 0);
    return m;
}

TEST(Stencil, FourTrianglesTakeFarVerticesAsDiagonals) {
    const SurfaceMesh m = plus_ring({false, false, false, false}, {true, true, true, true});
    const auto [rings, s, pts] = node_0_stencil(m);
    ASSERT_EQ(pts.size(), 8u);
    for (std::size_t k = 0; k < 4; ++k) {
        const Index a = rings.neighbours.values[k];
        EXPECT_EQ(pts[k].node, a);
        EXPECT_EQ(pts[4 + k].node, 5 + (a - 1)) << "the far vertex across outer edge of sector " << k;
    }
    expect_quadratics_exact(s, m, kNoPlanes, 0, 1e-12, "M = 4, triangles");
}

TEST(Stencil, FourTrianglesWithABoundaryOuterEdgeAreInvalid) {
    const SurfaceMesh m = plus_ring({false, false, false, false}, {true, true, false, true});
    const Stencils s = stencils_of(m);
    check_layout(s, m);
    EXPECT_FALSE(s.valid[0]);
}

TEST(Stencil, NeedleFarVertexIsDroppedForTheOtherSectorsCrossDerivatives) {
    // Sector 0's outer triangle is a needle: its far vertex lies a thousand sector sizes out
    // (the apex of a fan of needles, as at the mixed M6's wing tip). As the diagonal it would
    // make f_ξη about a thousand times too large; the one-sided estimates of the other three
    // sectors, each exact for quadratics, stand in for it.
    SurfaceMesh m = plus_ring({false, false, false, false}, {true, true, true, true});
    m.points[5] = Vec3(600.0, 800.0, 0.0);
    const Stencils s = stencils_of(m);
    check_layout(s, m);
    ASSERT_TRUE(s.valid[0]);
    const auto pts = row(s, 0);
    EXPECT_EQ(pts.size(), 7u);
    for (const auto& p : pts) EXPECT_NE(p.node, 5) << "the needle's apex entered the stencil";
    expect_quadratics_exact(s, m, kNoPlanes, 0, 1e-12, "M = 4, one needle");
    // With every far vertex that far out, nothing is left for f_ξη: the node is not smoothed.
    for (Index k = 5; k <= 8; ++k) m.points[sz(k)] *= 1000.0;
    EXPECT_FALSE(stencils_of(m).valid[0]);
}

TEST(Stencil, ThreeTrianglesWithANeedleFarVertexAreInvalid) {
    SurfaceMesh m = three_triangles(true);
    m.points[4] *= 500.0;
    const Stencils s = stencils_of(m);
    check_layout(s, m);
    EXPECT_FALSE(s.valid[0]) << "the interleaved M = 6 ring needs all three diagonals";
}

TEST(Stencil, UnionJackValence4NodesGiveCentralDifferences) {
    // 2×2 blocks of squares, each split by diagonals through the block centre: nodes with i + j
    // odd have M = 4 and only triangles, and their far vertices are the grid diagonals.
    const int nb = 3, n = 2 * nb;
    SurfaceMesh m;
    m.patches.push_back({"wall", PatchKind::Wall});
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) m.points.emplace_back(double(i), double(j), 0.0);
    auto id = [n](int i, int j) { return static_cast<Index>(j * (n + 1) + i); };
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const Index ll = id(i, j), lr = id(i + 1, j), ur = id(i + 1, j + 1), ul = id(i, j + 1);
            if ((i % 2) == (j % 2)) {  // the block centre is ll or ur
                m.add_face({ll, lr, ur}, 0);
                m.add_face({ll, ur, ul}, 0);
            } else {
                m.add_face({ll, lr, ul}, 0);
                m.add_face({lr, ur, ul}, 0);
            }
        }
    const NodeRings rings = node_rings(m);
    const Stencils s = build_stencils(m, rings, {}, {});
    check_layout(s, m);
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::vector<double> f(sz(m.num_points()));
    for (double& v : f) v = u(rng);
    int tested = 0;
    for (int j = 1; j < n; ++j)
        for (int i = 1; i < n; ++i) {
            const Index o = id(i, j);
            ASSERT_TRUE(s.valid[sz(o)]) << "(" << i << "," << j << ")";
            const Index M = rings.neighbours.row_size(o);
            EXPECT_EQ(M, (i + j) % 2 ? 4 : 8);
            if (M != 4) continue;
            const std::size_t b = sz(rings.neighbours.offsets[sz(o)]);
            const Index n0 = rings.neighbours.values[b];
            const int ai = static_cast<int>(n0) % (n + 1) - i, aj = static_cast<int>(n0) / (n + 1) - j;
            const int bi = -aj, bj = ai;  // neighbour 1 is neighbour 0 turned 90°
            ASSERT_EQ(rings.neighbours.values[b + 1], id(i + bi, j + bj));
            auto node = [&](int p, int q) { return id(i + p * ai + q * bi, j + p * aj + q * bj); };
            const auto pts = row(s, o);
            ASSERT_EQ(pts.size(), 8u);
            EXPECT_EQ(pts[4].node, node(1, 1));
            EXPECT_EQ(pts[5].node, node(-1, 1));
            EXPECT_EQ(pts[6].node, node(-1, -1));
            EXPECT_EQ(pts[7].node, node(1, -1));
            auto F = [&](int p, int q) { return f[sz(node(p, q))]; };
            const D5 want{(F(1, 0) - F(-1, 0)) / 2, (F(0, 1) - F(0, -1)) / 2, F(1, 0) - 2 * F(0, 0) + F(-1, 0),
                          (F(1, 1) - F(-1, 1) - F(1, -1) + F(-1, -1)) / 4, F(0, 1) - 2 * F(0, 0) + F(0, -1)};
            expect_d5(apply_values(s, o, f), want, 1e-14, "node (" + std::to_string(i) + "," + std::to_string(j) + ")");
            ++tested;
        }
    EXPECT_EQ(tested, 2 * (nb - 1) * nb);
}

// ---------------------------------------------------------------- mixed rings

TEST(Stencil, MixedRingM4) {
    // Sectors: quad (diagonal NE), triangle with an outer triangle (far vertex NW), quad
    // (diagonal SW), triangle with an outer *quad* across S-E whose corner nearest to
    // S + E − o is SE (the other corner, Q, is farther).
    SurfaceMesh m = plus_ring({true, false, true, false}, {false, true, false, false});
    const Index se = 8;
    const Index q = static_cast<Index>(m.points.size());
    m.points.emplace_back(1.5, -0.2, 0.0);
    m.add_face({1, 4, se, q}, 0);  // E, S, SE, Q: across the outer edge S→E
    const auto [rings, s, pts] = node_0_stencil(m);
    ASSERT_EQ(pts.size(), 8u);
    const Frame fr = frame_of(s, m, kNoPlanes, 0);
    for (std::size_t k = 0; k < 4; ++k) {
        // Diagonal k sits at logical (±1, ±1) in the quadrant of sector k.
        const Vec3 p = m.points[sz(pts[4 + k].node)];
        const double th = kPi / 4 + kPi / 2 * static_cast<double>(k);
        EXPECT_NEAR(fr.xi(p), std::sqrt(2.0) * std::cos(th), 1e-14)
            << "diagonal " << k << " is node " << pts[4 + k].node;
        EXPECT_NEAR(fr.eta(p), std::sqrt(2.0) * std::sin(th), 1e-14)
            << "diagonal " << k << " is node " << pts[4 + k].node;
    }
    bool has_se = false;
    for (const auto& p : pts) {
        EXPECT_NE(p.node, q) << "the far quad's corner farther from S + E was chosen";
        has_se |= p.node == se;
    }
    EXPECT_TRUE(has_se);
    expect_quadratics_exact(s, m, kNoPlanes, 0, 1e-12, "mixed M = 4");
}

TEST(Stencil, MixedRingM5UsesEdgeNeighboursOnly) {
    // Five neighbours on the unit circle, sectors quad, triangle, quad, triangle, triangle.
    const int M = 5;
    SurfaceMesh m;
    m.patches.push_back({"wall", PatchKind::Wall});
    m.points.push_back(Vec3(1.0, 2.0, -0.5));
    for (int k = 0; k < M; ++k) m.points.push_back(on_circle(0.2 + 2 * kPi * k / M, 1.0, m.points[0]));
    auto n = [](int k) { return static_cast<Index>(1 + k % M); };
    for (int k = 0; k < M; ++k) {
        if (k == 0 || k == 2) {
            const Index d = static_cast<Index>(m.points.size());
            m.points.push_back(on_circle(0.2 + 2 * kPi * (k + 0.5) / M, 1.4, m.points[0]));
            m.add_face({0, n(k), d, n(k + 1)}, 0);
        } else {
            m.add_face({0, n(k), n(k + 1)}, 0);
        }
    }
    const Stencils s = stencils_of(m);
    check_layout(s, m);
    ASSERT_TRUE(s.valid[0]);
    const auto pts = row(s, 0);
    ASSERT_EQ(pts.size(), 5u);
    for (const auto& p : pts) {
        EXPECT_GE(p.node, 1);
        EXPECT_LE(p.node, M) << "a diagonal entered the M = 5 stencil";
    }
    expect_quadratics_exact(s, m, kNoPlanes, 0, 1e-12, "mixed M = 5");
}

// ---------------------------------------------------------------- open rings and mirror planes

TEST(Stencil, GridEdgeOnSymmetryPlaneIsCompletedByMirrorImages) {
    const int nx = 6, ny = 6;
    const SurfaceMesh m = quad_grid(nx, ny);
    auto id = [nx](int i, int j) { return static_cast<Index>(j * (nx + 1) + i); };
    std::vector<MirrorPlane> planes(1);
    planes[0].point = Vec3(0.0, 0.0, 0.0);
    planes[0].normal = Vec3(0.0, 1.0, 0.0);
    std::vector<Index> node_plane(sz(m.num_points()), kNone);
    for (int i = 0; i <= nx; ++i) node_plane[sz(id(i, 0))] = 0;
    const NodeRings rings = node_rings(m);
    const Stencils s = build_stencils(m, rings, node_plane, planes);
    check_layout(s, m);

    for (int j = 0; j <= ny; ++j)
        for (int i = 0; i <= nx; ++i) {
            const Index o = id(i, j);
            const bool interior = i > 0 && i < nx && j > 0 && j < ny;
            const bool plane_edge = j == 0 && i > 0 && i < nx;
            EXPECT_EQ(s.valid[sz(o)] != 0, interior || plane_edge)
                << "node (" << i << "," << j << "): corners (M = 2) and open nodes without a plane are invalid";
        }

    std::mt19937 rng(3);
    for (int i = 1; i < nx; ++i) {
        const Index o = id(i, 0);
        const auto pts = row(s, o);
        ASSERT_EQ(pts.size(), 8u);
        // Completed ring E, N, W, N' (ghost of N) and diagonals NE, NW, NW', NE'.
        const Index E = id(i + 1, 0), N = id(i, 1), W = id(i - 1, 0), NE = id(i + 1, 1), NW = id(i - 1, 1);
        const std::array<StencilPoint, 8> want{StencilPoint{E, kNone},  {N, kNone},  {W, kNone}, {N, 0},
                                               StencilPoint{NE, kNone}, {NW, kNone}, {NW, 0},    {NE, 0}};
        for (std::size_t k = 0; k < 8; ++k) {
            EXPECT_EQ(pts[k].node, want[k].node) << "node (" << i << ",0) point " << k;
            EXPECT_EQ(pts[k].mirror, want[k].mirror) << "node (" << i << ",0) point " << k;
        }
        EXPECT_TRUE(point_position(m, planes, pts[3]).isApprox(Vec3(i, -1.0, 0.0)));
        EXPECT_TRUE(point_position(m, planes, pts[6]).isApprox(Vec3(i - 1.0, -1.0, 0.0)));
        EXPECT_TRUE(point_position(m, planes, pts[7]).isApprox(Vec3(i + 1.0, -1.0, 0.0)));

        // Any quadratic evaluated at the true (mirrored) positions: exact.
        expect_quadratics_exact(s, m, planes, o, 1e-12, "plane node (" + std::to_string(i) + ",0)");

        // A field even in y, with the ghosts taking their node's value (what mirroring a
        // symmetric field means): exact, and the odd derivatives vanish.
        std::uniform_real_distribution<double> u(-2.0, 2.0);
        const double a = u(rng), b = u(rng), d = u(rng), g = u(rng), h = u(rng);
        auto f = [&](const Vec3& p) {
            return a + b * p.x() + d * p.x() * p.x() + g * p.y() * p.y() + h * p.x() * p.y() * p.y();
        };
        std::vector<double> v(sz(m.num_points()));
        for (Index k = 0; k < m.num_points(); ++k) v[sz(k)] = f(m.points[sz(k)]);
        const D5 got = apply_values(s, o, v);
        const double x = i;
        // ξ = +x, η = +y at these nodes (checked above: neighbour 0 is E, neighbour 1 is N).
        const D5 want_d{b + 2 * d * x, 0.0, 2 * d, 0.0, 2 * g + 2 * h * x};
        expect_d5(got, want_d, 1e-12, "even field at (" + std::to_string(i) + ",0)");
        EXPECT_EQ(got[Stencils::Eta], 0.0) << "f_N and its ghost's value cancel exactly";
    }
}

TEST(Stencil, OpenNodeWithoutPlaneIsInvalid) {
    const SurfaceMesh m = quad_grid(3, 3);
    std::vector<Index> node_plane(sz(m.num_points()), kNone);
    std::vector<MirrorPlane> planes(1);
    planes[0].normal = Vec3::UnitY();
    node_plane[1] = 0;  // only (1, 0) has a plane
    const Stencils s = build_stencils(m, node_rings(m), node_plane, planes);
    check_layout(s, m);
    EXPECT_TRUE(s.valid[1]);
    EXPECT_FALSE(s.valid[2]) << "(2, 0) is open and has no plane";
    EXPECT_FALSE(s.valid[0]) << "(0, 0) is a corner";
}

TEST(Stencil, CornersOnAPlaneAreInvalid) {
    const SurfaceMesh m = quad_grid(2, 2);
    std::vector<MirrorPlane> planes(1);
    planes[0].normal = Vec3::UnitY();
    std::vector<Index> node_plane(sz(m.num_points()), 0);  // every node "on" the plane
    const Stencils s = build_stencils(m, node_rings(m), node_plane, planes);
    check_layout(s, m);
    EXPECT_FALSE(s.valid[0]) << "corner, M = 2";
    EXPECT_FALSE(s.valid[2]) << "corner, M = 2";
    EXPECT_TRUE(s.valid[1]) << "edge node on the plane";
}

TEST(Stencil, OpenTriangleFanOnPlaneCompletesToRegularSix) {
    // Half disc: node 0 on the plane y = 0, open ring at 0°, 60°, 120°, 180° (M = 4, triangles).
    // With the mirror images of the 120° and 60° neighbours it is the regular M = 6 ring.
    SurfaceMesh m;
    m.patches.push_back({"wall", PatchKind::Wall});
    const Vec3 c(2.0, 0.0, 1.0);
    m.points.push_back(c);
    for (int k = 0; k < 4; ++k) m.points.push_back(on_circle(kPi / 3 * k, 1.0, c));
    for (int k = 0; k < 3; ++k) m.add_face({0, static_cast<Index>(1 + k), static_cast<Index>(2 + k)}, 0);
    for (Vec3& p : m.points) p.y() = std::abs(p.y()) < 1e-15 ? 0.0 : p.y();
    std::vector<MirrorPlane> planes(1);
    planes[0].normal = Vec3(0.0, -1.0, 0.0);  // the sign of the normal does not matter
    std::vector<Index> node_plane(sz(m.num_points()), kNone);
    node_plane[0] = node_plane[1] = node_plane[4] = 0;
    const NodeRings rings = node_rings(m);
    ASSERT_FALSE(rings.closed[0]);
    const Stencils s = build_stencils(m, rings, node_plane, planes);
    check_layout(s, m);
    ASSERT_TRUE(s.valid[0]);
    const auto pts = row(s, 0);
    ASSERT_EQ(pts.size(), 6u);
    const std::array<StencilPoint, 6> want{StencilPoint{1, kNone}, {2, kNone}, {3, kNone}, {4, kNone}, {3, 0}, {2, 0}};
    for (std::size_t k = 0; k < 6; ++k) {
        EXPECT_EQ(pts[k].node, want[k].node) << k;
        EXPECT_EQ(pts[k].mirror, want[k].mirror) << k;
    }
    expect_quadratics_exact(s, m, planes, 0, 1e-12, "half disc");
    EXPECT_FALSE(s.valid[1]) << "(M = 2) corner of the half disc";
    EXPECT_FALSE(s.valid[4]) << "(M = 2) corner of the half disc";
}

TEST(Stencil, OpenTriangleRingOnPlaneMirrorsFarVertices) {
    // Node 0 on y = 0 with triangles (0, E, N), (0, N, W) and outer triangles to NE and NW:
    // open M = 3 completes to M = 4 with diagonals NE, NW and their mirror images.
    SurfaceMesh m;
    m.patches.push_back({"wall", PatchKind::Wall});
    const std::array<Vec3, 6> p{Vec3(0., 0., 0.),  Vec3(1., 0., 0.), Vec3(0., 1., 0.),
                                Vec3(-1., 0., 0.), Vec3(1., 1., 0.), Vec3(-1., 1., 0.)};
    for (const Vec3& x : p) m.points.push_back(x + Vec3(3.0, 0.0, -2.0));
    m.add_face({0, 1, 2}, 0);
    m.add_face({0, 2, 3}, 0);
    m.add_face({2, 1, 4}, 0);
    m.add_face({3, 2, 5}, 0);
    std::vector<MirrorPlane> planes(1);
    planes[0].point = Vec3(7.0, 0.0, 5.0);
    planes[0].normal = Vec3::UnitY();
    std::vector<Index> node_plane(sz(m.num_points()), kNone);
    node_plane[0] = node_plane[1] = node_plane[3] = 0;
    const Stencils s = build_stencils(m, node_rings(m), node_plane, planes);
    check_layout(s, m);
    ASSERT_TRUE(s.valid[0]);
    const auto pts = row(s, 0);
    ASSERT_EQ(pts.size(), 8u);
    const std::array<StencilPoint, 8> want{StencilPoint{1, kNone}, {2, kNone}, {3, kNone}, {2, 0},
                                           StencilPoint{4, kNone}, {5, kNone}, {5, 0},     {4, 0}};
    for (std::size_t k = 0; k < 8; ++k) {
        EXPECT_EQ(pts[k].node, want[k].node) << k;
        EXPECT_EQ(pts[k].mirror, want[k].mirror) << k;
    }
    expect_quadratics_exact(s, m, planes, 0, 1e-12, "open triangle ring");
}

TEST(Stencil, OpenTriangleRingOnPlaneWithoutFarVerticesIsInvalid) {
    SurfaceMesh m;
    m.patches.push_back({"wall", PatchKind::Wall});
    for (const Vec3& x : {Vec3(0., 0., 0.), Vec3(1., 0., 0.), Vec3(0., 1., 0.), Vec3(-1., 0., 0.)})
        m.points.push_back(x);
    m.add_face({0, 1, 2}, 0);
    m.add_face({0, 2, 3}, 0);
    std::vector<MirrorPlane> planes(1);
    planes[0].normal = Vec3::UnitY();
    std::vector<Index> node_plane{0, 0, kNone, 0};
    const Stencils s = build_stencils(m, node_rings(m), node_plane, planes);
    check_layout(s, m);
    EXPECT_FALSE(s.valid[0]) << "the completed M = 4 ring has no diagonals";
}

}  // namespace
}  // namespace strata
