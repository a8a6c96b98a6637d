// The pyramid transition (pyramids.h).
//
// Each quad q of the layer top gets an apex a = c + h n (c the corner mean, n the unit
// vector area, h = height × mean edge length L; where q has an edge on a plane the top's open
// boundary lies in, standing on it at 30° or more and leaning towards it, n without its part
// towards the plane). h is taken from a descending list of candidates, h0, h0/2, h0/4, ... and
// finally min_height × (shortest edge) itself, and a candidate is
// accepted only if the pyramid passes every rule below. Rules depend on one pyramid alone
// ("static": the pyramid and the fixed top surface) or on a pair of pyramids.
//
// Static rules, for pyramid P at height h:
//  S1  not inverted: pyramid_min_scaled_jacobian > 0.
//  S2  no fold across a base edge. In the plane normal to the edge, the faces on both sides
//      of the edge (P's quad and each top face g across it) open an exterior wedge of angle
//      φ ∈ (0, 2π] (π flat, < π concave, > π convex; measured with the face centroids, so
//      it does not depend on g's orientation). P's side triangle over the edge must point
//      into P's half of the wedge with a margin: 0 < ψ < (1 − kFoldMargin) φ/2, ψ the angle of
//      the apex above P's face. g's own pyramid or triangle lies in the other half, so the two
//      never cross near the edge and keep an angle of at least kFoldMargin φ between them.
//      An edge with no face across (an open boundary of the top) counts as flat (φ = π): the
//      apex stays clear of the plane normal to the quad through that edge. On a plane (its
//      loop is planar: the layers' sides on a symmetry plane) that the quad stands on at 30°
//      or more and leans towards, the quad's mirror image in the plane counts as the face
//      across (φ < π), so the side keeps off the plane itself.
//  S3  apex clearance: the apex is at least kFaceClearance × h from every top face other
//      than P's own quad (quads as two triangles).
//  S4  no crossing: no side triangle of P meets a nearby top face except at shared corners.
// Pair rules, for pyramids P, Q at heights hP, hQ, with m = min(hP, hQ):
//  P1  each apex is at least kApexClearance × m from every side triangle of the other
//      pyramid (so also from its apex);
//  P2  lateral edges (corner–apex) not starting at the same corner are at least
//      kEdgeClearance × m apart;
//  P3  no side triangle of P meets one of Q except at shared corners (a shared base edge
//      is S2's business).
// "Meets" is a distance ≤ kTouch × h. Triangles sharing one corner v meet elsewhere only if
// the edge of one opposite v reaches the other triangle (their intersection is a segment from
// v whose other end lies on such an edge), so that is what is tested; with no shared corner
// the triangle–triangle distance is.
//
// Why these suffice: two closed pyramids with disjoint boundaries overlap only if one holds
// the other, and a pyramid can hold another's base only if the top surface crosses its sides
// (S4). Apex and edge clearances keep room for the tetrahedra between pyramids facing each
// other across a gap; they scale with h so that shortening always helps.
//
// Resolution. Phase 1: every pyramid independently takes its first candidate passing S1–S4;
// none passing is a TopologyError naming the quad. Phase 2, in rounds: the pairs with at
// least one pyramid changed in the previous round (all pairs in the first) are checked
// against P1–P3, and in every conflicting pair the taller pyramid (both when equal) moves to
// its next candidate that passes S1–S4 — the other one if the taller has none left; if
// neither has, TopologyError. All decisions of a round are taken from the heights at its
// start, so the result does not depend on the order of the loop. Heights only decrease, so
// the neighbour lists (a uniform grid over bounding boxes at the initial height, expanded by
// the largest clearance) stay valid throughout: O(n) checks per round after an O(n log n)
// sort, and few rounds (each moves a pyramid down one of its few candidates).

#include <strata/core/cell_quality.h>
#include <strata/core/error.h>
#include <strata/core/face_geometry.h>
#include <strata/core/format.h>
#include <strata/core/progress.h>
#include <strata/geometry/topology.h>
#include <strata/hybrid/pyramids.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

namespace strata {
namespace {

constexpr double kFoldMargin = 0.1;      // share of each half-wedge kept free next to the bisector
constexpr double kFaceClearance = 0.5;   // S3: apex ↔ other top faces, × h
constexpr double kApexClearance = 0.5;   // P1: apex ↔ other pyramid's sides, × min(hP, hQ)
constexpr double kEdgeClearance = 0.25;  // P2: lateral edges of two pyramids, × min(hP, hQ)
constexpr double kTouch = 1e-6;          // "meets": distance ≤ kTouch × h

// ---------------------------------------------------------------------------------------
// Distances between points, segments and triangles (Ericson, Real-Time Collision Detection,
// 5.1.5 and 5.1.9).

double point_segment_distance(const Vec3& p, const Vec3& a, const Vec3& b) {
    const Vec3 ab = b - a;
    const double l2 = ab.squaredNorm();
    const double t = l2 > 0.0 ? std::clamp((p - a).dot(ab) / l2, 0.0, 1.0) : 0.0;
    return (p - (a + t * ab)).norm();
}

double point_triangle_distance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
    const Vec3 ab = b - a, ac = c - a, ap = p - a;
    const double d1 = ab.dot(ap), d2 = ac.dot(ap);
    if (d1 <= 0.0 && d2 <= 0.0) return ap.norm();
    const Vec3 bp = p - b;
    const double d3 = ab.dot(bp), d4 = ac.dot(bp);
    if (d3 >= 0.0 && d4 <= d3) return bp.norm();
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return (p - (a + d1 / (d1 - d3) * ab)).norm();
    const Vec3 cp = p - c;
    const double d5 = ab.dot(cp), d6 = ac.dot(cp);
    if (d6 >= 0.0 && d5 <= d6) return cp.norm();
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return (p - (a + d2 / (d2 - d6) * ac)).norm();
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0)
        return (p - (b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b))).norm();
    const double sum = va + vb + vc;
    if (!(sum > 0.0))  // degenerate triangle: its edges are all there is
        return std::min(
            {point_segment_distance(p, a, b), point_segment_distance(p, b, c), point_segment_distance(p, c, a)});
    return (p - (a + ab * (vb / sum) + ac * (vc / sum))).norm();
}

double segment_segment_distance(const Vec3& p1, const Vec3& q1, const Vec3& p2, const Vec3& q2) {
    const Vec3 d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
    const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
    double s = 0.0, t = 0.0;
    if (a <= 0.0 && e <= 0.0) return r.norm();
    if (a <= 0.0) {
        t = std::clamp(f / e, 0.0, 1.0);
    } else {
        const double c = d1.dot(r);
        if (e <= 0.0) {
            s = std::clamp(-c / a, 0.0, 1.0);
        } else {
            const double b = d1.dot(d2), denom = a * e - b * b;
            s = denom > 1e-14 * a * e ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
            t = (b * s + f) / e;
            if (t < 0.0) {
                t = 0.0;
                s = std::clamp(-c / a, 0.0, 1.0);
            } else if (t > 1.0) {
                t = 1.0;
                s = std::clamp((b - c) / a, 0.0, 1.0);
            }
        }
    }
    return ((p1 + s * d1) - (p2 + t * d2)).norm();
}

struct Tri {
    std::array<Index, 3> id;  // node ids (apex k: nt + k), for shared-corner detection
    std::array<Vec3, 3> x;
};

double segment_triangle_distance(const Vec3& p, const Vec3& q, const Tri& t) {
    const Vec3 &a = t.x[0], &b = t.x[1], &c = t.x[2];
    const Vec3 n = (b - a).cross(c - a);
    const double dp = (p - a).dot(n), dq = (q - a).dot(n);
    if ((dp < 0.0 && dq > 0.0) || (dp > 0.0 && dq < 0.0)) {
        // The segment crosses the plane: through the triangle if the crossing point is in it.
        const Vec3 x = p + dp / (dp - dq) * (q - p);
        const double scale = std::max({(b - a).norm(), (c - a).norm(), (c - b).norm()});
        if (point_triangle_distance(x, a, b, c) <= 1e-12 * scale) return 0.0;
    }
    return std::min({point_triangle_distance(p, a, b, c), point_triangle_distance(q, a, b, c),
                     segment_segment_distance(p, q, a, b), segment_segment_distance(p, q, b, c),
                     segment_segment_distance(p, q, c, a)});
}

/// Segment pq meets triangle t: passes through it, or ends or lies within \p tol of it. (A
/// segment grazing the triangle's edge at a shallow angle to its plane is not caught within
/// tol: tol only absorbs rounding here, the clearances are separate rules.)
bool segment_meets_triangle(const Vec3& p, const Vec3& q, const Tri& t, double tol) {
    const Vec3 n = (t.x[1] - t.x[0]).cross(t.x[2] - t.x[0]);
    const double len = n.norm();
    if (!(len > 0.0)) return segment_triangle_distance(p, q, t) <= tol;  // degenerate triangle
    const double dp = (p - t.x[0]).dot(n) / len, dq = (q - t.x[0]).dot(n) / len;
    const bool p_on = std::abs(dp) <= tol, q_on = std::abs(dq) <= tol;
    if (p_on && q_on) return segment_triangle_distance(p, q, t) <= tol;  // in the plane
    if (p_on) return point_triangle_distance(p, t.x[0], t.x[1], t.x[2]) <= tol;
    if (q_on) return point_triangle_distance(q, t.x[0], t.x[1], t.x[2]) <= tol;
    if ((dp > 0.0) == (dq > 0.0)) return false;  // wholly on one side
    const Vec3 x = p + dp / (dp - dq) * (q - p);
    return point_triangle_distance(x, t.x[0], t.x[1], t.x[2]) <= tol;
}

/// point_triangle_distance(p, t) < d, rejecting by bounding box first.
bool point_near_triangle(const Vec3& p, const Tri& t, double d) {
    for (int k = 0; k < 3; ++k)
        if (p[k] < std::min({t.x[0][k], t.x[1][k], t.x[2][k]}) - d ||
            p[k] > std::max({t.x[0][k], t.x[1][k], t.x[2][k]}) + d)
            return false;
    return point_triangle_distance(p, t.x[0], t.x[1], t.x[2]) < d;
}

/// segment_segment_distance < d, rejecting by bounding box first.
bool segments_near(const Vec3& p1, const Vec3& q1, const Vec3& p2, const Vec3& q2, double d) {
    for (int k = 0; k < 3; ++k)
        if (std::min(p1[k], q1[k]) > std::max(p2[k], q2[k]) + d || std::min(p2[k], q2[k]) > std::max(p1[k], q1[k]) + d)
            return false;
    return segment_segment_distance(p1, q1, p2, q2) < d;
}

bool boxes_apart(const Tri& s, const Tri& t, double tol) {
    for (int d = 0; d < 3; ++d) {
        const double smin = std::min({s.x[0][d], s.x[1][d], s.x[2][d]});
        const double smax = std::max({s.x[0][d], s.x[1][d], s.x[2][d]});
        const double tmin = std::min({t.x[0][d], t.x[1][d], t.x[2][d]});
        const double tmax = std::max({t.x[0][d], t.x[1][d], t.x[2][d]});
        if (smin > tmax + tol || tmin > smax + tol) return true;
    }
    return false;
}

/// True if triangles \p s and \p t come within \p tol of each other anywhere but at the
/// corners they share. Two shared corners (a common edge) are never reported: that is the
/// fold rule's case.
bool triangles_meet(const Tri& s, const Tri& t, double tol) {
    if (boxes_apart(s, t, tol)) return false;
    int shared = 0, si = -1, ti = -1;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            if (s.id[i] == t.id[j]) {
                ++shared;
                si = i;
                ti = j;
            }
    if (shared >= 2) return false;
    if (shared == 1) {
        // The intersection is a segment from the shared corner ending on an edge opposite it.
        const Vec3 &s1 = s.x[(si + 1) % 3], &s2 = s.x[(si + 2) % 3];
        const Vec3 &t1 = t.x[(ti + 1) % 3], &t2 = t.x[(ti + 2) % 3];
        return segment_meets_triangle(s1, s2, t, tol) || segment_meets_triangle(t1, t2, s, tol);
    }
    for (int i = 0; i < 3; ++i) {
        if (segment_meets_triangle(s.x[i], s.x[(i + 1) % 3], t, tol)) return true;
        if (segment_meets_triangle(t.x[i], t.x[(i + 1) % 3], s, tol)) return true;
    }
    return false;
}

// ---------------------------------------------------------------------------------------

/// Why a pyramid cannot take a height.
struct Failure {
    enum Kind { None, Inverted, Fold, FaceClearance, FaceCrossing, Pyramid } kind = None;
    Index other = kNone;         // the top face or the other pyramid's quad
    Index a = kNone, b = kNone;  // Fold: the base edge
    bool ok() const { return kind == None; }
};

struct Box {
    Vec3 lo, hi;
    bool overlaps(const Box& o) const {
        return (lo.array() <= o.hi.array()).all() && (o.lo.array() <= hi.array()).all();
    }
};

/// A uniform grid of axis-aligned boxes: item lists per cell, found by sorting
/// (cell key, item) pairs. Items spanning too many cells are kept aside and tested always.
class BoxGrid {
public:
    BoxGrid(const Vec3& origin, double cell) : origin_(origin), inv_(1.0 / cell) {}

    void insert(Index item, const Box& b) {
        const auto lo = cell_of(b.lo), hi = cell_of(b.hi);
        std::int64_t cells = 1;
        for (int d = 0; d < 3; ++d) cells *= hi[d] - lo[d] + 1;
        if (cells > kMaxCells) {
            big_.push_back(item);
            return;
        }
        for (std::int64_t i = lo[0]; i <= hi[0]; ++i)
            for (std::int64_t j = lo[1]; j <= hi[1]; ++j)
                for (std::int64_t k = lo[2]; k <= hi[2]; ++k) entries_.emplace_back(key(i, j, k), item);
    }
    void finish() { std::sort(entries_.begin(), entries_.end()); }

    /// Items whose cells meet \p b's cells (a superset of the overlapping boxes), appended to
    /// \p out unsorted and possibly repeated.
    void query(const Box& b, std::vector<Index>& out) const {
        const auto lo = cell_of(b.lo), hi = cell_of(b.hi);
        for (std::int64_t i = lo[0]; i <= hi[0]; ++i)
            for (std::int64_t j = lo[1]; j <= hi[1]; ++j)
                for (std::int64_t k = lo[2]; k <= hi[2]; ++k) {
                    const std::uint64_t kk = key(i, j, k);
                    auto it = std::lower_bound(entries_.begin(), entries_.end(),
                                               std::pair<std::uint64_t, Index>(kk, std::numeric_limits<Index>::min()));
                    for (; it != entries_.end() && it->first == kk; ++it) out.push_back(it->second);
                }
        out.insert(out.end(), big_.begin(), big_.end());
    }

private:
    static constexpr std::int64_t kMaxCells = 4096;
    std::array<std::int64_t, 3> cell_of(const Vec3& x) const {
        std::array<std::int64_t, 3> c;
        for (int d = 0; d < 3; ++d)
            c[d] = std::clamp(static_cast<std::int64_t>(std::floor((x[d] - origin_[d]) * inv_)), std::int64_t{0},
                              (std::int64_t{1} << 21) - 1);
        return c;
    }
    static std::uint64_t key(std::int64_t i, std::int64_t j, std::int64_t k) {
        return static_cast<std::uint64_t>(i) | (static_cast<std::uint64_t>(j) << 21) |
               (static_cast<std::uint64_t>(k) << 42);
    }
    Vec3 origin_;
    double inv_;
    std::vector<std::pair<std::uint64_t, Index>> entries_;
    std::vector<Index> big_;
};

class Builder {
public:
    Builder(const SurfaceMesh& top, const PyramidParams& params, Progress* progress)
        : top_(top), params_(params), progress_(progress) {}

    PyramidLayer run();

private:
    // Per pyramid (one per quad, in face order).
    struct Pyr {
        Index face = kNone;
        std::array<Index, 4> v{};
        std::array<Vec3, 4> x;
        Vec3 c, n;
        double size = 0.0;            // mean edge length
        double shortest = 0.0;        // shortest edge length
        std::vector<double> heights;  // candidates, descending
        // S1–S4 at each candidate, evaluated when first needed: -1 unknown, 0 fails, 1 passes.
        std::vector<signed char> static_ok;  // aligned with heights
        std::vector<Failure> static_why;     // aligned with heights
        int level = -1;                      // current candidate
        double h() const { return heights[static_cast<std::size_t>(level)]; }
    };

    void setup();
    void build_neighbours();
    Tri face_tri(Index g, int t) const;
    int face_tris(Index g) const { return top_.face_size(g) == 4 ? 2 : 1; }
    Tri side(const Pyr& p, Index k, double h, int i) const;
    Failure check_static(Index k, double h) const;
    bool pair_conflict(Index k, Index m) const;
    int next_level(Index k);
    /// Throw the LocalTopologyError naming quad \p k, carrying its nodes and then those of the
    /// quads \p others (four each) that cannot be capped either.
    [[noreturn]] void fail(Index k, const Failure& why, double h, const std::vector<Index>& others = {}) const;

    const SurfaceMesh& top_;
    const PyramidParams& params_;
    Progress* progress_;
    std::vector<Pyr> pyr_;
    std::vector<Index> pyr_of_face_;  // face → pyramid or kNone
    std::vector<Vec3> face_centroid_;
    // Faces across each base edge: row 4k + i lists the faces other than pyramid k's quad on
    // the edge (v[i], v[i+1]).
    Csr across_;
    // Per row of across_ with no face across (an open edge of the top): the unit normal of the
    // plane its open boundary loop lies in (a symmetry plane), zero where that loop is not planar.
    std::vector<Vec3> open_plane_;
    Csr near_faces_;  // pyramid → top faces (other than its quad) whose boxes meet its reach
    Csr near_pyrs_;   // pyramid → other pyramids whose boxes meet its reach; symmetric
};

void Builder::setup() {
    if (!(params_.height > 0.0) || !std::isfinite(params_.height))
        throw InputError("pyramids: height must be a positive number (relative to the quad's mean edge), got " +
                         format_number(params_.height));
    if (!(params_.min_height > 0.0) || !(params_.min_height <= params_.height))
        throw InputError("pyramids: min_height must be positive and at most height (" + format_number(params_.height) +
                         "), got " + format_number(params_.min_height));
    const Index nf = top_.num_faces();
    pyr_of_face_.assign(static_cast<std::size_t>(nf), kNone);
    face_centroid_.resize(static_cast<std::size_t>(nf));
    for (Index f = 0; f < nf; ++f) {
        const Index s = top_.face_size(f);
        if (s != 3 && s != 4)
            throw TopologyError("pyramids: face " + std::to_string(f) + " of the layer top has " + std::to_string(s) +
                                " nodes; only triangles and quads can be capped");
        for (Index i = 0; i < s; ++i) {
            const Index v = top_.face_node(f, i);
            if (v < 0 || v >= top_.num_points())
                throw TopologyError("pyramids: face " + std::to_string(f) + " of the layer top refers to node " +
                                    std::to_string(v) + ", which does not exist");
        }
        face_centroid_[static_cast<std::size_t>(f)] = face_centroid(top_, top_.points, f);
        if (s != 4) continue;
        Pyr p;
        p.face = f;
        for (int i = 0; i < 4; ++i) {
            p.v[i] = top_.face_node(f, i);
            p.x[i] = top_.points[p.v[i]];
        }
        p.c = face_centroid_[static_cast<std::size_t>(f)];
        const Vec3 area = face_area_vector(top_, f);
        double shortest = std::numeric_limits<double>::max();
        for (int i = 0; i < 4; ++i) {
            const double l = (p.x[(i + 1) % 4] - p.x[i]).norm();
            p.size += 0.25 * l;
            shortest = std::min(shortest, l);
        }
        if (!(area.norm() > 1e-12 * p.size * p.size) || !std::isfinite(area.norm()) || !(shortest > 1e-12 * p.size))
            throw TopologyError("pyramids: quad " + std::to_string(f) + " of the layer top at " + format_point(p.c) +
                                " is degenerate (no area or a collapsed edge); check the wall surface there");
        p.n = area.normalized();
        // Candidates: h0, h0/2, ... while above the floor, then the floor itself. The floor
        // follows the shortest edge, so a stretched quad (a blunt trailing edge's 1:60 quads)
        // can still get a pyramid that does not lean over its short sides.
        p.shortest = shortest;
        const double h0 = params_.height * p.size, hmin = params_.min_height * shortest;
        for (double h = h0; h >= hmin * (1.0 - 1e-12); h *= 0.5) p.heights.push_back(h);
        if (p.heights.back() > hmin * (1.0 + 1e-12)) p.heights.push_back(hmin);
        pyr_of_face_[static_cast<std::size_t>(f)] = static_cast<Index>(pyr_.size());
        pyr_.push_back(std::move(p));
    }
}

void Builder::build_neighbours() {
    // Faces across each base edge.
    const EdgeTable et = edge_table(top_);
    // The planes of the top's planar open boundary loops (the layers' sides on a symmetry
    // plane), per edge.
    std::vector<Vec3> edge_plane(et.nodes.size(), Vec3::Zero());
    const Csr loops = boundary_loops(top_);
    for (Index l = 0; l < loops.rows(); ++l) {
        std::vector<Vec3> pts;
        for (const Index* v = loops.row_begin(l); v != loops.row_end(l); ++v) pts.push_back(top_.points[*v]);
        if (const PatchPlane pl = fit_plane(pts); pl.planar())
            for (Index i = 0, m = loops.row_size(l); i < m; ++i)
                edge_plane[static_cast<std::size_t>(
                    find_edge(et, loops.row_begin(l)[i], loops.row_begin(l)[(i + 1) % m]))] = pl.normal;
    }
    across_.offsets.assign(1, 0);
    open_plane_.clear();
    for (Pyr& p : pyr_)
        for (int i = 0; i < 4; ++i) {
            Vec3 m = Vec3::Zero();
            if (const Index ei = find_edge(et, p.v[i], p.v[(i + 1) % 4]); ei != kNone) {
                for (const Index* g = et.faces.row_begin(ei); g != et.faces.row_end(ei); ++g)
                    if (*g != p.face) across_.values.push_back(*g);
                m = edge_plane[static_cast<std::size_t>(ei)];
            }
            across_.offsets.push_back(static_cast<Index>(across_.values.size()));
            // Only a quad standing on the plane at 30° or more (the layers' top beside their
            // sides on a symmetry plane; not a flat wall's top lying in its own outline's plane).
            const Vec3 e = (p.x[(i + 1) % 4] - p.x[i]).normalized();
            const Vec3 d1 = (p.c - p.x[i]) - (p.c - p.x[i]).dot(e) * e;
            if (!(std::abs(d1.dot(m)) >= 0.5 * d1.norm())) m = Vec3::Zero();
            open_plane_.push_back(m);
            if (m == Vec3::Zero()) continue;
            // A quad leaning towards the plane (the layer top meeting a symmetry plane
            // obliquely, beside a swept edge) raises its apex parallel to the plane: along
            // its normal, the apex would come down onto the plane.
            if (d1.dot(m) < 0.0) m = -m;  // into the quad's side
            if (const double towards = p.n.dot(m); towards < 0.0) p.n = (p.n - towards * m).normalized();
        }

    // Reach of each pyramid: its box at the first candidate height, grown by the largest
    // clearance any rule asks of it (heights only decrease, so the box only shrinks).
    const std::size_t np = pyr_.size();
    std::vector<Box> pbox(np), reach(np);
    double mean_extent = 0.0;
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::max()), hi = -lo;
    for (std::size_t k = 0; k < np; ++k) {
        const Pyr& p = pyr_[k];
        const Vec3 apex = p.c + p.heights.front() * p.n;
        Box b{apex, apex};
        for (const Vec3& x : p.x) {
            b.lo = b.lo.cwiseMin(x);
            b.hi = b.hi.cwiseMax(x);
        }
        pbox[k] = b;
        const double grow =
            std::max({kFaceClearance, kApexClearance, kEdgeClearance}) * p.heights.front() + kTouch * p.heights.front();
        reach[k] = Box{b.lo - Vec3::Constant(grow), b.hi + Vec3::Constant(grow)};
        mean_extent += (reach[k].hi - reach[k].lo).maxCoeff() / static_cast<double>(np);
        lo = lo.cwiseMin(reach[k].lo);
        hi = hi.cwiseMax(reach[k].hi);
    }
    const Index nf = top_.num_faces();
    std::vector<Box> fbox(static_cast<std::size_t>(nf));
    for (Index f = 0; f < nf; ++f) {
        Box b{top_.points[top_.face_node(f, 0)], top_.points[top_.face_node(f, 0)]};
        for (const Index* v = top_.face_begin(f); v != top_.face_end(f); ++v) {
            b.lo = b.lo.cwiseMin(top_.points[*v]);
            b.hi = b.hi.cwiseMax(top_.points[*v]);
        }
        fbox[static_cast<std::size_t>(f)] = b;
        lo = lo.cwiseMin(b.lo);
        hi = hi.cwiseMax(b.hi);
    }
    // Cells about the size of a pyramid's reach, and at most 10^6 along the whole extent so
    // cell coordinates fit the grid's 21-bit keys.
    const double cell = std::max(mean_extent, (hi - lo).maxCoeff() * 1e-6);

    BoxGrid faces(lo, cell), pyrs(lo, cell);
    for (Index f = 0; f < nf; ++f) faces.insert(f, fbox[static_cast<std::size_t>(f)]);
    for (std::size_t k = 0; k < np; ++k) pyrs.insert(static_cast<Index>(k), pbox[k]);
    faces.finish();
    pyrs.finish();

    std::vector<Index> found;
    std::vector<std::vector<Index>> near_p(np);
    near_faces_.offsets.assign(1, 0);
    for (std::size_t k = 0; k < np; ++k) {
        found.clear();
        faces.query(reach[k], found);
        std::sort(found.begin(), found.end());
        found.erase(std::unique(found.begin(), found.end()), found.end());
        for (const Index g : found)
            if (g != pyr_[k].face && reach[k].overlaps(fbox[static_cast<std::size_t>(g)]))
                near_faces_.values.push_back(g);
        near_faces_.offsets.push_back(static_cast<Index>(near_faces_.values.size()));

        found.clear();
        pyrs.query(reach[k], found);
        std::sort(found.begin(), found.end());
        found.erase(std::unique(found.begin(), found.end()), found.end());
        for (const Index m : found)
            if (m != static_cast<Index>(k) && reach[k].overlaps(pbox[static_cast<std::size_t>(m)])) {
                near_p[k].push_back(m);
                near_p[static_cast<std::size_t>(m)].push_back(static_cast<Index>(k));
            }
    }
    near_pyrs_.offsets.assign(1, 0);
    for (auto& row : near_p) {
        std::sort(row.begin(), row.end());
        row.erase(std::unique(row.begin(), row.end()), row.end());
        near_pyrs_.values.insert(near_pyrs_.values.end(), row.begin(), row.end());
        near_pyrs_.offsets.push_back(static_cast<Index>(near_pyrs_.values.size()));
    }
}

Tri Builder::face_tri(Index g, int t) const {
    // Quads as (0,1,2) and (0,2,3).
    static constexpr int kCorner[2][3] = {{0, 1, 2}, {0, 2, 3}};
    Tri tri;
    for (int i = 0; i < 3; ++i) {
        tri.id[i] = top_.face_node(g, kCorner[t][i]);
        tri.x[i] = top_.points[tri.id[i]];
    }
    return tri;
}

Tri Builder::side(const Pyr& p, Index k, double h, int i) const {
    return Tri{{p.v[i], p.v[(i + 1) % 4], top_.num_points() + k}, {p.x[i], p.x[(i + 1) % 4], p.c + h * p.n}};
}

Failure Builder::check_static(Index k, double h) const {
    const Pyr& p = pyr_[static_cast<std::size_t>(k)];
    const Vec3 apex = p.c + h * p.n;
    // S1.
    std::vector<Vec3> corners(p.x.begin(), p.x.end());
    corners.push_back(apex);
    if (!(pyramid_min_scaled_jacobian(corners, {0, 1, 2, 3, 4}) > 0.0)) return {Failure::Inverted};
    // S2.
    for (int i = 0; i < 4; ++i) {
        const Vec3 &q0 = p.x[i], &q1 = p.x[(i + 1) % 4];
        const Vec3 e = (q1 - q0).normalized();
        auto across = [&](const Vec3& w) { return w - w.dot(e) * e; };  // component normal to the edge
        const Vec3 d1 = across(p.c - q0).normalized();                  // into the quad
        Vec3 up = e.cross(d1);                                          // normal to the quad, seen along the edge
        if (up.dot(p.n) < 0.0) up = -up;
        const Vec3 w = across(apex - q0);
        const double psi = std::atan2(w.dot(up), w.dot(d1));
        const Index row = 4 * k + i;
        auto limit_ok = [&](double phi) { return psi > 0.0 && psi < (1.0 - kFoldMargin) * 0.5 * phi; };
        if (across_.row_size(row) == 0) {
            // Counted as flat; on a plane that the quad leans towards, as the quad's mirror
            // image in it (where a symmetric flow's would be), so that the side over the edge
            // keeps off the plane by the margin too.
            double phi = std::numbers::pi;
            const Vec3& m = open_plane_[static_cast<std::size_t>(row)];
            if (const Vec3 d2 = across(p.c - 2.0 * (p.c - q0).dot(m) * m - q0); m != Vec3::Zero() && d2.norm() > 0.0) {
                const double mirror = std::atan2(d2.dot(up), d2.dot(d1));
                if (mirror > 0.0) phi = std::min(phi, mirror);
            }
            if (!limit_ok(phi)) return {Failure::Fold, kNone, p.v[i], p.v[(i + 1) % 4]};
        }
        for (const Index* g = across_.row_begin(row); g != across_.row_end(row); ++g) {
            const Vec3 d2 = across(face_centroid_[static_cast<std::size_t>(*g)] - q0);
            if (!(d2.norm() > 0.0)) continue;  // a degenerate face across: nothing to fold onto
            double phi = std::atan2(d2.dot(up), d2.dot(d1));
            if (phi < 0.0) phi += 2.0 * std::numbers::pi;
            if (!limit_ok(phi)) return {Failure::Fold, *g, p.v[i], p.v[(i + 1) % 4]};
        }
    }
    // S3, S4.
    std::array<Tri, 4> sides;
    for (int i = 0; i < 4; ++i) sides[i] = side(p, k, h, i);
    for (const Index* g = near_faces_.row_begin(k); g != near_faces_.row_end(k); ++g)
        for (int t = 0; t < face_tris(*g); ++t) {
            const Tri u = face_tri(*g, t);
            if (point_near_triangle(apex, u, kFaceClearance * h)) return {Failure::FaceClearance, *g};
            for (const Tri& s : sides)
                if (triangles_meet(s, u, kTouch * h)) return {Failure::FaceCrossing, *g};
        }
    return {};
}

bool Builder::pair_conflict(Index k, Index m) const {
    const Pyr &p = pyr_[static_cast<std::size_t>(k)], &q = pyr_[static_cast<std::size_t>(m)];
    const double hp = p.h(), hq = q.h(), hmin = std::min(hp, hq);
    const Vec3 ap = p.c + hp * p.n, aq = q.c + hq * q.n;
    std::array<Tri, 4> sp, sq;
    for (int i = 0; i < 4; ++i) {
        sp[i] = side(p, k, hp, i);
        sq[i] = side(q, m, hq, i);
    }
    // P1.
    for (int i = 0; i < 4; ++i) {
        if (point_near_triangle(ap, sq[i], kApexClearance * hmin)) return true;
        if (point_near_triangle(aq, sp[i], kApexClearance * hmin)) return true;
    }
    // P2.
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            if (p.v[i] != q.v[j] && segments_near(p.x[i], ap, q.x[j], aq, kEdgeClearance * hmin)) return true;
    // P3.
    for (const Tri& s : sp)
        for (const Tri& t : sq)
            if (triangles_meet(s, t, kTouch * hmin)) return true;
    return false;
}

int Builder::next_level(Index k) {
    Pyr& p = pyr_[static_cast<std::size_t>(k)];
    for (int l = p.level + 1; l < static_cast<int>(p.heights.size()); ++l) {
        const std::size_t i = static_cast<std::size_t>(l);
        if (p.static_ok[i] < 0) {
            p.static_why[i] = check_static(k, p.heights[i]);
            p.static_ok[i] = p.static_why[i].ok() ? 1 : 0;
        }
        if (p.static_ok[i]) return l;
    }
    return -1;
}

void Builder::fail(Index k, const Failure& why, double h, const std::vector<Index>& others) const {
    const Pyr& p = pyr_[static_cast<std::size_t>(k)];
    auto face_at = [&](Index g) {
        return "face " + std::to_string(g) + " of the layer top at " +
               format_point(face_centroid_[static_cast<std::size_t>(g)]);
    };
    std::string reason;
    switch (why.kind) {
        case Failure::Inverted:
            reason = "the pyramid inverts (the quad is too warped for an apex along its mean normal)";
            break;
        case Failure::Fold:
            reason = "its side over the edge (" + std::to_string(why.a) + ", " + std::to_string(why.b) +
                     ") folds onto " +
                     (why.other == kNone ? std::string("the open boundary there") : face_at(why.other));
            break;
        case Failure::FaceClearance:
            reason = "its apex comes closer than " + format_number(kFaceClearance) + " x its height to " +
                     face_at(why.other);
            break;
        case Failure::FaceCrossing:
            reason = "its side crosses " + face_at(why.other);
            break;
        case Failure::Pyramid: {
            const Pyr& q = pyr_[static_cast<std::size_t>(why.other)];
            reason =
                "it intersects or crowds the pyramid on quad " + std::to_string(q.face) + " at " + format_point(q.c);
            break;
        }
        case Failure::None:
            break;
    }
    std::vector<Index> nodes(p.v.begin(), p.v.end());
    for (const Index o : others) {
        const auto& v = pyr_[static_cast<std::size_t>(o)].v;
        nodes.insert(nodes.end(), v.begin(), v.end());
    }
    throw LocalTopologyError(
        "pyramids: quad " + std::to_string(p.face) + " of the layer top (centroid " + format_point(p.c) +
            ", mean edge " + format_number(p.size) + ") cannot be capped with a pyramid: " + reason +
            ", even with the apex at " + format_number(h) + " (min_height " + format_number(params_.min_height) +
            " x shortest edge " + format_number(p.shortest) +
            "). The layer top leaves no room there: use fewer layers or a smaller total "
            "layer thickness, or a smaller pyramid min_height" +
            (others.empty()
                 ? std::string()
                 : " (and " + std::to_string(others.size()) + " other quads of the layer top cannot be capped either)"),
        std::move(nodes));
}

PyramidLayer Builder::run() {
    report(progress_, "pyramids", 0.0);
    setup();
    PyramidLayer out;
    const Index np = static_cast<Index>(pyr_.size());
    if (np > 0) {
        build_neighbours();

        // Phase 1: each pyramid against the fixed top surface; every quad that fails is named
        // at once (the caller mends them all in one round, not one per march of the layers).
        std::vector<Index> failed;
        for (Index k = 0; k < np; ++k) {
            if (k % 4096 == 0) check_cancelled(progress_);
            Pyr& p = pyr_[static_cast<std::size_t>(k)];
            p.static_ok.assign(p.heights.size(), -1);
            p.static_why.assign(p.heights.size(), Failure{});
            p.level = -1;
            p.level = next_level(k);
            if (p.level < 0) failed.push_back(k);
        }
        if (!failed.empty()) {
            const Pyr& first = pyr_[static_cast<std::size_t>(failed.front())];
            fail(failed.front(), first.static_why.back(), first.heights.back(),
                 std::vector<Index>(failed.begin() + 1, failed.end()));
        }

        // Phase 2: pairs, in rounds.
        std::vector<char> active(static_cast<std::size_t>(np), 1), shorten(static_cast<std::size_t>(np), 0);
        std::vector<Index> act(static_cast<std::size_t>(np));
        for (Index k = 0; k < np; ++k) act[static_cast<std::size_t>(k)] = k;
        report(progress_, "pyramids", 0.5);
        while (!act.empty()) {
            check_cancelled(progress_);
            for (const Index k : act) {
                for (const Index* mp = near_pyrs_.row_begin(k); mp != near_pyrs_.row_end(k); ++mp) {
                    const Index m = *mp;
                    if (active[static_cast<std::size_t>(m)] && m < k) continue;  // seen from m
                    if (!pair_conflict(k, m)) continue;
                    const double hk = pyr_[static_cast<std::size_t>(k)].h(), hm = pyr_[static_cast<std::size_t>(m)].h();
                    const bool can_k = next_level(k) >= 0, can_m = next_level(m) >= 0;
                    const double tie = 1e-9 * std::max(hk, hm);
                    bool sk = hk > hm + tie || std::abs(hk - hm) <= tie;
                    bool sm = hm > hk + tie || std::abs(hk - hm) <= tie;
                    if (sk && !can_k) sk = false;
                    if (sm && !can_m) sm = false;
                    if (!sk && !sm) {  // the taller one is at its lowest: try the other
                        sk = can_k;
                        sm = !sk && can_m;
                    }
                    if (!sk && !sm) {
                        const Index who = hk >= hm ? k : m, other = who == k ? m : k;
                        fail(who, {Failure::Pyramid, other}, pyr_[static_cast<std::size_t>(who)].h());
                    }
                    if (sk) shorten[static_cast<std::size_t>(k)] = 1;
                    if (sm) shorten[static_cast<std::size_t>(m)] = 1;
                }
            }
            for (const Index k : act) active[static_cast<std::size_t>(k)] = 0;
            act.clear();
            for (Index k = 0; k < np; ++k)
                if (shorten[static_cast<std::size_t>(k)]) {
                    shorten[static_cast<std::size_t>(k)] = 0;
                    active[static_cast<std::size_t>(k)] = 1;
                    pyr_[static_cast<std::size_t>(k)].level = next_level(k);
                    act.push_back(k);
                }
        }
    }

    // Output.
    const Index nt = top_.num_points();
    out.surface.patches = top_.patches;
    out.surface.points = top_.points;
    out.apexes.reserve(static_cast<std::size_t>(np));
    out.pyramids.reserve(static_cast<std::size_t>(np));
    for (Index k = 0; k < np; ++k) {
        const Pyr& p = pyr_[static_cast<std::size_t>(k)];
        out.apexes.push_back(p.c + p.h() * p.n);
        out.pyramids.push_back({p.v[0], p.v[1], p.v[2], p.v[3], nt + k});
    }
    out.surface.points.insert(out.surface.points.end(), out.apexes.begin(), out.apexes.end());
    for (Index f = 0; f < top_.num_faces(); ++f) {
        const Index patch = top_.face_patch[static_cast<std::size_t>(f)];
        const Index k = pyr_of_face_[static_cast<std::size_t>(f)];
        if (k == kNone) {
            out.surface.add_face(top_.face_begin(f), 3, patch);
            continue;
        }
        // (q_i, q_{i+1}, apex): the pyramid's own outward side (validate.cpp's face table), so
        // the normal points away from the pyramid, into the region still to mesh.
        const auto& v = out.pyramids[static_cast<std::size_t>(k)];
        for (int i = 0; i < 4; ++i) out.surface.add_face({v[i], v[(i + 1) % 4], v[4]}, patch);
    }
    report(progress_, "pyramids", 1.0);
    return out;
}

}  // namespace

PyramidLayer build_pyramids(const SurfaceMesh& top, const PyramidParams& params, Progress* progress) {
    return Builder(top, params, progress).run();
}

}  // namespace strata
