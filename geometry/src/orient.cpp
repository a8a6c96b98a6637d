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

}  // namespace

SurfaceMesh orient_surface(const SurfaceMesh& mesh, OrientReport* report) {
    const Index nf = mesh.num_faces();
    const EdgeTable edges = edge_table(mesh);
    const Index ne = edges.faces.rows();

    // Face → its edges (CSR), from the edge → faces table.
    Csr face_edges;
    face_edges.offsets.assign(static_cast<std::size_t>(nf) + 1, 0);
    for (Index f : edges.faces.values) ++face_edges.offsets[f + 1];
    for (Index f = 0; f < nf; ++f) face_edges.offsets[f + 1] += face_edges.offsets[f];
    face_edges.values.resize(edges.faces.values.size());
    {
        std::vector<Index> cursor(face_edges.offsets.begin(), face_edges.offsets.end() - 1);
        for (Index e = 0; e < ne; ++e)
            for (const Index* f = edges.faces.row_begin(e); f != edges.faces.row_end(e); ++f)
                face_edges.values[cursor[*f]++] = e;
    }

    auto edge_text = [&](Index e) {
        const Index a = edges.nodes[e][0], b = edges.nodes[e][1];
        return "edge between node " + std::to_string(a) + " " + format_point(mesh.points[a], 9) + " and node " +
               std::to_string(b) + " " + format_point(mesh.points[b], 9);
    };

    // Breadth-first from the lowest face of each component. flip[g] is chosen so that g
    // traverses every shared edge opposite to its already placed neighbour.
    std::vector<Index> comp(static_cast<std::size_t>(nf), kNone);
    std::vector<char> flip(static_cast<std::size_t>(nf), 0);
    Csr comp_faces;  // component → its faces in BFS order
    comp_faces.values.reserve(static_cast<std::size_t>(nf));
    Index ncomp = 0;
    for (Index s = 0; s < nf; ++s) {
        if (comp[s] != kNone) continue;
        const std::size_t first = comp_faces.values.size();
        comp[s] = ncomp;
        comp_faces.values.push_back(s);
        for (std::size_t q = first; q < comp_faces.values.size(); ++q) {
            const Index f = comp_faces.values[q];
            for (const Index* ep = face_edges.row_begin(f); ep != face_edges.row_end(f); ++ep) {
                const Index e = *ep;
                const Index k = edges.faces.row_size(e);
                if (k == 1) continue;
                if (k > 2)
                    throw TopologyError("orient_surface: non-manifold " + edge_text(e) + " is shared by " +
                                        std::to_string(k) + " faces; run check_surface first and fix the surface");
                const Index* fs = edges.faces.row_begin(e);
                const Index g = fs[0] == f ? fs[1] : fs[0];
                const Index lo = edges.nodes[e][0], hi = edges.nodes[e][1];
                const bool same_direction = direction(mesh, f, lo, hi) == direction(mesh, g, lo, hi);
                const char want = static_cast<char>(flip[f] ^ (same_direction ? 1 : 0));
                if (comp[g] == kNone) {
                    comp[g] = ncomp;
                    flip[g] = want;
                    comp_faces.values.push_back(g);
                } else if (flip[g] != want) {
                    throw TopologyError(
                        "orient_surface: surface component " + std::to_string(ncomp) + " (containing face " +
                        std::to_string(s) + ") is not orientable (like a Moebius strip): faces " + std::to_string(f) +
                        " and " + std::to_string(g) + " cannot agree on the direction of the " + edge_text(e) +
                        "; it has no consistent inside and outside, fix the "
                        "surface in the CAD tool");
                }
            }
        }
        comp_faces.offsets.push_back(static_cast<Index>(comp_faces.values.size()));
        ++ncomp;
    }

    std::vector<char> closed(static_cast<std::size_t>(ncomp), 1);
    for (Index e = 0; e < ne; ++e)
        if (edges.faces.row_size(e) == 1) closed[comp[*edges.faces.row_begin(e)]] = 0;

    auto invert = [&](Index c) {
        for (const Index* f = comp_faces.row_begin(c); f != comp_faces.row_end(c); ++f) flip[*f] ^= 1;
    };

    // Open components: the BFS root's orientation is arbitrary, the majority is what the user
    // meant (an already consistent surface stays untouched). A tie keeps the root's.
    for (Index c = 0; c < ncomp; ++c) {
        if (closed[c]) continue;
        Index flipped = 0;
        for (const Index* f = comp_faces.row_begin(c); f != comp_faces.row_end(c); ++f) flipped += flip[*f];
        if (2 * flipped > comp_faces.row_size(c)) invert(c);
    }

    // Closed components: which ones enclose the flow domain ("outer")?
    std::vector<char> outer(static_cast<std::size_t>(ncomp), 0);
    for (Index f = 0; f < nf; ++f) {
        const Index p = mesh.face_patch[f];
        if (p >= 0 && p < static_cast<Index>(mesh.patches.size()) && mesh.patches[p].kind == PatchKind::Farfield)
            outer[comp[f]] = 1;
    }
    // One probe point per component (centroid of its lowest face): a component inside a
    // closed surface lies wholly inside it, as components do not intersect.
    std::vector<Vec3> probe(static_cast<std::size_t>(ncomp));
    for (Index c = 0; c < ncomp; ++c) probe[c] = face_centroid(mesh, mesh.points, *comp_faces.row_begin(c));
    for (Index c = 0; c < ncomp; ++c) {
        if (!closed[c] || outer[c]) continue;
        // Bounding box first: most pairs are rejected without touching the faces.
        BoundingBox box;
        box.min = box.max = mesh.points[mesh.face_node(*comp_faces.row_begin(c), 0)];
        for (const Index* f = comp_faces.row_begin(c); f != comp_faces.row_end(c); ++f)
            for (const Index* v = mesh.face_begin(*f); v != mesh.face_end(*f); ++v) {
                box.min = box.min.cwiseMin(mesh.points[*v]);
                box.max = box.max.cwiseMax(mesh.points[*v]);
            }
        for (Index d = 0; d < ncomp && !outer[c]; ++d) {
            if (d == c) continue;
            const Vec3& p = probe[d];
            if ((p.array() < box.min.array()).any() || (p.array() > box.max.array()).any()) continue;
            if (std::abs(winding_number(mesh, comp_faces.row_begin(c), comp_faces.row_end(c), flip, p)) > 0.5)
                outer[c] = 1;
        }
    }

    // Signed enclosed volume (divergence theorem) with the BFS orientation. Measured from the
    // component's centroid so that a body far from the origin does not lose the volume in
    // cancellation.
    Index num_closed = 0;
    for (Index c = 0; c < ncomp; ++c) {
        if (!closed[c]) continue;
        ++num_closed;
        Vec3 ref = Vec3::Zero();
        for (const Index* f = comp_faces.row_begin(c); f != comp_faces.row_end(c); ++f)
            ref += face_centroid(mesh, mesh.points, *f);
        ref /= static_cast<double>(comp_faces.row_size(c));
        double volume = 0.0;
        for (const Index* f = comp_faces.row_begin(c); f != comp_faces.row_end(c); ++f) {
            const double v = (face_centroid(mesh, mesh.points, *f) - ref).dot(face_area_vector(mesh, *f)) / 3.0;
            volume += flip[*f] ? -v : v;
        }
        // Outer surfaces point into the domain they enclose (negative volume), bodies point
        // outward into the flow (positive volume).
        if (volume != 0.0 && (volume < 0.0) != static_cast<bool>(outer[c])) invert(c);
    }

    // Reverse keeping the first node (a,b,c,d → a,d,c,b): node set and first node stay.
    SurfaceMesh out = mesh;
    Index flipped = 0;
    for (Index f = 0; f < nf; ++f) {
        if (!flip[f]) continue;
        std::reverse(out.face_nodes.begin() + out.face_offsets[f] + 1,
                     out.face_nodes.begin() + out.face_offsets[f + 1]);
        ++flipped;
    }
    if (report) {
        report->components = ncomp;
        report->flipped_faces = flipped;
        report->closed_components = num_closed;
    }
    return out;
}

}  // namespace strata
