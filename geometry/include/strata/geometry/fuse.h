#pragma once
/// \file
/// The Boolean union of overlapping closed components of a surface mesh (a fuselage and fins
/// given as separate STL files), by exact corefinement: CGAL's
/// Polygon_mesh_processing::corefine_and_compute_union, each face keeping its patch.

#include <strata/core/error.h>
#include <strata/core/surface_mesh.h>

namespace strata {

/// The TopologyError of fuse_components where parts touch along an edge or a point only (the
/// union of fins whose flat roots sit on a curved body would not bound a volume): a caller may
/// join them another way (prepare_mesh wraps them, PrepareParams::wrap).
class TouchingPartsError : public TopologyError {
public:
    using TopologyError::TopologyError;
};

/// What fuse_components did.
struct FuseReport {
    Index components = 0;  ///< closed wall components looked at
    Index fused = 0;       ///< of which unioned with another (they overlapped or touched)
    /// Flat slivers of the union (prepare_surface: flip_flat_triangles) flipped away.
    Index flipped_slivers = 0;
};

/// \p mesh (oriented as orient_surface leaves it; each body to be unioned is made outward
/// first, since orient_surface turns one whose probe point lies inside another inward) with its closed
/// components of walls that intersect one another replaced by their union; the others, and
/// every face that is not a wall's, kept as they are. Faces of the union keep the patch of the
/// face they came from (split faces: of the face they were cut from); quads of the components
/// unioned become two triangles. Deterministic. TopologyError naming the component (its first
/// face and patch) where one that must be unioned intersects itself, or where CGAL's union
/// fails; TouchingPartsError where the result would not bound a volume.
SurfaceMesh fuse_components(const SurfaceMesh& mesh, FuseReport* report = nullptr);

}  // namespace strata
