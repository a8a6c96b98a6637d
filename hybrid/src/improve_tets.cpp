#include <strata/hybrid/improve_tets.h>

#include <strata/core/error.h>
#include <strata/core/format.h>
#include <strata/core/parallel.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace strata {
namespace {

using Tet = std::array<Index, 4>;

constexpr int kMaxRing = 7;  // edge removal: rings of 3 to 7 tetrahedra (Catalan(5) = 42 triangulations)
constexpr double kNone = -std::numeric_limits<double>::infinity();
constexpr int kMaxCavity = 12;  // point insertion: tetrahedra replaced at most

/// A change is worth making when the worst tetrahedron it creates beats the worst it replaces
/// by a thousandth (so the passes end) and is valid.
bool improves(double made, double replaced) {
    return made > 0.0 && made > replaced + std::max(1e-3 * std::abs(replaced), 1e-12);
}

/// True when \p arranged (the same four nodes as \p t) is an even permutation of \p t: the
/// same orientation.
bool same_orientation(const Tet& t, const Tet& arranged) {
    std::array<int, 4> pos{};
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            if (t[static_cast<std::size_t>(j)] == arranged[static_cast<std::size_t>(i)]) pos[i] = j;
    int inversions = 0;
    for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j)
            if (pos[i] > pos[j]) ++inversions;
    return inversions % 2 == 0;
}

/// The nodes of \p t as (x, y, a, b) with the orientation of \p t.
Tet arranged_with(const Tet& t, Index x, Index y) {
    Tet r{x, y, -1, -1};
    int k = 2;
    for (const Index w : t)
        if (w != x && w != y) r[static_cast<std::size_t>(k++)] = w;
    if (!same_orientation(t, r)) std::swap(r[2], r[3]);
    return r;
}

bool has(const Tet& t, Index v) {
    return t[0] == v || t[1] == v || t[2] == v || t[3] == v;
}

class Improver {
public:
    Improver(TetFill& fill, Index num_fixed, double below)
        : p_(fill.points), tets_(std::move(fill.tets)), num_fixed_(num_fixed), below_(below) {
        q_.resize(tets_.size());
        alive_.assign(tets_.size(), 1);
        tried_.assign(tets_.size(), 0);
        node_tets_.resize(p_.size());
        changed_.assign(p_.size(), 1);
        node_tried_.assign(p_.size(), 0);
        for (std::size_t t = 0; t < tets_.size(); ++t) {
            q_[t] = quality(tets_[t]);
            for (const Index v : tets_[t]) node_tets_[static_cast<std::size_t>(v)].push_back(static_cast<Index>(t));
        }
    }

    /// The alive tetrahedra, in index order (the originals first, then those made, in order).
    std::vector<Tet> release() {
        std::vector<Tet> out;
        out.reserve(tets_.size());
        for (std::size_t t = 0; t < tets_.size(); ++t)
            if (alive_[t]) out.push_back(tets_[t]);
        return out;
    }

    void measure(Index& below, double& worst) const {
        below = 0;
        worst = 1.0;
        for (std::size_t t = 0; t < tets_.size(); ++t) {
            if (!alive_[t]) continue;
            if (q_[t] < below_) ++below;
            worst = std::min(worst, q_[t]);
        }
    }

    /// Tetrahedron \p t is gone or no longer below the bound.
    bool done_with(Index t) const {
        return !alive_[static_cast<std::size_t>(t)] || q_[static_cast<std::size_t>(t)] >= below_;
    }

    /// \p visit(t) for each tetrahedron still below the bound when its turn comes, in the order
    /// of worst_first(\p fixed_only), until the time budget runs out; cancellation checked
    /// whenever the count of those looked at has none of the bits of \p check_mask set.
    template <class Visit>
    void for_each_below(bool fixed_only, unsigned check_mask, const Progress* progress, Visit&& visit) {
        std::size_t done = 0;
        for (const Index t : worst_first(fixed_only)) {
            if ((++done & check_mask) == 0) check_cancelled(progress);
            if (over_budget()) break;
            if (done_with(t)) continue;
            visit(t);
        }
    }

    /// One pass over the tetrahedra below the bound, worst first; true if anything changed.
    bool pass(TetImproveReport& rep, const Progress* progress) {
        bool changed = false;
        for_each_below(false, 1023u, progress, [&](Index t) {
            if (!changed_since(tets_[static_cast<std::size_t>(t)], tried_[static_cast<std::size_t>(t)])) return;
            if (flip_or_remove(t, rep)) {
                changed = true;
                return;
            }
            tried_[static_cast<std::size_t>(t)] = ++clock_;
            for (const Index v : tets_[static_cast<std::size_t>(t)])
                if (move_node(v)) {
                    ++rep.moved_nodes;
                    changed = true;
                    if (done_with(t)) break;
                }
        });
        return changed;
    }

    /// Once flips and moves have done what they can: a point inserted round each tetrahedron
    /// still below the bound whose four corners are boundary nodes (where nothing else
    /// reaches), worst first; true if any was. Inserting wherever flips and moves failed, or
    /// during the passes, did worse (docs/ALGORITHM.md, "Tetrahedra improved after TetGen").
    bool insertion_pass(TetImproveReport& rep, const Progress* progress) {
        bool changed = false;
        for_each_below(true, 255u, progress, [&](Index t) {
            if (insert_point(t)) {
                ++rep.inserted_nodes;
                changed = true;
            }
        });
        return changed;
    }

    /// A face between two tetrahedra and its checkMesh skewness.
    struct SkewedFace {
        double skew;
        Index t;
        int i;  // the face of t opposite its node i
    };

    /// Every face between two tetrahedra, once: those above kTetSkewTarget, worst first (ties
    /// by tetrahedron and face); \p above_bound counts those above kFoamSkewness, what
    /// checkMesh fails (the fill's boundary faces are judged with the layers).
    std::vector<SkewedFace> skewed_faces(Index& above_bound, int threads) const {
        // Each face's skewness in parallel (reading only), gathered in order: the same for any
        // thread count. -1: the fill's boundary, or counted from the tetrahedron across.
        const auto nt = static_cast<std::int64_t>(tets_.size());
        std::vector<std::array<double, 4>> k(static_cast<std::size_t>(nt));
#pragma omp parallel for schedule(static) num_threads(thread_count(threads, nt))
        for (std::int64_t t = 0; t < nt; ++t) {
            auto& kt = k[static_cast<std::size_t>(t)];
            kt.fill(-1.0);
            if (!alive_[static_cast<std::size_t>(t)]) continue;
            for (int i = 0; i < 4; ++i) {
                const auto f = face_of(tets_[static_cast<std::size_t>(t)], i);
                const Index n = across(static_cast<Index>(t), f[0], f[1], f[2]);
                if (n < static_cast<Index>(t)) continue;
                kt[static_cast<std::size_t>(i)] =
                    skewness(tets_[static_cast<std::size_t>(t)], &tets_[static_cast<std::size_t>(n)], f);
            }
        }
        above_bound = 0;
        std::vector<SkewedFace> faces;
        for (std::int64_t t = 0; t < nt; ++t)
            for (int i = 0; i < 4; ++i) {
                const double v = k[static_cast<std::size_t>(t)][static_cast<std::size_t>(i)];
                if (v > kFoamSkewness) ++above_bound;
                if (v > kTetSkewTarget) faces.push_back({v, static_cast<Index>(t), i});
            }
        std::sort(faces.begin(), faces.end(), [](const SkewedFace& x, const SkewedFace& y) {
            return x.skew != y.skew ? x.skew > y.skew : (x.t != y.t ? x.t < y.t : x.i < y.i);
        });
        return faces;
    }

    /// Each of \p faces (skewed_faces) still there and above kTetSkewTarget, in order, replaced
    /// by the 2-3 flip across it or the removal of one of its edges that leaves the smallest
    /// skewness on the faces of the tetrahedra made, if that is below the face's and below what
    /// the faces replaced had, the faces of the fill's boundary among them no worse than they
    /// were or kTetSkewTarget, and the worst tetrahedron made no worse than the worst replaced;
    /// true if any was. Skewness is what checkMesh fails a mesh on (above 4) that the scaled
    /// Jacobian does not see: two tetrahedra side by side whose centres' line passes far from
    /// their shared face.
    bool skew_pass(const std::vector<SkewedFace>& faces, TetImproveReport& rep, const Progress* progress) {
        bool changed = false;
        std::size_t done = 0;
        for (const SkewedFace& face : faces) {
            if ((++done & 255u) == 0) check_cancelled(progress);
            if (over_budget()) break;
            if (!alive_[static_cast<std::size_t>(face.t)]) continue;
            const Tet tet = tets_[static_cast<std::size_t>(face.t)];
            const auto f = face_of(tet, face.i);
            const Index n = across(face.t, f[0], f[1], f[2]);
            if (n < 0) continue;
            const double now = skew(tet, &tets_[static_cast<std::size_t>(n)], f);
            if (!(now > kTetSkewTarget)) continue;
            std::vector<Change> options;
            options.push_back(flip23(face.t, tet, face.i));
            for (int e = 0; e < 3; ++e)
                options.push_back(
                    remove_edge(f[static_cast<std::size_t>(e)], f[static_cast<std::size_t>((e + 1) % 3)]));
            const Change* best = nullptr;
            double best_skew = now;
            for (const Change& c : options) {
                if (c.removed.empty()) continue;
                double replaced = 1.0;
                std::vector<Tet> old;
                for (const Index o : c.removed) {
                    replaced = std::min(replaced, q_[static_cast<std::size_t>(o)]);
                    old.push_back(tets_[static_cast<std::size_t>(o)]);
                }
                if (!(c.made >= replaced)) continue;
                const SkewOf before = skews(old, c.removed), after = skews(c.tets, c.removed);
                if (after.interior < best_skew && after.interior < before.interior &&
                    after.boundary <= std::max(before.boundary, kTetSkewTarget))
                    best = &c, best_skew = after.interior;
            }
            if (!best) continue;
            for (const Index o : best->removed) kill(o);
            for (const Tet& t : best->tets) add(t);
            ++rep.skew_changes;
            changed = true;
        }
        return changed;
    }

    /// The work allowed, in tetrahedron qualities computed.
    void set_budget(std::uint64_t b) {
        budget_ = b;
    }
    bool over_budget() const {
        return evaluations_ > budget_;
    }

private:
    /// The tetrahedra below the bound (\p fixed_only: whose corners are all boundary nodes),
    /// worst first, ties by index.
    std::vector<Index> worst_first(bool fixed_only) const {
        std::vector<std::pair<double, Index>> bad;
        for (std::size_t t = 0; t < tets_.size(); ++t)
            if (alive_[t] && q_[t] < below_ && (!fixed_only || all_fixed(tets_[t])))
                bad.emplace_back(q_[t], static_cast<Index>(t));
        std::sort(bad.begin(), bad.end());
        std::vector<Index> order(bad.size());
        for (std::size_t i = 0; i < bad.size(); ++i) order[i] = bad[i].second;
        return order;
    }

    /// Whether anything a change at \p t depends on changed after \p when: a tetrahedron made
    /// or removed at one of its nodes, or a node moved in a tetrahedron through one of them
    /// (both stamp the nodes concerned). The ring of an edge, the tetrahedron across a face and
    /// the star of a node all contain one of the nodes stamped.
    bool changed_since(const Tet& t, std::uint64_t when) const {
        for (const Index v : t)
            if (changed_[static_cast<std::size_t>(v)] > when) return true;
        return false;
    }

    /// Whether every corner of \p t is a boundary node (none can move).
    bool all_fixed(const Tet& t) const {
        return t[0] < num_fixed_ && t[1] < num_fixed_ && t[2] < num_fixed_ && t[3] < num_fixed_;
    }

    void stamp(const Tet& t) {
        ++clock_;
        for (const Index v : t) changed_[static_cast<std::size_t>(v)] = clock_;
    }

    /// The tetrahedron's scaled Jacobian: at each corner det(e1, e2, e3) / (|e1| |e2| |e3|),
    /// and the determinant is six times the volume at every corner, so the minimum is 6 V over
    /// the largest product of a corner's three edge lengths (tet_min_scaled_jacobian's value
    /// to rounding, for a sixth of the work).
    double quality(const Tet& t) const {
        ++evaluations_;
        const Vec3& a = p_[static_cast<std::size_t>(t[0])];
        const Vec3& b = p_[static_cast<std::size_t>(t[1])];
        const Vec3& c = p_[static_cast<std::size_t>(t[2])];
        const Vec3& d = p_[static_cast<std::size_t>(t[3])];
        const double ab = (b - a).norm(), ac = (c - a).norm(), ad = (d - a).norm();
        const double bc = (c - b).norm(), bd = (d - b).norm(), cd = (d - c).norm();
        const double largest = std::max(std::max(ab * ac * ad, ab * bc * bd), std::max(ac * bc * cd, ad * bd * cd));
        const double q = (b - a).cross(c - a).dot(d - a) / largest;
        return std::isfinite(q) ? q : kNone;
    }

    /// The face of \p t opposite its node \p i.
    static std::array<Index, 3> face_of(const Tet& t, int i) {
        std::array<Index, 3> f{};
        int k = 0;
        for (int j = 0; j < 4; ++j)
            if (j != i) f[static_cast<std::size_t>(k++)] = t[static_cast<std::size_t>(j)];
        return f;
    }

    /// checkMesh's skewness of face \p f of \p t, shared with \p n (null: on the fill's
    /// boundary), counted in the work done.
    double skew(const Tet& t, const Tet* n, const std::array<Index, 3>& f) const {
        ++evaluations_;
        return skewness(t, n, f);
    }

    /// skew, not counted (safe to call from several threads).
    double skewness(const Tet& t, const Tet* n, const std::array<Index, 3>& f) const {
        auto centre = [&](const Tet& x) {
            return Vec3(0.25 * (p_[static_cast<std::size_t>(x[0])] + p_[static_cast<std::size_t>(x[1])] +
                                p_[static_cast<std::size_t>(x[2])] + p_[static_cast<std::size_t>(x[3])]));
        };
        const Vec3 co = centre(t);
        const Vec3 cn = n ? centre(*n) : co;
        const double k = face_skewness(p_.data(), f.data(), 3, co, n ? &cn : nullptr);
        return std::isfinite(k) ? k : std::numeric_limits<double>::infinity();
    }

    struct SkewOf {
        double interior = 0.0;  ///< the largest over faces with a tetrahedron on both sides
        double boundary = 0.0;  ///< the largest over faces of the fill's boundary
    };

    /// The skewness of the faces of \p set (tetrahedra that need not be in the mesh), a face's
    /// neighbour another of \p set or a tetrahedron of the mesh not in \p gone.
    SkewOf skews(const std::vector<Tet>& set, const std::vector<Index>& gone) const {
        SkewOf r;
        for (std::size_t s = 0; s < set.size(); ++s)
            for (int i = 0; i < 4; ++i) {
                const auto f = face_of(set[s], i);
                const Tet* n = nullptr;
                for (std::size_t o = 0; o < set.size() && !n; ++o)
                    if (o != s && has(set[o], f[0]) && has(set[o], f[1]) && has(set[o], f[2])) n = &set[o];
                for (const Index o : node_tets_[static_cast<std::size_t>(f[0])]) {
                    if (n) break;
                    const Tet& ot = tets_[static_cast<std::size_t>(o)];
                    if (has(ot, f[1]) && has(ot, f[2]) && std::find(gone.begin(), gone.end(), o) == gone.end()) n = &ot;
                }
                double& w = n ? r.interior : r.boundary;
                w = std::max(w, skew(set[s], n, f));
            }
        return r;
    }

    Index add(const Tet& t) {
        const Index id = static_cast<Index>(tets_.size());
        tets_.push_back(t);
        q_.push_back(quality(t));
        alive_.push_back(1);
        tried_.push_back(0);
        for (const Index v : t) node_tets_[static_cast<std::size_t>(v)].push_back(id);
        stamp(t);
        return id;
    }

    void kill(Index id) {
        alive_[static_cast<std::size_t>(id)] = 0;
        stamp(tets_[static_cast<std::size_t>(id)]);
        for (const Index v : tets_[static_cast<std::size_t>(id)]) {
            auto& l = node_tets_[static_cast<std::size_t>(v)];
            l.erase(std::find(l.begin(), l.end(), id));
        }
    }

    /// The other tetrahedron on face (a, b, c) of \p t, or -1 (a boundary face).
    Index across(Index t, Index a, Index b, Index c) const {
        for (const Index o : node_tets_[static_cast<std::size_t>(a)])
            if (o != t && has(tets_[static_cast<std::size_t>(o)], b) && has(tets_[static_cast<std::size_t>(o)], c))
                return o;
        return -1;
    }

    // A candidate change: the tetrahedra it removes and those it makes.
    struct Change {
        double made = kNone;
        std::vector<Index> removed;
        std::vector<Tet> tets;
    };

    /// The best 2-3 flip or edge removal of tetrahedron \p t's faces and edges; made if it improves.
    bool flip_or_remove(Index t, TetImproveReport& rep) {
        const Tet tet = tets_[static_cast<std::size_t>(t)];
        Change best;
        bool best_is_flip = false;
        for (int i = 0; i < 4; ++i) {
            Change c = flip23(t, tet, i);
            if (c.made > best.made) best = std::move(c), best_is_flip = true;
        }
        for (int i = 0; i < 4; ++i)
            for (int j = i + 1; j < 4; ++j) {
                Change c = remove_edge(tet[static_cast<std::size_t>(i)], tet[static_cast<std::size_t>(j)]);
                if (c.made > best.made) best = std::move(c), best_is_flip = false;
            }
        if (best.removed.empty()) return false;
        double replaced = 1.0;
        for (const Index o : best.removed) replaced = std::min(replaced, q_[static_cast<std::size_t>(o)]);
        if (!improves(best.made, replaced)) return false;
        for (const Index o : best.removed) kill(o);
        for (const Tet& n : best.tets) add(n);
        ++(best_is_flip ? rep.flips : rep.edge_removals);
        return true;
    }

    /// Tetrahedron \p t = (a, b, c, d) (d its node \p i) and its neighbour (a, b, c, e) become
    /// three round the edge d–e.
    Change flip23(Index t, const Tet& tet, int i) const {
        const Index d = tet[static_cast<std::size_t>(i)];
        Tet abcd{-1, -1, -1, d};
        int k = 0;
        for (const Index w : tet)
            if (w != d) abcd[static_cast<std::size_t>(k++)] = w;
        if (!same_orientation(tet, abcd)) std::swap(abcd[0], abcd[1]);
        const Index n = across(t, abcd[0], abcd[1], abcd[2]);
        if (n < 0) return {};
        Index e = -1;
        for (const Index w : tets_[static_cast<std::size_t>(n)])
            if (w != abcd[0] && w != abcd[1] && w != abcd[2]) e = w;
        // (a, b, c, d) positive: (e, d, a, b), (e, d, b, c), (e, d, c, a) are the positive three.
        Change c;
        c.made = 1.0;
        for (int s = 0; s < 3; ++s) {
            const Tet nt{e, d, abcd[static_cast<std::size_t>(s)], abcd[static_cast<std::size_t>((s + 1) % 3)]};
            const double q = quality(nt);
            if (!(q > 0.0)) return {};
            c.made = std::min(c.made, q);
            c.tets.push_back(nt);
        }
        c.removed = {t, n};
        return c;
    }

    /// The tetrahedra round edge u–v (a closed ring of 3 to kMaxRing) replaced by the best
    /// triangulation of the ring polygon, each triangle joined to u and to v.
    Change remove_edge(Index u, Index v) const {
        std::array<Index, kMaxRing> ring_tet{}, from{}, to{};
        int m = 0;
        for (const Index o : node_tets_[static_cast<std::size_t>(u)]) {
            const Tet& ot = tets_[static_cast<std::size_t>(o)];
            if (!has(ot, v)) continue;
            if (m == kMaxRing) return {};
            const Tet r = arranged_with(ot, u, v);  // (u, v, p, q) positive: the ring runs p -> q
            ring_tet[static_cast<std::size_t>(m)] = o;
            from[static_cast<std::size_t>(m)] = r[2];
            to[static_cast<std::size_t>(m)] = r[3];
            ++m;
        }
        if (m < 3) return {};
        // Walk the ring; it must close through all m (an edge on the boundary leaves it open).
        std::array<Index, kMaxRing> c{};
        c[0] = from[0];
        for (int k = 1; k <= m; ++k) {
            const Index prev = c[static_cast<std::size_t>(k - 1)];
            int next = -1;
            for (int s = 0; s < m; ++s)
                if (from[static_cast<std::size_t>(s)] == prev) next = s;
            if (next < 0) return {};
            const Index w = to[static_cast<std::size_t>(next)];
            if (k == m) {
                if (w != c[0]) return {};
            } else {
                for (int s = 0; s < k; ++s)
                    if (c[static_cast<std::size_t>(s)] == w) return {};
                c[static_cast<std::size_t>(k)] = w;
            }
        }
        // Triangle (i, k, j), i < k < j along the ring: tetrahedra (c_k, c_i, c_j, u) and
        // (c_i, c_k, c_j, v) are the positive ones.
        auto pair_of = [&](int i, int k, int j) {
            const auto ci = c[static_cast<std::size_t>(i)], ck = c[static_cast<std::size_t>(k)],
                       cj = c[static_cast<std::size_t>(j)];
            return std::array<Tet, 2>{Tet{ck, ci, cj, u}, Tet{ci, ck, cj, v}};
        };
        double best[kMaxRing][kMaxRing];
        int split[kMaxRing][kMaxRing];
        for (int len = 1; len < m; ++len)
            for (int i = 0; i + len < m; ++i) {
                const int j = i + len;
                split[i][j] = -1;
                if (len == 1) {
                    best[i][j] = std::numeric_limits<double>::infinity();
                    continue;
                }
                best[i][j] = kNone;
                for (int k = i + 1; k < j; ++k) {
                    const double sub = std::min(best[i][k], best[k][j]);
                    if (sub <= best[i][j]) continue;
                    const auto pr = pair_of(i, k, j);
                    const double q = std::min(quality(pr[0]), quality(pr[1]));
                    if (!(q > 0.0)) continue;
                    const double val = std::min(sub, q);
                    if (val > best[i][j]) best[i][j] = val, split[i][j] = k;
                }
            }
        if (!(best[0][m - 1] > 0.0)) return {};
        Change ch;
        ch.made = best[0][m - 1];
        std::vector<std::pair<int, int>> todo{{0, m - 1}};
        while (!todo.empty()) {
            const auto [i, j] = todo.back();
            todo.pop_back();
            if (j - i < 2) continue;
            const int k = split[i][j];
            const auto pr = pair_of(i, k, j);
            ch.tets.push_back(pr[0]);
            ch.tets.push_back(pr[1]);
            todo.emplace_back(i, k);
            todo.emplace_back(k, j);
        }
        ch.removed.assign(ring_tet.begin(), ring_tet.begin() + m);
        return ch;
    }

    /// A new point in a cavity round tetrahedron \p t: the cavity's tetrahedra replaced by the
    /// point joined to each face of the cavity's boundary, the point placed where the worst of
    /// them is best (a pattern search from the cavity's centroid). The cavity starts as \p t
    /// and grows by the tetrahedron across the face whose new tetrahedron is worst, up to
    /// kMaxCavity; made if it improves on the cavity's worst. This reaches what no flip and no
    /// move of a node can: a sliver whose four corners are on the boundary, two of its faces on
    /// it (a shallow valley of the layer top), with a point above the valley.
    bool insert_point(Index t) {
        std::vector<Index> cavity{t};
        const Index np = static_cast<Index>(p_.size());
        p_.emplace_back(Vec3::Zero());  // the candidate point, np; removed unless it is kept
        std::vector<Tet> made;
        for (;;) {
            // The cavity's boundary: each face of a cavity tetrahedron with no cavity tetrahedron
            // across; the new tetrahedron is that one with np in place of the face's opposite node.
            made.clear();
            std::vector<Index> across_of;
            double replaced = 1.0;
            Vec3 centre = Vec3::Zero();
            double edge = 0.0;
            for (const Index c : cavity) {
                const Tet& ct = tets_[static_cast<std::size_t>(c)];
                replaced = std::min(replaced, q_[static_cast<std::size_t>(c)]);
                for (int i = 0; i < 4; ++i) {
                    const auto f = face_of(ct, i);
                    const Index n = across(c, f[0], f[1], f[2]);
                    if (n >= 0 && std::find(cavity.begin(), cavity.end(), n) != cavity.end()) continue;
                    Tet nt = ct;
                    nt[static_cast<std::size_t>(i)] = np;
                    made.push_back(nt);
                    across_of.push_back(n);
                    for (const Index v : f) centre += p_[static_cast<std::size_t>(v)];
                    edge += (p_[static_cast<std::size_t>(f[1])] - p_[static_cast<std::size_t>(f[0])]).norm();
                }
            }
            // A cavity round a node would leave it in no tetrahedron (a point the mesh carries
            // and checkMesh fails): growing cannot undo that.
            if (swallows_node(cavity, made)) break;
            centre /= 3.0 * static_cast<double>(made.size());
            edge /= static_cast<double>(made.size());
            auto worst_of = [&](const Vec3& x) {
                p_[static_cast<std::size_t>(np)] = x;
                double w = std::numeric_limits<double>::infinity();
                for (const Tet& m : made) w = std::min(w, quality(m));
                return w;
            };
            Vec3 at = centre;
            double now = worst_of(at);
            double step = 0.25 * edge;
            for (int round = 0; round < 32 && step > 1e-3 * edge; ++round) {
                bool moved = false;
                for (int axis = 0; axis < 3 && !moved; ++axis)
                    for (const double sign : {1.0, -1.0}) {
                        Vec3 x = at;
                        x[axis] += sign * step;
                        const double q = worst_of(x);
                        if (q > now) {
                            now = q, at = x, moved = true;
                            break;
                        }
                    }
                if (!moved) step *= 0.5;
            }
            if (improves(now, replaced)) {
                p_[static_cast<std::size_t>(np)] = at;
                node_tets_.emplace_back();
                changed_.push_back(0);
                node_tried_.push_back(0);
                for (const Index c : cavity) kill(c);
                for (const Tet& m : made) add(m);
                return true;
            }
            // Grow across the interior face whose new tetrahedron is worst (a face on the
            // boundary stays one: the cavity grows round it).
            p_[static_cast<std::size_t>(np)] = at;
            Index grow = -1;
            double grow_q = std::numeric_limits<double>::infinity();
            for (std::size_t m = 0; m < made.size(); ++m) {
                if (across_of[m] < 0) continue;
                const double q = quality(made[m]);
                if (q < grow_q) grow_q = q, grow = across_of[m];
            }
            if (grow < 0 || static_cast<int>(cavity.size()) >= kMaxCavity) break;
            cavity.push_back(grow);
        }
        p_.pop_back();
        return false;
    }

    /// Whether a node of the \p cavity's tetrahedra is on none of the tetrahedra \p made from its
    /// boundary faces: inside the cavity, so replacing it would drop the node.
    bool swallows_node(const std::vector<Index>& cavity, const std::vector<Tet>& made) const {
        for (const Index c : cavity)
            for (const Index v : tets_[static_cast<std::size_t>(c)]) {
                const bool kept = std::any_of(made.begin(), made.end(), [v](const Tet& m) {
                    return std::find(m.begin(), m.end(), v) != m.end();
                });
                if (!kept) return true;
            }
        return false;
    }

    /// Move node \p v (one TetGen added, on no boundary face) to where the worst tetrahedron
    /// round it is best: a pattern search along the axes, the step halved when no move helps.
    bool move_node(Index v) {
        if (v < num_fixed_ || changed_[static_cast<std::size_t>(v)] <= node_tried_[static_cast<std::size_t>(v)])
            return false;
        node_tried_[static_cast<std::size_t>(v)] = ++clock_;
        const std::vector<Index> star = node_tets_[static_cast<std::size_t>(v)];
        if (star.empty()) return false;
        double mean = 0.0;
        int count = 0;
        for (const Index o : star) {
            const Tet& t = tets_[static_cast<std::size_t>(o)];
            for (int i = 0; i < 4; ++i) {
                const Index w = t[static_cast<std::size_t>(i)];
                if (w == v) continue;
                // The face through v opposite w: with no tetrahedron across, it is on the
                // boundary, and v stays.
                Index a = -1, b = -1;
                for (const Index x : t)
                    if (x != v && x != w) (a < 0 ? a : b) = x;
                if (across(o, v, a, b) < 0) return false;
                mean += (p_[static_cast<std::size_t>(w)] - p_[static_cast<std::size_t>(v)]).norm();
                ++count;
            }
        }
        auto worst_at = [&]() {
            double q = 1.0;
            for (const Index o : star) q = std::min(q, quality(tets_[static_cast<std::size_t>(o)]));
            return q;
        };
        const Vec3 start = p_[static_cast<std::size_t>(v)];
        const double old = worst_at();
        Vec3 at = start;
        double now = old;
        double step = 0.1 * mean / count;
        for (int round = 0; round < 16 && step > 1e-3 * mean / count; ++round) {
            bool moved = false;
            for (int axis = 0; axis < 3 && !moved; ++axis)
                for (const double sign : {1.0, -1.0}) {
                    Vec3 x = at;
                    x[axis] += sign * step;
                    p_[static_cast<std::size_t>(v)] = x;
                    const double q = worst_at();
                    if (q > now) {
                        now = q, at = x, moved = true;
                        break;
                    }
                }
            if (!moved) step *= 0.5;
        }
        if (!improves(now, old)) {
            p_[static_cast<std::size_t>(v)] = start;
            return false;
        }
        p_[static_cast<std::size_t>(v)] = at;
        for (const Index o : star) {
            q_[static_cast<std::size_t>(o)] = quality(tets_[static_cast<std::size_t>(o)]);
            stamp(tets_[static_cast<std::size_t>(o)]);
        }
        return true;
    }

    std::vector<Vec3>& p_;
    std::vector<Tet> tets_;
    std::vector<double> q_;
    std::vector<char> alive_;
    std::vector<std::vector<Index>> node_tets_;
    // Change stamps: a node's last change, a tetrahedron's and a node's last fruitless attempt.
    std::uint64_t clock_ = 1;
    mutable std::uint64_t evaluations_ = 0;  // tetrahedron qualities computed: the work done
    std::uint64_t budget_ = 0;
    std::vector<std::uint64_t> changed_, tried_, node_tried_;
    Index num_fixed_;
    double below_;
};

}  // namespace

void check_tet_improve_params(const TetImproveParams& params) {
    check_threads(params.threads, "TetImproveParams::threads");
    if (!(params.below >= 0.0 && params.below < 1.0))
        throw InputError("improve_tets: TetImproveParams::below = " + format_number(params.below) +
                         ": need a scaled-Jacobian bound in [0, 1) (0: off)");
    if (!(params.evaluations_per_tet > 0.0 && params.evaluations_per_tet < 1e9 && params.evaluations_floor >= 0.0 &&
          params.evaluations_floor < 1e15))
        throw InputError(
            "improve_tets: TetImproveParams::evaluations_per_tet = " + format_number(params.evaluations_per_tet) +
            ", evaluations_floor = " + format_number(params.evaluations_floor) +
            ": need a work budget above 0 per tetrahedron and a floor of 0 or more");
    if (params.max_passes < 1)
        throw InputError("improve_tets: TetImproveParams::max_passes = " + std::to_string(params.max_passes) +
                         ": need at least 1");
}

TetImproveReport improve_tets(TetFill& fill, Index num_fixed, const TetImproveParams& params, Progress* progress) {
    check_tet_improve_params(params);
    if (num_fixed < 0 || num_fixed > static_cast<Index>(fill.points.size()))
        throw InputError("improve_tets: num_fixed = " + std::to_string(num_fixed) + " for " +
                         std::to_string(fill.points.size()) + " points");
    TetImproveReport rep;
    rep.below = params.below;
    if (params.below == 0.0 || fill.tets.empty()) return rep;
    const auto start = std::chrono::steady_clock::now();
    const auto num_tets = static_cast<std::uint64_t>(fill.tets.size());
    Improver im(fill, num_fixed, params.below);  // takes fill.tets
    im.set_budget(static_cast<std::uint64_t>(params.evaluations_floor +
                                             params.evaluations_per_tet * static_cast<double>(num_tets)));
    im.measure(rep.below_before, rep.min_before);
    // Reported after each pass as a share of the most passes it may make (its insertion pass and
    // the three after it included), never 1: the caller ends the stage.
    const auto passed = [&] { report(progress, "tetrahedra", rep.passes / (params.max_passes + 5.0)); };
    while (rep.passes < params.max_passes) {
        check_cancelled(progress);
        ++rep.passes;
        const bool changed = im.pass(rep, progress);
        passed();
        if (!changed) break;
    }
    if (im.insertion_pass(rep, progress))
        for (int extra = 0; extra < 3; ++extra) {
            check_cancelled(progress);
            ++rep.passes;
            if (!im.pass(rep, progress)) break;
        }
    // One scan of the faces when none is skewed (the usual case), one more after each pass that changed any.
    std::vector<Improver::SkewedFace> skewed = im.skewed_faces(rep.skewed_before, params.threads);
    rep.skewed_after = rep.skewed_before;
    for (int round = 0; round < 3 && !skewed.empty() && !im.over_budget(); ++round) {
        check_cancelled(progress);
        if (!im.skew_pass(skewed, rep, progress)) break;
        skewed = im.skewed_faces(rep.skewed_after, params.threads);
    }
    im.measure(rep.below_after, rep.min_after);
    rep.budget_reached = im.over_budget();
    fill.tets = im.release();
    rep.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return rep;
}

}  // namespace strata
