#pragma once
/// \file
/// Private to strata_hybrid: the parts of fill_with_tets shared by its two meshers (the input's
/// checks, the boundary's triangles by node set, the result's independent check) and the two
/// meshers behind it, TetGen (tetgen_fill.cpp) and HXT (hxt_fill.cpp).

#include <strata/core/surface_mesh.h>
#include <strata/hybrid/tetgen_fill.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace strata::tet_fill {

/// "boundary triangle F (patch 'P') at (x, y, z)".
std::string face_name(const SurfaceMesh& b, Index f);

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
inline TriKey tri_key(Index a, Index b, Index c) {
    std::array<Index, 3> v{a, b, c};
    std::sort(v.begin(), v.end());
    return {v};
}
using FaceIndex = std::unordered_map<TriKey, Index, TriKeyHash>;

/// InputError where the boundary, the hole points or the parameters cannot be meshed.
void check_input(const SurfaceMesh& b, const std::vector<Vec3>& holes, const TetFillParams& p);

/// Volume enclosed by the boundary (divergence theorem; positive when normals point out).
double enclosed_volume(const SurfaceMesh& b);

/// Boundary triangle by node set; InputError on a repeated triangle.
FaceIndex index_faces(const SurfaceMesh& b);

/// The fill checked independently of the mesher that made it (\p mesher names it in the
/// errors): the boundary points come back unchanged with their ids, every tet has positive
/// volume, every boundary triangle is a face of exactly one tet with that tet on the side its
/// normal points away from, and the tet volumes sum to the volume the boundary encloses.
/// Together (a tet face cannot have a vertex of another tet inside it in a conforming mesh) this
/// means no point was added on the boundary. BackendError, or InputError for a wrongly oriented
/// boundary.
void check_fill(const SurfaceMesh& b, const FaceIndex& face_of, const TetFill& fill, double boundary_volume,
                std::string_view mesher);

/// TetGen's fill (tetgen_fill.cpp) of a boundary that passed check_input and encloses \p volume.
TetFill fill_with_tetgen(const SurfaceMesh& boundary, const FaceIndex& face_of, double volume,
                         const std::vector<Vec3>& holes, const TetFillParams& params, Progress* progress);

/// HXT's fill (hxt_fill.cpp), the same contract but for the hole points: the region filled is
/// the one every connected part of the boundary bounds, what one part alone encloses is left
/// empty.
TetFill fill_with_hxt(const SurfaceMesh& boundary, const FaceIndex& face_of, double volume,
                      const TetFillParams& params, const Progress* progress);

}  // namespace strata::tet_fill
