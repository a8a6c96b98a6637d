// The tetrahedral fill: Strata's one adapter to TetGen 1.5 (Debian's libtet). TetGen itself
// is loaded and called through tetgen_library.h, the size field built in tetgen_sizing.h.
//
// What happens:
//  1. The boundary is checked (triangles only, ids in range, finite, no repeated triangle,
//     encloses a positive volume, i.e. normals point out of the region) and handed to
//     TetGen as a PLC: one facet of one polygon per triangle, the hole seeds as volume holes.
//  2. TetGen runs with  p Y z Q [q<ratio>[/<angle>]] [a<vol>] [m]:
//       p  the input is a PLC;
//       Y  the boundary triangles are kept exactly: no Steiner point on the boundary (the
//          layer top must stay conforming with the prisms/pyramids under it);
//       z  0-based indices, so TetGen's point i is our point i;
//       Q  quiet (TetGen prints to stdout otherwise);
//       q  radius-edge [/ min dihedral] bound, only with params.refine;
//       a  global volume bound, only with params.refine and max_volume > 0;
//       m  sizing field (only with params.refine and growth > 0), see below.
//  3. The result is converted (Gmsh tet order, positive volume) and checked independently of
//     TetGen: the boundary points come back unchanged with their ids, every tet has positive
//     volume, every boundary triangle is a face of exactly one tet with that tet on the side
//     its normal points away from, and the tet volumes sum to the volume the boundary
//     encloses. Together (a tet face cannot have a vertex of another tet inside it in a
//     conforming mesh) this means no Steiner point lies on the boundary. A violation is a
//     BackendError, a wrongly oriented boundary an InputError.
//
// Memory: tetgenio's destructor frees every array with delete[] (deinitialize()), so the
// arrays given to it are allocated with new[] and owned by the tetgenio from that moment.

#include "tetgen_sizing.h"

#include <strata/core/error.h>
#include <strata/core/format.h>
#include <strata/core/mesh_check.h>
#include <strata/hybrid/tetgen_fill.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <unordered_map>
#include <vector>

namespace strata {
namespace {

std::string face_name(const SurfaceMesh& b, Index f) {
    std::string s = "boundary triangle " + std::to_string(f);
    const Index p = b.face_patch[f];
    if (p >= 0 && p < static_cast<Index>(b.patches.size())) s += " (patch '" + b.patches[p].name + "')";
    Vec3 c = Vec3::Zero();
    for (int i = 0; i < 3; ++i) c += b.points[b.face_node(f, i)];
    return s + " at " + format_point(c / 3.0);
}

/// (1/6) a·(b×c): the triangle's share of the volume it and the rest of a closed surface enclose.
double triangle_volume_term(const Vec3& a, const Vec3& b, const Vec3& c) {
    return a.dot(b.cross(c)) / 6.0;
}

/// det(v1−v0, v2−v0, v3−v0) / 6.
double tet_volume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
    return (b - a).cross(c - a).dot(d - a) / 6.0;
}

// ---------------------------------------------------------------------------------------
// Input checks.

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

// ---------------------------------------------------------------------------------------
// TetGen input, switches and failures.

/// Points and facets (one triangle each) and hole seeds into \p io; the arrays are new[]ed
/// and owned by io from here on (tetgenio::deinitialize delete[]s them).
void set_plc(tetgenio& io, const SurfaceMesh& b, const std::vector<Vec3>& holes) {
    io.firstnumber = 0;
    io.numberofpoints = static_cast<int>(b.points.size());
    io.pointlist = new REAL[3 * b.points.size()];
    for (std::size_t i = 0; i < b.points.size(); ++i)
        for (int k = 0; k < 3; ++k) io.pointlist[3 * i + k] = b.points[i][k];

    const int nf = static_cast<int>(b.num_faces());
    io.facetlist = new tetgenio::facet[nf];
    io.numberoffacets = nf;  // every facet initialised before deinitialize could walk it
    for (int f = 0; f < nf; ++f) tetgenio::init(&io.facetlist[f]);
    for (int f = 0; f < nf; ++f) {
        tetgenio::facet& fa = io.facetlist[f];
        fa.polygonlist = new tetgenio::polygon[1];
        tetgenio::init(&fa.polygonlist[0]);
        fa.numberofpolygons = 1;
        fa.polygonlist[0].vertexlist = new int[3];
        fa.polygonlist[0].numberofvertices = 3;
        for (int i = 0; i < 3; ++i) fa.polygonlist[0].vertexlist[i] = static_cast<int>(b.face_node(f, i));
    }

    if (!holes.empty()) {
        io.holelist = new REAL[3 * holes.size()];
        io.numberofholes = static_cast<int>(holes.size());
        for (std::size_t h = 0; h < holes.size(); ++h)
            for (int k = 0; k < 3; ++k) io.holelist[3 * h + k] = holes[h][k];
    }
}

// ---------------------------------------------------------------------------------------
// Result conversion and checks.

/// Sorted node triple: the key of a triangle regardless of orientation.
struct TriKey {
    std::array<Index, 3> v;
    bool operator==(const TriKey& o) const { return v == o.v; }
};
struct TriKeyHash {
    std::size_t operator()(const TriKey& k) const {
        std::size_t h = static_cast<std::size_t>(k.v[0]) * 0x9E3779B97F4A7C15ull;
        h ^= static_cast<std::size_t>(k.v[1]) + 0x9E3779B97F4A7C15ull + (h << 6) + (h >> 2);
        h ^= static_cast<std::size_t>(k.v[2]) + 0x9E3779B97F4A7C15ull + (h << 6) + (h >> 2);
        return h;
    }
};
TriKey tri_key(Index a, Index b, Index c) {
    std::array<Index, 3> v{a, b, c};
    std::sort(v.begin(), v.end());
    return {v};
}
using FaceIndex = std::unordered_map<TriKey, Index, TriKeyHash>;

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

TetFill convert_and_check(const SurfaceMesh& b, const FaceIndex& face_of, const tetgenio& out, double boundary_volume) {
    const std::string where = "fill_with_tets: ";
    const Index nb = b.num_points();
    if (out.numberofpoints < nb || out.pointlist == nullptr)
        throw BackendError(where + "TetGen returned " + std::to_string(out.numberofpoints) + " points for " +
                           std::to_string(nb) +
                           " boundary nodes: it dropped or merged some (duplicate or unused nodes); merge "
                           "coincident nodes and remove unused ones first");
    if (out.numberoftetrahedra <= 0 || out.tetrahedronlist == nullptr)
        throw BackendError(where +
                           "TetGen produced no tetrahedra: a hole point lies in the region to fill (hole points "
                           "go inside the cavities, e.g. inside the body), or the boundary does not enclose a "
                           "region");
    if (out.numberofcorners != 4 || out.firstnumber != 0)
        throw BackendError(where + "TetGen returned tets of " + std::to_string(out.numberofcorners) +
                           " nodes numbered from " + std::to_string(out.firstnumber) + " (expected 4 from 0)");

    TetFill fill;
    fill.points.resize(static_cast<std::size_t>(out.numberofpoints));
    for (int i = 0; i < out.numberofpoints; ++i)
        fill.points[i] = Vec3(out.pointlist[3 * i], out.pointlist[3 * i + 1], out.pointlist[3 * i + 2]);
    for (Index i = 0; i < nb; ++i)
        if (fill.points[i] != b.points[i])
            throw BackendError(where + "TetGen moved or renumbered boundary node " + std::to_string(i) + " at " +
                               format_point(b.points[i]) + " (now " + format_point(fill.points[i]) +
                               "); merge coincident nodes and remove unused ones first");

    // TetGen 1.5 writes a tet (a, b, c, d) with its orient3d(a, b, c, d) < 0, i.e. d on the
    // side (a, b, c)'s right-hand normal points to: already Gmsh's order. The sign of every tet
    // is checked below rather than assumed.
    const Index np = static_cast<Index>(fill.points.size());
    fill.tets.resize(static_cast<std::size_t>(out.numberoftetrahedra));
    double tet_volume_sum = 0.0;
    for (int t = 0; t < out.numberoftetrahedra; ++t) {
        const int* v = out.tetrahedronlist + 4 * static_cast<std::size_t>(t);
        std::array<Index, 4> tet{v[0], v[1], v[2], v[3]};
        for (Index x : tet)
            if (x < 0 || x >= np)
                throw BackendError(where + "TetGen's tet " + std::to_string(t) + " uses node " + std::to_string(x) +
                                   " of " + std::to_string(np));
        const double vol =
            tet_volume(fill.points[tet[0]], fill.points[tet[1]], fill.points[tet[2]], fill.points[tet[3]]);
        if (!(vol > 0.0))
            throw BackendError(where + "TetGen's tet " + std::to_string(t) + " at " +
                               format_point(0.25 * (fill.points[tet[0]] + fill.points[tet[1]] + fill.points[tet[2]] +
                                                    fill.points[tet[3]])) +
                               " has volume " + format_number(vol, 3) + " (not positive)");
        tet_volume_sum += vol;
        fill.tets[t] = tet;
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
                               " is not a face of the tet mesh: TetGen split it (a Steiner point on the boundary) "
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
                           ": TetGen's mesh overlaps or leaves gaps (a missing hole point?)");
    return fill;
}

/// run(), and where TetGen fails at a place of the boundary (one of its internal checks, or
/// its codes 2-5), the place: its run repeated with its trace finds the boundary face (or
/// edge) it was recovering, and the failure becomes a LocalTopologyError at that face's nodes (the caller may change
/// the boundary there and try again). Where the trace names no place the BackendError stands.
void run_locating(const std::string& switches, const SurfaceMesh& b, const FaceIndex& face_of, tetgenio& in,
                  tetgenio& out, tetgenio* background, const Progress* progress) {
    try {
        tetgen::run(switches, in, out, background, progress);
    } catch (const tetgen::LocalFailure& e) {
        const std::vector<int> ids = tetgen::locate_failure(switches, in, background, progress);
        if (ids.empty()) throw;
        std::vector<Index> nodes(ids.begin(), ids.end());
        std::string where;
        if (nodes.size() == 3) {
            if (const auto it = face_of.find(tri_key(nodes[0], nodes[1], nodes[2])); it != face_of.end())
                where = face_name(b, it->second);
        }
        if (where.empty()) {
            where = nodes.size() == 2 ? "boundary edge" : "boundary nodes";
            Vec3 c = Vec3::Zero();
            for (const Index v : nodes) {
                where += " " + std::to_string(v);
                c += b.points[static_cast<std::size_t>(v)];
            }
            where += " at " + format_point(c / static_cast<double>(nodes.size()));
        }
        throw LocalTopologyError(std::string(e.what()) + "; it was recovering " + where, std::move(nodes));
    }
}

}  // namespace

TetFill fill_with_tets(const SurfaceMesh& boundary, const std::vector<Vec3>& holes, const TetFillParams& params,
                       const Progress* progress) {
    check_input(boundary, holes, params);
    const double volume = enclosed_volume(boundary);
    if (!(volume > 0.0))
        throw InputError("fill_with_tets: the boundary encloses a volume of " + format_number(volume, 6) +
                         " (not positive): its normals point into the region to fill; orient it with normals "
                         "out of the region (outer boundary outward, cavity walls into the cavity)");
    const FaceIndex face_of = index_faces(boundary);

    const bool sizing = params.refine && params.growth > 0.0;
    const double tolerance = tetgen::tolerance_keeping_points(boundary.points);
    tetgenio in, out;
    set_plc(in, boundary, holes);
    if (!sizing) {
        run_locating(tetgen::switches(params, false, false, tolerance), boundary, face_of, in, out, nullptr, progress);
        return convert_and_check(boundary, face_of, out, volume);
    }

    const tetgen::SizeField h(boundary, params.growth, params.max_volume);
    if (!params.background_mesh) {  // sizes at the boundary points only, interpolated by TetGen
        tetgen::set_sizes(in, boundary.num_points(), h);
        run_locating(tetgen::switches(params, true, false, tolerance), boundary, face_of, in, out, nullptr, progress);
        return convert_and_check(boundary, face_of, out, volume);
    }
    tetgenio background;
    {
        tetgenio bg_in;
        set_plc(bg_in, tetgen::background_boundary(boundary), {});  // convex, cavities included (c, no holes)
        tetgen::run(tetgen::switches(params, false, true, tolerance), bg_in, background, nullptr, progress);
    }
    if (background.numberofpoints < boundary.num_points() || background.numberoftetrahedra <= 0)
        throw BackendError(
            "fill_with_tets: TetGen's background mesh for the sizing field is empty or lost boundary nodes; "
            "check the hole points (inside the cavities) and merge coincident nodes");
    tetgen::set_sizes(background, boundary.num_points(), h);
    tetgen::set_sizes(in, boundary.num_points(), h);
    run_locating(tetgen::switches(params, true, false, tolerance), boundary, face_of, in, out, &background, progress);
    return convert_and_check(boundary, face_of, out, volume);
}

}  // namespace strata
