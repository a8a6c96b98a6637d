#include <strata/core/format.h>
#include <strata/core/mesh_check.h>
#include <strata/geometry/topology.h>

#include <strata/core/error.h>
#include <strata/core/face_geometry.h>
#include <strata/core/union_find.h>

#include "model_span.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <map>
#include <numeric>
#include <string>
#include <tuple>
#include <unordered_map>
#include <utility>
#include <vector>

namespace strata {
namespace {

std::string node_text(const SurfaceMesh& mesh, Index v) {
    return "node " + std::to_string(v) + " at " + format_point(mesh.points[v], 9);
}

/// Every function here indexes points by face node ids; a corrupt id would be undefined
/// behaviour rather than an error, so refuse it up front (O(#face nodes)). Coordinates and
/// patches are not looked at: connectivity does not need them (check_surface names NaNs).
/// \p patch_per_face: the caller copies face_patch face by face, so it needs one entry per face
/// (whether each names a patch is check_surface's business).
void require_valid_ids(const SurfaceMesh& mesh, const char* who, bool patch_per_face = false) {
    require_sound(check_surface_arrays(mesh, {.require_faces = false, .coordinates = false, .patches = false}),
                  std::string(who) + ": ");
    if (patch_per_face && mesh.face_patch.size() != static_cast<std::size_t>(mesh.num_faces()))
        throw InputError(std::string(who) + ": face patches: " + std::to_string(mesh.face_patch.size()) +
                         " entries for " + std::to_string(mesh.num_faces()) + " faces");
}

/// Integer cell of the merge hash grid.
struct CellKey {
    std::int64_t x, y, z;
    bool operator==(const CellKey&) const = default;
};
struct CellHash {
    std::size_t operator()(const CellKey& k) const noexcept {
        // Large odd multipliers mix the three coordinates; collisions only cost a longer bucket.
        std::uint64_t h = static_cast<std::uint64_t>(k.x) * 0x9E3779B97F4A7C15ull;
        h ^= static_cast<std::uint64_t>(k.y) * 0xC2B2AE3D27D4EB4Full + (h << 6) + (h >> 2);
        h ^= static_cast<std::uint64_t>(k.z) * 0x165667B19E3779F9ull + (h << 6) + (h >> 2);
        return static_cast<std::size_t>(h);
    }
};

bool is_finite(const Vec3& p) {
    return std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z());
}

/// Does face \p f traverse the undirected edge (a, b) as a → b?
bool traverses(const SurfaceMesh& mesh, Index f, Index a, Index b) {
    const Index* v = mesh.face_begin(f);
    const Index n = mesh.face_size(f);
    for (Index i = 0; i < n; ++i)
        if (v[i] == a && v[(i + 1) % n] == b) return true;
    return false;
}

}  // namespace

SurfaceMesh merge_coincident_nodes(const SurfaceMesh& mesh, double rel_tol) {
    require_valid_ids(mesh, "merge_coincident_nodes");
    const Index n = mesh.num_points();
    std::vector<char> used(n, 0);
    for (Index v : mesh.face_nodes) used[v] = 1;

    // Tolerance relative to the bounding box of the used, finite nodes: unused nodes are
    // dropped anyway and a NaN must not poison the box (check_surface reports it later).
    BoundingBox box;
    bool any = false;
    Index num_used = 0;
    for (Index i = 0; i < n; ++i) {
        if (!used[i]) continue;
        ++num_used;
        const Vec3& p = mesh.points[i];
        if (!is_finite(p)) continue;
        if (!any) {
            box.min = box.max = p;
            any = true;
        } else {
            box.min = box.min.cwiseMin(p);
            box.max = box.max.cwiseMax(p);
        }
    }
    // Below this span (check_surface's bound too) the tolerance, the cells and p ± reach below
    // are finite, and so are the integer cell coordinates. A relative tolerance over 1 merges
    // every node (they are all within the diagonal), so capping it changes nothing but keeps
    // an absurd one finite.
    require_model_span(box, "merge_coincident_nodes: ");
    const double diag = box.diagonal();
    const double tol = (rel_tol > 0.0 && std::isfinite(rel_tol)) ? std::min(rel_tol, 2.0) * diag : 0.0;
    // Cells of a few tolerances: a tolerance ball then usually lies in one cell (1 hash lookup
    // instead of 27), at most 8. The floor of diag·1e-12 keeps the integer cell coordinates
    // (relative to box.min) far from overflow when the tolerance is zero or tiny.
    double cell = std::max(4.0 * tol, diag * 1e-12);
    if (!(cell > 0.0)) cell = 1.0;
    const double tol2 = tol * tol;
    const double reach = tol * (1.0 + 1e-6);
    auto cell_of = [&](double x, double lo) { return static_cast<std::int64_t>(std::floor((x - lo) / cell)); };

    // Greedy in increasing id order: each node joins the lowest-id representative within the
    // tolerance, otherwise becomes one. Only representatives enter the grid, so clusters do
    // not chain across many tolerances and the result does not depend on hashing order.
    std::vector<Index> rep(n, kNone);
    std::vector<Index> chain(n, kNone);  // next representative in the same cell
    std::unordered_map<CellKey, Index, CellHash> head;
    head.reserve(static_cast<std::size_t>(num_used));
    for (Index i = 0; i < n; ++i) {
        if (!used[i]) continue;
        const Vec3& p = mesh.points[i];
        if (!is_finite(p)) {
            rep[i] = i;
            continue;
        }
        const CellKey k{cell_of(p.x(), box.min.x()), cell_of(p.y(), box.min.y()), cell_of(p.z(), box.min.z())};
        // The cells the ball of radius tol around p overlaps (a hair wider, so rounding of
        // p ± tol cannot miss a representative at exactly the tolerance).
        const CellKey k0{cell_of(p.x() - reach, box.min.x()), cell_of(p.y() - reach, box.min.y()),
                         cell_of(p.z() - reach, box.min.z())};
        const CellKey k1{cell_of(p.x() + reach, box.min.x()), cell_of(p.y() + reach, box.min.y()),
                         cell_of(p.z() + reach, box.min.z())};
        Index best = kNone;
        for (std::int64_t x = k0.x; x <= k1.x; ++x)
            for (std::int64_t y = k0.y; y <= k1.y; ++y)
                for (std::int64_t z = k0.z; z <= k1.z; ++z) {
                    auto it = head.find(CellKey{x, y, z});
                    if (it == head.end()) continue;
                    for (Index j = it->second; j != kNone; j = chain[j])
                        if ((mesh.points[j] - p).squaredNorm() <= tol2 && (best == kNone || j < best)) best = j;
                }
        if (best != kNone) {
            rep[i] = best;
        } else {
            rep[i] = i;
            auto [it, inserted] = head.try_emplace(k, i);
            if (!inserted) {
                chain[i] = it->second;
                it->second = i;
            }
        }
    }

    // Representatives keep their relative order.
    std::vector<Index> new_id(n, kNone);
    SurfaceMesh out;
    for (Index i = 0; i < n; ++i)
        if (used[i] && rep[i] == i) {
            new_id[i] = out.num_points();
            out.points.push_back(mesh.points[i]);
        }
    out.face_offsets = mesh.face_offsets;
    out.face_nodes.resize(mesh.face_nodes.size());
    for (std::size_t k = 0; k < mesh.face_nodes.size(); ++k) out.face_nodes[k] = new_id[rep[mesh.face_nodes[k]]];
    out.face_patch = mesh.face_patch;
    out.patches = mesh.patches;
    return out;
}

namespace {

/// \p out's points: those of \p points its faces use, order kept; its faces renumbered.
void drop_unused_nodes(const std::vector<Vec3>& points, SurfaceMesh& out) {
    std::vector<Index> new_id(points.size(), kNone);
    for (Index v : out.face_nodes) new_id[static_cast<std::size_t>(v)] = 0;
    out.points.clear();
    for (std::size_t i = 0; i < points.size(); ++i)
        if (new_id[i] != kNone) {
            new_id[i] = static_cast<Index>(out.points.size());
            out.points.push_back(points[i]);
        }
    for (Index& v : out.face_nodes) v = new_id[static_cast<std::size_t>(v)];
}

}  // namespace

SurfaceMesh remove_duplicate_faces(const SurfaceMesh& mesh, Index* removed) {
    require_valid_ids(mesh, "remove_duplicate_faces", true);
    return remove_duplicate_faces(mesh, edge_table(mesh), removed);
}

SurfaceMesh remove_duplicate_faces(const SurfaceMesh& mesh, const EdgeTable& et, Index* removed) {
    if (removed) *removed = 0;
    // A face and its copy share every edge: only faces on a common edge are compared (the
    // edges of a clean surface have two faces each, so this costs an edge table, no more).
    auto key = [&](Index f) {
        const Index* v = mesh.face_begin(f);
        const Index k = mesh.face_size(f);
        // The face's nodes from its lowest, in its own order: one key for every rotation.
        const Index low = static_cast<Index>(std::min_element(v, v + k) - v);
        std::array<Index, 4> out{kNone, kNone, kNone, kNone};
        for (Index i = 0; i < k && i < 4; ++i) out[static_cast<std::size_t>(i)] = v[(low + i) % k];
        return out;
    };
    std::vector<char> copy(static_cast<std::size_t>(mesh.num_faces()), 0);
    Index count = 0;
    for (Index e = 0; e < et.faces.rows(); ++e) {
        const Index* fs = et.faces.row_begin(e);
        const Index n = et.faces.row_size(e);
        for (Index a = 0; a < n; ++a)
            for (Index b = a + 1; b < n; ++b) {
                const Index f = fs[a], g = fs[b];  // f < g: the later is the copy
                if (copy[static_cast<std::size_t>(g)] || mesh.face_size(f) != mesh.face_size(g) ||
                    mesh.face_size(f) > 4 || key(f) != key(g))
                    continue;
                copy[static_cast<std::size_t>(g)] = 1;
                ++count;
            }
    }
    if (count == 0) return mesh;
    SurfaceMesh out;
    out.patches = mesh.patches;
    out.points = mesh.points;
    for (Index f = 0; f < mesh.num_faces(); ++f)
        if (!copy[static_cast<std::size_t>(f)]) out.add_face(mesh.face_begin(f), mesh.face_size(f), mesh.face_patch[f]);
    if (removed) *removed = count;
    return out;
}

SurfaceMesh split_t_junctions(const SurfaceMesh& mesh, Index* split) {
    require_valid_ids(mesh, "split_t_junctions", true);
    return split_t_junctions(mesh, edge_table(mesh), split);
}

namespace {

/// split_t_junctions with nodes within \p share of an open edge's length of it; \p r counts the
/// faces split and keeps the widest gap so closed.
SurfaceMesh split_near_open_edges(const SurfaceMesh& mesh, const EdgeTable& et, double share, Stitching& r) {
    r = Stitching{};
    // The open edges and the nodes on them.
    std::vector<Index> open_edges;
    std::vector<char> on_open(static_cast<std::size_t>(mesh.num_points()), 0);
    for (std::size_t e = 0; e < et.nodes.size(); ++e)
        if (et.faces.row_size(static_cast<Index>(e)) == 1) {
            open_edges.push_back(static_cast<Index>(e));
            for (const Index v : et.nodes[e]) on_open[static_cast<std::size_t>(v)] = 1;
        }
    if (open_edges.empty()) return mesh;
    // The nodes on open edges by x, so that each edge looks only at those within its x-range.
    std::vector<Index> open_nodes;
    for (Index v = 0; v < mesh.num_points(); ++v)
        if (on_open[static_cast<std::size_t>(v)]) open_nodes.push_back(v);
    auto x_of = [&](Index v) { return mesh.points[static_cast<std::size_t>(v)].x(); };
    std::sort(open_nodes.begin(), open_nodes.end(),
              [&](Index u, Index v) { return x_of(u) < x_of(v) || (x_of(u) == x_of(v) && u < v); });
    // Per face: the nodes to insert on each of its edges, by their parameter along it.
    std::map<Index, std::vector<std::pair<int, std::vector<std::pair<double, Index>>>>> inserts;
    for (const Index e : open_edges) {
        const Index a = et.nodes[static_cast<std::size_t>(e)][0], b = et.nodes[static_cast<std::size_t>(e)][1];
        const Vec3 &pa = mesh.points[static_cast<std::size_t>(a)], &pb = mesh.points[static_cast<std::size_t>(b)];
        const Vec3 ab = pb - pa;
        const double len2 = ab.squaredNorm();
        if (!(len2 > 0.0)) continue;
        const double tol = share * std::sqrt(len2);
        std::vector<std::pair<double, Index>> inside;
        const auto from = std::lower_bound(open_nodes.begin(), open_nodes.end(), std::min(pa.x(), pb.x()) - tol,
                                           [&](Index v, double x) { return x_of(v) < x; });
        for (auto it = from; it != open_nodes.end() && x_of(*it) <= std::max(pa.x(), pb.x()) + tol; ++it) {
            const Index m = *it;
            if (m == a || m == b) continue;
            const Vec3 am = mesh.points[static_cast<std::size_t>(m)] - pa;
            const double t = am.dot(ab) / len2;
            if (!(t > 1e-6 && t < 1.0 - 1e-6)) continue;
            const double gap = (am - t * ab).norm();
            if (!(gap <= tol)) continue;
            inside.emplace_back(t, m);
            if (gap > r.widest) r.widest = gap, r.at = mesh.points[static_cast<std::size_t>(m)];
        }
        if (inside.empty()) continue;
        const Index f = et.faces.row_begin(e)[0];
        if (mesh.face_size(f) != 3) continue;
        int c = 0;  // the face's edge c runs from corner c to corner c + 1
        while (!((mesh.face_node(f, c) == a && mesh.face_node(f, (c + 1) % 3) == b) ||
                 (mesh.face_node(f, c) == b && mesh.face_node(f, (c + 1) % 3) == a)))
            ++c;
        std::sort(inside.begin(), inside.end());
        if (mesh.face_node(f, c) == b) {  // along the face's own direction
            for (auto& [t, m] : inside) t = 1.0 - t;
            std::sort(inside.begin(), inside.end());
        }
        inserts[f].emplace_back(c, std::move(inside));
    }
    if (inserts.empty()) return mesh;
    SurfaceMesh out;
    out.patches = mesh.patches;
    out.points = mesh.points;
    Index count = 0;
    for (Index f = 0; f < mesh.num_faces(); ++f) {
        const auto it = inserts.find(f);
        if (it == inserts.end()) {
            out.add_face(mesh.face_begin(f), mesh.face_size(f), mesh.face_patch[f]);
            continue;
        }
        // The triangle's boundary with the inserted nodes, then a fan from the corner whose two
        // edges got none (the nodes all lie on the edge opposite it).
        std::array<std::vector<Index>, 3> along;
        for (const auto& [c, nodes] : it->second)
            for (const auto& [t, m] : nodes) along[static_cast<std::size_t>(c)].push_back(m);
        std::vector<Index> poly;
        for (int c = 0; c < 3; ++c) {
            poly.push_back(mesh.face_node(f, c));
            for (const Index m : along[static_cast<std::size_t>(c)]) poly.push_back(m);
        }
        int apex = -1;
        for (int k = 0; k < 3 && apex < 0; ++k)
            if (along[static_cast<std::size_t>(k)].empty() && along[static_cast<std::size_t>((k + 2) % 3)].empty())
                apex = k;
        if (apex < 0) {  // several edges split: keep the face as it is (the check names it)
            out.add_face(mesh.face_begin(f), 3, mesh.face_patch[f]);
            continue;
        }
        // The polygon from the apex: apex, then round to the node before it.
        const Index top = mesh.face_node(f, apex);
        const auto start = std::find(poly.begin(), poly.end(), top) - poly.begin();
        std::vector<Index> ring;
        for (std::size_t i = 1; i < poly.size(); ++i)
            ring.push_back(poly[(static_cast<std::size_t>(start) + i) % poly.size()]);
        for (std::size_t i = 0; i + 1 < ring.size(); ++i) out.add_face({top, ring[i], ring[i + 1]}, mesh.face_patch[f]);
        ++count;
    }
    r.split = count;
    return out;
}

}  // namespace

SurfaceMesh split_t_junctions(const SurfaceMesh& mesh, const EdgeTable& et, Index* split) {
    Stitching r;
    SurfaceMesh out = split_near_open_edges(mesh, et, 1e-6, r);
    if (split) *split = r.split;
    return out;
}

SurfaceMesh stitch_cracks(const SurfaceMesh& mesh, double share, Stitching* report) {
    if (report) *report = Stitching{};
    const EdgeTable et = edge_table(mesh);
    Stitching r;
    SurfaceMesh out = split_near_open_edges(mesh, et, share, r);
    if (r.split == 0) return mesh;
    // All or nothing: every edge of the result between two faces, or the input as it was (an
    // opening meant to be there, a half model's cut, stays open and untouched).
    const EdgeTable after = edge_table(out);
    for (Index e = 0; e < after.faces.rows(); ++e)
        if (after.faces.row_size(e) != 2) return mesh;
    if (report) *report = r;
    return out;
}

SurfaceMesh remove_hanging_sheets(const SurfaceMesh& mesh, HangingSheets* report) {
    if (report) *report = HangingSheets{};
    const EdgeTable et = edge_table(mesh);
    UnionFind sheet(static_cast<std::size_t>(mesh.num_faces()));
    bool non_manifold = false;
    for (Index e = 0; e < et.faces.rows(); ++e) {
        if (et.faces.row_size(e) == 2) sheet.unite(et.faces.row_begin(e)[0], et.faces.row_begin(e)[1]);
        non_manifold = non_manifold || et.faces.row_size(e) > 2;
    }
    if (!non_manifold) return mesh;
    std::vector<char> free_edge(static_cast<std::size_t>(mesh.num_faces()), 0), on_fold(free_edge);
    for (Index e = 0; e < et.faces.rows(); ++e)
        for (const Index* f = et.faces.row_begin(e); f != et.faces.row_end(e); ++f) {
            const auto s = static_cast<std::size_t>(sheet.find(*f));
            if (et.faces.row_size(e) == 1) free_edge[s] = 1;
            if (et.faces.row_size(e) > 2) on_fold[s] = 1;
        }
    // The candidate sheets, smallest first; one goes where every edge of three or more faces it
    // lies on keeps two faces without it (a flap goes, not the body it hangs on).
    std::map<Index, std::vector<Index>> faces_of;
    for (Index f = 0; f < mesh.num_faces(); ++f) {
        const Index s = sheet.find(f);
        if (free_edge[static_cast<std::size_t>(s)] && on_fold[static_cast<std::size_t>(s)]) faces_of[s].push_back(f);
    }
    std::vector<std::pair<std::size_t, Index>> order;
    for (const auto& [s, faces] : faces_of) order.emplace_back(faces.size(), s);
    std::sort(order.begin(), order.end());
    std::vector<Index> kept(static_cast<std::size_t>(et.faces.rows()));
    for (Index e = 0; e < et.faces.rows(); ++e) kept[static_cast<std::size_t>(e)] = et.faces.row_size(e);
    std::vector<char> drop(static_cast<std::size_t>(mesh.num_faces()), 0);
    HangingSheets r;
    for (const auto& [size, s] : order) {
        std::map<Index, Index> on_edge;  // fold edge -> this sheet's faces on it
        for (const Index f : faces_of[s])
            for (Index c = 0; c < mesh.face_size(f); ++c) {
                const Index e = find_edge(et, mesh.face_node(f, c), mesh.face_node(f, (c + 1) % mesh.face_size(f)));
                if (e != kNone && et.faces.row_size(e) > 2) ++on_edge[e];  // kNone: a collapsed edge (a, a)
            }
        bool hangs = true;
        for (const auto& [e, n] : on_edge) hangs = hangs && kept[static_cast<std::size_t>(e)] - n >= 2;
        if (!hangs) continue;
        for (const auto& [e, n] : on_edge) kept[static_cast<std::size_t>(e)] -= n;
        for (const Index f : faces_of[s]) drop[static_cast<std::size_t>(f)] = 1;
        if (r.sheets++ == 0) r.at = face_centroid(mesh, mesh.points, faces_of[s].front());
        r.faces += static_cast<Index>(faces_of[s].size());
    }
    if (r.faces == 0) return mesh;
    for (Index e = 0; e < et.faces.rows(); ++e)  // all or nothing: every edge of two faces at most
        if (kept[static_cast<std::size_t>(e)] > 2) return mesh;
    if (report) *report = r;
    return remove_faces(mesh, drop);
}

SurfaceMesh flip_flat_triangles(const SurfaceMesh& mesh, double rel_height, Index* flipped) {
    SurfaceMesh out = mesh;
    Index count = 0;
    for (int round = 0; round < 8; ++round) {
        const EdgeTable et = edge_table(out);
        std::vector<char> touched(static_cast<std::size_t>(out.num_faces()), 0);
        Index now = 0;
        for (Index f = 0; f < out.num_faces(); ++f) {
            if (out.face_size(f) != 3 || touched[static_cast<std::size_t>(f)]) continue;
            // The longest edge (a, b), in the face's order, and the apex c.
            int longest = 0;
            double len2 = -1.0;
            for (int i = 0; i < 3; ++i) {
                const double l =
                    (out.points[out.face_node(f, (i + 1) % 3)] - out.points[out.face_node(f, i)]).squaredNorm();
                if (l > len2) len2 = l, longest = i;
            }
            const Index a = out.face_node(f, longest), b = out.face_node(f, (longest + 1) % 3),
                        c = out.face_node(f, (longest + 2) % 3);
            const double height = 2.0 * face_area_vector(out, f).norm() / std::sqrt(len2);
            if (!(len2 > 0.0) || !(height < rel_height * std::sqrt(len2))) continue;
            const Index e = find_edge(et, a, b);
            if (e == kNone || et.faces.row_size(e) != 2) continue;
            const Index g = et.faces.row_begin(e)[0] == f ? et.faces.row_begin(e)[1] : et.faces.row_begin(e)[0];
            if (out.face_size(g) != 3 || touched[static_cast<std::size_t>(g)] || out.face_patch[g] != out.face_patch[f])
                continue;
            Index d = kNone;
            bool opposite = false;  // g runs b → a, as a consistent neighbour does
            for (int i = 0; i < 3; ++i) {
                const Index x = out.face_node(g, i), y = out.face_node(g, (i + 1) % 3);
                if (x == b && y == a) opposite = true, d = out.face_node(g, (i + 2) % 3);
            }
            if (!opposite || d == c || find_edge(et, c, d) != kNone) continue;
            Index* fn = out.face_nodes.data() + out.face_offsets[f];
            Index* gn = out.face_nodes.data() + out.face_offsets[g];
            fn[0] = a, fn[1] = d, fn[2] = c;
            gn[0] = d, gn[1] = b, gn[2] = c;
            touched[static_cast<std::size_t>(f)] = touched[static_cast<std::size_t>(g)] = 1;
            ++now;
        }
        count += now;
        if (now == 0) break;
    }
    if (flipped) *flipped = count;
    return out;
}

SurfaceMesh remove_collapsed_faces(const SurfaceMesh& mesh, Index* changed) {
    require_valid_ids(mesh, "remove_collapsed_faces", true);
    SurfaceMesh out;
    out.patches = mesh.patches;
    Index count = 0;
    std::vector<Index> nodes;
    for (Index f = 0; f < mesh.num_faces(); ++f) {
        const Index* v = mesh.face_begin(f);
        const Index k = mesh.face_size(f);
        // The corners without a repeat of the one before (cyclically): a quad's adjacent
        // repeat drops out, an opposite one is left for the count below.
        nodes.clear();
        for (Index i = 0; i < k; ++i)
            if (v[i] != v[(i + k - 1) % k]) nodes.push_back(v[i]);
        bool distinct = true;
        for (std::size_t i = 0; i < nodes.size(); ++i)
            for (std::size_t j = i + 1; j < nodes.size(); ++j) distinct = distinct && nodes[i] != nodes[j];
        if (nodes.size() == static_cast<std::size_t>(k) && distinct) {
            out.add_face(v, k, mesh.face_patch[f]);
            continue;
        }
        ++count;
        if (nodes.size() == 3 && distinct) out.add_face(nodes.data(), 3, mesh.face_patch[f]);
    }
    if (changed) *changed = count;
    if (count == 0) {
        out.points = mesh.points;  // the faces are the same: so are the nodes
        return out;
    }
    drop_unused_nodes(mesh.points, out);
    return out;
}

SurfaceMesh split_long_edges(const SurfaceMesh& mesh, double max_length, Index max_faces, Index* splits) {
    if (!(max_length > 0.0) || !std::isfinite(max_length))
        throw InputError("split_long_edges: the longest edge kept must be a positive length, got " +
                         format_number(max_length));
    SurfaceMesh out = mesh;
    const double limit2 = max_length * max_length;
    Index count = 0;
    // An edge's key: its squared length, then its nodes; the longest of a face is its largest key.
    using Key = std::tuple<double, Index, Index>;
    const auto key = [&out](Index a, Index b) {
        return Key{(out.points[b] - out.points[a]).squaredNorm(), std::min(a, b), std::max(a, b)};
    };
    const auto longest = [&](Index f) {
        int best = 0;
        for (int i = 1; i < 3; ++i)
            if (key(out.face_node(f, i), out.face_node(f, (i + 1) % 3)) >
                key(out.face_node(f, best), out.face_node(f, (best + 1) % 3)))
                best = i;
        return best;
    };
    while (out.num_faces() < max_faces) {
        const EdgeTable et = edge_table(out);
        // The edges to split this round: too long, and the longest edge of every face on them.
        std::vector<std::pair<Key, Index>> todo;
        for (Index e = 0; e < static_cast<Index>(et.nodes.size()); ++e) {
            const auto [a, b] = et.nodes[static_cast<std::size_t>(e)];
            const Key k = key(a, b);
            if (!(std::get<0>(k) > limit2)) continue;
            bool terminal = true;
            for (const Index* f = et.faces.row_begin(e); f != et.faces.row_end(e) && terminal; ++f) {
                if (out.face_size(*f) != 3) {
                    terminal = false;
                    break;
                }
                const int i = longest(*f);
                const Index x = out.face_node(*f, i), y = out.face_node(*f, (i + 1) % 3);
                terminal = std::min(x, y) == a && std::max(x, y) == b;
            }
            if (terminal) todo.emplace_back(k, e);
        }
        if (todo.empty()) break;
        std::sort(todo.begin(), todo.end(), [](const auto& x, const auto& y) { return x.first > y.first; });
        std::vector<char> touched(static_cast<std::size_t>(out.num_faces()), 0);
        Index now = 0;
        for (const auto& [k, e] : todo) {
            if (out.num_faces() >= max_faces) break;
            bool free = true;
            for (const Index* f = et.faces.row_begin(e); f != et.faces.row_end(e); ++f)
                free = free && !touched[static_cast<std::size_t>(*f)];
            if (!free) continue;
            const auto [a, b] = et.nodes[static_cast<std::size_t>(e)];
            const Index m = static_cast<Index>(out.points.size());
            out.points.push_back(0.5 * (out.points[a] + out.points[b]));
            for (const Index* f = et.faces.row_begin(e); f != et.faces.row_end(e); ++f) {
                touched[static_cast<std::size_t>(*f)] = 1;
                // The face's corners (u, v, w) with u → v the split edge in the face's order.
                int i = 0;
                while (!(std::minmax(out.face_node(*f, i), out.face_node(*f, (i + 1) % 3)) == std::minmax(a, b))) ++i;
                const Index u = out.face_node(*f, i), v = out.face_node(*f, (i + 1) % 3),
                            w = out.face_node(*f, (i + 2) % 3);
                Index* fn = out.face_nodes.data() + out.face_offsets[static_cast<std::size_t>(*f)];
                fn[0] = u, fn[1] = m, fn[2] = w;
                const std::array<Index, 3> half{m, v, w};
                out.add_face(half.data(), 3, out.face_patch[*f]);
            }
            ++now;
        }
        count += now;
    }
    if (splits) *splits = count;
    return out;
}

SurfaceMesh remove_faces(const SurfaceMesh& mesh, const std::vector<char>& drop) {
    require_valid_ids(mesh, "remove_faces", true);
    if (drop.size() != static_cast<std::size_t>(mesh.num_faces()))
        throw InputError("remove_faces: " + std::to_string(drop.size()) + " flags for " +
                         std::to_string(mesh.num_faces()) + " faces");
    SurfaceMesh out;
    out.patches = mesh.patches;
    for (Index f = 0; f < mesh.num_faces(); ++f)
        if (!drop[static_cast<std::size_t>(f)]) out.add_face(mesh.face_begin(f), mesh.face_size(f), mesh.face_patch[f]);
    drop_unused_nodes(mesh.points, out);
    return out;
}

Csr vertex_faces(const SurfaceMesh& mesh) {
    require_valid_ids(mesh, "vertex_faces");
    const Index n = mesh.num_points();
    Csr r;
    r.offsets.assign(static_cast<std::size_t>(n) + 1, 0);
    // A face that repeats a node (collapsed) is listed once for it.
    auto first_occurrence = [&](Index f, Index i) {
        const Index* v = mesh.face_begin(f);
        for (Index j = 0; j < i; ++j)
            if (v[j] == v[i]) return false;
        return true;
    };
    for (Index f = 0; f < mesh.num_faces(); ++f)
        for (Index i = 0; i < mesh.face_size(f); ++i)
            if (first_occurrence(f, i)) ++r.offsets[mesh.face_node(f, i) + 1];
    for (Index v = 0; v < n; ++v) r.offsets[v + 1] += r.offsets[v];
    r.values.resize(static_cast<std::size_t>(r.offsets.back()));
    std::vector<Index> cursor(r.offsets.begin(), r.offsets.end() - 1);
    for (Index f = 0; f < mesh.num_faces(); ++f)  // increasing f → rows sorted
        for (Index i = 0; i < mesh.face_size(f); ++i)
            if (first_occurrence(f, i)) r.values[cursor[mesh.face_node(f, i)]++] = f;
    return r;
}

Index find_edge(const EdgeTable& edges, Index a, Index b) {
    const std::array<Index, 2> key{std::min(a, b), std::max(a, b)};
    const auto it = std::lower_bound(edges.nodes.begin(), edges.nodes.end(), key);
    return it != edges.nodes.end() && *it == key ? static_cast<Index>(it - edges.nodes.begin()) : kNone;
}

EdgeTable edge_table(const SurfaceMesh& mesh) {
    require_valid_ids(mesh, "edge_table");
    const Index n = mesh.num_points();
    // Bucket the half-edges by their low node (counting sort, O(n)), then sort each small
    // bucket by (high node, face): edges come out sorted by (low, high), faces increasing.
    std::vector<Index> start(static_cast<std::size_t>(n) + 1, 0);
    auto for_each_half_edge = [&](auto&& fn) {
        for (Index f = 0; f < mesh.num_faces(); ++f) {
            const Index* v = mesh.face_begin(f);
            const Index s = mesh.face_size(f);
            for (Index i = 0; i < s; ++i) {
                const Index a = v[i], b = v[(i + 1) % s];
                if (a != b) fn(std::min(a, b), std::max(a, b), f);
            }
        }
    };
    for_each_half_edge([&](Index lo, Index, Index) { ++start[lo + 1]; });
    for (Index v = 0; v < n; ++v) start[v + 1] += start[v];
    std::vector<std::pair<Index, Index>> half(static_cast<std::size_t>(start.back()));  // (high, face)
    std::vector<Index> cursor(start.begin(), start.end() - 1);
    for_each_half_edge([&](Index lo, Index hi, Index f) { half[cursor[lo]++] = {hi, f}; });

    EdgeTable t;
    t.nodes.reserve(half.size() / 2 + 1);
    t.faces.values.reserve(half.size());
    for (Index lo = 0; lo < n; ++lo) {
        auto b = half.begin() + start[lo], e = half.begin() + start[lo + 1];
        std::sort(b, e);
        for (auto it = b; it != e;) {
            const Index hi = it->first;
            t.nodes.push_back({lo, hi});
            Index last = kNone;
            for (; it != e && it->first == hi; ++it)
                if (it->second != last) {  // a collapsed face may list an edge twice
                    t.faces.values.push_back(it->second);
                    last = it->second;
                }
            t.faces.offsets.push_back(static_cast<Index>(t.faces.values.size()));
        }
    }
    return t;
}

Csr boundary_loops(const SurfaceMesh& mesh) {
    const EdgeTable t = edge_table(mesh);
    const Index n = mesh.num_points();
    std::vector<Index> next(n, kNone);
    std::vector<char> incoming(n, 0);
    auto touching = [&](Index v) {
        return TopologyError("boundary_loops: two boundary loops touch at " + node_text(mesh, v) +
                             " (or the faces there are inconsistently oriented); a node may lie on "
                             "at most one boundary loop: split the node or fix the surface in the CAD tool");
    };
    for (std::size_t e = 0; e < t.nodes.size(); ++e) {
        if (t.faces.row_size(static_cast<Index>(e)) != 1) continue;
        const Index f = *t.faces.row_begin(static_cast<Index>(e));
        Index a = t.nodes[e][0], b = t.nodes[e][1];
        if (!traverses(mesh, f, a, b)) std::swap(a, b);
        if (next[a] != kNone) throw touching(a);
        if (incoming[b]) throw touching(b);
        next[a] = b;
        incoming[b] = 1;
    }
    // Each node has at most one boundary edge in and one out, so the boundary is a set of
    // disjoint cycles (or broken chains if orientation is inconsistent). Starting from the
    // lowest unvisited node makes every loop start at its lowest node id.
    Csr loops;
    std::vector<char> visited(n, 0);
    for (Index s = 0; s < n; ++s) {
        if (next[s] == kNone || visited[s]) continue;
        Index v = s;
        do {
            visited[v] = 1;
            loops.values.push_back(v);
            v = next[v];
            if (v == kNone || (visited[v] && v != s))
                throw TopologyError("boundary_loops: the boundary through " + node_text(mesh, s) +
                                    " does not close into a loop; the faces are inconsistently oriented "
                                    "(run orient_surface first) or the surface is non-manifold there");
        } while (v != s);
        loops.offsets.push_back(static_cast<Index>(loops.values.size()));
    }
    return loops;
}

std::vector<Index> face_components(const SurfaceMesh& mesh, Index* num_components) {
    const EdgeTable t = edge_table(mesh);
    const Index nf = mesh.num_faces();
    std::vector<Index> parent(static_cast<std::size_t>(nf));
    std::iota(parent.begin(), parent.end(), Index{0});
    auto find = [&](Index f) {
        while (parent[f] != f) {
            parent[f] = parent[parent[f]];  // path halving
            f = parent[f];
        }
        return f;
    };
    for (Index e = 0; e < t.faces.rows(); ++e) {
        const Index* fs = t.faces.row_begin(e);
        for (Index k = 1; k < t.faces.row_size(e); ++k) {
            const Index a = find(fs[0]), b = find(fs[k]);
            if (a != b) parent[std::max(a, b)] = std::min(a, b);
        }
    }
    std::vector<Index> id(static_cast<std::size_t>(nf), kNone), comp(static_cast<std::size_t>(nf));
    Index count = 0;
    for (Index f = 0; f < nf; ++f) {
        const Index r = find(f);
        if (id[r] == kNone) id[r] = count++;  // numbered in order of their lowest face
        comp[f] = id[r];
    }
    if (num_components) *num_components = count;
    return comp;
}

NodeRings node_rings(const SurfaceMesh& mesh) {
    const Csr vf = vertex_faces(mesh);
    const Index n = mesh.num_points();

    NodeRings r;
    r.neighbours.offsets.reserve(static_cast<std::size_t>(n) + 1);
    r.neighbours.values.reserve(vf.values.size() + static_cast<std::size_t>(n));
    r.faces.reserve(vf.values.size() + static_cast<std::size_t>(n));
    r.diagonals.reserve(vf.values.size() + static_cast<std::size_t>(n));
    r.closed.assign(static_cast<std::size_t>(n), 0);

    // One sector per incident face: walking counter-clockwise around o inside face f goes
    // from the node after o (`next`) to the node before o (`prev`).
    struct Sector {
        Index next, prev, face, diagonal;
    };
    std::vector<Sector> sectors;
    // Node-indexed scratch, reset after each node, so chaining sectors is O(1) per sector
    // (O(total ring size) overall, also for high-valence poles).
    std::vector<Index> by_next(static_cast<std::size_t>(n), kNone);
    std::vector<char> is_prev(static_cast<std::size_t>(n), 0);

    for (Index o = 0; o < n; ++o) {
        sectors.clear();
        for (const Index* fp = vf.row_begin(o); fp != vf.row_end(o); ++fp) {
            const Index f = *fp;
            const Index* v = mesh.face_begin(f);
            const Index s = mesh.face_size(f);
            Index i = 0;
            while (v[i] != o) ++i;
            const Sector sec{v[(i + 1) % s], v[(i + s - 1) % s], f, s == 4 ? v[(i + 2) % 4] : kNone};
            if (sec.next == o || sec.prev == o || sec.next == sec.prev)
                throw TopologyError("node_rings: face " + std::to_string(f) + " at " + node_text(mesh, o) +
                                    " repeats a node; run check_surface and remove collapsed faces");
            sectors.push_back(sec);
        }
        auto reset = [&] {
            for (const Sector& s : sectors) {
                by_next[s.next] = kNone;
                is_prev[s.prev] = 0;
            }
        };
        const Index ns = static_cast<Index>(sectors.size());
        for (Index k = 0; k < ns; ++k) {
            const Sector& s = sectors[k];
            // Two faces leaving o along the same edge, or arriving along the same edge: the edge
            // is used twice in one direction (inconsistent orientation) or is non-manifold.
            const bool clash_next = by_next[s.next] != kNone;
            const bool clash_prev = is_prev[s.prev] != 0;
            if (clash_next || clash_prev) {
                const Index other = clash_next ? sectors[by_next[s.next]].face : kNone;
                const Index m = clash_next ? s.next : s.prev;
                reset();
                throw TopologyError("node_rings: " + node_text(mesh, o) + ": the edge to node " + std::to_string(m) +
                                    " is traversed in the same direction by face " + std::to_string(s.face) +
                                    (other != kNone ? " and face " + std::to_string(other) : std::string()) +
                                    "; orient the surface consistently (orient_surface) and check it "
                                    "is manifold (check_surface)");
            }
            by_next[s.next] = k;
            is_prev[s.prev] = 1;
        }
        // An open fan starts at the neighbour no sector arrives at; a closed one at the
        // sector of the lowest incident face (deterministic).
        Index start = ns > 0 ? 0 : kNone;
        Index open_starts = 0;
        for (Index k = 0; k < ns; ++k)
            if (!is_prev[sectors[k].next]) {
                if (open_starts == 0) start = k;
                ++open_starts;
            }
        Index walked = 0;
        bool closed = false;
        if (start != kNone && open_starts <= 1) {
            Index k = start;
            while (true) {
                const Sector& s = sectors[k];
                r.neighbours.values.push_back(s.next);
                r.faces.push_back(s.face);
                r.diagonals.push_back(s.diagonal);
                ++walked;
                const Index nk = by_next[s.prev];
                if (nk == start) {
                    closed = true;
                    break;
                }
                if (nk == kNone || walked > ns) {
                    // Open side: the last neighbour closes the list, its sector is empty.
                    r.neighbours.values.push_back(s.prev);
                    r.faces.push_back(kNone);
                    r.diagonals.push_back(kNone);
                    break;
                }
                k = nk;
            }
        }
        reset();
        if (walked != ns || open_starts > 1) {
            const Index fans = std::max<Index>(open_starts, 2);
            throw TopologyError("node_rings: " + node_text(mesh, o) + " is a non-manifold vertex: its " +
                                std::to_string(ns) + " faces form " +
                                (open_starts > 1 ? std::to_string(fans) : std::string("several")) +
                                " separate fans touching at the node; split the node or fix the surface "
                                "in the CAD tool");
        }
        r.closed[o] = closed ? 1 : 0;
        r.neighbours.offsets.push_back(static_cast<Index>(r.neighbours.values.size()));
    }
    return r;
}

}  // namespace strata
