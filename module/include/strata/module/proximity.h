#pragma once
/// \file
/// How far the flow domain reaches from each wall node along its marching direction before
/// another surface (a facing wall, the node's own body across a gap, a symmetry, farfield or
/// outflow patch), and the layer thickness that leaves room there. The rays: ray_cast.h (one
/// AABB tree of the whole surface, built once; the same result for any thread count).

#include <strata/core/surface_mesh.h>

#include <limits>
#include <vector>

namespace strata {

/// What a wall node's ray met first.
struct ProximityHit {
    double distance = std::numeric_limits<double>::infinity();  ///< along the unit direction; inf: nothing
    bool wall = false;                                          ///< a wall face (its layers grow too)
    /// How squarely the ray meets the face: −(unit face normal) · direction, 1 head-on, near 0
    /// at a grazing hit (face normals point into the flow, so a ray through the flow meets
    /// them from the front).
    double facing = 1.0;
};

/// For wall node i at \p origins[i] (node \p surface_node[i] of \p surface), the first face of
/// \p surface along the unit vector \p directions[i]. Faces incident to the node are skipped
/// (the ray starts on them), and so are faces parallel to the ray (a node marching in a
/// symmetry plane sees that plane edge-on). Quads count as their two triangles.
std::vector<ProximityHit> cast_proximity_rays(const SurfaceMesh& surface, const std::vector<Index>& surface_node,
                                              const std::vector<Vec3>& origins, const std::vector<Vec3>& directions,
                                              int threads);

/// How much of the distance to the first surface a node's layers may fill.
struct ProximityParams {
    double facing_wall = 0.45;  ///< against a wall whose layers grow towards them (both sides: 0.9 in all)
    double other_patch = 0.9;   ///< against a symmetry, farfield or other patch (nothing grows from it)
    /// How fast the limit may rise along the wall, in thickness per unit of wall distance, so
    /// neighbouring columns differ gently (the Poisson smoothing needs a smooth front).
    double slope = 0.25;
    /// The same for the extra limits thickness_limits is given (build_hybrid_mesh's front
    /// rounds: columns lowered where the layer top met itself), so how far such a lowering
    /// spreads; the two envelopes are taken apart and the lower holds. build_hybrid_mesh
    /// halves it for the columns its rounds keep lowering (down to \p slope, or to itself if
    /// smaller; LayerConstraints::node_front_slope), and goes down to that for the columns its
    /// fifth round on lowers: a lowering stays local unless the front keeps meeting itself there.
    /// At 0.25 from the first round the fused wing-fuselage kept 36 % of its wall nodes with
    /// every layer, at 1 it keeps 63 %.
    double front_slope = 1.0;
    /// Hits less square than this (ProximityHit::facing, the cosine of the angle between the ray
    /// and the face's normal) do not limit: two walls meeting at a concave corner of 60° or more
    /// (a wing-body junction, the Apollo base and nozzle) see each other obliquely, and their
    /// layers merge there under the Poisson smoothing's concave terms instead of colliding; a
    /// narrow gap or a thin wedge sees its other side nearly head-on. The front check before
    /// TetGen catches what this lets through.
    double min_facing = 0.5;
};

/// The largest layer thickness at each node of \p wall (its nodes are the origins above):
/// the hit distance times the share for what was hit (hits below min_facing ignored), then lowered wherever a
/// neighbour's limit plus slope × the edge length between them is smaller (a Lipschitz envelope over the wall's edges,
/// computed exactly by a Dijkstra sweep). \p extra (empty, or one per wall node) bounds a node further before the
/// envelope is taken. Infinity where nothing limits.
std::vector<double> thickness_limits(const SurfaceMesh& wall, const std::vector<ProximityHit>& hits,
                                     const ProximityParams& params, const std::vector<double>& extra = {});

}  // namespace strata
