// fill_with_tets: the input's checks, the choice of mesher, and the independent check of what
// the mesher returned; TetGen's part is tetgen_fill.cpp, HXT's hxt_fill.cpp.

#include "tet_fill_parts.h"

#include <strata/core/error.h>
#include <strata/core/format.h>
#include <strata/core/mesh_check.h>
#include <strata/hybrid/tetgen_fill.h>

#include <cmath>
#include <limits>
#include <string>

namespace strata {
namespace {

/// (1/6) a·(b×c): the triangle's share of the volume it and the rest of a closed surface enclose.
double triangle_volume_term(const Vec3& a, const Vec3& b, const Vec3& c) {
    return a.dot(b.cross(c)) / 6.0;
}

/// det(v1−v0, v2−v0, v3−v0) / 6.
double tet_volume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
    return (b - a).cross(c - a).dot(d - a) / 6.0;
}

}  // namespace

namespace tet_fill {

std::string face_name(const SurfaceMesh& b, Index f) {
    std::string s = "boundary triangle " + std::to_string(f);
    const Index p = b.face_patch[f];
    if (p >= 0 && p < static_cast<Index>(b.patches.size())) s += " (patch '" + b.patches[p].name + "')";
    Vec3 c = Vec3::Zero();
    for (int i = 0; i < 3; ++i) c += b.points[b.face_node(f, i)];
    return s + " at " + format_point(c / 3.0);
}

void check_input(const SurfaceMesh& b, const std::vector<Vec3>& holes, const TetFillParams& p) {
    const std::string where = "fill_with_tets: ";
    // One check for every stage; TetGen fills a triangulated boundary (quads are split first,
    // by pyramids on the layer top). A non-finite coordinate is the caller's input here too.
    const MeshProblems arrays = check_surface_arrays(b, {.triangles_only = true, .word = "boundary face"});
    if (!arrays.ok()) throw InputError(where + arrays.lines.front());
    if (b.points.size() > static_cast<std::size_t>(std::numeric_limits<int>::max() / 3) ||
        b.face_nodes.size() > static_cast<std::size_t>(std::numeric_limits<int>::max()))
        throw InputError(where + "the boundary is too large for TetGen's 32-bit ints");
    for (std::size_t h = 0; h < holes.size(); ++h)
        if (!holes[h].allFinite())
            throw InputError(where + "hole point " + std::to_string(h) + " has a non-finite coordinate");

    if (p.refine) {
        if (!(p.radius_edge >= 1.0) || !std::isfinite(p.radius_edge))
            throw InputError(where + "radius_edge = " + format_number(p.radius_edge) +
                             " is below 1: TetGen would refine without end; use 1.2 or more");
        if (!(p.min_dihedral >= 0.0 && p.min_dihedral < 70.0))
            throw InputError(where + "min_dihedral = " + format_number(p.min_dihedral) +
                             " degrees is outside [0, 70); TetGen reaches about 15-18 in practice");
        if (!(p.max_dihedral == 0.0 || (p.max_dihedral > 90.0 && p.max_dihedral < 180.0)))
            throw InputError(where + "max_dihedral = " + format_number(p.max_dihedral) +
                             " degrees is outside (90, 180); 0 keeps TetGen's own bound (165)");
        if (!(p.max_volume >= 0.0) || !std::isfinite(p.max_volume))
            throw InputError(where + "max_volume = " + format_number(p.max_volume) +
                             " must be 0 (no bound) or positive");
        if (!(p.growth >= 0.0) || !std::isfinite(p.growth))
            throw InputError(where + "growth = " + format_number(p.growth) + " must be 0 (no sizing) or positive");
    }
}

/// Volume enclosed by the boundary (divergence theorem; positive when normals point out).
double enclosed_volume(const SurfaceMesh& b) {
    double v = 0.0;
    for (Index f = 0; f < b.num_faces(); ++f)
        v +=
            triangle_volume_term(b.points[b.face_node(f, 0)], b.points[b.face_node(f, 1)], b.points[b.face_node(f, 2)]);
    return v;
}

/// Boundary triangle by node set; throws InputError on a repeated triangle.
FaceIndex index_faces(const SurfaceMesh& b) {
    FaceIndex face_of;
    face_of.reserve(static_cast<std::size_t>(b.num_faces()) * 2);
    for (Index f = 0; f < b.num_faces(); ++f) {
        const auto [it, fresh] = face_of.emplace(tri_key(b.face_node(f, 0), b.face_node(f, 1), b.face_node(f, 2)), f);
        if (!fresh)
            throw InputError("fill_with_tets: " + face_name(b, f) + " has the same nodes as " +
                             face_name(b, it->second) + "; remove duplicate triangles");
    }
    return face_of;
}

void check_fill(const SurfaceMesh& b, const FaceIndex& face_of, const TetFill& fill, double boundary_volume,
                std::string_view mesher) {
    const std::string where = "fill_with_tets: ";
    const std::string who(mesher);
    const Index nb = b.num_points();
    if (fill.points.size() < b.points.size())
        throw BackendError(where + who + " returned " + std::to_string(fill.points.size()) + " points for " +
                           std::to_string(nb) +
                           " boundary nodes: it dropped or merged some (duplicate or unused nodes); merge "
                           "coincident nodes and remove unused ones first");
    if (fill.tets.empty())
        throw BackendError(where + who +
                           " produced no tetrahedra: a hole point lies in the region to fill (hole points "
                           "go inside the cavities, e.g. inside the body), or the boundary does not enclose a "
                           "region");
    for (Index i = 0; i < nb; ++i)
        if (fill.points[i] != b.points[i])
            throw BackendError(where + who + " moved or renumbered boundary node " + std::to_string(i) + " at " +
                               format_point(b.points[i]) + " (now " + format_point(fill.points[i]) +
                               "); merge coincident nodes and remove unused ones first");

    const Index np = static_cast<Index>(fill.points.size());
    double tet_volume_sum = 0.0;
    for (std::size_t t = 0; t < fill.tets.size(); ++t) {
        const auto& tet = fill.tets[t];
        for (Index x : tet)
            if (x < 0 || x >= np)
                throw BackendError(where + who + "'s tet " + std::to_string(t) + " uses node " + std::to_string(x) +
                                   " of " + std::to_string(np));
        const double vol =
            tet_volume(fill.points[tet[0]], fill.points[tet[1]], fill.points[tet[2]], fill.points[tet[3]]);
        if (!(vol > 0.0))
            throw BackendError(where + who + "'s tet " + std::to_string(t) + " at " +
                               format_point(0.25 * (fill.points[tet[0]] + fill.points[tet[1]] + fill.points[tet[2]] +
                                                    fill.points[tet[3]])) +
                               " has volume " + format_number(vol, 3) + " (not positive)");
        tet_volume_sum += vol;
    }

    // Every boundary triangle must be a face of exactly one tet, which lies on the side the
    // triangle's normal points away from.
    std::vector<int> count(static_cast<std::size_t>(b.num_faces()), 0);
    std::vector<char> wrong_side(static_cast<std::size_t>(b.num_faces()), 0);
    static constexpr int kFace[4][4] = {{1, 2, 3, 0}, {0, 2, 3, 1}, {0, 1, 3, 2}, {0, 1, 2, 3}};  // 3 nodes + opposite
    for (const auto& tet : fill.tets) {
        for (const auto& lf : kFace) {
            if (tet[lf[0]] >= nb || tet[lf[1]] >= nb || tet[lf[2]] >= nb) continue;
            const auto it = face_of.find(tri_key(tet[lf[0]], tet[lf[1]], tet[lf[2]]));
            if (it == face_of.end()) continue;
            const Index f = it->second;
            ++count[f];
            const Vec3 &x0 = b.points[b.face_node(f, 0)], &x1 = b.points[b.face_node(f, 1)],
                       &x2 = b.points[b.face_node(f, 2)];
            if (tet_volume(x0, x1, x2, fill.points[tet[lf[3]]]) >= 0.0) wrong_side[f] = 1;
        }
    }
    for (Index f = 0; f < b.num_faces(); ++f) {
        if (count[f] == 0)
            throw BackendError(where + face_name(b, f) +
                               " is not a face of the tet mesh: " + who + " split it (a Steiner point on the boundary) "
                               "or left its side empty (a hole point on the wrong side)");
        if (count[f] > 1)
            throw BackendError(where + face_name(b, f) + " is a face of " + std::to_string(count[f]) +
                               " tets: the region lies on both of its sides (an internal or unclosed boundary "
                               "part, or a missing hole point for a cavity)");
    }
    for (Index f = 0; f < b.num_faces(); ++f)
        if (wrong_side[f])
            throw InputError(where + face_name(b, f) +
                             " points into the region to fill; orient the boundary with normals out of the "
                             "region (outer boundary outward, cavity walls into the cavity)");

    // The tets fill exactly the enclosed region: no overlap, no gap.
    const double scale = std::max(std::abs(boundary_volume), std::numeric_limits<double>::min());
    if (std::abs(tet_volume_sum - boundary_volume) > 1e-9 * scale)
        throw BackendError(where + "the tets' volume " + format_number(tet_volume_sum, 12) +
                           " differs from the volume the boundary encloses " + format_number(boundary_volume, 12) +
                           ": " + who + "'s mesh overlaps or leaves gaps (a missing hole point?)");
}

}  // namespace tet_fill

std::string_view to_string(TetMesher mesher) {
    return mesher == TetMesher::Hxt ? "hxt" : "tetgen";
}

TetMesher parse_tet_mesher(std::string_view text) {
    if (text == "tetgen") return TetMesher::TetGen;
    if (text == "hxt") return TetMesher::Hxt;
    throw InputError("tetrahedral mesher '" + std::string(text) + "': use tetgen (the default) or hxt (Gmsh's HXT, parallel)");
}

TetFill fill_with_tets(const SurfaceMesh& boundary, const std::vector<Vec3>& holes, const TetFillParams& params,
                       Progress* progress) {
    tet_fill::check_input(boundary, holes, params);
    const double volume = tet_fill::enclosed_volume(boundary);
    if (!(volume > 0.0))
        throw InputError("fill_with_tets: the boundary encloses a volume of " + format_number(volume, 6) +
                         " (not positive): its normals point into the region to fill; orient it with normals "
                         "out of the region (outer boundary outward, cavity walls into the cavity)");
    const tet_fill::FaceIndex face_of = tet_fill::index_faces(boundary);
    if (params.mesher == TetMesher::Hxt) return tet_fill::fill_with_hxt(boundary, face_of, volume, params, progress);
    return tet_fill::fill_with_tetgen(boundary, face_of, volume, holes, params, progress);
}

}  // namespace strata
