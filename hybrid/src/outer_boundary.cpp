// Re-meshing the planes the layers end on (symmetry, outflow, box sides): outer_boundary.h.

#include <strata/core/error.h>
#include <strata/core/face_geometry.h>
#include <strata/core/format.h>
#include <strata/geometry/topology.h>
#include <strata/hybrid/outer_boundary.h>
#include <strata/hybrid/plane_mesh.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <unordered_map>

namespace strata {
namespace {

std::uint64_t edge_key(Index a, Index b) {
    const auto lo = static_cast<std::uint64_t>(static_cast<std::uint32_t>(std::min(a, b)));
    const auto hi = static_cast<std::uint64_t>(static_cast<std::uint32_t>(std::max(a, b)));
    return (lo << 32) | hi;
}

/// Positions in (0, L) of the points that split a straight segment of length L into pieces
/// growing from size \p ha at 0 and \p hb at L by 20 % per piece, up to \p hmax: the target
/// size h(s) = min(hmax, ha + 0.2 s, hb + 0.2 (L − s)) equidistributed (∫ ds / h per piece = 1).
std::vector<double> graded_cuts(double L, double ha, double hb, double hmax) {
    constexpr int kSamples = 400;
    constexpr double kGrowth = 0.2;
    auto h = [&](double s) { return std::max(1e-300, std::min({hmax, ha + kGrowth * s, hb + kGrowth * (L - s)})); };
    std::vector<double> cum(kSamples + 1, 0.0);
    for (int i = 0; i < kSamples; ++i) {
        const double s0 = L * i / kSamples, s1 = L * (i + 1) / kSamples;
        cum[static_cast<std::size_t>(i) + 1] =
            cum[static_cast<std::size_t>(i)] + 0.5 * (s1 - s0) * (1.0 / h(s0) + 1.0 / h(s1));
    }
    const int n = std::max(1, static_cast<int>(std::lround(cum.back())));
    std::vector<double> cuts;
    for (int k = 1; k < n; ++k) {
        const double target = cum.back() * k / n;
        const auto it = std::lower_bound(cum.begin(), cum.end(), target);
        const std::size_t i = static_cast<std::size_t>(std::max<std::ptrdiff_t>(1, it - cum.begin()));
        const double t = (target - cum[i - 1]) / (cum[i] - cum[i - 1]);
        cuts.push_back(L * (static_cast<double>(i - 1) + t) / kSamples);
    }
    return cuts;
}

/// Everything the re-meshing shares between patches: the outer points (each input node,
/// layer-top node and new point once) and the cut patch edges.
struct Builder {
    const SurfaceMesh& surface;
    const LayerMesh& layers;
    OuterBoundary out;
    std::vector<Index> wall_of;                 ///< input node → wall node, kNone off the walls
    std::vector<Index> input_map;               ///< input node → outer point
    std::vector<Index> top_map;                 ///< wall node → outer point (its layer-top node)
    std::vector<double> top_size;               ///< wall node → mean length of the layer-top edges at its top node
    std::vector<std::vector<Index>> chains;     ///< input nodes of each cut patch edge, from its start
    std::vector<std::vector<Index>> chain_pts;  ///< outer points replacing it, from its start
    std::unordered_map<std::uint64_t, Index> chain_of;  ///< input edge → chain
    /// A fan's plane node (an input node on the walls' open boundary with several columns: a
    /// sharp trailing edge on a symmetry plane): its columns in the order the layer top's
    /// boundary passes them, and the input nodes before and after them there.
    struct Fan {
        Index before = kNone, after = kNone;
        std::vector<Index> columns;
    };
    std::unordered_map<Index, Fan> fans;

    Builder(const SurfaceMesh& s, const LayerMesh& l) : surface(s), layers(l) {
        wall_of.assign(static_cast<std::size_t>(s.num_points()), kNone);
        bool split = false;  // an input node with several columns (a fan)
        for (std::size_t i = 0; i < l.input_node.size(); ++i) {
            Index& w = wall_of[static_cast<std::size_t>(l.input_node[i])];
            split |= w != kNone;
            w = static_cast<Index>(i);
        }
        input_map.assign(static_cast<std::size_t>(s.num_points()), kNone);
        top_map.assign(static_cast<std::size_t>(l.wall_nodes()), kNone);
        std::vector<int> count(static_cast<std::size_t>(l.wall_nodes()), 0);
        top_size.assign(static_cast<std::size_t>(l.wall_nodes()), 0.0);
        const SurfaceMesh& t = l.top;
        for (Index f = 0; f < t.num_faces(); ++f)
            for (Index i = 0, n = t.face_size(f); i < n; ++i) {
                const Index a = t.face_node(f, i), b = t.face_node(f, (i + 1) % n);
                const double len = (t.points[a] - t.points[b]).norm();
                for (Index v : {a, b}) {
                    top_size[static_cast<std::size_t>(v)] += len;
                    ++count[static_cast<std::size_t>(v)];
                }
            }
        for (std::size_t i = 0; i < count.size(); ++i)
            if (count[i] > 0) top_size[i] /= count[i];
        if (split) find_fans();
    }

    /// fans: the runs of one input node's columns along the layer top's boundary loops.
    void find_fans() {
        const Csr loops = boundary_loops(layers.top);
        auto input = [&](Index w) { return layers.input_node[static_cast<std::size_t>(w)]; };
        for (Index l = 0; l < loops.rows(); ++l) {
            const Index* lv = loops.row_begin(l);
            const Index m = loops.row_size(l);
            // Start where the input node changes, so that no run is split.
            Index s0 = 0;
            while (s0 < m && input(lv[s0]) == input(lv[(s0 + m - 1) % m])) ++s0;
            if (s0 == m) continue;
            for (Index i = 0; i < m;) {
                const Index v = input(lv[(s0 + i) % m]);
                Index j = i + 1;
                while (j < m && input(lv[(s0 + j) % m]) == v) ++j;
                if (j - i > 1) {
                    Fan& f = fans[v];
                    if (!f.columns.empty())
                        throw TopologyError("the walls' open boundary passes the fan at " +
                                            format_point(surface.points[v]) + " twice");
                    f.before = input(lv[(s0 + i + m - 1) % m]);
                    f.after = input(lv[(s0 + j) % m]);
                    for (Index k = i; k < j; ++k) f.columns.push_back(lv[(s0 + k) % m]);
                }
                i = j;
            }
        }
    }

    /// The outer points of input node \p v on a patch's boundary loop coming from input node
    /// \p prev: point_of(v), or a fan's columns' top points, from prev's side.
    void append_points(Index v, Index prev, std::vector<Index>& pts) {
        const auto it = fans.find(v);
        if (it == fans.end()) {
            pts.push_back(point_of(v));
            return;
        }
        const Fan& f = it->second;
        if (prev != f.before && prev != f.after)
            throw TopologyError("the fan at " + format_point(surface.points[v]) +
                                " does not end on the plane's boundary it lies on");
        const std::size_t n = f.columns.size();
        for (std::size_t k = 0; k < n; ++k) {
            const Index w = f.columns[prev == f.before ? k : n - 1 - k];
            Index& t = top_map[static_cast<std::size_t>(w)];
            if (t == kNone) t = add_point(layers.top.points[w], w);
            pts.push_back(t);
        }
    }

    bool is_wall_face(Index f) const {
        return surface.patches[static_cast<std::size_t>(surface.face_patch[f])].kind == PatchKind::Wall;
    }
    const std::string& patch_name(Index p) const { return surface.patches[static_cast<std::size_t>(p)].name; }

    Index add_point(const Vec3& p, Index top) {
        out.mesh.points.push_back(p);
        out.top_node.push_back(top);
        return out.mesh.num_points() - 1;
    }
    /// The outer point of input node v: itself, or its layer-top node if it is on the walls.
    Index point_of(Index v) {
        const Index w = wall_of[static_cast<std::size_t>(v)];
        if (w != kNone) {
            Index& t = top_map[static_cast<std::size_t>(w)];
            if (t == kNone) t = add_point(layers.top.points[w], w);
            return t;
        }
        Index& m = input_map[static_cast<std::size_t>(v)];
        if (m == kNone) m = add_point(surface.points[v], kNone);
        return m;
    }

    /// The edges between two non-wall patches, at least one re-meshed, that start at the walls:
    /// followed from the wall node to the next wall node or junction of patch edges, and cut at
    /// the top of the layers.
    void cut_patch_edges(const std::vector<char>& remesh) {
        const EdgeTable et = edge_table(surface);
        const Index ne = static_cast<Index>(et.nodes.size());
        std::vector<char> is_pe(static_cast<std::size_t>(ne), 0);  // edge between two non-wall patches
        std::vector<Index> degree(static_cast<std::size_t>(surface.num_points()), 0);
        std::unordered_map<std::uint64_t, Index> edge_id;
        for (Index e = 0; e < ne; ++e) {
            if (et.faces.row_size(e) != 2) continue;
            const Index f0 = et.faces.row_begin(e)[0], f1 = et.faces.row_begin(e)[1];
            const Index p0 = surface.face_patch[f0], p1 = surface.face_patch[f1];
            if (is_wall_face(f0) || is_wall_face(f1) || p0 == p1) continue;
            if (!remesh[static_cast<std::size_t>(p0)] && !remesh[static_cast<std::size_t>(p1)]) continue;
            is_pe[static_cast<std::size_t>(e)] = 1;
            for (Index v : et.nodes[static_cast<std::size_t>(e)]) ++degree[static_cast<std::size_t>(v)];
            edge_id.emplace(
                edge_key(et.nodes[static_cast<std::size_t>(e)][0], et.nodes[static_cast<std::size_t>(e)][1]), e);
        }
        // Patch-edge neighbours per node (small: only nodes on patch edges have any).
        std::unordered_map<Index, std::vector<Index>> nbrs;
        for (Index e = 0; e < ne; ++e)
            if (is_pe[static_cast<std::size_t>(e)]) {
                const auto& ab = et.nodes[static_cast<std::size_t>(e)];
                nbrs[ab[0]].push_back(ab[1]);
                nbrs[ab[1]].push_back(ab[0]);
            }
        std::vector<Index> starts;
        for (const auto& [v, list] : nbrs)
            if (wall_of[static_cast<std::size_t>(v)] != kNone) starts.push_back(v);
        std::sort(starts.begin(), starts.end());  // deterministic order
        for (Index c : starts) {
            std::vector<Index> first = nbrs[c];
            std::sort(first.begin(), first.end());
            for (Index n1 : first) {
                if (chain_of.count(edge_key(c, n1))) continue;  // walked from its other end
                std::vector<Index> chain{c, n1};
                while (wall_of[static_cast<std::size_t>(chain.back())] == kNone &&
                       degree[static_cast<std::size_t>(chain.back())] == 2) {
                    const auto& nb = nbrs[chain.back()];
                    const Index next = nb[0] == chain[chain.size() - 2] ? nb[1] : nb[0];
                    if (next == chain.front()) break;  // a closed curve through one wall node
                    chain.push_back(next);
                }
                const Index id = static_cast<Index>(chains.size());
                for (std::size_t i = 0; i + 1 < chain.size(); ++i) chain_of[edge_key(chain[i], chain[i + 1])] = id;
                chain_pts.push_back(cut_chain(chain));
                chains.push_back(std::move(chain));
            }
        }
    }

    /// The outer points replacing patch edge \p c (input nodes from a wall node): its ends
    /// (layer-top nodes at wall ends), the original nodes beyond the layers, graded new points
    /// between.
    std::vector<Index> cut_chain(const std::vector<Index>& c) {
        const std::size_t k = c.size() - 1;
        const Vec3 &p0 = surface.points[c.front()], &pk = surface.points[c.back()];
        struct End {
            bool wall = false;
            Vec3 base, top, dir;  // dir: unit, along the layers' column
            double height = 0.0, size = 0.0;
        };
        auto end_of = [&](Index v, Index next) {
            End e;
            const Index w = wall_of[static_cast<std::size_t>(v)];
            e.base = e.top = surface.points[v];
            if (w == kNone) return e;
            e.wall = true;
            e.top = layers.top.points[w];
            e.height = (e.top - e.base).norm();
            e.dir = (e.top - e.base) / e.height;
            e.size = top_size[static_cast<std::size_t>(w)];
            // The layers must have marched along the patch edge.
            const Vec3 along = (surface.points[next] - e.base).normalized();
            if ((e.top - e.base).cross(along).norm() > 1e-3 * e.height || e.dir.dot(along) <= 0.0)
                throw TopologyError("the layers at " + format_point(e.base) +
                                    " leave the edge between two non-wall patches "
                                    "that they should march along (their top is at " +
                                    format_point(e.top) + "): the patches meeting there must be planar");
            return e;
        };
        const End a = end_of(c.front(), c[1]), b = end_of(c.back(), c[k - 1]);
        // Original interior nodes beyond the layers at both ends, in order.
        std::vector<std::size_t> kept;
        for (std::size_t i = 1; i < k; ++i) {
            const Vec3& p = surface.points[c[i]];
            if (a.wall && (p - p0).dot(a.dir) < a.height + 0.5 * a.size) continue;
            if (b.wall && (p - pk).dot(b.dir) < b.height + 0.5 * b.size) continue;
            kept.push_back(i);
        }
        auto too_short = [&](const End& e, const Vec3& far) {
            return TopologyError("the layers at " + format_point(e.base) + " (" + format_number(e.height) +
                                 " thick) reach beyond the end of the patch edge they march along, at " +
                                 format_point(far) +
                                 ": use thinner layers (fewer DistributionParams::layers, or a smaller "
                                 "DistributionParams::first_height or DistributionParams::growth)");
        };
        if (kept.empty()) {
            if (a.wall && !b.wall && (pk - p0).dot(a.dir) < a.height + 0.25 * a.size) throw too_short(a, pk);
            if (b.wall && !a.wall && (p0 - pk).dot(b.dir) < b.height + 0.25 * b.size) throw too_short(b, p0);
            if (a.wall && b.wall && (b.top - a.top).dot(pk - p0) < 0.25 * (a.size + b.size)) throw too_short(a, pk);
        }
        std::vector<Index> pts{point_of(c.front())};
        // Graded points on the straight piece from x to y, sizes hx at x and hy at y.
        auto fill = [&](const Vec3& x, const Vec3& y, double hx, double hy) {
            const double len = (y - x).norm();
            for (double s : graded_cuts(len, hx, hy, std::max({hx, hy})))
                pts.push_back(add_point(x + (s / len) * (y - x), kNone));
        };
        auto spacing = [&](std::size_t i) {  // original spacing at chain node i
            double h = 0.0;
            int n = 0;
            if (i > 0) h += (surface.points[c[i]] - surface.points[c[i - 1]]).norm(), ++n;
            if (i < k) h += (surface.points[c[i]] - surface.points[c[i + 1]]).norm(), ++n;
            return h / n;
        };
        if (kept.empty()) {
            if (a.wall || b.wall) fill(a.top, b.top, a.wall ? a.size : spacing(0), b.wall ? b.size : spacing(k));
        } else {
            if (a.wall) fill(a.top, surface.points[c[kept.front()]], a.size, spacing(kept.front()));
            for (std::size_t i : kept) pts.push_back(point_of(c[i]));
            if (b.wall) fill(surface.points[c[kept.back()]], b.top, spacing(kept.back()), b.size);
        }
        pts.push_back(point_of(c.back()));
        return pts;
    }

    /// The boundary of re-meshed patch \p patch as loops of outer points.
    std::vector<std::vector<Index>> patch_loops(Index patch) {
        SurfaceMesh sub;
        std::vector<Index> input_of, local(static_cast<std::size_t>(surface.num_points()), kNone);
        for (Index f = 0; f < surface.num_faces(); ++f) {
            if (surface.face_patch[f] != patch) continue;
            Index v[4];
            const Index n = surface.face_size(f);
            for (Index i = 0; i < n; ++i) {
                Index& l = local[static_cast<std::size_t>(surface.face_node(f, i))];
                if (l == kNone) {
                    l = static_cast<Index>(input_of.size());
                    input_of.push_back(surface.face_node(f, i));
                    sub.points.push_back(surface.points[surface.face_node(f, i)]);
                }
                v[i] = l;
            }
            sub.add_face(v, n, 0);
        }
        const Csr loops = boundary_loops(sub);
        std::vector<std::vector<Index>> result;
        for (Index l = 0; l < loops.rows(); ++l) {
            std::vector<Index> loop;
            for (const Index* v = loops.row_begin(l); v != loops.row_end(l); ++v)
                loop.push_back(input_of[static_cast<std::size_t>(*v)]);
            // Start at a wall node, so that no cut patch edge is entered half way.
            const auto w = std::find_if(loop.begin(), loop.end(),
                                        [&](Index v) { return wall_of[static_cast<std::size_t>(v)] != kNone; });
            if (w != loop.end()) std::rotate(loop.begin(), w, loop.end());
            const std::size_t m = loop.size();
            std::vector<Index> pts;
            for (std::size_t i = 0; i < m;) {
                const Index a = loop[i], b = loop[(i + 1) % m];
                const auto it = chain_of.find(edge_key(a, b));
                if (it == chain_of.end()) {
                    append_points(a, loop[(i + m - 1) % m], pts);
                    ++i;
                    continue;
                }
                const std::vector<Index>& c = chains[static_cast<std::size_t>(it->second)];
                std::vector<Index> cp = chain_pts[static_cast<std::size_t>(it->second)];
                const bool forward = c.front() == a;
                if (!forward) std::reverse(cp.begin(), cp.end());
                const std::size_t edges = c.size() - 1;
                for (std::size_t j = 0; j <= edges; ++j)
                    if (loop[(i + j) % m] != (forward ? c[j] : c[edges - j]))
                        throw TopologyError("patch '" + patch_name(patch) +
                                            "': its boundary leaves the edge it shares with "
                                            "another patch at " +
                                            format_point(surface.points[loop[(i + j) % m]]) +
                                            " (a non-manifold patch boundary)");
                pts.insert(pts.end(), cp.begin(), cp.end() - 1);
                i += edges;
            }
            result.push_back(std::move(pts));
        }
        return result;
    }

    /// Mesh re-meshed patch \p patch (planar, plane \p pl) inside \p loops.
    void mesh_patch(Index patch, const PatchPlane& pl, const std::vector<std::vector<Index>>& loops, double growth) {
        const std::string ctx = "re-meshing patch '" + patch_name(patch) + "' around the layers";
        for (const auto& loop : loops)
            for (Index p : loop) {
                const double off = std::abs((out.mesh.points[p] - pl.point).dot(pl.normal));
                if (off > 1e-6 * pl.size)
                    throw TopologyError(
                        ctx + ": the point " + format_point(out.mesh.points[p]) + " of its new boundary is " +
                        std::to_string(off) + " off the plane" +
                        (out.top_node[static_cast<std::size_t>(p)] != kNone ? " (a node of the layer top)" : ""));
            }
        // Graded from the layer top (the tetrahedra's rule), not from the patch's own outline.
        std::vector<char> top(out.mesh.points.size(), 0);
        for (std::size_t p = 0; p < top.size(); ++p) top[p] = out.top_node[p] != kNone;
        const PlaneMesh pm = mesh_plane_region(out.mesh.points, loops, pl.point, pl.normal, ctx, growth, top);
        // New points are appended in order, so their ids are the ones mesh_plane_region gave.
        for (const Vec3& x : pm.new_points) add_point(x, kNone);
        for (const auto& t : pm.triangles) out.mesh.add_face({t[0], t[1], t[2]}, patch);
    }
};

}  // namespace

OuterBoundary outer_boundary(const SurfaceMesh& surface, const LayerMesh& layers, double growth) {
    Builder b(surface, layers);
    b.out.mesh.patches = surface.patches;
    // Patches that the walls touch.
    std::vector<char> remesh(surface.patches.size(), 0);
    for (Index f = 0; f < surface.num_faces(); ++f) {
        if (b.is_wall_face(f)) continue;
        for (const Index* v = surface.face_begin(f); v != surface.face_end(f); ++v)
            if (b.wall_of[static_cast<std::size_t>(*v)] != kNone)
                remesh[static_cast<std::size_t>(surface.face_patch[f])] = 1;
    }
    std::vector<PatchPlane> plane(surface.patches.size());
    for (Index p = 0; p < static_cast<Index>(surface.patches.size()); ++p) {
        if (!remesh[static_cast<std::size_t>(p)]) continue;
        plane[static_cast<std::size_t>(p)] = patch_plane(surface, p);
        const PatchPlane& pl = plane[static_cast<std::size_t>(p)];
        if (!pl.planar())
            throw InputError(
                "patch '" + b.patch_name(p) + "' meets the walls, so the layers end on it, but it is not planar (" +
                format_number(pl.deviation) + " off its best plane over a size of " + format_number(pl.size) +
                "): the hybrid stage re-meshes only planar symmetry, outflow or farfield patches around the "
                "layers; mark it as a wall (PrepareParams::patch_kinds " +
                b.patch_name(p) + "=wall) or cut the domain with a plane there");
        b.out.remeshed.push_back(p);
    }
    b.cut_patch_edges(remesh);
    for (Index p : b.out.remeshed) b.mesh_patch(p, plane[static_cast<std::size_t>(p)], b.patch_loops(p), growth);
    // The other non-wall patches as they are.
    for (Index f = 0; f < surface.num_faces(); ++f) {
        if (b.is_wall_face(f) || remesh[static_cast<std::size_t>(surface.face_patch[f])]) continue;
        Index v[4];
        const Index n = surface.face_size(f);
        for (Index i = 0; i < n; ++i) v[i] = b.point_of(surface.face_node(f, i));
        b.out.mesh.add_face({v[0], v[1], v[2]}, surface.face_patch[f]);
        if (n == 4) b.out.mesh.add_face({v[0], v[2], v[3]}, surface.face_patch[f]);
    }
    return std::move(b.out);
}

}  // namespace strata
