#include <strata/module/stencil.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace strata {
namespace {

/// A ring point in the making: a stencil point and its position, for choosing diagonals.
struct RingPoint {
    StencilPoint sp;
    Vec3 pos;
    bool dropped = false;  ///< a diagonal rejected by usable_diagonal (sp.node is kNone)
};

/// How far (in lengths of the sector's longer edge) a diagonal may lie from a + b − o, where a
/// parallelogram sector (o, a, b) has it. On the example surfaces 99 % of the far vertices lie
/// within 1.6 (median 0.3–0.6, the hemisphere-cylinder's worst 3.5) and quad corners within
/// 0.7; the apexes of the mixed M6's needle fans lie 680–1040 lengths away. Any reach from 2
/// to 10 gives the same M6 layers.
constexpr double kDiagonalReach = 4.0;

/// Whether \p d can stand for the logical corner (1, 1) of the sector (o, a, b) in f_ξη. Only
/// the diagonals enter f_ξη, and they do not count in the metrics g11, g22, g12 that weigh the
/// terms of the Poisson equation, so a diagonal far from its sector (the far vertex across a
/// triangle's outer edge when that triangle is a needle, as in the wing-tip fans of the mixed
/// M6) makes r_ξη and the node's update huge: 23 layer heights in the first sweep at the M6's
/// node next to the trailing-edge tip, after which point Jacobi diverges.
bool usable_diagonal(const Vec3& o, const Vec3& a, const Vec3& b, const Vec3& d) {
    const double reach = kDiagonalReach * std::max((a - o).norm(), (b - o).norm());
    return (d - (a + b - o)).norm() <= reach;
}

Vec3 position(const SurfaceMesh& mesh, const std::vector<MirrorPlane>& planes, StencilPoint p) {
    const Vec3& x = mesh.points[p.node];
    return p.mirror == kNone ? x : planes[p.mirror].reflect(x);
}

/// The "diagonal" of the sector (o, a, b) when it is a triangle: the node of the face across
/// the outer edge (a, b) nearest to a + b − o, the logical position (1, 1) of the sector
/// (ALGORITHM.md section 3: for a triangle neighbour, its far vertex). kNone if (a, b) is a
/// boundary edge.
Index far_vertex(const SurfaceMesh& mesh, const Csr& vf, Index sector_face, Index o, Index a, Index b) {
    const Vec3 target = mesh.points[a] + mesh.points[b] - mesh.points[o];
    for (const Index* f = vf.row_begin(a); f != vf.row_end(a); ++f) {
        if (*f == sector_face) continue;
        bool has_b = false;
        for (const Index* v = mesh.face_begin(*f); v != mesh.face_end(*f); ++v) has_b |= *v == b;
        if (!has_b) continue;
        Index best = kNone;
        double best_d = 0.0;
        for (const Index* v = mesh.face_begin(*f); v != mesh.face_end(*f); ++v) {
            if (*v == a || *v == b) continue;
            const double d = (mesh.points[*v] - target).squaredNorm();
            if (best == kNone || d < best_d) best = *v, best_d = d;
        }
        return best;
    }
    return kNone;
}

/// Eq. 8 weights for M ≥ 5 points at θ_m = 2πm/M.
void eq8(const std::vector<RingPoint>& ring, Stencils& s) {
    const double m = static_cast<double>(ring.size());
    std::array<double, 5> centre{0, 0, 0, 0, 0};
    for (std::size_t k = 0; k < ring.size(); ++k) {
        const double t = 2.0 * std::numbers::pi * static_cast<double>(k) / m;
        const double c = std::cos(t), sn = std::sin(t);
        const std::array<double, 5> w{2.0 / m * c, 2.0 / m * sn, 2.0 / m * (4.0 * c * c - 1.0), 8.0 / m * c * sn,
                                      2.0 / m * (4.0 * sn * sn - 1.0)};
        for (int d = 0; d < 5; ++d) centre[d] -= w[d];
        s.points.push_back(ring[k].sp);
        s.weights.push_back(w);
        s.direction.push_back({c, sn});
    }
    s.centre.push_back(centre);
}

/// Eqs. 9–10 for M = 4: edge neighbours \p edge at θ = 0, π/2, π, 3π/2, diagonals \p diag
/// at θ̂ = π/4, 3π/4, .... A diagonal whose node is kNone here was rejected (see
/// usable_diagonal): f_ξη is then the mean of the one-sided estimates
/// ±(f̂_k − f_k − f_{k+1} + f_o) of the remaining sectors, each exact for quadratics. With all
/// four sectors the edge terms cancel and this is Eq. 10 itself, weight for weight.
void eq9(const std::vector<RingPoint>& edge, const std::vector<RingPoint>& diag, Stencils& s) {
    int usable = 0;
    for (int k = 0; k < 4; ++k) usable += diag[k].sp.node != kNone ? 1 : 0;
    const double share = 1.0 / usable;  // 1/4 with every diagonal: Eq. 10's (2/M) cos θ̂ sin θ̂
    std::array<double, 5> centre{0, 0, 0, 0, 0};
    const std::size_t first = s.weights.size();
    for (int k = 0; k < 4; ++k) {
        const double t = std::numbers::pi * 0.5 * k;
        const double c = std::round(std::cos(t)), sn = std::round(std::sin(t));
        const std::array<double, 5> w{0.5 * c, 0.5 * sn, c * c, 0.0, sn * sn};
        for (int d = 0; d < 5; ++d) centre[d] -= w[d];
        s.points.push_back(edge[k].sp);
        s.weights.push_back(w);
        s.direction.push_back({c, sn});
    }
    for (int k = 0; k < 4; ++k) {
        if (diag[k].sp.node == kNone) continue;
        // Sector k spans edge neighbours k and k+1; its diagonal sits at ξη = +1, −1, +1, −1.
        // Written exactly (±1/4 with all four), as the edge weights above are rounded, so the
        // weights are exactly the central differences'.
        const double cs = k % 2 == 0 ? share : -share;
        const std::array<double, 5> w{0.0, 0.0, 0.0, cs, 0.0};
        centre[3] += cs;
        s.weights[first + k][3] -= cs;
        s.weights[first + (k + 1) % 4][3] -= cs;
        s.points.push_back(diag[k].sp);
        s.weights.push_back(w);
        s.direction.push_back({0.0, 0.0});  // diagonals carry no concave-smoothing direction
    }
    s.centre.push_back(centre);
}

}  // namespace

Stencils build_stencils(const SurfaceMesh& mesh, const NodeRings& rings, const std::vector<Index>& node_plane,
                        const std::vector<MirrorPlane>& planes) {
    const Csr vf = vertex_faces(mesh);
    Stencils s;
    const Index n = mesh.num_points();
    s.valid.assign(static_cast<std::size_t>(n), 0);
    std::vector<RingPoint> edge, diag, ring;
    for (Index o = 0; o < n; ++o) {
        const Index b = rings.neighbours.offsets[o];
        const Index m = rings.neighbours.row_size(o);
        const bool closed = rings.closed[o] != 0;
        const Index plane = node_plane.empty() ? kNone : node_plane[o];
        edge.clear();
        diag.clear();
        bool ok = m >= 2 && (closed || plane != kNone);
        // Sector k spans edge neighbours k and k+1; its diagonal is the quad's opposite
        // corner or the far vertex across the outer edge.
        auto sector_diag = [&](Index k) -> Index {
            const Index a = rings.neighbours.values[b + k];
            const Index c = rings.neighbours.values[b + (k + 1) % m];
            const Index d = rings.diagonals[b + k];
            if (d != kNone) return d;
            const Index f = rings.faces[b + k];
            return f == kNone ? kNone : far_vertex(mesh, vf, f, o, a, c);
        };
        // A sector's diagonal, or a dropped one when it is too far from the sector to stand
        // for its corner (1, 1).
        auto sector_point = [&](Index k, const Vec3& pa, const Vec3& pc) -> RingPoint {
            const Index d = sector_diag(k);
            if (d == kNone) return {{kNone, kNone}, Vec3::Zero()};
            if (!usable_diagonal(mesh.points[o], pa, pc, mesh.points[d])) return {{kNone, kNone}, Vec3::Zero(), true};
            return {{d, kNone}, mesh.points[d]};
        };
        if (ok && closed) {
            for (Index k = 0; k < m; ++k) {
                const Index a = rings.neighbours.values[b + k];
                edge.push_back({{a, kNone}, mesh.points[a]});
            }
            for (Index k = 0; k < m; ++k) {
                diag.push_back(sector_point(k, edge[k].pos, edge[(k + 1) % m].pos));
                if (diag.back().sp.node == kNone && !diag.back().dropped) ok = ok && m >= 5;  // needed only for M ≤ 4
            }
        } else if (ok) {
            // Open ring on a plane: n_0 .. n_{M-1}, then the mirror images n'_{M-2} .. n'_1,
            // with the sectors mirrored alike (ALGORITHM.md section 8).
            if (m < 3) ok = false;
            for (Index k = 0; ok && k < m; ++k) {
                const Index a = rings.neighbours.values[b + k];
                edge.push_back({{a, kNone}, mesh.points[a]});
            }
            for (Index k = 0; ok && k + 1 < m; ++k) diag.push_back(sector_point(k, edge[k].pos, edge[k + 1].pos));
            if (ok) {
                for (Index k = m - 2; k >= 1; --k) {
                    const StencilPoint sp{rings.neighbours.values[b + k], plane};
                    edge.push_back({sp, position(mesh, planes, sp)});
                }
                for (Index k = m - 2; k >= 0; --k) {
                    const RingPoint d = diag[static_cast<std::size_t>(k)];
                    const StencilPoint sp{d.sp.node, d.sp.node == kNone ? kNone : plane};
                    diag.push_back({sp, d.sp.node == kNone ? Vec3::Zero() : position(mesh, planes, sp), d.dropped});
                }
            }
            const std::size_t mm = edge.size();
            for (std::size_t k = 0; ok && k < diag.size(); ++k)
                if (diag[k].sp.node == kNone && !diag[k].dropped && mm <= 4) ok = false;
        }
        // Eq. 9 does without a dropped diagonal if another sector keeps one; the interleaved
        // M = 6 ring of M = 3 needs all three.
        std::size_t kept = 0, dropped = 0;
        for (const RingPoint& d : diag) (d.dropped ? dropped : kept) += 1;
        if (edge.size() == 4 && kept == 0) ok = false;
        if (edge.size() == 3 && dropped > 0) ok = false;
        const std::size_t mm = edge.size();
        if (ok && mm >= 5) {
            eq8(edge, s);
        } else if (ok && mm == 4) {
            eq9(edge, diag, s);
        } else if (ok && mm == 3) {
            // Knupp's procedure: interleave the diagonals, then Eq. 8 with M = 6.
            ring.clear();
            for (std::size_t k = 0; k < 3; ++k) {
                ring.push_back(edge[k]);
                ring.push_back(diag[k]);
            }
            eq8(ring, s);
        } else {
            ok = false;
            s.centre.push_back({0, 0, 0, 0, 0});
        }
        s.valid[static_cast<std::size_t>(o)] = ok ? 1 : 0;
        s.offsets.push_back(static_cast<Index>(s.points.size()));
    }
    return s;
}

}  // namespace strata
