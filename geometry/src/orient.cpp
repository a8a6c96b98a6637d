#include <strata/core/format.h>
#include <strata/geometry/check.h>

#include <strata/core/error.h>
#include <strata/core/face_geometry.h>
#include <strata/geometry/topology.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

namespace strata {
namespace {

/// +1 if face f traverses the edge (lo, hi) as lo → hi, -1 if hi → lo.
int direction(const SurfaceMesh& mesh, Index f, Index lo, Index hi) {
    const Index* v = mesh.face_begin(f);
    const Index n = mesh.face_size(f);
    for (Index i = 0; i < n; ++i) {
        const Index a = v[i], b = v[(i + 1) % n];
        if (a == lo && b == hi) return 1;
        if (a == hi && b == lo) return -1;
    }
    return 0;  // not reached for an edge of f
}

/// Solid angle of triangle (a, b, c) seen from the origin, signed by its orientation
/// (Van Oosterom & Strackee); atan2 keeps it accurate for nearly flat or distant triangles.
double solid_angle(const Vec3& a, const Vec3& b, const Vec3& c) {
    const double la = a.norm(), lb = b.norm(), lc = c.norm();
    const double num = a.dot(b.cross(c));
    const double den = la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la;
    return 2.0 * std::atan2(num, den);
}

/// Generalised winding number of the faces \p faces around \p p: ±1 inside a closed surface,
/// 0 outside, whatever the mesh quality (no ray casting, no degenerate hits).
/// \p flip marks faces whose node order counts reversed (the BFS result, not yet applied).
double winding_number(const SurfaceMesh& mesh, const Index* faces, const Index* faces_end,
                      const std::vector<char>& flip, const Vec3& p) {
    double sum = 0.0;
    for (const Index* f = faces; f != faces_end; ++f) {
        const Index* v = mesh.face_begin(*f);
        const Vec3 a = mesh.points[v[0]] - p, b = mesh.points[v[1]] - p, c = mesh.points[v[2]] - p;
        double w = solid_angle(a, b, c);
        if (mesh.face_size(*f) == 4) w += solid_angle(a, c, mesh.points[v[3]] - p);
        sum += flip[*f] ? -w : w;
    }
    return sum / (4.0 * std::numbers::pi);
}

/// Face → its edges (CSR), from the edge → faces table.
Csr face_edges_of(const EdgeTable& edges, Index nf) {
    const Index ne = edges.faces.rows();
    Csr face_edges;
    face_edges.offsets.assign(static_cast<std::size_t>(nf) + 1, 0);
    for (Index f : edges.faces.values) ++face_edges.offsets[f + 1];
    for (Index f = 0; f < nf; ++f) face_edges.offsets[f + 1] += face_edges.offsets[f];
    face_edges.values.resize(edges.faces.values.size());
    std::vector<Index> cursor(face_edges.offsets.begin(), face_edges.offsets.end() - 1);
    for (Index e = 0; e < ne; ++e)
        for (const Index* f = edges.faces.row_begin(e); f != edges.faces.row_end(e); ++f)
            face_edges.values[cursor[*f]++] = e;
    return face_edges;
}

/// The connected components of a surface with one consistent orientation each.
struct Components {
    Index count = 0;
    std::vector<Index> of_face;  ///< face → its component
    std::vector<char> flip;      ///< face → reverse it (the orientation chosen so far)
    Csr faces;                   ///< component → its faces in BFS order
    std::vector<char> closed;    ///< component → no boundary edge

    void invert(Index c) {
        for (const Index* f = faces.row_begin(c); f != faces.row_end(c); ++f) flip[*f] ^= 1;
    }
};

std::string edge_text(const SurfaceMesh& mesh, const EdgeTable& edges, Index e) {
    const Index a = edges.nodes[e][0], b = edges.nodes[e][1];
    return "edge between node " + std::to_string(a) + " " + format_point(mesh.points[a], 9) + " and node " +
           std::to_string(b) + " " + format_point(mesh.points[b], 9);
}

/// Breadth-first from the lowest face of each component. flip[g] is chosen so that g
/// traverses every shared edge opposite to its already placed neighbour. TopologyError on a
/// non-manifold edge or a non-orientable component.
Components consistent_orientation(const SurfaceMesh& mesh, const EdgeTable& edges) {
    const Index nf = mesh.num_faces();
    const Csr face_edges = face_edges_of(edges, nf);
    Components c;
    c.of_face.assign(static_cast<std::size_t>(nf), kNone);
    c.flip.assign(static_cast<std::size_t>(nf), 0);
    c.faces.values.reserve(static_cast<std::size_t>(nf));
    for (Index s = 0; s < nf; ++s) {
        if (c.of_face[s] != kNone) continue;
        const std::size_t first = c.faces.values.size();
        c.of_face[s] = c.count;
        c.faces.values.push_back(s);
        for (std::size_t q = first; q < c.faces.values.size(); ++q) {
            const Index f = c.faces.values[q];
            for (const Index* ep = face_edges.row_begin(f); ep != face_edges.row_end(f); ++ep) {
                const Index e = *ep;
                const Index k = edges.faces.row_size(e);
                if (k == 1) continue;
                if (k > 2)
                    throw TopologyError("orient_surface: non-manifold " + edge_text(mesh, edges, e) + " is shared by " +
                                        std::to_string(k) + " faces; run check_surface first and fix the surface");
                const Index* fs = edges.faces.row_begin(e);
                const Index g = fs[0] == f ? fs[1] : fs[0];
                const Index lo = edges.nodes[e][0], hi = edges.nodes[e][1];
                const bool same_direction = direction(mesh, f, lo, hi) == direction(mesh, g, lo, hi);
                const char want = static_cast<char>(c.flip[f] ^ (same_direction ? 1 : 0));
                if (c.of_face[g] == kNone) {
                    c.of_face[g] = c.count;
                    c.flip[g] = want;
                    c.faces.values.push_back(g);
                } else if (c.flip[g] != want) {
                    throw TopologyError("orient_surface: surface component " + std::to_string(c.count) +
                                        " (containing face " + std::to_string(s) +
                                        ") is not orientable (like a Moebius strip): faces " + std::to_string(f) +
                                        " and " + std::to_string(g) + " cannot agree on the direction of the " +
                                        edge_text(mesh, edges, e) +
                                        "; it has no consistent inside and outside, fix the "
                                        "surface in the CAD tool");
                }
            }
        }
        c.faces.offsets.push_back(static_cast<Index>(c.faces.values.size()));
        ++c.count;
    }
    c.closed.assign(static_cast<std::size_t>(c.count), 1);
    for (Index e = 0; e < edges.faces.rows(); ++e)
        if (edges.faces.row_size(e) == 1) c.closed[c.of_face[*edges.faces.row_begin(e)]] = 0;
    return c;
}

/// Closed components that enclose the flow domain: those with a farfield face, and those that
/// contain another component (its probe point, the centroid of its lowest face: a component
/// inside a closed surface lies wholly inside it, as components do not intersect); with
/// \p internal_flow also those that lie in no other closed component.
std::vector<char> outer_components(const SurfaceMesh& mesh, const Components& comps, bool internal_flow) {
    std::vector<char> outer(static_cast<std::size_t>(comps.count), 0);
    for (Index f = 0; f < mesh.num_faces(); ++f) {
        const Index p = mesh.face_patch[f];
        if (p >= 0 && p < static_cast<Index>(mesh.patches.size()) && mesh.patches[p].kind == PatchKind::Farfield)
            outer[comps.of_face[f]] = 1;
    }
    std::vector<Vec3> probe(static_cast<std::size_t>(comps.count));
    for (Index c = 0; c < comps.count; ++c) probe[c] = face_centroid(mesh, mesh.points, *comps.faces.row_begin(c));
    std::vector<char> inside_another(static_cast<std::size_t>(comps.count), 0);
    for (Index c = 0; c < comps.count; ++c) {
        if (!comps.closed[c]) continue;
        // Bounding box first: most pairs are rejected without touching the faces.
        BoundingBox box;
        box.min = box.max = mesh.points[mesh.face_node(*comps.faces.row_begin(c), 0)];
        for (const Index* f = comps.faces.row_begin(c); f != comps.faces.row_end(c); ++f)
            for (const Index* v = mesh.face_begin(*f); v != mesh.face_end(*f); ++v) {
                box.min = box.min.cwiseMin(mesh.points[*v]);
                box.max = box.max.cwiseMax(mesh.points[*v]);
            }
        for (Index d = 0; d < comps.count; ++d) {
            if (d == c) continue;
            if (outer[c] && !internal_flow) break;  // outer already; which others it holds does not matter
            const Vec3& p = probe[d];
            if ((p.array() < box.min.array()).any() || (p.array() > box.max.array()).any()) continue;
            if (std::abs(winding_number(mesh, comps.faces.row_begin(c), comps.faces.row_end(c), comps.flip, p)) > 0.5)
                outer[c] = 1, inside_another[static_cast<std::size_t>(d)] = 1;
        }
    }
    if (internal_flow)
        for (Index c = 0; c < comps.count; ++c)
            if (comps.closed[c] && !inside_another[static_cast<std::size_t>(c)]) outer[c] = 1;
    return outer;
}

/// The mean of component \p c's face centroids: the point volumes are measured from, so that a
/// body far from the origin does not lose its volume in cancellation.
Vec3 centroid_of(const SurfaceMesh& mesh, const Components& comps, Index c) {
    Vec3 ref = Vec3::Zero();
    for (const Index* f = comps.faces.row_begin(c); f != comps.faces.row_end(c); ++f)
        ref += face_centroid(mesh, mesh.points, *f);
    return ref / static_cast<double>(comps.faces.row_size(c));
}

/// Signed volume component \p c's faces enclose from \p ref with their current orientation
/// (divergence theorem; a closed component's whole volume).
double volume_from(const SurfaceMesh& mesh, const Components& comps, Index c, const Vec3& ref) {
    double volume = 0.0;
    for (const Index* f = comps.faces.row_begin(c); f != comps.faces.row_end(c); ++f) {
        const double v = (face_centroid(mesh, mesh.points, *f) - ref).dot(face_area_vector(mesh, *f)) / 3.0;
        volume += comps.flip[*f] ? -v : v;
    }
    return volume;
}

/// Signed volume closed component \p c encloses with its current orientation.
double enclosed_volume(const SurfaceMesh& mesh, const Components& comps, Index c) {
    return volume_from(mesh, comps, c, centroid_of(mesh, comps, c));
}

/// Per component: for an open one whose open boundary lies in one plane (a half model cut along
/// its symmetry plane), the signed volume it encloses with that cut closed by a flat cap (the
/// faces' term plus the cap's: its vector area, traversing every open edge against the faces,
/// from a point of the plane); 0 for any other component, and where that volume is round-off
/// (below 1e-9 of the cube of the component's extent: a flat sheet lying in its own rim's plane).
std::vector<double> capped_volumes(const SurfaceMesh& mesh, const EdgeTable& edges, const Components& comps) {
    const auto nc = static_cast<std::size_t>(comps.count);
    std::vector<std::vector<Vec3>> cut(nc);
    std::vector<std::vector<std::pair<Vec3, Vec3>>> open(nc);  // the open edges as the faces go
    for (Index e = 0; e < edges.faces.rows(); ++e) {
        if (edges.faces.row_size(e) != 1) continue;
        const Index f = edges.faces.row_begin(e)[0];
        const auto c = static_cast<std::size_t>(comps.of_face[static_cast<std::size_t>(f)]);
        const Index lo = edges.nodes[static_cast<std::size_t>(e)][0], hi = edges.nodes[static_cast<std::size_t>(e)][1];
        const bool forward = (direction(mesh, f, lo, hi) > 0) != static_cast<bool>(comps.flip[f]);
        open[c].emplace_back(mesh.points[forward ? lo : hi], mesh.points[forward ? hi : lo]);
        cut[c].push_back(mesh.points[lo]);
        cut[c].push_back(mesh.points[hi]);
    }
    std::vector<double> volume(nc, 0.0);
    for (Index c = 0; c < comps.count; ++c) {
        const auto u = static_cast<std::size_t>(c);
        if (cut[u].empty()) continue;
        const PatchPlane plane = fit_plane(cut[u]);
        if (!plane.planar()) continue;
        const Vec3& o = plane.point;
        Vec3 cap = Vec3::Zero();                                         // the cap's vector area, times 2
        for (const auto& [a, b] : open[u]) cap += (b - o).cross(a - o);  // the cap goes b → a
        const Vec3 ref = centroid_of(mesh, comps, c);
        std::vector<Vec3> nodes;
        for (const Index* f = comps.faces.row_begin(c); f != comps.faces.row_end(c); ++f)
            for (const Index* v = mesh.face_begin(*f); v != mesh.face_end(*f); ++v) nodes.push_back(mesh.points[*v]);
        const double size = bounding_box(nodes).diagonal();
        const double v = volume_from(mesh, comps, c, ref) + (o - ref).dot(0.5 * cap) / 3.0;
        if (std::abs(v) > 1e-9 * size * size * size) volume[u] = v;
    }
    return volume;
}

}  // namespace

SurfaceMesh orient_surface(const SurfaceMesh& mesh, OrientReport* report, bool internal_flow) {
    const EdgeTable edges = edge_table(mesh);
    Components comps = consistent_orientation(mesh, edges);
    if (internal_flow && std::none_of(comps.closed.begin(), comps.closed.end(), [](char c) { return c != 0; }))
        throw InputError(
            "internal flow (PrepareParams::internal_flow) asks for walls that enclose the fluid, but no part of the "
            "surface is closed (" +
            std::to_string(comps.count) +
            " open components): close the duct with its inflow and outflow patches, or mesh the flow around "
            "the surface without it");

    // Open components: the BFS root's orientation is arbitrary, the majority is what the user
    // meant (an already consistent surface stays untouched). A tie keeps the root's. But a half
    // model (its open boundary in one plane: the symmetry plane) is a body whose cut is closed
    // by that plane: it points outward into the flow, whatever its file said (a CAD tool's
    // export of the fluid's boundary points into the body, and the layers would grow inside).
    for (Index c = 0; c < comps.count; ++c) {
        if (comps.closed[c]) continue;
        Index flipped = 0;
        for (const Index* f = comps.faces.row_begin(c); f != comps.faces.row_end(c); ++f) flipped += comps.flip[*f];
        if (2 * flipped > comps.faces.row_size(c)) comps.invert(c);
    }
    if (!internal_flow && std::any_of(comps.closed.begin(), comps.closed.end(), [](char c) { return c == 0; })) {
        const std::vector<double> capped = capped_volumes(mesh, edges, comps);
        for (Index c = 0; c < comps.count; ++c)
            if (capped[static_cast<std::size_t>(c)] < 0.0) comps.invert(c);
    }

    // Closed components: outer surfaces point into the domain they enclose (negative volume),
    // bodies point outward into the flow (positive volume).
    const std::vector<char> outer = outer_components(mesh, comps, internal_flow);
    Index num_closed = 0;
    for (Index c = 0; c < comps.count; ++c) {
        if (!comps.closed[c]) continue;
        ++num_closed;
        const double volume = enclosed_volume(mesh, comps, c);
        if (volume != 0.0 && (volume < 0.0) != static_cast<bool>(outer[c])) comps.invert(c);
    }

    // Reverse keeping the first node (a,b,c,d → a,d,c,b): node set and first node stay.
    SurfaceMesh out = mesh;
    Index flipped = 0;
    for (Index f = 0; f < mesh.num_faces(); ++f) {
        if (!comps.flip[f]) continue;
        std::reverse(out.face_nodes.begin() + out.face_offsets[f] + 1,
                     out.face_nodes.begin() + out.face_offsets[f + 1]);
        ++flipped;
    }
    if (report) {
        report->components = comps.count;
        report->flipped_faces = flipped;
        report->closed_components = num_closed;
    }
    return out;
}

}  // namespace strata
