// Fans at sharp convex edges and corners: fans.h.

#include "fans.h"

#include <strata/core/error.h>
#include <strata/core/face_geometry.h>
#include <strata/core/union_find.h>
#include <strata/geometry/normals.h>
#include <strata/geometry/topology.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <numeric>

namespace strata {
namespace {

constexpr double kFeatureDeg = 30.0;  ///< convex edges that close a fan's chains (the M6 tip cap's turn 30-47°)
constexpr double kWedgeDeg = 90.0;    ///< widest wedge between two columns of a fan
/// Least det(a, b, c) of the directions of a corner's columns over each of its cells: below,
/// the corner's cells would be flat (its sides' normals nearly in one plane), and the fan
/// edge there that turns least is dropped. A box corner spans 1, a wing's trailing edge at
/// its root 0.66.
constexpr double kCornerSpan = 0.25;
/// A node with two fan edges whose outward bisectors (the edges' own middle directions) differ
/// by more than this (a delta wing's apex, where its two sharp leading edges meet at 62°: 112°)
/// gets each edge's columns between its two sides and a corner polygon closing them, as a
/// corner does. Shared columns there would twist the wedges on both edges by half that angle,
/// more than half the widest wedge (kWedgeDeg); a lower bound splits smooth chains too
/// (docs/DESIGN_NOTES.md).
constexpr double kChainTurnDeg = 90.0;

Vec3 unit(const Vec3& v) {
    const double l = v.norm();
    return l > 0.0 ? Vec3(v / l) : Vec3::Zero();
}

/// Spherical interpolation from unit \p a to unit \p b (less than 180° apart).
Vec3 slerp(const Vec3& a, const Vec3& b, double t) {
    const double ang = std::acos(std::clamp(a.dot(b), -1.0, 1.0));
    if (ang < 1e-9) return a;
    const double s = std::sin(ang);
    return unit(std::sin((1.0 - t) * ang) / s * a + std::sin(t * ang) / s * b);
}

/// The angle (degrees) by which unit normals \p nf and \p ng of two faces meeting at an edge
/// through \p a turn, if the edge is convex (each face's centroid, \p cf, \p cg, lies behind the
/// other's plane); else -1.
double convex_turn_deg(const Vec3& nf, const Vec3& cf, const Vec3& ng, const Vec3& cg, const Vec3& a) {
    if (!((cg - a).dot(nf) < 0.0 && (cf - a).dot(ng) < 0.0)) return -1.0;
    return std::acos(std::clamp(nf.dot(ng), -1.0, 1.0)) * 180.0 / std::numbers::pi;
}

/// The fan of triangles closing a polygon of column directions \p dirs (as a corner's cells
/// on the wall are: a tetrahedron per triangle) whose worst triangle spans most, det(a, b, c):
/// that worst span, and in \p from the polygon corner the fan starts at.
double best_corner_fan(const std::vector<Vec3>& dirs, std::size_t& from) {
    const std::size_t p = dirs.size();
    auto span = [&](std::size_t a, std::size_t b, std::size_t c) {
        return dirs[a % p].dot(dirs[b % p].cross(dirs[c % p]));
    };
    double best = -2.0;
    from = 0;
    for (std::size_t s = 0; s < p; ++s) {
        double worst = 2.0;
        for (std::size_t t = 1; t + 1 < p; ++t) worst = std::min(worst, span(s, s + t, s + t + 1));
        if (worst > best) best = worst, from = s;
    }
    return best;
}

/// Whether face \p f goes from \p a to \p b.
bool goes(const SurfaceMesh& m, Index f, Index a, Index b) {
    const Index n = m.face_size(f);
    for (Index c = 0; c < n; ++c)
        if (m.face_node(f, c) == a && m.face_node(f, (c + 1) % n) == b) return true;
    return false;
}

/// Unit vector in face \p f's plane, perpendicular to its edge (a, b), pointing into the face.
Vec3 into_face(const SurfaceMesh& m, Index f, Index a, Index b) {
    const Vec3 e = unit(m.points[b] - m.points[a]);
    const Vec3 d = face_centroid(m, m.points, f) - m.points[a];
    return unit(d - d.dot(e) * e);
}

}  // namespace

namespace {

/// Drop the fan edges at nodes with only one until none is left, but for the nodes where a
/// chain may end (\p ends: a plane node, whose open ring splits into two sectors, or a terminal,
/// whose columns the chain's last quads close onto: fans.h), then the edges whose two nodes are
/// both terminals with that one edge (nothing there splits). Returns the fan edges per node.
std::vector<std::vector<Index>> prune(const EdgeTable& et, std::size_t un, const std::vector<Vec3>& anchor,
                                      const std::vector<char>& ends, std::vector<char>& keep) {
    auto loose = [&](std::size_t i) { return i >= ends.size() || !ends[i]; };
    const auto ne = et.nodes.size();
    std::vector<std::vector<Index>> at(un);
    for (std::size_t e = 0; e < ne; ++e)
        if (keep[e])
            for (const Index v : et.nodes[e]) at[static_cast<std::size_t>(v)].push_back(static_cast<Index>(e));
    std::vector<int> degree(un, 0);
    std::vector<Index> queue;
    for (std::size_t i = 0; i < un; ++i)
        if ((degree[i] = static_cast<int>(at[i].size())) == 1 && loose(i)) queue.push_back(static_cast<Index>(i));
    while (!queue.empty()) {
        const Index i = queue.back();
        queue.pop_back();
        for (const Index e : at[static_cast<std::size_t>(i)]) {
            if (!keep[static_cast<std::size_t>(e)]) continue;
            keep[static_cast<std::size_t>(e)] = 0;
            for (const Index v : et.nodes[static_cast<std::size_t>(e)])
                if (--degree[static_cast<std::size_t>(v)] == 1 && loose(static_cast<std::size_t>(v)))
                    queue.push_back(v);
        }
    }
    auto lone_terminal = [&](Index v) {
        const auto u = static_cast<std::size_t>(v);
        return degree[u] == 1 && (u >= anchor.size() || anchor[u] == Vec3::Zero());
    };
    for (std::size_t e = 0; e < ne; ++e)
        if (keep[e] && lone_terminal(et.nodes[e][0]) && lone_terminal(et.nodes[e][1])) keep[e] = 0;
    for (std::size_t i = 0; i < un; ++i) {
        auto& a = at[i];
        a.erase(std::remove_if(a.begin(), a.end(), [&](Index e) { return !keep[static_cast<std::size_t>(e)]; }),
                a.end());
    }
    return at;
}

/// Whether node \p i ends its chain with one fan edge and no plane (\p at per node): its one
/// sector's column is the end of every column of its fan edge.
bool terminal(const std::vector<std::vector<Index>>& at, const std::vector<Vec3>& anchor, std::size_t i) {
    return at[i].size() == 1 && (i >= anchor.size() || anchor[i] == Vec3::Zero());
}

/// What assemble builds the fan wall from: the wall, its edge table, the fan edges (\p keep, a
/// 2-core, \p at per node), each edge's turn (degrees) and each node's plane (\p anchor, zero
/// where none).
struct FanEdges {
    const SurfaceMesh& wall;
    const EdgeTable& et;
    const std::vector<char>& keep;
    const std::vector<std::vector<Index>>& at;
    const std::vector<double>& turn;
    const std::vector<Vec3>& anchor;
};

/// Wedges per fan edge: ceil(turn / 90°), the largest along the chain (runs through nodes with
/// two fan edges) so that the columns between match along it; 0 for the other edges.
std::vector<int> chain_wedges(const FanEdges& in) {
    const auto ne = in.et.nodes.size();
    std::vector<int> wedges(ne, 0);
    UnionFind runs(ne);
    for (std::size_t i = 0; i < in.at.size(); ++i)
        if (in.at[i].size() == 2) runs.unite(in.at[i][0], in.at[i][1]);
    std::vector<double> worst(ne, 0.0);
    for (std::size_t e = 0; e < ne; ++e)
        if (in.keep[e]) {
            double& w = worst[static_cast<std::size_t>(runs.find(static_cast<Index>(e)))];
            w = std::max(w, in.turn[e]);
        }
    for (std::size_t e = 0; e < ne; ++e)
        if (in.keep[e])
            wedges[e] =
                std::max(1, static_cast<int>(std::ceil(
                                worst[static_cast<std::size_t>(runs.find(static_cast<Index>(e)))] / kWedgeDeg - 1e-9)));
    return wedges;
}

/// Per node, the plane its columns lean into and by how much (0: none).
struct Lean {
    std::vector<Vec3> plane;
    std::vector<double> weight;
    /// Direction \p d leaned into node \p i's plane.
    Vec3 operator()(std::size_t i, const Vec3& d) const {
        return weight[i] > 0.0 ? unit(d - weight[i] * d.dot(plane[i]) * plane[i]) : d;
    }
};

/// A plane node's columns lie in its plane; along the chain from it, the columns lean into
/// that plane the more the nearer they are to it (weight 1 - distance / plane_reach). Fixed
/// and unsmoothed, a swept trailing edge's columns beside the plane would otherwise cross it
/// within the layers' thickness, and those of the plane node's strip would twist.
Lean plane_lean(const FanEdges& in, double plane_reach) {
    const auto un = in.at.size();
    Lean lean{std::vector<Vec3>(un, Vec3::Zero()), std::vector<double>(un, 0.0)};
    for (std::size_t a = 0; a < un; ++a) {
        if (in.anchor[a] == Vec3::Zero() || in.at[a].size() != 1) continue;
        const Vec3& p = in.anchor[a];
        lean.plane[a] = p, lean.weight[a] = 1.0;
        Index prev = static_cast<Index>(a), e = in.at[a][0];
        for (;;) {
            const auto& ab = in.et.nodes[static_cast<std::size_t>(e)];
            const Index cur = ab[0] == prev ? ab[1] : ab[0];
            const auto uc = static_cast<std::size_t>(cur);
            const double w = 1.0 - std::abs((in.wall.points[cur] - in.wall.points[a]).dot(p)) / plane_reach;
            if (!(w > 0.0) || in.anchor[uc] != Vec3::Zero()) break;
            if (w > lean.weight[uc]) lean.plane[uc] = p, lean.weight[uc] = w;
            if (in.at[uc].size() != 2) break;  // a corner
            e = in.at[uc][0] == e ? in.at[uc][1] : in.at[uc][0];
            prev = cur;
        }
    }
    return lean;
}

/// A new column of \p out at wall node \p i, marching along \p dir; its id.
Index add_column(FanWall& out, const SurfaceMesh& wall, Index i, const Vec3& dir) {
    out.mesh.points.push_back(wall.points[i]);
    out.base.push_back(i);
    out.direction.push_back(dir);
    return static_cast<Index>(out.mesh.points.size() - 1);
}

/// The columns of the fan nodes' sectors: the faces round a fan node between two of its fan
/// edges (or, at a plane node, between its fan edge and the open boundary).
struct Sectors {
    std::vector<std::array<Index, 4>> corner_node;  ///< per face corner: its column
    std::map<std::pair<Index, Index>, Index> node;  ///< (node, a face of the sector) → column
};

/// The faces round fan node \p i (row i of \p vf) in sets, one per sector: two faces sharing
/// an edge at i that has no fan are of one sector.
UnionFind sectors_round(const FanEdges& in, const Csr& vf, Index i) {
    const SurfaceMesh& wall = in.wall;
    const Index* f0 = vf.row_begin(i);
    const auto m = static_cast<std::size_t>(vf.row_size(i));
    UnionFind sec(m);
    for (std::size_t p = 0; p < m; ++p)
        for (std::size_t q = p + 1; q < m; ++q) {
            const Index fp = f0[p], fq = f0[q];
            for (Index c = 0; c < wall.face_size(fp); ++c) {
                const Index x = wall.face_node(fp, c);
                if (x == i) continue;
                bool in_q = false;
                for (const Index* v = wall.face_begin(fq); v != wall.face_end(fq); ++v) in_q |= *v == x;
                const Index e = in_q ? find_edge(in.et, i, x) : kNone;
                if (e != kNone && !in.keep[static_cast<std::size_t>(e)])
                    sec.unite(static_cast<Index>(p), static_cast<Index>(q));
            }
        }
    return sec;
}

/// Splits fan node \p i into a column per sector, along the max-min direction of the corner
/// normals at i of the sector's faces (leaned by \p lean). The sector of the node's lowest
/// face keeps the node's id, the others get new columns.
void split_node(const FanEdges& in, const Csr& vf, const Lean& lean, Index i, Sectors& s, FanWall& out) {
    const SurfaceMesh& wall = in.wall;
    const Index* f0 = vf.row_begin(i);
    const auto m = static_cast<std::size_t>(vf.row_size(i));
    UnionFind sec = sectors_round(in, vf, i);
    std::map<Index, std::vector<Vec3>> corners_of;
    for (std::size_t p = 0; p < m; ++p) {
        const Index f = f0[p];
        const Index n = wall.face_size(f);
        for (Index c = 0; c < n; ++c)
            if (wall.face_node(f, c) == i) {
                const Vec3& o = wall.points[i];
                corners_of[sec.find(static_cast<Index>(p))].push_back(
                    unit((wall.points[wall.face_node(f, (c + 1) % n)] - o)
                             .cross(wall.points[wall.face_node(f, (c + n - 1) % n)] - o)));
            }
    }
    bool first = true;
    for (const auto& [root, corners] : corners_of) {
        const Vec3 dir = lean(static_cast<std::size_t>(i), unit(max_min_dot_direction(corners)));
        const Index id = first ? i : add_column(out, wall, i, dir);
        if (first) out.direction[static_cast<std::size_t>(i)] = dir;
        first = false;
        for (std::size_t p = 0; p < m; ++p)
            if (sec.find(static_cast<Index>(p)) == root) {
                s.node[{i, f0[p]}] = id;
                const Index f = f0[p];
                for (Index c = 0; c < wall.face_size(f); ++c)
                    if (wall.face_node(f, c) == i)
                        s.corner_node[static_cast<std::size_t>(f)][static_cast<std::size_t>(c)] = id;
            }
    }
}

/// Starts \p out as the wall with its nodes' columns, and splits each fan node into its
/// sectors' columns (counting the fan nodes, corners and plane nodes).
Sectors split_sectors(const FanEdges& in, const Csr& vf, const Lean& lean, FanWall& out) {
    const SurfaceMesh& wall = in.wall;
    const Index nn = wall.num_points(), nf = wall.num_faces();
    const auto un = static_cast<std::size_t>(nn);
    Sectors s;
    s.corner_node.resize(static_cast<std::size_t>(nf));
    for (Index f = 0; f < nf; ++f) {
        auto& c = s.corner_node[static_cast<std::size_t>(f)];
        c = {kNone, kNone, kNone, kNone};
        std::copy(wall.face_begin(f), wall.face_end(f), c.begin());
    }
    out.mesh.patches = wall.patches;
    out.mesh.points = wall.points;
    out.base.resize(un);
    std::iota(out.base.begin(), out.base.end(), Index{0});
    out.direction.assign(un, Vec3::Zero());
    for (Index i = 0; i < nn; ++i) {
        if (in.at[static_cast<std::size_t>(i)].empty()) continue;
        ++out.fan_nodes;
        out.corners += in.at[static_cast<std::size_t>(i)].size() > 2 ? 1 : 0;
        out.plane_nodes += in.anchor[static_cast<std::size_t>(i)] != Vec3::Zero() ? 1 : 0;
        split_node(in, vf, lean, i, s, out);
        // A terminal's one column stops at the wall (FanWall::terminals); as a ghost it is smoothed
        // like any other node.
        if (terminal(in.at, in.anchor, static_cast<std::size_t>(i))) {
            out.direction[static_cast<std::size_t>(i)] = Vec3::Zero();
            out.terminals.push_back(i);
        }
    }
    return s;
}

/// The outward bisector of fan edge \p e's two sides at a node whose sector normals are \p na, \p nb.
Vec3 outward_bisector(const FanEdges& in, Index e, const Vec3& na, const Vec3& nb) {
    const Index a = in.et.nodes[static_cast<std::size_t>(e)][0], b = in.et.nodes[static_cast<std::size_t>(e)][1];
    const Index f = in.et.faces.row_begin(e)[0], g = in.et.faces.row_begin(e)[1];
    return unit(na + nb - into_face(in.wall, f, a, b) - into_face(in.wall, g, a, b));
}

/// The directions of the \p w - 1 columns between unit \p na and \p nb, through \p ref halfway.
std::vector<Vec3> mid_directions(const Vec3& na, const Vec3& nb, const Vec3& ref, int w) {
    std::vector<Vec3> dirs;
    for (int q = 1; q < w; ++q) {
        const double t = static_cast<double>(q) / w;
        dirs.push_back(t <= 0.5 ? slerp(na, ref, 2.0 * t) : slerp(ref, nb, 2.0 * t - 1.0));
    }
    return dirs;
}

/// Fan edge \p e's two faces: first the one that goes from its low node to its high one.
std::pair<Index, Index> edge_sides(const FanEdges& in, Index e) {
    const Index a = in.et.nodes[static_cast<std::size_t>(e)][0], b = in.et.nodes[static_cast<std::size_t>(e)][1];
    Index f = in.et.faces.row_begin(e)[0], g = in.et.faces.row_begin(e)[1];
    if (!goes(in.wall, f, a, b)) std::swap(f, g);
    return {f, g};
}

/// Whether node \p i, with two fan edges (of one run, so of one wedge count \p w ≥ 2) and two
/// sector columns, is split like a corner: where the chain turns sharply (kChainTurnDeg), each
/// edge gets its own columns and a polygon closes them, if that polygon's cells span well
/// (kCornerSpan; else the shared columns stay).
bool splits_like_corner(const FanEdges& in, const Sectors& s, const FanWall& out, Index i, int w) {
    const auto& es = in.at[static_cast<std::size_t>(i)];
    Index lo = kNone, hi = kNone;
    for (auto it = s.node.lower_bound({i, std::numeric_limits<Index>::min()});
         it != s.node.end() && it->first.first == i; ++it)
        lo = lo == kNone ? it->second : std::min(lo, it->second), hi = std::max(hi, it->second);
    if (lo == hi) return false;
    const Vec3& nl = out.direction[static_cast<std::size_t>(lo)];
    const Vec3& nh = out.direction[static_cast<std::size_t>(hi)];
    const Vec3 r0 = outward_bisector(in, es[0], nl, nh), r1 = outward_bisector(in, es[1], nl, nh);
    if (std::acos(std::clamp(r0.dot(r1), -1.0, 1.0)) * 180.0 / std::numbers::pi <= kChainTurnDeg) return false;
    std::vector<Vec3> poly{nl};
    for (const Vec3& d : mid_directions(nl, nh, r0, w)) poly.push_back(d);
    poly.push_back(nh);
    const std::vector<Vec3> back = mid_directions(nl, nh, r1, w);
    poly.insert(poly.end(), back.rbegin(), back.rend());
    std::size_t from = 0;
    const double fwd = best_corner_fan(poly, from);
    std::reverse(poly.begin(), poly.end());
    return std::max(fwd, best_corner_fan(poly, from)) >= kCornerSpan;
}

/// The columns of each fan edge's ends, made on first use: at a node with two fan edges,
/// shared between both (its two sectors, in the order of their column ids); at a corner (or a
/// node split like one), each edge's own.
class ColumnRuns {
public:
    ColumnRuns(const FanEdges& in, const std::vector<int>& wedges, const Lean& lean, const Sectors& s,
               const std::vector<char>& split, FanWall& out)
        : in_(in), wedges_(wedges), lean_(lean), s_(s), split_(split), out_(out) {}

    /// Whether node \p i is closed by a polygon of its columns.
    bool cornered(Index i) const {
        return in_.at[static_cast<std::size_t>(i)].size() > 2 || split_[static_cast<std::size_t>(i)];
    }

    /// The columns at node \p i of fan edge \p e, from its first side's sector (edge_sides) to the other's.
    std::vector<Index> operator()(Index i, Index e) {
        const auto [f, g] = edge_sides(in_, e);
        const Index sf = s_.node.at({i, f}), sg = s_.node.at({i, g});
        const int w = wedges_[static_cast<std::size_t>(e)];
        if (terminal(in_.at, in_.anchor, static_cast<std::size_t>(i)))
            return std::vector<Index>(static_cast<std::size_t>(w) + 1, sf);  // one sector: sf is sg
        std::vector<Index> run{sf};
        if (!cornered(i)) {
            std::vector<Index> mid = shared(i, std::min(sf, sg), std::max(sf, sg), w);
            if (sf != std::min(sf, sg)) std::reverse(mid.begin(), mid.end());
            run.insert(run.end(), mid.begin(), mid.end());
        } else {
            const std::vector<Index>& mid = own(i, e, sf, sg, w);
            run.insert(run.end(), mid.begin(), mid.end());
        }
        run.push_back(sg);
        return run;
    }

private:
    /// New columns at node \p i between directions \p na and \p nb (\p w wedges), through \p ref.
    std::vector<Index> between(Index i, const Vec3& na, const Vec3& nb, const Vec3& ref, int w) {
        std::vector<Index> ids;
        for (const Vec3& d : mid_directions(na, nb, ref, w)) ids.push_back(add_column(out_, in_.wall, i, d));
        return ids;
    }

    /// The columns node \p i's fan edges share, from its lower sector column \p lo to \p hi.
    const std::vector<Index>& shared(Index i, Index lo, Index hi, int w) {
        auto it = shared_.find(i);
        if (it == shared_.end()) {
            const auto& es = in_.at[static_cast<std::size_t>(i)];
            const Vec3& nl = out_.direction[static_cast<std::size_t>(lo)];
            const Vec3& nh = out_.direction[static_cast<std::size_t>(hi)];
            const Vec3 ref = lean_(
                static_cast<std::size_t>(i),
                es.size() == 1 ? outward_bisector(in_, es[0], nl, nh)
                               : unit(outward_bisector(in_, es[0], nl, nh) + outward_bisector(in_, es[1], nl, nh)));
            it = shared_.emplace(i, between(i, nl, nh, ref, w)).first;
        }
        return it->second;
    }

    /// Fan edge \p e's own columns at node \p i, from its sector column \p sf to \p sg.
    const std::vector<Index>& own(Index i, Index e, Index sf, Index sg, int w) {
        auto it = own_.find({i, e});
        if (it == own_.end()) {
            const Vec3 &nf = out_.direction[static_cast<std::size_t>(sf)],
                       &ng = out_.direction[static_cast<std::size_t>(sg)];
            it = own_.emplace(
                         std::make_pair(i, e),
                         between(i, nf, ng, lean_(static_cast<std::size_t>(i), outward_bisector(in_, e, nf, ng)), w))
                     .first;
        }
        return it->second;
    }

    const FanEdges& in_;
    const std::vector<int>& wedges_;
    const Lean& lean_;
    const Sectors& s_;
    const std::vector<char>& split_;
    FanWall& out_;
    std::map<Index, std::vector<Index>> shared_;                 // node → columns from its lower sector column
    std::map<std::pair<Index, Index>, std::vector<Index>> own_;  // (node, edge) → columns from its first side's
};

/// Corner node → the directed column edges its fans' quads leave open.
using CornerEdges = std::map<Index, std::vector<std::pair<Index, Index>>>;

/// Adds the wall's faces with their corners' columns to \p out, then the fans' quads along each
/// fan edge; returns the edges the quads leave open at the corners.
CornerEdges add_faces(const FanEdges& in, const Sectors& s, ColumnRuns& runs, FanWall& out) {
    const SurfaceMesh& wall = in.wall;
    const Index nf = wall.num_faces();
    for (Index f = 0; f < nf; ++f)
        out.mesh.add_face(s.corner_node[static_cast<std::size_t>(f)].data(), wall.face_size(f), wall.face_patch[f]);
    out.fan_face.assign(static_cast<std::size_t>(nf), 0);
    CornerEdges corner_edges;
    for (std::size_t e = 0; e < in.et.nodes.size(); ++e) {
        if (!in.keep[e]) continue;
        const Index a = in.et.nodes[e][0], b = in.et.nodes[e][1];
        const std::vector<Index> ra = runs(a, static_cast<Index>(e)), rb = runs(b, static_cast<Index>(e));
        const Index f = edge_sides(in, static_cast<Index>(e)).first;
        for (std::size_t q = 0; q + 1 < ra.size(); ++q) {
            // A terminal's run is its one column repeated: its quads are triangles.
            if (ra[q] == ra[q + 1])
                out.mesh.add_face({rb[q], ra[q], rb[q + 1]}, wall.face_patch[f]);
            else if (rb[q] == rb[q + 1])
                out.mesh.add_face({rb[q], ra[q], ra[q + 1]}, wall.face_patch[f]);
            else
                out.mesh.add_face({rb[q], ra[q], ra[q + 1], rb[q + 1]}, wall.face_patch[f]);
            out.fan_face.push_back(1);
            if (runs.cornered(a)) corner_edges[a].push_back({ra[q], ra[q + 1]});
            if (runs.cornered(b)) corner_edges[b].push_back({rb[q + 1], rb[q]});
        }
    }
    return corner_edges;
}

/// The polygon of corner \p i's columns that its fans' quads (\p edges) leave open, in order.
std::vector<Index> corner_polygon(Index i, const std::vector<std::pair<Index, Index>>& edges) {
    std::map<Index, Index> next;  // the polygon goes opposite to the quads' edges
    for (const auto& [x, y] : edges) next[y] = x;
    std::vector<Index> poly{next.begin()->first};
    while (poly.size() <= edges.size()) {
        const auto it = next.find(poly.back());
        if (it == next.end()) break;
        if (it->second == poly.front()) break;
        poly.push_back(it->second);
    }
    if (poly.size() != edges.size())
        throw TopologyError("internal: the fans at the corner " + std::to_string(i) + " do not close into one polygon");
    return poly;
}

/// Closes corner \p i's polygon \p poly in \p out. On the wall the polygon's cells are a
/// tetrahedron per triangle (the node, and the triangle's columns one step out), or a pyramid
/// on a quad: each as good as the three directions it spans, det(a, b, c). A quad whose every
/// corner spans well stays one; otherwise the fan of triangles whose worst triangle spans
/// most. False, with nothing added, where even that spans too little (kCornerSpan).
bool close_corner(const std::vector<Index>& poly, Index patch, FanWall& out) {
    const std::size_t p = poly.size();
    std::vector<Vec3> dirs;
    for (const Index c : poly) dirs.push_back(out.direction[static_cast<std::size_t>(c)]);
    auto span = [&](std::size_t a, std::size_t b, std::size_t c) {
        return dirs[a % p].dot(dirs[b % p].cross(dirs[c % p]));
    };
    std::size_t from = 0;
    const double best = best_corner_fan(dirs, from);
    if (best < kCornerSpan) return false;
    double quad = 2.0;
    for (std::size_t c = 0; c < p; ++c) quad = std::min(quad, span(c + p - 1, c, c + 1));
    if (p == 3 || (p == 4 && quad >= 0.5 * best && quad > 0.0)) {
        out.mesh.add_face(poly.data(), static_cast<Index>(p), patch);
        out.fan_face.push_back(1);
    } else {
        for (std::size_t t = 1; t + 1 < p; ++t) {
            out.mesh.add_face({poly[from], poly[(from + t) % p], poly[(from + t + 1) % p]}, patch);
            out.fan_face.push_back(1);
        }
    }
    return true;
}

/// Corner \p i's fan edge that turns least.
Index weakest_edge(const FanEdges& in, Index i) {
    Index weakest = kNone;
    for (const Index e : in.at[static_cast<std::size_t>(i)])
        if (weakest == kNone || in.turn[static_cast<std::size_t>(e)] < in.turn[static_cast<std::size_t>(weakest)])
            weakest = e;
    return weakest;
}

/// The fan wall for the fan edges \p keep (a 2-core, \p at per node), or the fan edges to drop
/// before trying again (\p bad, empty if none): where a corner's columns span too little
/// (nearly in one plane: its cells would be flat), the corner's fan edge that turns least.
FanWall assemble(const SurfaceMesh& wall, const EdgeTable& et, const std::vector<char>& keep,
                 const std::vector<std::vector<Index>>& at, const std::vector<double>& turn,
                 const std::vector<Vec3>& anchor, double plane_reach, std::vector<Index>& bad) {
    const FanEdges in{wall, et, keep, at, turn, anchor};
    FanWall out;
    bad.clear();
    const Index nn = wall.num_points();
    const auto un = static_cast<std::size_t>(nn);
    const auto ne = et.nodes.size();
    for (std::size_t e = 0; e < ne; ++e) out.fan_edges += keep[e] ? 1 : 0;
    const std::vector<int> wedges = chain_wedges(in);
    const Lean lean = plane_lean(in, plane_reach);
    const Csr vf = vertex_faces(wall);
    const Sectors sectors = split_sectors(in, vf, lean, out);
    // A node with two fan edges of two wedges or more (with one there are no columns between
    // to share) may be split like a corner.
    std::vector<char> split(un, 0);
    for (std::size_t i = 0; i < un; ++i)
        if (at[i].size() == 2 && wedges[static_cast<std::size_t>(at[i][0])] >= 2)
            split[i] =
                splits_like_corner(in, sectors, out, static_cast<Index>(i), wedges[static_cast<std::size_t>(at[i][0])]);
    for (std::size_t i = 0; i < un; ++i) out.corners += split[i];
    ColumnRuns runs(in, wedges, lean, sectors, split, out);
    for (const auto& [i, edges] : add_faces(in, sectors, runs, out)) {
        const std::vector<Index> poly = corner_polygon(i, edges);
        if (!close_corner(poly, wall.face_patch[vf.row_begin(i)[0]], out)) {
            bad.push_back(weakest_edge(in, i));  // one at a time: dropping it may leave the other corners sound
            return out;
        }
    }
    out.columns = out.mesh.num_points() - nn;
    return out;
}

}  // namespace

FanWall build_fans(const SurfaceMesh& wall, const Csr& loops, const std::vector<Vec3>& plane_normal, double plane_reach,
                   double fan_angle_deg, const std::vector<char>& excluded) {
    FanWall out;
    if (!(fan_angle_deg > 0.0)) return out;
    const Index nn = wall.num_points(), nf = wall.num_faces();
    const auto un = static_cast<std::size_t>(nn);
    const EdgeTable et = edge_table(wall);
    const auto ne = et.nodes.size();
    std::vector<char> boundary(un, 0);
    for (Index l = 0; l < loops.rows(); ++l)
        for (const Index* v = loops.row_begin(l); v != loops.row_end(l); ++v)
            boundary[static_cast<std::size_t>(*v)] = 1;
    std::vector<char> open = boundary;
    for (std::size_t i = 0; i < excluded.size() && i < un; ++i) open[i] |= excluded[i];
    // Plane nodes: on the open boundary, held in one plane (a symmetry plane), not excluded.
    // A chain may end at one, with one fan edge.
    std::vector<Vec3> anchor(un, Vec3::Zero());
    for (std::size_t i = 0; i < un && i < plane_normal.size(); ++i)
        if (boundary[i] && !(i < excluded.size() && excluded[i])) anchor[i] = plane_normal[i];
    auto blocked = [&](Index v) {
        return open[static_cast<std::size_t>(v)] && anchor[static_cast<std::size_t>(v)] == Vec3::Zero();
    };
    std::vector<Vec3> normal(static_cast<std::size_t>(nf));
    for (Index f = 0; f < nf; ++f) normal[static_cast<std::size_t>(f)] = unit(face_area_vector(wall, f));

    // Convex edges turning 30° or more; those of their chains that hold an edge turning
    // fan_angle_deg or more.
    std::vector<double> turn(ne, 0.0);
    std::vector<char> keep(ne, 0);
    bool any_seed = false;
    UnionFind chains(un);
    std::vector<Index> at_boundary;  // nodes with an edge of 30° or more to the open boundary
    for (std::size_t e = 0; e < ne; ++e) {
        const Index a = et.nodes[e][0], b = et.nodes[e][1];
        if (et.faces.row_size(static_cast<Index>(e)) != 2) continue;
        const Index f = et.faces.row_begin(static_cast<Index>(e))[0], g = et.faces.row_begin(static_cast<Index>(e))[1];
        const Vec3 &nf_ = normal[static_cast<std::size_t>(f)], &ng = normal[static_cast<std::size_t>(g)];
        if (nf_ == Vec3::Zero() || ng == Vec3::Zero()) continue;
        const double t = convex_turn_deg(nf_, face_centroid(wall, wall.points, f), ng,
                                         face_centroid(wall, wall.points, g), wall.points[a]);
        if (t < kFeatureDeg) continue;
        turn[e] = t;  // kept or not: the edges without a fan are said why (unfanned)
        if (blocked(a) || blocked(b) ||
            (boundary[static_cast<std::size_t>(a)] && boundary[static_cast<std::size_t>(b)])) {
            if (boundary[static_cast<std::size_t>(a)] || boundary[static_cast<std::size_t>(b)])
                at_boundary.insert(at_boundary.end(), {a, b});
            continue;
        }
        keep[e] = 1;
        chains.unite(a, b);
        any_seed |= t >= fan_angle_deg;
    }
    // A plane node's open ring splits into two sectors by one fan edge; with more, none.
    {
        std::vector<int> degree(un, 0);
        for (std::size_t e = 0; e < ne; ++e)
            if (keep[e])
                for (const Index v : et.nodes[e]) ++degree[static_cast<std::size_t>(v)];
        for (std::size_t e = 0; e < ne; ++e)
            for (const Index v : et.nodes[e])
                if (keep[e] && boundary[static_cast<std::size_t>(v)] && degree[static_cast<std::size_t>(v)] > 1) {
                    keep[e] = 0;
                    at_boundary.push_back(v);
                }
    }
    // Why each edge of fan_angle_deg or more that ends without a fan has none: its chain (the
    // convex edges of 30° or more joined to it) reaches the open boundary, or ends otherwise.
    std::vector<char> reaches_boundary(un, 0);
    for (const Index v : at_boundary) reaches_boundary[static_cast<std::size_t>(chains.find(v))] = 1;
    auto explain = [&](FanWall& fw) {
        std::vector<char> fanned(un, 0);
        for (std::size_t e = 0; e < ne; ++e)
            if (keep[e])
                for (const Index v : et.nodes[e]) fanned[static_cast<std::size_t>(v)] = 1;
        std::map<Index, NoFan> why;
        for (std::size_t e = 0; e < ne; ++e) {
            if (keep[e] || turn[e] < fan_angle_deg) continue;
            for (const Index v : et.nodes[e]) {
                const auto u = static_cast<std::size_t>(v);
                if (fanned[u] || (u < excluded.size() && excluded[u])) continue;
                // A plane node whose chain failed to close at its other end is unclosed.
                const bool to_boundary = (boundary[u] && anchor[u] == Vec3::Zero()) ||
                                         reaches_boundary[static_cast<std::size_t>(chains.find(v))];
                auto [it, fresh] = why.emplace(v, to_boundary ? NoFan::Open : NoFan::Unclosed);
                if (!fresh && to_boundary) it->second = NoFan::Open;
            }
        }
        fw.unfanned.assign(why.begin(), why.end());
        return std::move(fw);
    };
    if (!any_seed) return explain(out);
    std::vector<char> seeded(un, 0);
    for (std::size_t e = 0; e < ne; ++e)
        if (keep[e] && turn[e] >= fan_angle_deg) seeded[static_cast<std::size_t>(chains.find(et.nodes[e][0]))] = 1;
    for (std::size_t e = 0; e < ne; ++e)
        if (keep[e] && !seeded[static_cast<std::size_t>(chains.find(et.nodes[e][0]))]) keep[e] = 0;

    // Where a chain may end (prune): a plane node, or a terminal: a node off the open boundary,
    // not excluded, on an edge turning fan_angle_deg or more (at a concave junction, where the
    // edge fades into a smooth wall, or beside a node whose fan was dropped). Such a node's one
    // column stops at the wall, as it would without a fan; a node of a milder edge only (a tip
    // cap's) keeps one growing direction instead, its chain without a fan.
    std::vector<char> ends(un, 0);
    for (std::size_t i = 0; i < un; ++i) ends[i] = anchor[i] != Vec3::Zero();
    for (std::size_t e = 0; e < ne; ++e)
        if (keep[e] && turn[e] >= fan_angle_deg)
            for (const Index v : et.nodes[e]) ends[static_cast<std::size_t>(v)] |= !open[static_cast<std::size_t>(v)];
    // Each round drops one fan edge, so this ends.
    for (;;) {
        const std::vector<std::vector<Index>> at = prune(et, un, anchor, ends, keep);
        if (std::none_of(keep.begin(), keep.end(), [](char k) { return k != 0; })) return explain(out);
        std::vector<Index> bad;
        FanWall fw = assemble(wall, et, keep, at, turn, anchor, plane_reach, bad);
        if (bad.empty()) return explain(fw);
        for (const Index e : bad) keep[static_cast<std::size_t>(e)] = 0;
    }
}

std::vector<char> sharp_single_nodes(const SurfaceMesh& wall, const std::vector<Vec3>& plane_normal,
                                     double min_turn_deg) {
    const auto n = static_cast<std::size_t>(wall.num_points());
    std::vector<char> sharp(n, 0);
    const EdgeTable et = edge_table(wall);
    for (Index e = 0; e < et.faces.rows(); ++e) {
        const Index a = et.nodes[static_cast<std::size_t>(e)][0], b = et.nodes[static_cast<std::size_t>(e)][1];
        const Index* fs = et.faces.row_begin(e);
        const Vec3 nf = unit(face_area_vector(wall, fs[0]));
        if (nf == Vec3::Zero()) continue;
        const Vec3 cf = face_centroid(wall, wall.points, fs[0]);
        const Vec3& pa = wall.points[a];
        double turn = -1.0;
        if (et.faces.row_size(e) == 2) {
            const Vec3 ng = unit(face_area_vector(wall, fs[1]));
            if (ng == Vec3::Zero()) continue;
            turn = convex_turn_deg(nf, cf, ng, face_centroid(wall, wall.points, fs[1]), pa);
        } else if (et.faces.row_size(e) == 1 && static_cast<std::size_t>(b) < plane_normal.size()) {
            const Vec3& p = plane_normal[static_cast<std::size_t>(a)];
            if (p == Vec3::Zero() || (p - plane_normal[static_cast<std::size_t>(b)]).norm() > 1e-12) continue;
            turn = convex_turn_deg(nf, cf, nf - 2.0 * nf.dot(p) * p, cf - 2.0 * (cf - pa).dot(p) * p, pa);
        }
        if (turn >= min_turn_deg) sharp[static_cast<std::size_t>(a)] = sharp[static_cast<std::size_t>(b)] = 1;
    }
    return sharp;
}

bool collapse_cell(CellType& type, std::array<Index, 8>& id) {
    const int n = type == CellType::Tet ? 4 : type == CellType::Pyramid ? 5 : type == CellType::Prism ? 6 : 8;
    std::vector<Index> distinct(id.begin(), id.begin() + n);
    std::sort(distinct.begin(), distinct.end());
    distinct.erase(std::unique(distinct.begin(), distinct.end()), distinct.end());
    if (static_cast<int>(distinct.size()) == n) return true;
    const std::array<Index, 8> v = id;
    if (type == CellType::Prism && v[0] == v[1] && v[1] == v[2]) {  // the apex below the top
        id = {v[3], v[5], v[4], v[0], kNone, kNone, kNone, kNone};
        type = CellType::Tet;
        return distinct.size() == 4;
    }
    if (distinct.size() == 4 && type != CellType::Hex) {
        // Four distinct nodes of a prism or pyramid: a tetrahedron, its order from the cell's.
        std::array<Index, 8> t{};
        int k = 0;
        for (int c = 0; c < n; ++c)
            if (std::find(t.begin(), t.begin() + k, v[static_cast<std::size_t>(c)]) == t.begin() + k)
                t[static_cast<std::size_t>(k++)] = v[static_cast<std::size_t>(c)];
        type = CellType::Tet;
        id = t;
        return true;
    }
    if (type == CellType::Hex && distinct.size() == 5 && v[0] == v[1] && v[1] == v[2] && v[2] == v[3]) {
        id = {v[4], v[7], v[6], v[5], v[0], kNone, kNone, kNone};  // the apex below the top
        type = CellType::Pyramid;
        return true;
    }
    if (type == CellType::Hex && distinct.size() == 6) {
        if (v[0] == v[3] && v[1] == v[2]) {
            id = {v[0], v[7], v[4], v[1], v[6], v[5], kNone, kNone};
        } else if (v[0] == v[1] && v[2] == v[3]) {
            id = {v[0], v[4], v[5], v[3], v[7], v[6], kNone, kNone};
        } else {
            return false;
        }
        type = CellType::Prism;
        return true;
    }
    if (type == CellType::Prism && distinct.size() == 5) {
        for (int c = 0; c < 3; ++c)
            if (v[static_cast<std::size_t>(c)] == v[static_cast<std::size_t>(c + 3)]) {
                // A collapsed vertical edge: a pyramid on the opposite side face.
                const int a = (c + 1) % 3, b = (c + 2) % 3;
                id = {v[static_cast<std::size_t>(a)],
                      v[static_cast<std::size_t>(a + 3)],
                      v[static_cast<std::size_t>(b + 3)],
                      v[static_cast<std::size_t>(b)],
                      v[static_cast<std::size_t>(c)],
                      kNone,
                      kNone,
                      kNone};
                type = CellType::Pyramid;
                return true;
            }
    }
    return false;
}

}  // namespace strata
