#include "wall_size.h"

#include <strata/core/face_geometry.h>
#include <strata/core/format.h>
#include <strata/core/solver_checks.h>
#include <strata/core/union_find.h>
#include <strata/io/gmsh_session.h>

#include <gmsh.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <map>
#include <numbers>
#include <optional>

namespace strata {

void EntitySizes::cap(int dim, int tag, double size) {
    const auto [it, fresh] = size_.emplace(std::make_pair(dim, tag), size);
    if (!fresh) it->second = std::min(it->second, size);
}

void EntitySizes::cap_boundary(int dim, int tag, double size) {
    gmsh::vectorpair down;
    gmsh::model::getBoundary({{dim, tag}}, down, false, false, true);  // recursive: down to the points
    for (const auto& [d, t] : down) cap(d, std::abs(t), size);
    if (dim == 2) {
        down.clear();
        gmsh::model::getBoundary({{dim, tag}}, down, false, false, false);  // the curves
        for (const auto& [d, t] : down) cap(d, std::abs(t), size);
    }
}

void EntitySizes::cap_surface(int tag, double size) {
    cap(2, tag, size);
    cap_boundary(2, tag, size);
}

void EntitySizes::cap_curve(int tag, double size) {
    cap(1, tag, size);
    cap_boundary(1, tag, size);
}

SizeCallback::SizeCallback(const EntitySizes& sizes, double factor, const std::vector<const PointSizes*>& points)
    : size_(sizes.sizes()), factor_(factor) {
    for (const PointSizes* p : points)
        if (p && !p->empty()) points_.push_back(p);
    for (auto& [entity, size] : size_) size /= factor;
    gmsh::model::mesh::setSizeCallback([this](int dim, int tag, double x, double y, double z) {
        const auto it = size_.find({dim, tag});
        double size = it == size_.end() ? 1e22 : it->second;
        for (const PointSizes* p : points_) size = std::min(size, (*p)(Vec3(x, y, z)) / factor_);
        return size;
    });
}

SizeCallback::~SizeCallback() {
    try {
        gmsh::model::mesh::removeSizeCallback();
    } catch (...) {  // Gmsh's API reports through exceptions; a destructor must not throw
    }
}

namespace {

/// What a cap aims at, as a share of the limit: Gmsh's edges run up to 1.4 times the size asked.
constexpr double kCapShare = 0.7;

/// The point of each mesh node, to find Gmsh's curve nodes in \p mesh (the same coordinates).
std::map<std::array<double, 3>, Index> node_at(const SurfaceMesh& mesh) {
    std::map<std::array<double, 3>, Index> at;
    for (Index i = 0; i < mesh.num_points(); ++i) {
        const Vec3& p = mesh.points[static_cast<std::size_t>(i)];
        at.emplace(std::array<double, 3>{p.x(), p.y(), p.z()}, i);
    }
    return at;
}

/// A column leaning more than this off a face's normal stands on an edge of 110 degrees or more
/// (twice it): without a fan, the layers stop at the wall there (module's --sharp-edge-stop
/// default; module/ is above geometry/, so it is not shared) and the face gets no cell.
constexpr double kStopLeanDeg = 55.0;

/// The nodes before and after \p v in each face of \p fs (faces round \p v).
void corner_neighbours(const SurfaceMesh& mesh, Index v, const std::vector<Index>& fs, std::vector<Index>& before,
                       std::vector<Index>& after) {
    before.assign(fs.size(), kNone);
    after.assign(fs.size(), kNone);
    for (std::size_t i = 0; i < fs.size(); ++i) {
        const Index f = fs[i], n = mesh.face_size(f);
        for (Index c = 0; c < n; ++c)
            if (mesh.face_node(f, c) == v) {
                before[i] = mesh.face_node(f, (c + n - 1) % n);
                after[i] = mesh.face_node(f, (c + 1) % n);
            }
    }
}

/// The faces round a node, given by their nodes \p before and \p after it (corner_neighbours),
/// oriented alike across the edges they share (Gmsh orients each surface by its own
/// parametrization, so the mesh's faces need not agree): +1 per face oriented as the first, -1
/// turned round; empty where they cannot be (a non-manifold node, or faces not all joined).
std::vector<int> orient_round(const std::vector<Index>& before, const std::vector<Index>& after) {
    const std::size_t k = before.size();
    if (k == 0) return {};
    // Breadth-first from the first face: a neighbour across edge v-w runs it the other way
    // when the two agree.
    std::vector<int> sign(k, 0);
    sign[0] = 1;
    for (std::vector<std::size_t> queue{0}; !queue.empty();) {
        const std::size_t i = queue.back();
        queue.pop_back();
        for (std::size_t j = 0; j < k; ++j) {
            if (j == i) continue;
            int relation = 0;  // +1: the same orientation, -1: opposite
            if (after[i] == before[j] || before[i] == after[j]) relation = 1;
            if (after[i] == after[j] || before[i] == before[j]) relation = relation == 0 ? -1 : 2;
            if (relation == 0) continue;
            if (relation == 2) return {};
            if (sign[j] == 0) {
                sign[j] = sign[i] * relation;
                queue.push_back(j);
            } else if (sign[j] != sign[i] * relation) {
                return {};
            }
        }
    }
    if (std::find(sign.begin(), sign.end(), 0) != sign.end()) return {};
    return sign;
}

/// The direction a column starts along at each node of \p faces_at (node → its wall faces): the
/// corner-angle weighted mean of those faces' normals, oriented consistently round the node
/// across the edges they share (Gmsh orients each surface by its own parametrization, so the
/// mesh's faces need not agree). Zero where the faces round a node cannot be oriented so (a
/// non-manifold node) or cancel.
std::map<Index, Vec3> start_directions(const SurfaceMesh& mesh, const std::map<Index, std::vector<Index>>& faces_at) {
    std::map<Index, Vec3> out;
    for (const auto& [v, fs] : faces_at) {
        const std::size_t k = fs.size();
        // Each face's nodes before and after v, its normal and its corner angle at v.
        std::vector<Index> before, after;
        corner_neighbours(mesh, v, fs, before, after);
        std::vector<Vec3> normal(k);
        std::vector<double> angle(k);
        for (std::size_t i = 0; i < k; ++i) {
            const Vec3& x = mesh.points[static_cast<std::size_t>(v)];
            const Vec3 a = mesh.points[static_cast<std::size_t>(after[i])] - x,
                       b = mesh.points[static_cast<std::size_t>(before[i])] - x;
            normal[i] = face_area_vector(mesh, fs[i]).normalized();
            angle[i] = std::atan2(a.cross(b).norm(), a.dot(b));
        }
        const std::vector<int> sign = orient_round(before, after);
        const bool consistent = !sign.empty();
        Vec3 d = Vec3::Zero();
        double total = 0.0;
        for (std::size_t i = 0; i < k && consistent; ++i) {
            d += static_cast<double>(sign[i]) * angle[i] * normal[i];
            total += angle[i];
        }
        // Normals that cancel (faces back to back, as two bodies' copies of the face they touch
        // along) leave rounding, not a direction.
        out[v] = consistent && d.norm() > 1e-6 * total ? Vec3(d.normalized()) : Vec3(Vec3::Zero());
    }
    return out;
}

/// Round the end points of the sharp curves: which curves there are of one kind, and how many
/// other sharp edges of each kind the point's node has (curve_kinds).
struct CurveKinds {
    /// (curve, end point) → the kind of the curve's edge at the point's node: +1 or -1, the same
    /// for two edges both convex or both concave there (the faces round the node oriented alike
    /// through the edges they share, as Gmsh's surfaces each have their own orientation); 0
    /// where it cannot be told (no mesh node at the point, a node whose faces do not orient).
    std::map<std::pair<int, int>, int> kind;
    /// (end point, kind) → the edges of the point's node that turn kChainDeg or more and lie on
    /// no sharp curve (a coarse wall's facets, through which fans.cpp's chains run too).
    std::map<std::pair<int, int>, int> facets;
    /// The kind of curve \p c at its end point \p q (0 where unknown).
    int kind_at(int c, int q) const {
        const auto it = kind.find({c, q});
        return it == kind.end() ? 0 : it->second;
    }
};

/// CurveKinds for the sharp curves \p points_of (curve → its end points); \p edges_of gives a
/// curve's sharp edges as (node, node, face, face), \p chain_deg the turn that makes an edge sharp.
template <class EdgesOf>
CurveKinds curve_kinds(const SurfaceMesh& mesh, const std::map<std::array<double, 3>, Index>& at,
                       const std::map<std::array<Index, 2>, std::vector<Index>>& faces_of_edge,
                       const std::map<Index, std::vector<Index>>& faces_at,
                       const std::map<int, std::vector<int>>& points_of, EdgesOf&& edges_of, double chain_deg) {
    CurveKinds out;
    std::map<int, std::vector<int>> curves_at;  // point → its sharp curves
    for (const auto& [c, pts] : points_of)
        for (const int q : pts) curves_at[q].push_back(c);
    for (const auto& [q, cs] : curves_at) {
        std::vector<std::size_t> tags;
        std::vector<double> xyz, uvw;
        gmsh::model::mesh::getNodes(tags, xyz, uvw, 0, q, false, false);
        if (xyz.size() < 3) continue;
        const auto node = at.find({xyz[0], xyz[1], xyz[2]});
        if (node == at.end()) continue;
        const Index p = node->second;
        const auto round = faces_at.find(p);
        if (round == faces_at.end()) continue;
        const std::vector<Index>& fs = round->second;
        std::vector<Index> before, after;
        corner_neighbours(mesh, p, fs, before, after);
        const std::vector<int> sign = orient_round(before, after);  // the faces round p oriented alike
        if (sign.empty()) continue;
        // The kind of edge (p, x) between faces f and g, and its turn in degrees.
        auto kind_of = [&](Index f, Index g, double* turn) {
            const auto i = std::find(fs.begin(), fs.end(), f), j = std::find(fs.begin(), fs.end(), g);
            if (i == fs.end() || j == fs.end()) return 0;
            const Vec3 n1 = static_cast<double>(sign[static_cast<std::size_t>(i - fs.begin())]) *
                            face_area_vector(mesh, f).normalized();
            const Vec3 n2 = static_cast<double>(sign[static_cast<std::size_t>(j - fs.begin())]) *
                            face_area_vector(mesh, g).normalized();
            if (turn) *turn = std::acos(std::clamp(n1.dot(n2), -1.0, 1.0)) * 180.0 / std::numbers::pi;
            const Vec3 to2 = face_centroid(mesh, mesh.points, g) - mesh.points[static_cast<std::size_t>(p)];
            return n1.dot(to2) < 0.0 ? 1 : -1;  // the other face below the first: convex
        };
        std::set<Index> on_curves;  // other ends of p's edges on sharp curves
        for (const int c : cs)
            for (const auto& e : edges_of(c)) {
                if (e[0] != p && e[1] != p) continue;
                on_curves.insert(e[0] == p ? e[1] : e[0]);
                if (const int k = kind_of(e[2], e[3], nullptr)) out.kind[{c, q}] = k;
                break;
            }
        std::set<Index> others(after.begin(), after.end());  // p's neighbours
        others.insert(before.begin(), before.end());
        for (const Index x : others) {
            const auto e = faces_of_edge.find({std::min(p, x), std::max(p, x)});
            if (on_curves.count(x) || e == faces_of_edge.end() || e->second.size() != 2) continue;
            double turn = 0.0;
            const int k = kind_of(e->second[0], e->second[1], &turn);
            if (k != 0 && turn >= chain_deg) ++out.facets[{q, k}];
        }
    }
    return out;
}

/// fans.cpp's kFeatureDeg and kWedgeDeg (module/ is above geometry/: they cannot be shared):
/// the turn of the convex edges that close a fan's chain, and the widest wedge of a fan.
constexpr double kChainDeg = 30.0, kWedgeDeg = 90.0;

/// A wall edge on a curve between two wall surfaces that turns kChainDeg or more: its ends and
/// nodes, its faces and their normals (oriented alike), and its turn in degrees.
struct SharpEdge {
    Vec3 a, b, n1, n2;
    double turn;
    Index ia = kNone, ib = kNone, f1 = kNone, f2 = kNone;
};

/// The curves between two wall surfaces with sharp edges (SharpEdge).
struct SharpCurves {
    std::map<int, std::vector<SharpEdge>> edges_of;  ///< curve → its sharp edges
    std::map<int, double> sharpest;                  ///< curve → its largest turn
};

/// The sharp edges of the Gmsh curve \p c, found in \p mesh by their nodes' points (\p at),
/// added to \p s.
void add_sharp_edges(const SurfaceMesh& mesh, int c, const std::map<std::array<double, 3>, Index>& at,
                     const std::map<std::array<Index, 2>, std::vector<Index>>& faces_of_edge, SharpCurves& s) {
    std::vector<std::size_t> tags, line_nodes;
    std::vector<double> xyz, uvw;
    gmsh::model::mesh::getNodes(tags, xyz, uvw, 1, c, true, false);
    std::map<std::size_t, Index> index_of;
    for (std::size_t i = 0; i < tags.size(); ++i) {
        const auto it = at.find({xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]});
        if (it != at.end()) index_of.emplace(tags[i], it->second);
    }
    std::vector<std::size_t> line_tags;
    gmsh::model::mesh::getElementsByType(1, line_tags, line_nodes, c);
    for (std::size_t l = 0; l + 1 < line_nodes.size(); l += 2) {
        const auto ia = index_of.find(line_nodes[l]), ib = index_of.find(line_nodes[l + 1]);
        if (ia == index_of.end() || ib == index_of.end()) continue;
        const Index a = ia->second, b = ib->second;
        const auto fe = faces_of_edge.find({std::min(a, b), std::max(a, b)});
        if (fe == faces_of_edge.end() || fe->second.size() != 2) continue;
        const Index f1 = fe->second[0], f2 = fe->second[1];
        // Gmsh orients each surface by its own parametrization: one whose faces run the edge the
        // same way as the other's is turned round.
        auto runs_forward = [&](Index f) {
            for (Index i = 0, n = mesh.face_size(f); i < n; ++i)
                if (mesh.face_node(f, i) == a) return mesh.face_node(f, (i + 1) % n) == b;
            return false;
        };
        const Vec3 n1 = face_area_vector(mesh, f1).normalized();
        Vec3 n2 = face_area_vector(mesh, f2).normalized();
        if (runs_forward(f1) == runs_forward(f2)) n2 = -n2;
        const double turn = std::acos(std::clamp(n1.dot(n2), -1.0, 1.0)) * 180.0 / std::numbers::pi;
        // Faces back to back (two bodies' copies of the face they touch along, which --fuse
        // removes) are not an edge of the wall.
        if (!(turn >= kChainDeg) || (n2 - n1.dot(n2) * n1).norm() < 1e-6) continue;
        s.edges_of[c].push_back({mesh.points[static_cast<std::size_t>(a)], mesh.points[static_cast<std::size_t>(b)], n1,
                                 n2, turn, a, b, f1, f2});
        double& m = s.sharpest[c];
        m = std::max(m, turn);
    }
}

/// The sharp curves between two wall surfaces of \p walls (each such curve's wall surfaces into
/// \p curve_up).
SharpCurves sharp_curves(const SurfaceMesh& mesh, const std::set<int>& walls,
                         const std::map<std::array<double, 3>, Index>& at,
                         const std::map<std::array<Index, 2>, std::vector<Index>>& faces_of_edge,
                         std::map<int, std::vector<int>>& curve_up) {
    SharpCurves s;
    gmsh::vectorpair curves;
    gmsh::model::getEntities(curves, 1);
    for (const auto& [dim, c] : curves) {
        std::vector<int> up, down;
        gmsh::model::getAdjacencies(1, c, up, down);
        if (up.size() != 2 || !walls.count(up[0]) || !walls.count(up[1])) continue;
        curve_up[c] = up;
        add_sharp_edges(mesh, c, at, faces_of_edge, s);
    }
    return s;
}

/// Drops the sharp curves (from \p points_of, curve → its end points, and \p sharpest) of
/// chains that do not close: two sharp curves meeting at a point are of one chain where they
/// are of one kind there (\p kinds: both convex or both concave, told apart round the point's
/// node, the only orientation known here), and a chain's curve that ends on a point with no
/// other curve of its kind goes (the graph's 2-core), unless that point lies on a surface that
/// is not a wall (a chain may end on a symmetry plane), or its node has sharp edges of the
/// curve's kind off the curves (a coarse wall's facets, through which fans.cpp's chains go on).
/// Otherwise walls would be meshed finer for fans that fans.cpp then does not build.
void prune_open_chains(const CurveKinds& kinds, const std::set<int>& walls, std::map<int, std::vector<int>>& points_of,
                       std::map<int, double>& sharpest) {
    // (point, kind) → curve ends there, and the sharp facets a chain may go on through
    std::map<std::pair<int, int>, int> degree = kinds.facets;
    for (const auto& [c, pts] : points_of)
        for (const int q : pts) ++degree[{q, kinds.kind_at(c, q)}];
    std::map<int, bool> open_end;  // point → on a surface that is not a wall
    auto plane_point = [&](int q) {
        const auto [it, fresh] = open_end.emplace(q, false);
        if (fresh) {
            std::vector<int> up, down;
            gmsh::model::getAdjacencies(0, q, up, down);
            for (const int c : up) {
                std::vector<int> sides, ends;
                gmsh::model::getAdjacencies(1, std::abs(c), sides, ends);
                for (const int f : sides) it->second = it->second || !walls.count(f);
            }
        }
        return it->second;
    };
    for (bool pruned = true; pruned;) {
        pruned = false;
        for (auto it = points_of.begin(); it != points_of.end();) {
            const int c = it->first;
            const bool loose = std::any_of(it->second.begin(), it->second.end(), [&](int q) {
                return degree[{q, kinds.kind_at(c, q)}] < 2 && !plane_point(q);
            });
            if (!loose) {
                ++it;
                continue;
            }
            for (const int q : it->second) --degree[{q, kinds.kind_at(c, q)}];
            sharpest.erase(c);
            it = points_of.erase(it);
            pruned = true;
        }
    }
}

/// Each sharp curve of \p points_of (curve → its end points) → its chain (the lowest index, in
/// tag order, of the sharp curves joined to it through end points where they are of one kind).
std::map<int, Index> chains_of(const std::map<int, std::vector<int>>& points_of, const CurveKinds& kinds) {
    std::map<int, std::size_t> index_of;
    for (const auto& [c, pts] : points_of) index_of.emplace(c, index_of.size());
    UnionFind joined(index_of.size());
    std::map<std::pair<int, int>, std::size_t> first_at;  // (point, kind) → the first sharp curve on it
    for (const auto& [c, pts] : points_of)
        for (const int q : pts) {
            const auto [it, added] = first_at.emplace(std::make_pair(q, kinds.kind_at(c, q)), index_of[c]);
            if (!added) joined.unite(static_cast<Index>(it->second), static_cast<Index>(index_of[c]));
        }
    std::map<int, Index> chain;
    for (const auto& [c, i] : index_of) chain[c] = joined.find(static_cast<Index>(i));
    return chain;
}

/// Adds to the fan curves \p fan the sharp curves that share an end point with one, of its
/// kind there.
void add_fan_neighbours(const std::map<int, std::vector<int>>& points_of, const CurveKinds& kinds, std::set<int>& fan) {
    std::set<std::pair<int, int>> fan_points;
    for (int c : fan)
        for (int q : points_of.at(c)) fan_points.insert({q, kinds.kind_at(c, q)});
    // An init-capture: clang 14 cannot capture a structured binding (scripts/fuzz.sh builds with it).
    for (const auto& [c, pts] : points_of)
        if (std::any_of(pts.begin(), pts.end(), [&, curve = c](int q) {
                return fan_points.count({q, kinds.kind_at(curve, q)}) > 0;
            }))
            fan.insert(c);
}

/// Adds the mesh nodes (found by their points, \p at) of the curves \p chain to \p fan_nodes.
void add_curve_nodes(const std::set<int>& chain, const std::map<std::array<double, 3>, Index>& at,
                     std::set<Index>& fan_nodes) {
    for (int c : chain) {
        std::vector<std::size_t> tags;
        std::vector<double> xyz, uvw;
        gmsh::model::mesh::getNodes(tags, xyz, uvw, 1, c, true, false);
        for (std::size_t i = 0; i < tags.size(); ++i) {
            const auto it = at.find({xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]});
            if (it != at.end()) fan_nodes.insert(it->second);
        }
    }
}

/// Wedges per curve of \p chain: as many as the sharpest curve of its chain (\p chain_of) needs
/// (fans.cpp gives a whole run of fan edges the count of its sharpest: a blade's 90-degree
/// closing edges, in the run of its 160-degree edge, get two wedges of 45 degrees).
std::map<int, int> chain_wedges(const std::set<int>& chain, const std::map<int, Index>& chain_of,
                                const std::map<int, double>& sharpest) {
    std::map<int, int> wedges_of;
    std::map<Index, double> sharpest_of_chain;
    for (const int c : chain) {
        double& m = sharpest_of_chain[chain_of.at(c)];
        m = std::max(m, sharpest.at(c));
    }
    for (const int c : chain)
        wedges_of[c] = std::max(1, static_cast<int>(std::ceil(sharpest_of_chain[chain_of.at(c)] / kWedgeDeg - 1e-9)));
    return wedges_of;
}

/// The first wedge of the fan on each curve of \p fan (its \p wedges_of wedges at most 90 degrees
/// apart, from n1 towards n2) under a first layer of \p h, into \p out: the worst aspect
/// ratio, and on curves over \p limit the edge length that gives kCapShare of it.
void measure_fan_wedges(const std::set<int>& fan, const std::map<int, std::vector<SharpEdge>>& edges_of,
                        const std::map<int, int>& wedges_of, double h, double limit, WallAspect& out) {
    for (int c : fan) {
        double curve_worst = 0.0, need = std::numeric_limits<double>::infinity();
        for (const SharpEdge& e : edges_of.at(c)) {
            const double wedge = e.turn / wedges_of.at(c) * std::numbers::pi / 180.0;
            const Vec3 t = (e.n2 - e.n1.dot(e.n2) * e.n1).normalized();
            const Vec3 d2 = std::cos(wedge) * e.n1 + std::sin(wedge) * t;
            const double ar = fan_wedge_aspect_ratio(e.a, e.b, e.n1, d2, h);
            if (!std::isfinite(ar)) continue;
            curve_worst = std::max(curve_worst, ar);
            // The aspect ratio grows with the edge's length: the length that gives 0.7 of the limit.
            need = std::min(need, (e.b - e.a).norm() * kCapShare * limit / ar);
        }
        out.worst = std::max(out.worst, curve_worst);
        if (curve_worst > limit) out.curve_need[c] = need;
    }
}

/// The fan curves of WallLimits::fan_angle_deg (wall_aspect): each one's first wedge measured
/// into \p out (worst, curve_need), the nodes on every fan curve into \p fan_nodes (their
/// columns start along each side's normal).
void fan_curves(const SurfaceMesh& mesh, const std::set<int>& walls, const WallLimits& params,
                const std::map<std::array<Index, 2>, std::vector<Index>>& faces_of_edge,
                const std::map<Index, std::vector<Index>>& faces_at, WallAspect& out, std::set<Index>& fan_nodes) {
    // Fans: the first cell of a fan on a wall edge whose faces turn by the fan angle or more, and
    // on the convex edges of 30 degrees or more that close its chain (fans.cpp: a wing's tip and
    // root; here the curves of 30 degrees or more of its kind that share an end point with such
    // a curve, on chains that close). Only the curves are meshed finer (Gmsh grades the
    // surfaces beside them from their boundary sizes).
    const auto at = node_at(mesh);
    SharpCurves sharp = sharp_curves(mesh, walls, at, faces_of_edge, out.curve_up);
    std::map<int, std::vector<int>> points_of;  // sharp curve → its end points
    for (const auto& [c, turn] : sharp.sharpest) {
        gmsh::vectorpair ends;
        gmsh::model::getBoundary({{1, c}}, ends, false, false, false);
        for (const auto& [d, t] : ends) points_of[c].push_back(std::abs(t));
    }
    // Without a curve at the fan angle there is no fan and nothing to prune (nor Gmsh to ask).
    const bool any_fan = std::any_of(sharp.sharpest.begin(), sharp.sharpest.end(),
                                     [&](const auto& ct) { return ct.second >= params.fan_angle_deg; });
    const CurveKinds kinds = !any_fan ? CurveKinds{}
                                      : curve_kinds(
                                            mesh, at, faces_of_edge, faces_at, points_of,
                                            [&](int c) {
                                                std::vector<std::array<Index, 4>> e;
                                                for (const SharpEdge& x : sharp.edges_of[c])
                                                    e.push_back({x.ia, x.ib, x.f1, x.f2});
                                                return e;
                                            },
                                            kChainDeg);
    if (any_fan) prune_open_chains(kinds, walls, points_of, sharp.sharpest);
    // The fan curves: those at the fan angle, and the sharp ones that share an end point with them.
    std::set<int> fan;
    for (const auto& [c, turn] : sharp.sharpest)
        if (turn >= params.fan_angle_deg) fan.insert(c);
    // The chains: every sharp curve joined to a fan curve through sharp curves' end points, as
    // fans.cpp's chains run. Their nodes start along each side's normal (fan_nodes); but only
    // the fan curves and their neighbours are sized for the wedges, for the sizing does not
    // predict the cells beside a chain's columns that then stop at the wall.
    const std::map<int, Index> chain_of = chains_of(points_of, kinds);
    std::set<Index> fan_chains;
    for (const int c : fan) fan_chains.insert(chain_of.at(c));
    std::set<int> chain;
    for (const auto& [c, pts] : points_of)
        if (fan_chains.count(chain_of.at(c))) chain.insert(c);
    add_fan_neighbours(points_of, kinds, fan);
    add_curve_nodes(chain, at, fan_nodes);
    measure_fan_wedges(fan, sharp.edges_of, chain_wedges(chain, chain_of, sharp.sharpest), params.first_height,
                       params.max_aspect_ratio, out);
}

/// Each wall surface of \p out's boundary curves: their lengths in the current mesh and the
/// surfaces on their other side (refine_walls' estimate of what a capped neighbour's curves do).
void wall_boundaries(WallAspect& out) {
    std::map<int, double> length;  // curve → its mesh length
    for (const auto& [s, unused] : out.area) {
        std::vector<int> up, down;
        gmsh::model::getAdjacencies(2, s, up, down);
        for (int c : down) {
            c = std::abs(c);
            auto [it, fresh] = length.emplace(c, 0.0);
            if (fresh) {
                std::vector<std::size_t> tags, line_tags, line_nodes;
                std::vector<double> xyz, uvw;
                gmsh::model::mesh::getNodes(tags, xyz, uvw, 1, c, true, false);
                std::map<std::size_t, Vec3> x;
                for (std::size_t i = 0; i < tags.size(); ++i)
                    x[tags[i]] = Vec3(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
                gmsh::model::mesh::getElementsByType(1, line_tags, line_nodes, c);
                for (std::size_t l = 0; l + 1 < line_nodes.size(); l += 2) {
                    const auto p = x.find(line_nodes[l]), q = x.find(line_nodes[l + 1]);
                    if (p != x.end() && q != x.end()) it->second += (p->second - q->second).norm();
                }
            }
            std::vector<int> sides, ends;
            gmsh::model::getAdjacencies(1, c, sides, ends);
            std::vector<int> others;
            for (int o : sides)
                if (o != s) others.push_back(o);
            out.boundary[s].push_back({it->second, std::move(others)});
        }
    }
}

}  // namespace

WallAspect wall_aspect(const SurfaceMesh& mesh, const std::vector<int>& face_surface, const std::set<int>& walls,
                       const WallLimits& params) {
    const double h = params.first_height, limit = params.max_aspect_ratio;
    WallAspect out;
    std::map<int, double> worst;
    std::map<int, double>& area = out.area;
    std::map<int, Index>& faces = out.faces;
    auto corner = [&](Index f, Index i) -> const Vec3& {
        return mesh.points[static_cast<std::size_t>(mesh.face_node(f, i))];
    };
    // Wall edges → their faces, for the fans below; wall nodes → their faces, for the columns'
    // directions; nodes on a face that is not a wall's (their columns follow that patch).
    std::map<std::array<Index, 2>, std::vector<Index>> faces_of_edge;
    std::map<Index, std::vector<Index>> faces_at;
    std::set<Index> by_other;
    for (Index f = 0; f < mesh.num_faces(); ++f) {
        const Index n = mesh.face_size(f);
        if (!walls.count(face_surface[static_cast<std::size_t>(f)])) {
            for (Index i = 0; i < n; ++i) by_other.insert(mesh.face_node(f, i));
            continue;
        }
        area[face_surface[static_cast<std::size_t>(f)]] += face_area_vector(mesh, f).norm();
        ++faces[face_surface[static_cast<std::size_t>(f)]];
        for (Index i = 0; i < n; ++i) {
            const Index a = mesh.face_node(f, i), b = mesh.face_node(f, (i + 1) % n);
            faces_of_edge[{std::min(a, b), std::max(a, b)}].push_back(f);
            faces_at[a].push_back(f);
        }
    }
    std::set<Index> fan_nodes;
    if (params.fan_angle_deg > 0.0) fan_curves(mesh, walls, params, faces_of_edge, faces_at, out, fan_nodes);

    // Each wall face's first cell: its columns along their start directions (a fan's, and one
    // beside another patch, along the face's normal), leaning off the face on its edges; a
    // column leaning too far for one direction stops at the wall, and the cell over the face
    // is then the step cell closing it (a pyramid or tetrahedron down to that node: its top
    // corner there is the node itself), flatter than the prism: about the face's width over h.
    const std::map<Index, Vec3> start = start_directions(mesh, faces_at);
    const double stop_cos = std::cos(kStopLeanDeg * std::numbers::pi / 180.0);
    for (Index f = 0; f < mesh.num_faces(); ++f) {
        const int s = face_surface[static_cast<std::size_t>(f)];
        if (!walls.count(s)) continue;
        const Index n = mesh.face_size(f);
        const Vec3 normal = face_area_vector(mesh, f).normalized();
        std::array<Vec3, 4> c, d;
        Index stopped = 0;
        for (Index i = 0; i < n; ++i) {
            const Index v = mesh.face_node(f, i);
            c[static_cast<std::size_t>(i)] = corner(f, i);
            Vec3 dir = normal;
            const auto it = start.find(v);
            if (!fan_nodes.count(v) && !by_other.count(v) && it != start.end() && it->second != Vec3::Zero()) {
                dir = it->second.dot(normal) < 0.0 ? Vec3(-it->second) : it->second;
                if (dir.dot(normal) < stop_cos) {
                    dir = Vec3::Zero();
                    ++stopped;
                }
            }
            d[static_cast<std::size_t>(i)] = dir;
        }
        if (stopped == n) continue;  // no layer over it
        // A lean the cell cannot take (no volume) is left to the marching: the right prism's.
        double ar = leaning_prism_aspect_ratio(c.data(), d.data(), static_cast<int>(n), h);
        if (!std::isfinite(ar)) {
            if (stopped > 0) continue;
            ar = right_prism_aspect_ratio(c.data(), static_cast<int>(n), h);
        }
        double& w = worst[s];
        w = std::max(w, ar);
    }
    for (const auto& [s, w] : worst) {
        out.worst = std::max(out.worst, w);
        if (w > limit) out.surfaces.push_back(s);
    }
    if (!out.surfaces.empty() || !out.curve_need.empty()) wall_boundaries(out);  // only refine_walls' rounds use it
    return out;
}

EntitySizes entity_sizes(const WallCaps& caps) {
    EntitySizes sizes;
    for (const auto& [s, size] : caps.surface) sizes.cap_surface(s, size);
    for (const auto& [c, size] : caps.curve) sizes.cap_curve(c, size);
    return sizes;
}

void refine_walls(const WallLimits& params, WallAspect now, WallSizeReport& r,
                  const std::function<bool(const WallCaps&, WallAspect&)>& remesh) {
    r.max_aspect_ratio = params.max_aspect_ratio;
    r.worst_before = r.worst_after = now.worst;
    WallCaps caps;
    constexpr int kRounds = 3;
    for (int round = 0; round < kRounds && (!now.surfaces.empty() || !now.curve_need.empty()); ++round) {
        for (int s : now.surfaces) {
            const auto [it, fresh] = caps.surface.emplace(s, kCapShare * params.max_aspect_ratio * params.first_height);
            if (!fresh) it->second *= kCapShare;
        }
        for (const auto& [c, need] : now.curve_need) {
            const auto [it, fresh] = caps.curve.emplace(c, need);
            if (!fresh) it->second = std::min(it->second, need);
        }
        // The faces to expect: the capped surfaces at their cap, the others as they are, and the
        // surfaces beside a finer curve graded from it (counted at the geometric mean of the two
        // sizes: a rough figure, for the budget only).
        double estimate = 0.0;
        for (const auto& [s, a] : now.area) {
            const auto capped = caps.surface.find(s);
            estimate +=
                capped != caps.surface.end() ? faces_at_size(a, capped->second) : static_cast<double>(now.faces.at(s));
        }
        for (const auto& [c, need] : caps.curve) {
            const auto up = now.curve_up.find(c);
            if (up == now.curve_up.end()) continue;
            for (int s : up->second) {
                if (!now.area.count(s) || caps.surface.count(s)) continue;
                const double a = now.area.at(s), n = static_cast<double>(now.faces.at(s));
                const double current = std::sqrt(a / (0.4330127 * n));
                estimate += faces_at_size(a, std::sqrt(need * std::max(current, need))) - n;
            }
        }
        // A surface left as it is takes the sizes of its boundary curves into its interior
        // (Gmsh's Mesh.MeshSizeExtendFromBoundary): those on a capped surface's boundary are
        // at its cap. Counted as the share of its boundary so capped, at that cap: a surface
        // whose whole boundary is capped (a farfield sphere between two capped planes) is
        // meshed at the cap throughout.
        for (const auto& [s, a] : now.area) {
            if (caps.surface.count(s)) continue;
            const auto b = now.boundary.find(s);
            if (b == now.boundary.end()) continue;
            double total = 0.0, capped = 0.0, cap = std::numeric_limits<double>::infinity();
            for (const WallAspect::Side& side : b->second) {
                total += side.length;
                for (int o : side.others) {
                    const auto it = caps.surface.find(o);
                    if (it == caps.surface.end()) continue;
                    capped += side.length;
                    cap = std::min(cap, it->second);
                    break;
                }
            }
            if (!(total > 0.0) || !(capped > 0.0)) continue;
            const double n = static_cast<double>(now.faces.at(s));
            estimate += std::max(0.0, capped / total * faces_at_size(a, cap) - n);
        }
        r.faces_estimate = estimate;
        // The size to name: the surfaces' (what --size can give), else the finest curve's.
        r.cap = std::numeric_limits<double>::infinity();
        for (const auto& [s, size] : caps.surface) r.cap = std::min(r.cap, size);
        if (caps.surface.empty())
            for (const auto& [c, size] : caps.curve) r.cap = std::min(r.cap, size);
        if (estimate > params.faces_budget) {
            r.over_budget = round == 0;  // later rounds keep the better mesh they have
            break;
        }
        WallAspect measured;
        if (!remesh(caps, measured)) break;  // the mesh of the round before stands
        now = std::move(measured);
        r.worst_after = now.worst;
        r.surfaces = static_cast<Index>(caps.surface.size());
        r.curves = static_cast<Index>(caps.curve.size());
    }
}

}  // namespace strata
