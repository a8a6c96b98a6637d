#pragma once
/// \file
/// First hits of rays from surface nodes against the surface itself: one AABB tree of its
/// triangles (CGAL), built once per call; one ray per node, in parallel, the same result for
/// any thread count.

#include <strata/core/surface_mesh.h>

#include <limits>
#include <vector>

namespace strata {

struct RayHit {
    double distance = std::numeric_limits<double>::infinity();  ///< along the unit direction; inf: nothing
    Index face = kNone;                                         ///< the face hit
};

/// For ray i from \p origins[i] (at node \p nodes[i] of \p surface) along the unit vector
/// \p directions[i]: the first face of \p surface it meets. Faces incident to the node are
/// skipped (the ray starts on them), and so are faces parallel to the ray (seen edge-on, as
/// from a node moving in a symmetry plane). Quads count as their two triangles; a zero or
/// non-finite direction meets nothing.
std::vector<RayHit> first_hits(const SurfaceMesh& surface, const std::vector<Index>& nodes,
                               const std::vector<Vec3>& origins, const std::vector<Vec3>& directions, int threads);

}  // namespace strata
