// The tetrahedral fill by Gmsh's HXT (fill_with_tets with TetMesher::Hxt); hxt_library.cpp says
// how HXT is called.
//
// What happens:
//  1. Each connected part of the boundary (triangles joined through their nodes) is one HXT
//     surface, and the one volume to fill is the region bounded by all of them: a cavity that
//     one part encloses alone (inside the layer top) is another region HXT neither refines nor
//     returns, so no hole points are needed.
//  2. The boundary nodes carry TetGen's sizes (tetgen::SizeField: each node its own mean edge
//     length, h = h_wall + growth · d away from the wall, capped at the farfield's), and every
//     point HXT would insert is given h at its place (in parallel), both times kSizePerEdge,
//     so that both meshers grade alike.
//  3. HXT's Delaunay, boundary recovery and refinement run on TetFillParams::threads threads
//     (not its improvement: hxt_library.h says why; improve_tets follows as after TetGen); the boundary's points keep their ids, HXT's points follow in
//     its order, the tets of other regions are dropped and those of the volume checked as
//     TetGen's are (tet_fill::check_fill): a point HXT's boundary recovery put on the boundary
//     fails there, with the advice to use TetGen.

#include "hxt_library.h"
#include "tet_fill_parts.h"
#include "tetgen_sizing.h"

#include <strata/core/error.h>
#include <strata/core/parallel.h>

#include <numeric>
#include <string>
#include <vector>

namespace strata::tet_fill {
namespace {
/// HXT's size per target edge length: HXT spaces its points about 1.48 × the size it is given
/// (mean tet edge over h at 1.2, 2.2 and 3.2 from a cube: 1.50, 1.48, 1.46; HxtFill.
/// SizeGradingFollowsGrowth), so it is given h / 1.48 for the mean edge to be h, as TetGen's is.
constexpr double kSizePerEdge = 0.68;

/// Each face's connected part of \p b (faces joined through a common node), numbered from 0
/// in the order of their first faces.
std::vector<std::uint32_t> connected_parts(const SurfaceMesh& b, std::uint32_t& parts) {
    std::vector<Index> parent(static_cast<std::size_t>(b.num_points()));
    std::iota(parent.begin(), parent.end(), Index{0});
    auto root = [&](Index v) {
        while (parent[v] != v) v = parent[v] = parent[parent[v]];
        return v;
    };
    for (Index f = 0; f < b.num_faces(); ++f)
        for (int i = 1; i < 3; ++i) {
            const Index r0 = root(b.face_node(f, 0)), ri = root(b.face_node(f, i));
            if (r0 != ri) parent[std::max(r0, ri)] = std::min(r0, ri);
        }
    std::vector<std::uint32_t> part_of_root(parent.size(), UINT32_MAX), part(static_cast<std::size_t>(b.num_faces()));
    parts = 0;
    for (Index f = 0; f < b.num_faces(); ++f) {
        std::uint32_t& p = part_of_root[root(b.face_node(f, 0))];
        if (p == UINT32_MAX) p = parts++;
        part[f] = p;
    }
    return part;
}

hxt::Input hxt_input(const SurfaceMesh& b, const tetgen::SizeField* h) {
    hxt::Input in;
    in.points.resize(b.points.size());
    in.sizes.assign(b.points.size(), 0.0);  // 0: HXT takes the mean length of the node's edges
    for (std::size_t i = 0; i < b.points.size(); ++i) {
        in.points[i] = {b.points[i].x(), b.points[i].y(), b.points[i].z()};
        if (h) in.sizes[i] = kSizePerEdge * h->boundary_size(static_cast<Index>(i));
    }
    in.triangles.resize(static_cast<std::size_t>(b.num_faces()));
    for (Index f = 0; f < b.num_faces(); ++f)
        for (int k = 0; k < 3; ++k) in.triangles[f][k] = static_cast<std::uint32_t>(b.face_node(f, k));
    std::uint32_t parts = 0;
    in.triangle_surface = connected_parts(b, parts);
    in.surfaces.resize(parts);
    std::iota(in.surfaces.begin(), in.surfaces.end(), 0u);
    return in;
}

/// HXT's volume as a TetFill: the boundary's points, then HXT's points that a tet uses (in HXT's
/// order); the tets as HXT orients them, which is Gmsh's order (check_fill checks every sign).
TetFill to_fill(const SurfaceMesh& b, const hxt::Output& out) {
    const std::size_t nb = b.points.size();
    std::vector<Index> id(out.points.size(), -1);
    for (std::size_t i = 0; i < nb && i < out.points.size(); ++i) id[i] = static_cast<Index>(i);
    for (const auto& t : out.tets)
        for (const std::uint32_t v : t)
            if (v < id.size() && id[v] < 0) id[v] = 0;  // used: numbered below, in HXT's order
    TetFill fill;
    fill.points.reserve(out.points.size());
    for (std::size_t i = 0; i < out.points.size(); ++i) {
        if (id[i] < 0) continue;
        id[i] = static_cast<Index>(fill.points.size());
        fill.points.emplace_back(out.points[i][0], out.points[i][1], out.points[i][2]);
    }
    fill.tets.reserve(out.tets.size());
    for (const auto& t : out.tets) {
        std::array<Index, 4> tet{};
        for (int k = 0; k < 4; ++k) tet[k] = t[k] < id.size() ? id[t[k]] : Index{-1};
        fill.tets.push_back(tet);
    }
    return fill;
}

}  // namespace

TetFill fill_with_hxt(const SurfaceMesh& boundary, const FaceIndex& face_of, double volume,
                      const TetFillParams& params, const Progress* progress) {
    check_cancelled(progress);
    const bool sizing = params.refine && params.growth > 0.0;
    std::unique_ptr<tetgen::SizeField> h;
    if (sizing) h = std::make_unique<tetgen::SizeField>(boundary, params.growth, params.max_volume);
    const int threads = thread_count(params.threads);
    hxt::SizeFunction size;
    if (h)
        size = [&](const double* xyz, std::size_t n, double* sizes) {
            const auto count = static_cast<long long>(n);
#pragma omp parallel for num_threads(thread_count(threads, count)) schedule(static)
            for (long long i = 0; i < count; ++i) sizes[i] = kSizePerEdge * (*h)(Vec3(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]));
        };
    const std::string advice = "; the default tetrahedral mesher, TetGen (--tets tetgen), may fill it";
    try {
        const hxt::Output out =
            hxt::run(hxt_input(boundary, h.get()), size, {.threads = threads, .refine = params.refine}, progress);
        TetFill fill = to_fill(boundary, out);
        check_fill(boundary, face_of, fill, volume, "HXT");
        check_cancelled(progress);
        return fill;
    } catch (const BackendError& e) {
        throw BackendError(std::string(e.what()) + advice);
    }
}

}  // namespace strata::tet_fill
