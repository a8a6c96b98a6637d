// The tetrahedral fill by TetGen 1.5 (Debian's libtet), the default mesher of fill_with_tets
// (tet_fill.cpp checks the input and the result for either mesher). TetGen itself is loaded and
// called through tetgen_library.h, the size field built in tetgen_sizing.h.
//
// What happens:
//  1. The boundary, already checked, is handed to TetGen as a PLC: one facet of one polygon per
//     triangle, the hole seeds as volume holes.
//  2. TetGen runs with  p Y z Q [q<ratio>[/<angle>]] [a<vol>] [m]:
//       p  the input is a PLC;
//       Y  the boundary triangles are kept exactly: no Steiner point on the boundary (the
//          layer top must stay conforming with the prisms/pyramids under it);
//       z  0-based indices, so TetGen's point i is our point i;
//       Q  quiet (TetGen prints to stdout otherwise);
//       q  radius-edge [/ min dihedral] bound, only with params.refine;
//       a  global volume bound, only with params.refine and max_volume > 0;
//       m  sizing field (only with params.refine and growth > 0), see below.
//  3. The result is converted (Gmsh tet order) and checked independently of TetGen
//     (tet_fill::check_fill).
//
// Memory: tetgenio's destructor frees every array with delete[] (deinitialize()), so the
// arrays given to it are allocated with new[] and owned by the tetgenio from that moment.

#include "tet_fill_parts.h"
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

namespace strata::tet_fill {
namespace {

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

/// TetGen's output as a TetFill (TetGen 1.5 writes a tet (a, b, c, d) with its
/// orient3d(a, b, c, d) < 0, i.e. d on the side (a, b, c)'s right-hand normal points to: already
/// Gmsh's order; check_fill checks every sign), then checked by check_fill.
TetFill convert_and_check(const SurfaceMesh& b, const FaceIndex& face_of, const tetgenio& out, double boundary_volume) {
    if (out.numberofcorners != 4 || out.firstnumber != 0)
        throw BackendError("fill_with_tets: TetGen returned tets of " + std::to_string(out.numberofcorners) +
                           " nodes numbered from " + std::to_string(out.firstnumber) + " (expected 4 from 0)");
    TetFill fill;
    if (out.pointlist != nullptr) {
        fill.points.resize(static_cast<std::size_t>(std::max(out.numberofpoints, 0)));
        for (std::size_t i = 0; i < fill.points.size(); ++i)
            fill.points[i] = Vec3(out.pointlist[3 * i], out.pointlist[3 * i + 1], out.pointlist[3 * i + 2]);
    }
    if (out.tetrahedronlist != nullptr) {
        fill.tets.resize(static_cast<std::size_t>(std::max(out.numberoftetrahedra, 0)));
        for (std::size_t t = 0; t < fill.tets.size(); ++t) {
            const int* v = out.tetrahedronlist + 4 * t;
            fill.tets[t] = {v[0], v[1], v[2], v[3]};
        }
    }
    check_fill(b, face_of, fill, boundary_volume, "TetGen");
    return fill;
}

/// run(), and where TetGen fails at a place of the boundary (one of its internal checks, or
/// its codes 2-5), the place: its run repeated with its trace finds the boundary face (or
/// edge) it was recovering, and the failure becomes a LocalTopologyError at that face's nodes (the caller may change
/// the boundary there and try again). Where the trace names no place the BackendError stands.
void run_locating(const std::string& switches, const SurfaceMesh& b, const FaceIndex& face_of, tetgenio& in,
                  tetgenio& out, tetgenio* background, Progress* progress) {
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

TetFill fill_with_tetgen(const SurfaceMesh& boundary, const FaceIndex& face_of, double volume,
                         const std::vector<Vec3>& holes, const TetFillParams& params, Progress* progress) {
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
    // The background mesh took 15 to 25 % of the fill's time on the sphere, the M6 and the airliner.
    ProgressRange first(progress, 0.0, 0.2), then(progress, 0.2, 1.0);
    {
        tetgenio bg_in;
        set_plc(bg_in, tetgen::background_boundary(boundary), {});  // convex, cavities included (c, no holes)
        tetgen::run(tetgen::switches(params, false, true, tolerance), bg_in, background, nullptr,
                    progress ? &first : nullptr);
    }
    if (background.numberofpoints < boundary.num_points() || background.numberoftetrahedra <= 0)
        throw BackendError(
            "fill_with_tets: TetGen's background mesh for the sizing field is empty or lost boundary nodes; "
            "check the hole points (inside the cavities) and merge coincident nodes");
    tetgen::set_sizes(background, boundary.num_points(), h);
    tetgen::set_sizes(in, boundary.num_points(), h);
    run_locating(tetgen::switches(params, true, false, tolerance), boundary, face_of, in, out, &background,
                 progress ? &then : nullptr);
    return convert_and_check(boundary, face_of, out, volume);
}

}  // namespace strata::tet_fill
