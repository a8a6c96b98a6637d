#pragma once
/// \file
/// Self-intersection test of a surface mesh with exact predicates (CGAL), for the front the
/// tetrahedra are to fill against: TetGen must never be the first to find that it crosses
/// itself (it stops without saying where).

#include <strata/core/surface_mesh.h>

#include <array>
#include <cstddef>
#include <string>
#include <vector>

namespace strata {

/// Two faces of a surface (a < b) that meet other than by sharing exactly one node or one edge.
struct FacePair {
    Index a = kNone, b = kNone;
    bool operator==(const FacePair&) const = default;
};

/// Every pair of faces of \p mesh that intersect other than along what they share by node
/// ids: faces that cross or touch, coplanar faces that overlap across a shared edge or node,
/// repeated faces. Quads are tested as their two triangles (split along the diagonal from
/// their first node), degenerate triangles (collinear corners) are skipped. Exact predicates
/// (CGAL's Epick kernel) on a box-intersection broad phase, the exact tests on \p threads
/// threads (0: OpenMP's default; the result is the same for any count); sorted by (a, b); at
/// most \p max_pairs (0: all).
std::vector<FacePair> self_intersections(const SurfaceMesh& mesh, std::size_t max_pairs = 0, int threads = 0);

/// A triangle of a surface mesh: its node ids and the face it belongs to.
struct SurfaceTriangle {
    std::array<Index, 3> v;
    Index face = kNone;
};

/// The triangles of \p mesh for geometric queries: a triangle as it is, a quad a b c d as
/// a b c and a c d; triangles whose corners are collinear (exactly) are left out.
std::vector<SurfaceTriangle> surface_triangles(const SurfaceMesh& mesh);

/// "face 12 (patch 'layer_top') at (x, y, z)": for messages about the pairs above.
std::string describe_face(const SurfaceMesh& mesh, Index f);

/// "face 12 (...) at (...) meets face 40 (...) at (...)": a pair above, for messages.
std::string describe_pair(const SurfaceMesh& mesh, const FacePair& pair);

}  // namespace strata
