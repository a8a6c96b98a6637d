#include <strata/core/enum_names.h>
#include <strata/core/error.h>
#include <strata/core/face_geometry.h>
#include <strata/core/parallel.h>
#include <strata/geometry/normals.h>
#include <strata/geometry/topology.h>

#include <Eigen/Geometry>  // cross()

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <numeric>
#include <string>

namespace strata {

namespace {

// A face whose vector area is below this fraction of its summed squared edge lengths is a
// sliver or a collapsed face: its normal direction is rounding noise, so it is skipped.
constexpr double kDegenerateArea = 1e-12;

// Unit face normals closer than this (chord length) are one normal for MaxMinDot: the cap
// through three normals is ill-conditioned when two nearly coincide, and dropping one moves
// the optimum by at most this much.
constexpr double kSameNormal = 1e-9;

// Slack of "normal inside the cap" on dot products of unit vectors (a few hundred ulps), so
// that the normals defining a cap test as inside it despite rounding.
constexpr double kInside = 1e-13;

// Below this sine of the triangle's angle, three normals are taken as lying on one great
// circle and their circumscribed cap is not computed (see cap_through).
constexpr double kCollinear = 1e-9;

// MaxMinDot answers whose minimum dot product is not above this are useless as a marching
// direction (the incident faces span a hemisphere or more).
constexpr double kMinUsefulDot = 1e-12;

// Incident faces with more distinct normals than this (rare: poles of UV-sphere meshes) are
// handled without the stack buffer, recomputing face normals on the fly, so node_normals
// never allocates beyond its result.
constexpr int kStackNormals = 64;

// Vector area of face f and whether it is usable (not degenerate, no NaN).
bool face_area(const SurfaceMesh& mesh, const std::vector<Vec3>& points, Index f, Vec3& area_vector) {
    area_vector = face_area_vector(mesh, points, f);
    const Index n = mesh.face_size(f);
    const Index* v = mesh.face_begin(f);
    double edges2 = 0.0;
    for (Index i = 0; i < n; ++i) edges2 += (points[v[(i + 1) % n]] - points[v[i]]).squaredNorm();
    // Written so that NaN compares false and counts as degenerate.
    return area_vector.norm() > kDegenerateArea * edges2;
}

// The vector area of each face as the normals use it: zero where the face is degenerate.
// LiveAreas computes it from the points at each call, CachedAreas reads it from an array
// filled once per set of positions (node_normals_at); both give the same bits. unit(f) is the
// face's unit normal, zero where the face is degenerate.
struct LiveAreas {
    const SurfaceMesh& mesh;
    const std::vector<Vec3>& points;
    Vec3 operator()(Index f) const {
        Vec3 a;
        return face_area(mesh, points, f, a) ? a : Vec3::Zero();
    }
    Vec3 unit(Index f) const { return (*this)(f).normalized(); }
};

struct CachedAreas {
    const std::vector<Vec3>& areas;
    const std::vector<Vec3>& units;  ///< areas[f].normalized()
    Vec3 operator()(Index f) const { return areas[static_cast<std::size_t>(f)]; }
    const Vec3& unit(Index f) const { return units[static_cast<std::size_t>(f)]; }
};

bool usable(const Vec3& area_vector) {
    return area_vector.squaredNorm() != 0.0;
}

// Interior angle of face f at its corner \p node (radians); 0 if an edge there has zero length.
double corner_angle(const SurfaceMesh& mesh, const std::vector<Vec3>& points, Index f, Index node) {
    const Index n = mesh.face_size(f);
    const Index* v = mesh.face_begin(f);
    Index i = 0;
    while (i < n - 1 && v[i] != node) ++i;
    const Vec3 e1 = points[v[(i + 1) % n]] - points[node];
    const Vec3 e2 = points[v[(i + n - 1) % n]] - points[node];
    // atan2 of |sin| and cos keeps full accuracy at angles near 0 and π, unlike acos.
    return std::atan2(e1.cross(e2).norm(), e1.dot(e2));
}

// Normalised sum, or zero when the terms cancel (a folded surface) or there are none.
Vec3 normalised(const Vec3& sum, double magnitude_of_terms) {
    const double len = sum.norm();
    if (!(len > 1e-12 * magnitude_of_terms)) return Vec3::Zero();
    return sum / len;
}

/// Σ term(f, a) over the usable incident faces (a: the face's area vector), normalised against
/// Σ weight: \p term returns the face's contribution and its weight.
template <class Areas, class Term>
Vec3 weighted_sum(const Areas& area, const Index* begin, const Index* end, Term&& term) {
    Vec3 sum = Vec3::Zero();
    double total = 0.0;
    for (const Index* f = begin; f != end; ++f) {
        const Vec3 a = area(*f);
        if (!usable(a)) continue;
        const auto [contribution, weight] = term(*f, a);
        sum += contribution;
        total += weight;
    }
    return normalised(sum, total);
}

template <class Areas>
Vec3 area_weighted(const Areas& area, const Index* begin, const Index* end) {
    return weighted_sum(area, begin, end,
                        [](Index, const Vec3& a) { return std::pair<Vec3, double>(a, a.norm()); });
}

template <class Areas>
Vec3 angle_weighted(const SurfaceMesh& mesh, const std::vector<Vec3>& points, const Areas& area, Index node,
                    const Index* begin, const Index* end) {
    return weighted_sum(area, begin, end, [&](Index f, const Vec3& a) {
        const double angle = corner_angle(mesh, points, f, node);
        return std::pair<Vec3, double>(angle * a.normalized(), angle);
    });
}

// Nelson Max's weights: sum of (e1 × e2) / (|e1|² |e2|²) over the node's corners, e1 and e2
// the face's edges from the node to the next and previous vertices (counter-clockwise, so
// e1 × e2 points along the face normal). A face that lists the node more than once (pinched)
// contributes every corner at it, as its area vector would.
template <class Areas>
Vec3 max_weighted(const SurfaceMesh& mesh, const std::vector<Vec3>& points, const Areas& area, Index node,
                  const Index* begin, const Index* end) {
    Vec3 sum = Vec3::Zero();
    double total = 0.0;
    for (const Index* f = begin; f != end; ++f) {
        if (!usable(area(*f))) continue;
        const Index n = mesh.face_size(*f);
        const Index* v = mesh.face_begin(*f);
        for (Index i = 0; i < n; ++i) {
            if (v[i] != node) continue;
            const Vec3 e1 = points[v[(i + 1) % n]] - points[node];
            const Vec3 e2 = points[v[(i + n - 1) % n]] - points[node];
            const double w = e1.squaredNorm() * e2.squaredNorm();
            // Zero-length edge (or one so short its square underflows): no direction.
            if (!(w > 0.0)) continue;
            const Vec3 term = e1.cross(e2) / w;
            if (!term.allFinite()) continue;
            sum += term;
            total += term.norm();
        }
    }
    return normalised(sum, total);
}

// ---- MaxMinDot: the minimum spherical cap enclosing the incident unit normals ----------
//
// max over unit n of min_i n·n_i is the axis of the smallest cap {x : c·x ≥ t} on the unit
// sphere that holds every n_i. For normals in an open hemisphere this is the LP-type problem
// min |w| subject to w·n_i ≥ 1 (c = w/|w|, t = 1/|w|), of combinatorial dimension 3, so
// Welzl's minimum-enclosing-disc recursion carries over with caps for discs: the cap is fixed
// by one normal (c = n_1), two (the bisector) or three (the circumscribed cap, on the side
// where c·n_i > 0 since w·n_i = 1). Expected linear time in a well-mixed order.

struct Cap {
    Vec3 c;    // unit axis
    double t;  // cosine of the angular radius
};

bool inside(const Cap& cap, const Vec3& x) {
    // Zero vectors stand for degenerate faces on the no-buffer path: they constrain nothing.
    return cap.c.dot(x) >= cap.t - kInside || x.squaredNorm() == 0.0;
}

Cap cap_through(const Vec3& a) {
    return {a, 1.0};
}

Cap cap_through(const Vec3& a, const Vec3& b) {
    const Vec3 m = a + b;
    const double len = m.norm();
    // Opposite normals: no cap smaller than the whole sphere; the final check falls back.
    if (!(len > 1e-150)) return {a, -1.0};
    const Vec3 c = m / len;
    return {c, std::min(c.dot(a), c.dot(b))};
}

Cap cap_through(const Vec3& a, const Vec3& b, const Vec3& p) {
    const Vec3 ab = b - a, ap = p - a;
    Vec3 c = ab.cross(ap);
    const double len = c.norm();
    if (len > kCollinear * ab.norm() * ap.norm()) {
        c /= len;
        if (c.dot(a) + c.dot(b) + c.dot(p) < 0.0) c = -c;
        return {c, std::min({c.dot(a), c.dot(b), c.dot(p)})};
    }
    // Three normals on (nearly) one great circle: in exact arithmetic Welzl never asks for
    // their common cap (none smaller than a hemisphere exists), so this is rounding; take
    // the smallest pairwise cap holding all three, which is the right cap to within kCollinear.
    Cap best{a, -2.0};
    for (const Cap& cap : {cap_through(a, b), cap_through(a, p), cap_through(b, p)})
        if (inside(cap, a) && inside(cap, b) && inside(cap, p) && cap.t > best.t) best = cap;
    return best.t > -2.0 ? best : Cap{a, -1.0};
}

// A step coprime to n near n/φ: visiting i·step mod n spreads normals that arrive sorted
// around the node (the usual order of a fan), which would be Welzl's quadratic worst case.
constexpr int golden_step_of(int n) {
    if (n <= 2) return 1;
    int step = std::max(1, static_cast<int>(0.6180339887498949 * n));
    while (std::gcd(step, n) != 1) ++step;
    return step;
}

// golden_step_of(n) for the stack path's n, computed at compile time: a node's normal is taken
// at every sweep, and the gcd loop's divisions are not cheap beside Welzl's few caps.
constexpr auto kGoldenSteps = [] {
    std::array<int, kStackNormals + 1> steps{};
    for (int n = 0; n <= kStackNormals; ++n) steps[static_cast<std::size_t>(n)] = golden_step_of(n);
    return steps;
}();

int golden_step(int n) {
    return n <= kStackNormals ? kGoldenSteps[static_cast<std::size_t>(n)] : golden_step_of(n);
}

/// Welzl's recursion, unrolled, over at(0 .. n-1) in that order.
template <class At>
Cap welzl_cap(int n, At at) {
    int first = 0;
    Vec3 p0 = at(0);
    while (p0.squaredNorm() == 0.0 && ++first < n) p0 = at(first);
    Cap cap = cap_through(p0);
    for (int i = first + 1; i < n; ++i) {
        const Vec3 p = at(i);
        if (inside(cap, p)) continue;
        cap = cap_through(p);  // p is on the boundary of the cap of normals 0..i
        for (int j = 0; j < i; ++j) {
            const Vec3 q = at(j);
            if (inside(cap, q)) continue;
            cap = cap_through(p, q);  // ... and so is q for normals 0..j
            for (int k = 0; k < j; ++k) {
                const Vec3 r = at(k);
                if (!inside(cap, r)) cap = cap_through(p, q, r);
            }
        }
    }
    return cap;
}

// Smallest cap holding normal(0 .. n-1); normal(i) is a unit vector or zero (ignored).
template <class NormalAt>
Cap smallest_cap(int n, NormalAt normal) {
    const int step = golden_step(n);
    if (n <= kStackNormals) {
        // The normals in visiting order (i·step mod n, stepped without a division), once:
        // Welzl's loops revisit them often.
        std::array<Vec3, kStackNormals> visit;
        for (int i = 0, at = 0; i < n; ++i, at = at + step >= n ? at + step - n : at + step)
            visit[static_cast<std::size_t>(i)] = normal(at);
        return welzl_cap(n, [&](int i) -> const Vec3& { return visit[static_cast<std::size_t>(i)]; });
    }
    return welzl_cap(n, [&](int i) { return normal(static_cast<int>((static_cast<long long>(i) * step) % n)); });
}

template <class Areas>
Vec3 max_min_dot(const SurfaceMesh& mesh, const std::vector<Vec3>& points, const Areas& area, Index node,
                 const Index* begin, const Index* end) {
    // Distinct unit normals on the stack; flat regions repeat one normal many times.
    std::array<Vec3, kStackNormals> normals;
    int count = 0;
    bool overflow = false;
    for (const Index* f = begin; f != end && !overflow; ++f) {
        const Vec3 n = area.unit(*f);
        if (n.squaredNorm() == 0.0) continue;
        bool seen = false;
        for (int i = 0; i < count && !seen; ++i) seen = (normals[i] - n).squaredNorm() < kSameNormal * kSameNormal;
        if (seen) continue;
        if (count == kStackNormals)
            overflow = true;
        else
            normals[count++] = n;
    }
    if (count == 0) return Vec3::Zero();  // unused node, or only degenerate faces

    Cap cap;
    if (!overflow) {
        cap = smallest_cap(count, [&](int i) { return normals[i]; });
    } else {
        cap = smallest_cap(static_cast<int>(end - begin),
                           [&](int i) -> Vec3 { return area.unit(begin[i]); });
    }

    // The cap's own t carries the kInside slack; judge the answer by its true minimum.
    double min_dot = 1.0;
    if (!overflow) {
        for (int i = 0; i < count; ++i) min_dot = std::min(min_dot, cap.c.dot(normals[i]));
    } else {
        for (const Index* f = begin; f != end; ++f) {
            const Vec3 n = area.unit(*f);
            if (n.squaredNorm() != 0.0) min_dot = std::min(min_dot, cap.c.dot(n));
        }
    }
    // The faces span a hemisphere or more (a cusp, a folded or zero-thickness edge): no
    // direction sees them all from outside, so the angle-weighted normal is a fair compromise.
    if (!(min_dot > kMinUsefulDot)) return angle_weighted(mesh, points, area, node, begin, end);
    return cap.c;
}

/// Node \p v's normal by \p method, its faces' vector areas given by \p area.
template <class Areas>
Vec3 node_normal(const SurfaceMesh& mesh, const std::vector<Vec3>& points, const Areas& area, NormalMethod method,
                 const Csr& vertex_faces, Index v) {
    const Index* begin = vertex_faces.row_begin(v);
    const Index* end = vertex_faces.row_end(v);
    if (begin == end) return Vec3::Zero();
    switch (method) {
        case NormalMethod::AreaWeighted:
            return area_weighted(area, begin, end);
        case NormalMethod::AngleWeighted:
            return angle_weighted(mesh, points, area, v, begin, end);
        case NormalMethod::MaxMinDot:
            return max_min_dot(mesh, points, area, v, begin, end);
        case NormalMethod::Max:
            return max_weighted(mesh, points, area, v, begin, end);
    }
    return Vec3::Zero();
}

}  // namespace

Vec3 max_min_dot_direction(const std::vector<Vec3>& directions, double* min_dot) {
    double lowest = -1.0;
    Vec3 axis = Vec3::Zero();
    const int n = static_cast<int>(directions.size());
    bool any = false;
    for (const Vec3& d : directions) any |= d.squaredNorm() != 0.0;
    if (any) {
        axis = smallest_cap(n, [&](int i) { return directions[static_cast<std::size_t>(i)]; }).c;
        lowest = 1.0;
        for (const Vec3& d : directions)
            if (d.squaredNorm() != 0.0) lowest = std::min(lowest, axis.dot(d));
    }
    if (min_dot) *min_dot = lowest;
    return axis;
}

std::vector<Vec3> node_normals(const SurfaceMesh& mesh, const std::vector<Vec3>& points, const Csr& vertex_faces,
                               NormalMethod method, int threads) {
    const Index n = static_cast<Index>(points.size());
    if (n != mesh.num_points() || vertex_faces.rows() != n)
        throw InputError("node_normals: " + std::to_string(points.size()) + " positions and " +
                         std::to_string(vertex_faces.rows()) + " node→face rows given for a mesh of " +
                         std::to_string(mesh.num_points()) +
                         " nodes; pass one position per mesh node and vertex_faces(mesh)");
    std::vector<Vec3> normals(points.size(), Vec3::Zero());
    const LiveAreas area{mesh, points};
    // Each node is independent (reads only): the result does not depend on the thread count.
#pragma omp parallel for schedule(static) num_threads(thread_count(threads, n))
    for (Index v = 0; v < n; ++v) normals[v] = node_normal(mesh, points, area, method, vertex_faces, v);
    return normals;
}

void node_normals_at(const SurfaceMesh& mesh, const std::vector<Vec3>& points, const Csr& vertex_faces,
                     NormalMethod method, const std::vector<Index>& nodes, NormalScratch& scratch,
                     std::vector<Vec3>& normals, int threads) {
    const Index faces = mesh.num_faces();
    scratch.areas.resize(static_cast<std::size_t>(faces));
    scratch.units.resize(static_cast<std::size_t>(faces));
    scratch.face_marked.resize(static_cast<std::size_t>(faces), 0);
    normals.resize(points.size(), Vec3::Zero());
    const LiveAreas live{mesh, points};
    if (nodes.size() * 4 >= points.size()) {
        // Most nodes: every face round one of them, found face by face.
        scratch.node_marked.resize(points.size(), 0);
        for (Index v : nodes) scratch.node_marked[static_cast<std::size_t>(v)] = 1;
#pragma omp parallel for schedule(static) num_threads(thread_count(threads, faces))
        for (Index f = 0; f < faces; ++f) {
            bool round = false;
            for (const Index* v = mesh.face_begin(f); v != mesh.face_end(f); ++v)
                round = round || scratch.node_marked[static_cast<std::size_t>(*v)];
            if (round) scratch.set(f, live(f));
        }
        for (Index v : nodes) scratch.node_marked[static_cast<std::size_t>(v)] = 0;
    } else {
        // A few: their faces, each once.
        scratch.faces.clear();
        for (Index v : nodes)
            for (const Index* f = vertex_faces.row_begin(v); f != vertex_faces.row_end(v); ++f)
                if (!scratch.face_marked[static_cast<std::size_t>(*f)]) {
                    scratch.face_marked[static_cast<std::size_t>(*f)] = 1;
                    scratch.faces.push_back(*f);
                }
        const auto nf = static_cast<Index>(scratch.faces.size());
#pragma omp parallel for schedule(static) num_threads(thread_count(threads, nf))
        for (Index i = 0; i < nf; ++i) {
            const Index f = scratch.faces[static_cast<std::size_t>(i)];
            scratch.set(f, live(f));
        }
        for (Index f : scratch.faces) scratch.face_marked[static_cast<std::size_t>(f)] = 0;
    }
    const CachedAreas area{scratch.areas, scratch.units};
    const auto nn = static_cast<Index>(nodes.size());
#pragma omp parallel for schedule(static) num_threads(thread_count(threads, nn))
    for (Index i = 0; i < nn; ++i) {
        const Index v = nodes[static_cast<std::size_t>(i)];
        normals[static_cast<std::size_t>(v)] = node_normal(mesh, points, area, method, vertex_faces, v);
    }
}

std::vector<Vec3> node_normals(const SurfaceMesh& mesh, const std::vector<Vec3>& points, NormalMethod method,
                               int threads) {
    return node_normals(mesh, points, vertex_faces(mesh), method, threads);
}

}  // namespace strata
