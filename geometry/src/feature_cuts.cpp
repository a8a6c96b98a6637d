// Cuts that make every long sharp edge a boundary between regions: feature_cuts.h.

#include <strata/core/union_find.h>
#include <strata/geometry/feature_cuts.h>
#include <strata/geometry/topology.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <tuple>

namespace strata {
namespace {

constexpr double kPi = 3.141592653589793;
/// A sharp edge whose faces' normals differ by more than 100 degrees (a wedge under 80 degrees)
/// is cut out of its region: a new face across it would fold. Milder creases inside a region
/// are left to Gmsh, which rounds them (as without cuts). Above 90 so that a box's right
/// angles, whose normals' product rounds either side of 0, never count.
const double kCosFolding = std::cos(100.0 * kPi / 180.0);

/// One undirected edge and the triangles on it.
struct Edge {
    Index a = 0, b = 0;  ///< a < b
    Index t0 = kNone, t1 = kNone;
    bool t0_has_ab = false;  ///< t0 runs a → b (so t1, if consistent, runs b → a)
    bool manifold = false;   ///< exactly two triangles
    bool sharp = false;
    bool barrier = false;
};

/// The triangles' edges from geometry/topology.h's edge table, sorted by (a, b), t0 < t1.
std::vector<Edge> edges_of(const std::vector<Vec3>& points, const std::vector<std::array<Index, 3>>& triangles) {
    SurfaceMesh mesh;
    mesh.points = points;
    for (const auto& t : triangles) mesh.add_face(t.data(), 3, 0);
    const EdgeTable table = edge_table(mesh);
    std::vector<Edge> edges(table.nodes.size());
    for (std::size_t i = 0; i < edges.size(); ++i) {
        Edge& e = edges[i];
        e.a = table.nodes[i][0];
        e.b = table.nodes[i][1];
        const auto k = static_cast<Index>(i);
        e.t0 = *table.faces.row_begin(k);
        e.manifold = table.faces.row_size(k) == 2;
        if (e.manifold) e.t1 = table.faces.row_begin(k)[1];
        const auto& tri = triangles[static_cast<std::size_t>(e.t0)];
        for (int j = 0; j < 3; ++j)
            e.t0_has_ab |= tri[static_cast<std::size_t>(j)] == e.a && tri[static_cast<std::size_t>((j + 1) % 3)] == e.b;
    }
    return edges;
}

bool passable(const Edge& e) {
    return e.manifold && !e.sharp && !e.barrier;
}

/// Each triangle's unit normal (zero where degenerate) and centre.
struct TriangleFrames {
    std::vector<Vec3> normal, centre;
};

TriangleFrames frames_of(const std::vector<Vec3>& points, const std::vector<std::array<Index, 3>>& triangles) {
    const std::size_t nt = triangles.size();
    auto at = [&](Index v) -> const Vec3& { return points[static_cast<std::size_t>(v)]; };
    TriangleFrames fr;
    fr.normal.resize(nt);
    fr.centre.resize(nt);
    for (std::size_t t = 0; t < nt; ++t) {
        const auto& tri = triangles[t];
        const Vec3 n = (at(tri[1]) - at(tri[0])).cross(at(tri[2]) - at(tri[0]));
        const double len = n.norm();
        fr.normal[t] = len > 0.0 && std::isfinite(len) ? Vec3(n / len) : Vec3::Zero();
        fr.centre[t] = (at(tri[0]) + at(tri[1]) + at(tri[2])) / 3.0;
    }
    return fr;
}

/// The positions in \p edges of the sharp edges inside one region (regions: triangles joined
/// across passable edges) whose faces would fold if a new face crossed them.
std::vector<std::size_t> inner_sharp_edges(const std::vector<Edge>& edges, const std::vector<Vec3>& normal) {
    UnionFind regions(normal.size());
    for (const Edge& e : edges)
        if (passable(e)) regions.unite(e.t0, e.t1);
    std::vector<std::size_t> inner;
    for (std::size_t i = 0; i < edges.size(); ++i) {
        const Edge& e = edges[i];
        if (e.manifold && e.sharp && !e.barrier && regions.find(e.t0) == regions.find(e.t1) &&
            normal[static_cast<std::size_t>(e.t0)].dot(normal[static_cast<std::size_t>(e.t1)]) < kCosFolding)
            inner.push_back(i);
    }
    return inner;
}

/// A chain: (position in inner, walked a → b) of each of its edges, in order.
using Chain = std::vector<std::pair<std::size_t, bool>>;

/// Chains: paths of inner edges through nodes with two of them. Open chains start at their ends
/// (or at branch nodes); the rest are loops.
std::vector<Chain> chains_of(const std::vector<Edge>& edges, const std::vector<std::size_t>& inner) {
    // (node, inner edge) pairs, sorted by node, give each node's inner edges.
    std::vector<std::pair<Index, std::size_t>> incident;
    for (std::size_t k = 0; k < inner.size(); ++k) {
        incident.emplace_back(edges[inner[k]].a, k);
        incident.emplace_back(edges[inner[k]].b, k);
    }
    std::sort(incident.begin(), incident.end());
    auto at_node = [&](Index v) {
        const auto lo = std::lower_bound(incident.begin(), incident.end(), std::make_pair(v, std::size_t{0}));
        auto hi = lo;
        while (hi != incident.end() && hi->first == v) ++hi;
        return std::make_pair(lo, hi);
    };
    auto degree = [&](Index v) {
        const auto [lo, hi] = at_node(v);
        return hi - lo;
    };
    std::vector<char> walked(inner.size(), 0);
    std::vector<Chain> chains;
    auto walk = [&](Index from, std::size_t k) {
        Chain chain;
        while (true) {
            walked[k] = 1;
            const Edge& e = edges[inner[k]];
            const bool forward = e.a == from;
            chain.emplace_back(k, forward);
            const Index to = forward ? e.b : e.a;
            if (degree(to) != 2) break;
            const auto [lo, hi] = at_node(to);
            const std::size_t next = lo->second == k ? (lo + 1)->second : lo->second;
            if (walked[next]) break;
            from = to;
            k = next;
        }
        chains.push_back(std::move(chain));
    };
    for (const auto& [v, k] : incident)
        if (!walked[k] && degree(v) != 2) walk(v, k);
    for (std::size_t k = 0; k < inner.size(); ++k)
        if (!walked[k]) walk(edges[inner[k]].a, k);
    return chains;
}

/// Each triangle's label and distance to its seed.
struct Labels {
    std::vector<Index> label;
    std::vector<double> dist;
};

/// Each chain at least \p min_length long seeds labels 2c and 2c + 1 on its two sides (c counts
/// the long chains; the triangle running along the chain's direction is side 0), at distance 0;
/// the other triangles have none, at infinity. \p kept: the number of long chains.
Labels seed_sides(const std::vector<Vec3>& points, const std::vector<Edge>& edges,
                  const std::vector<std::size_t>& inner, const std::vector<Chain>& chains, std::size_t nt,
                  double min_length, Index& kept) {
    auto at = [&](Index v) -> const Vec3& { return points[static_cast<std::size_t>(v)]; };
    Labels s{std::vector<Index>(nt, kNone), std::vector<double>(nt, std::numeric_limits<double>::infinity())};
    kept = 0;
    for (const auto& chain : chains) {
        double length = 0.0;
        for (const auto& [k, fwd] : chain) length += (at(edges[inner[k]].b) - at(edges[inner[k]].a)).norm();
        if (!(length >= min_length)) continue;
        for (const auto& [k, fwd] : chain) {
            const Edge& e = edges[inner[k]];
            const bool t0_along = e.t0_has_ab == fwd;
            const Index side0 = t0_along ? e.t0 : e.t1, side1 = t0_along ? e.t1 : e.t0;
            for (const auto& [t, l] : {std::pair{side0, 2 * kept}, std::pair{side1, 2 * kept + 1}}) {
                Index& mine = s.label[static_cast<std::size_t>(t)];
                if (mine == kNone || l < mine) mine = l;
                s.dist[static_cast<std::size_t>(t)] = 0.0;
            }
        }
        ++kept;
    }
    return s;
}

/// Triangle adjacency across passable edges, then a Dijkstra from every seed at once over
/// centre-to-centre distances: each triangle takes the label of the nearest side.
void grow_labels(const std::vector<Edge>& edges, const std::vector<Vec3>& centre, Labels& s) {
    std::vector<std::pair<Index, Index>> links;  // (triangle, neighbour), both ways
    for (const Edge& e : edges)
        if (passable(e)) {
            links.emplace_back(e.t0, e.t1);
            links.emplace_back(e.t1, e.t0);
        }
    std::sort(links.begin(), links.end());
    std::vector<Index>& label = s.label;
    std::vector<double>& dist = s.dist;
    using Item = std::tuple<double, Index, Index>;  // distance, label, triangle
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
    for (std::size_t t = 0; t < label.size(); ++t)
        if (label[t] != kNone) queue.emplace(0.0, label[t], static_cast<Index>(t));
    while (!queue.empty()) {
        const auto [d, l, t] = queue.top();
        queue.pop();
        if (d != dist[static_cast<std::size_t>(t)] || l != label[static_cast<std::size_t>(t)]) continue;
        auto lo = std::lower_bound(links.begin(), links.end(), std::make_pair(t, Index{0}));
        for (; lo != links.end() && lo->first == t; ++lo) {
            const auto u = static_cast<std::size_t>(lo->second);
            const double du = d + (centre[u] - centre[static_cast<std::size_t>(t)]).norm();
            if (du < dist[u] || (du == dist[u] && l < label[u])) {
                dist[u] = du;
                label[u] = l;
                queue.emplace(du, l, lo->second);
            }
        }
    }
}

}  // namespace

std::vector<std::array<Index, 2>> feature_cuts(const std::vector<Vec3>& points,
                                               const std::vector<std::array<Index, 3>>& triangles,
                                               const std::vector<std::array<Index, 2>>& barriers,
                                               double feature_angle_deg, double min_length) {
    const TriangleFrames fr = frames_of(points, triangles);
    std::vector<Edge> edges = edges_of(points, triangles);
    const double cos_feature = std::cos(feature_angle_deg * kPi / 180.0);
    for (Edge& e : edges) {
        e.barrier = std::binary_search(barriers.begin(), barriers.end(), std::array<Index, 2>{e.a, e.b});
        if (!e.manifold) continue;
        const Vec3 &n0 = fr.normal[static_cast<std::size_t>(e.t0)], &n1 = fr.normal[static_cast<std::size_t>(e.t1)];
        e.sharp = !n0.isZero() && !n1.isZero() && n0.dot(n1) < cos_feature;
    }
    const std::vector<std::size_t> inner = inner_sharp_edges(edges, fr.normal);
    if (inner.empty()) return {};
    const std::vector<Chain> chains = chains_of(edges, inner);
    Index kept = 0;
    Labels labels = seed_sides(points, edges, inner, chains, triangles.size(), min_length, kept);
    if (kept == 0) return {};
    grow_labels(edges, fr.centre, labels);
    std::vector<std::array<Index, 2>> cuts;
    for (const Edge& e : edges)
        if (e.manifold && !e.barrier) {
            const Index l0 = labels.label[static_cast<std::size_t>(e.t0)];
            const Index l1 = labels.label[static_cast<std::size_t>(e.t1)];
            if (l0 != kNone && l1 != kNone && l0 != l1) cuts.push_back({e.a, e.b});
        }
    return cuts;  // the edge table sorted them
}

}  // namespace strata
