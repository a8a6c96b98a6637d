// Edges far shorter than the mesh around them, collapsed: short_edges.h.

#include <strata/geometry/check.h>
#include <strata/geometry/short_edges.h>
#include <strata/geometry/topology.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <tuple>

namespace strata {
namespace {

constexpr double kPi = std::numbers::pi;
/// An edge whose faces' normals differ by more than this is a feature line (a node on it does
/// not move onto a smooth patch).
const double kCosFeature = std::cos(40.0 * kPi / 180.0);
/// A face that stays may turn by at most this much.
const double kCosMaxTurn = std::cos(45.0 * kPi / 180.0);
/// Nor get a corner sharper than both its old sharpest one and check.h's needle bound.
const double kSinNeedle = std::sin(kNeedleCornerDeg * kPi / 180.0);

Vec3 normal_of(const Vec3& a, const Vec3& b, const Vec3& c) {
    return (b - a).cross(c - a);
}

/// The sine of the sharpest corner of the triangle (0 if degenerate).
double min_corner_sine(const Vec3& a, const Vec3& b, const Vec3& c) {
    const double twice_area = normal_of(a, b, c).norm();
    const double ab = (b - a).norm(), bc = (c - b).norm(), ca = (a - c).norm();
    const double m = std::max({ab * ca, ab * bc, bc * ca});
    return m > 0.0 ? twice_area / m : 0.0;
}

/// The mutable mesh the collapses work on: triangles and quads as they came, a node → faces
/// list kept up to date.
struct Work {
    const SurfaceMesh& mesh;
    std::vector<std::array<Index, 4>> face;
    std::vector<int> size;
    std::vector<char> dead;
    std::vector<std::vector<Index>> node_faces;
    std::vector<char> removed;
    std::vector<char> movable;  ///< every face around is a wall triangle, and not on an open boundary
    std::vector<Index> patch_faces;

    explicit Work(const SurfaceMesh& m) : mesh(m) {
        const Index nf = m.num_faces(), nn = m.num_points();
        face.resize(static_cast<std::size_t>(nf));
        size.resize(static_cast<std::size_t>(nf));
        dead.assign(static_cast<std::size_t>(nf), 0);
        node_faces.resize(static_cast<std::size_t>(nn));
        removed.assign(static_cast<std::size_t>(nn), 0);
        movable.assign(static_cast<std::size_t>(nn), 1);
        patch_faces.assign(m.patches.size(), 0);
        for (Index f = 0; f < nf; ++f) {
            const auto fi = static_cast<std::size_t>(f);
            size[fi] = static_cast<int>(m.face_size(f));
            const bool wall_triangle =
                size[fi] == 3 && m.patches[static_cast<std::size_t>(m.face_patch[f])].kind == PatchKind::Wall;
            for (int i = 0; i < size[fi]; ++i) {
                const Index v = m.face_node(f, i);
                face[fi][static_cast<std::size_t>(i)] = v;
                node_faces[static_cast<std::size_t>(v)].push_back(f);
                if (!wall_triangle) movable[static_cast<std::size_t>(v)] = 0;
            }
            ++patch_faces[static_cast<std::size_t>(m.face_patch[f])];
        }
        const EdgeTable edges = edge_table(m);
        for (std::size_t e = 0; e < edges.nodes.size(); ++e)
            if (edges.faces.row_size(static_cast<Index>(e)) != 2)
                for (const Index v : edges.nodes[e]) movable[static_cast<std::size_t>(v)] = 0;
    }

    const Vec3& at(Index v) const { return mesh.points[static_cast<std::size_t>(v)]; }
    bool has(Index f, Index v) const {
        const auto fi = static_cast<std::size_t>(f);
        for (int i = 0; i < size[fi]; ++i)
            if (face[fi][static_cast<std::size_t>(i)] == v) return true;
        return false;
    }
    /// The nodes sharing a face with \p v (sorted, each once, \p v left out).
    std::vector<Index> neighbours(Index v) const {
        std::vector<Index> out;
        for (const Index f : node_faces[static_cast<std::size_t>(v)])
            for (int i = 0; i < size[static_cast<std::size_t>(f)]; ++i) {
                const Index w = face[static_cast<std::size_t>(f)][static_cast<std::size_t>(i)];
                if (w != v) out.push_back(w);
            }
        std::sort(out.begin(), out.end());
        out.erase(std::unique(out.begin(), out.end()), out.end());
        return out;
    }
    /// The median length of the edges of the faces around \p a and \p b, their own edge left out.
    double local_size(Index a, Index b) const {
        std::vector<std::pair<Index, Index>> edges;
        for (const Index v : {a, b})
            for (const Index f : node_faces[static_cast<std::size_t>(v)]) {
                const auto fi = static_cast<std::size_t>(f);
                for (int i = 0; i < size[fi]; ++i) {
                    Index p = face[fi][static_cast<std::size_t>(i)];
                    Index q = face[fi][static_cast<std::size_t>((i + 1) % size[fi])];
                    if (p > q) std::swap(p, q);
                    if (!(p == std::min(a, b) && q == std::max(a, b))) edges.emplace_back(p, q);
                }
            }
        std::sort(edges.begin(), edges.end());
        edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
        if (edges.empty()) return 0.0;
        std::vector<double> len;
        len.reserve(edges.size());
        for (const auto& [p, q] : edges) len.push_back((at(p) - at(q)).norm());
        const auto mid = len.begin() + static_cast<std::ptrdiff_t>(len.size() / 2);
        std::nth_element(len.begin(), mid, len.end());
        return *mid;
    }
    /// Feature lines through \p v: edges between two patches or whose faces turn more than 40°.
    int feature_degree(Index v) const {
        int degree = 0;
        for (const Index w : neighbours(v)) {
            Index f0 = kNone, f1 = kNone;
            int count = 0;
            for (const Index f : node_faces[static_cast<std::size_t>(v)])
                if (has(f, w)) (count++ == 0 ? f0 : f1) = f;
            if (count != 2) {
                ++degree;
                continue;
            }
            if (mesh.face_patch[f0] != mesh.face_patch[f1]) {
                ++degree;
                continue;
            }
            const Vec3 n0 = face_normal(f0), n1 = face_normal(f1);
            const double d = n0.norm() * n1.norm();
            if (!(d > 0.0) || n0.dot(n1) < kCosFeature * d) ++degree;
        }
        return degree;
    }
    Vec3 face_normal(Index f) const {
        const auto& v = face[static_cast<std::size_t>(f)];
        return normal_of(at(v[0]), at(v[1]), at(v[2]));
    }

    /// Collapse the edge (a, b) if it is safe; true if done. \p moved: the node that moved.
    bool collapse(Index a, Index b, Index& moved) {
        if (removed[static_cast<std::size_t>(a)] || removed[static_cast<std::size_t>(b)]) return false;
        std::vector<Index> shared;
        for (const Index f : node_faces[static_cast<std::size_t>(a)])
            if (has(f, b)) shared.push_back(f);
        if (shared.size() != 2) return false;
        for (const Index f : shared)
            if (size[static_cast<std::size_t>(f)] != 3) return false;
        // The node that moves: the one on fewer feature lines; on a tie the higher id.
        const int da = feature_degree(a), db = feature_degree(b);
        Index r = (da < db || (da == db && a > b)) ? a : b;
        Index k = r == a ? b : a;
        if (!movable[static_cast<std::size_t>(r)]) std::swap(r, k);
        if (!movable[static_cast<std::size_t>(r)]) return false;
        // Topology: the two nodes share exactly the third corners of the two faces, each of
        // which keeps at least three faces.
        std::vector<Index> opposite;
        for (const Index f : shared)
            for (int i = 0; i < 3; ++i) {
                const Index w = face[static_cast<std::size_t>(f)][static_cast<std::size_t>(i)];
                if (w != a && w != b) opposite.push_back(w);
            }
        if (opposite.size() != 2 || opposite[0] == opposite[1]) return false;
        std::sort(opposite.begin(), opposite.end());
        const std::vector<Index> nr = neighbours(r), nk = neighbours(k);
        std::vector<Index> common;
        std::set_intersection(nr.begin(), nr.end(), nk.begin(), nk.end(), std::back_inserter(common));
        if (common != opposite) return false;
        for (const Index w : opposite)
            if (node_faces[static_cast<std::size_t>(w)].size() < 4) return false;
        // A patch keeps a face.
        for (const Index f : shared) --patch_faces[static_cast<std::size_t>(mesh.face_patch[f])];
        bool patches_kept = true;
        for (const Index f : shared) patches_kept &= patch_faces[static_cast<std::size_t>(mesh.face_patch[f])] > 0;
        if (!patches_kept) {
            for (const Index f : shared) ++patch_faces[static_cast<std::size_t>(mesh.face_patch[f])];
            return false;
        }
        // Geometry: the faces that stay neither turn much nor get a new needle corner.
        const Vec3& target = at(k);
        for (const Index f : node_faces[static_cast<std::size_t>(r)]) {
            if (f == shared[0] || f == shared[1]) continue;
            const auto& v = face[static_cast<std::size_t>(f)];
            std::array<Vec3, 3> p{at(v[0]), at(v[1]), at(v[2])};
            std::array<Vec3, 3> q = p;
            for (int i = 0; i < 3; ++i)
                if (v[static_cast<std::size_t>(i)] == r) q[static_cast<std::size_t>(i)] = target;
            const Vec3 n0 = normal_of(p[0], p[1], p[2]), n1 = normal_of(q[0], q[1], q[2]);
            const double d = n0.norm() * n1.norm();
            const double before = min_corner_sine(p[0], p[1], p[2]), after = min_corner_sine(q[0], q[1], q[2]);
            if (!(d > 0.0) || n0.dot(n1) < kCosMaxTurn * d || after < std::min(before, kSinNeedle)) {
                for (const Index g : shared) ++patch_faces[static_cast<std::size_t>(mesh.face_patch[g])];
                return false;
            }
        }
        // Done: the two faces go, r's other faces take k.
        for (const Index f : shared) dead[static_cast<std::size_t>(f)] = 1;
        auto drop_dead = [&](Index v) {
            auto& list = node_faces[static_cast<std::size_t>(v)];
            list.erase(
                std::remove_if(list.begin(), list.end(), [&](Index f) { return dead[static_cast<std::size_t>(f)]; }),
                list.end());
        };
        for (const Index w : opposite) drop_dead(w);
        drop_dead(k);
        drop_dead(r);
        for (const Index f : node_faces[static_cast<std::size_t>(r)]) {
            auto& v = face[static_cast<std::size_t>(f)];
            for (int i = 0; i < 3; ++i)
                if (v[static_cast<std::size_t>(i)] == r) v[static_cast<std::size_t>(i)] = k;
            node_faces[static_cast<std::size_t>(k)].push_back(f);
        }
        std::sort(node_faces[static_cast<std::size_t>(k)].begin(), node_faces[static_cast<std::size_t>(k)].end());
        node_faces[static_cast<std::size_t>(r)].clear();
        removed[static_cast<std::size_t>(r)] = 1;
        moved = r;
        return true;
    }

    /// The edges shorter than \p ratio times their local size, shortest first: (length, a, b, share).
    std::vector<std::tuple<double, Index, Index, double>> short_edges(double ratio) const {
        const auto nn = static_cast<Index>(node_faces.size());
        // The longest edge at each node bounds the local size from above: a cheap first filter.
        std::vector<double> longest(static_cast<std::size_t>(nn), 0.0);
        std::vector<std::pair<Index, Index>> edges;
        for (std::size_t f = 0; f < face.size(); ++f) {
            if (dead[f]) continue;
            for (int i = 0; i < size[f]; ++i) {
                const Index p = face[f][static_cast<std::size_t>(i)];
                const Index q = face[f][static_cast<std::size_t>((i + 1) % size[f])];
                const double l = (at(p) - at(q)).norm();
                longest[static_cast<std::size_t>(p)] = std::max(longest[static_cast<std::size_t>(p)], l);
                longest[static_cast<std::size_t>(q)] = std::max(longest[static_cast<std::size_t>(q)], l);
                edges.emplace_back(std::min(p, q), std::max(p, q));
            }
        }
        std::sort(edges.begin(), edges.end());
        edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
        std::vector<std::tuple<double, Index, Index, double>> out;
        for (const auto& [p, q] : edges) {
            const double l = (at(p) - at(q)).norm();
            if (!(l < ratio * std::max(longest[static_cast<std::size_t>(p)], longest[static_cast<std::size_t>(q)])))
                continue;
            const double local = local_size(p, q);
            if (l < ratio * local) out.emplace_back(l, p, q, l / local);
        }
        std::sort(out.begin(), out.end());
        return out;
    }
};

}  // namespace

SurfaceMesh collapse_short_edges(const SurfaceMesh& mesh, double ratio, ShortEdgeReport* report) {
    ShortEdgeReport rep;
    if (!(ratio > 0.0) || mesh.num_faces() == 0) {
        if (report) *report = rep;
        return mesh;
    }
    // The usual case first, in one pass over the faces: no edge shorter than the share asked of
    // the longest edge at either end (which bounds the local size from above) means no work
    // (the mesh's node → face lists cost a quarter of the surface stage on 200k triangles).
    {
        std::vector<double> longest(static_cast<std::size_t>(mesh.num_points()), 0.0);
        for (Index f = 0; f < mesh.num_faces(); ++f)
            for (Index i = 0, n = mesh.face_size(f); i < n; ++i) {
                const Index p = mesh.face_node(f, i), q = mesh.face_node(f, (i + 1) % n);
                const double l =
                    (mesh.points[static_cast<std::size_t>(p)] - mesh.points[static_cast<std::size_t>(q)]).norm();
                for (const Index v : {p, q})
                    longest[static_cast<std::size_t>(v)] = std::max(longest[static_cast<std::size_t>(v)], l);
            }
        bool any = false;
        for (Index f = 0; f < mesh.num_faces() && !any; ++f)
            for (Index i = 0, n = mesh.face_size(f); i < n && !any; ++i) {
                const Index p = mesh.face_node(f, i), q = mesh.face_node(f, (i + 1) % n);
                const double l =
                    (mesh.points[static_cast<std::size_t>(p)] - mesh.points[static_cast<std::size_t>(q)]).norm();
                any = l < ratio * std::max(longest[static_cast<std::size_t>(p)], longest[static_cast<std::size_t>(q)]);
            }
        if (!any) {
            if (report) *report = rep;
            return mesh;
        }
    }
    Work w(mesh);
    // A collapse changes the lengths around it: look again until nothing changes (a few rounds
    // at most; bounded in case a mesh keeps offering new ones).
    for (int round = 0; round < 8; ++round) {
        bool any = false;
        for (const auto& [l, a, b, share] : w.short_edges(ratio)) {
            Index moved = kNone;
            if (!w.collapse(a, b, moved)) continue;
            any = true;
            ++rep.collapsed;
            if (l > rep.longest) rep.longest = l, rep.where = w.at(moved);
            rep.largest_share = std::max(rep.largest_share, share);
        }
        if (!any) break;
    }
    const auto left = w.short_edges(ratio);
    rep.left = static_cast<Index>(left.size());
    if (!left.empty()) {
        const auto best = std::min_element(left.begin(), left.end(), [](const auto& x, const auto& y) {
            return std::tie(std::get<3>(x), std::get<1>(x), std::get<2>(x)) <
                   std::tie(std::get<3>(y), std::get<1>(y), std::get<2>(y));
        });
        rep.left_share = std::get<3>(*best);
        rep.left_where = 0.5 * (w.at(std::get<1>(*best)) + w.at(std::get<2>(*best)));
    }
    if (report) *report = rep;
    if (rep.collapsed == 0) return mesh;
    SurfaceMesh out = mesh;
    for (Index f = 0; f < mesh.num_faces(); ++f) {
        const auto fi = static_cast<std::size_t>(f);
        for (int i = 0; i < w.size[fi]; ++i)
            out.face_nodes[static_cast<std::size_t>(out.face_offsets[fi] + i)] =
                w.face[fi][static_cast<std::size_t>(i)];
    }
    return remove_faces(out, w.dead);
}

}  // namespace strata
