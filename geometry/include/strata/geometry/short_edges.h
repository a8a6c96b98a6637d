#pragma once
/// \file
/// Edges far shorter than the mesh around them, collapsed. A CAD model's small edges (sliver
/// faces, the seams a Boolean union leaves where a wing's leading edge meets a fuselage almost
/// tangentially, a blunt trailing edge much thinner than the element size) each get a mesh
/// edge of their own, and the faces on both sides of it become needles: OpenCASCADE's union
/// of `wing_fuselage.step` left curves of 3.5e-5 m among faces of 0.04 m, 46 needles with a
/// corner under 3°, a prism at 0.0036 and a tetrahedron at 6e-9 beside them. Gmsh meshes
/// every CAD curve, however short; a surface mesh exported by a CAD tool has the same faces.
/// Collapsing such an edge moves one of its nodes onto the other (by at most the edge's
/// length, a small share of the local size) and removes the two faces on it.

#include <strata/core/surface_mesh.h>

namespace strata {

/// What collapse_short_edges did.
struct ShortEdgeReport {
    Index collapsed = 0;             ///< edges collapsed (two faces removed with each)
    double longest = 0.0;            ///< the longest edge collapsed: the furthest a node moved
    double largest_share = 0.0;      ///< the largest length / local size among them
    Vec3 where = Vec3::Zero();       ///< where the node that moved furthest was
    Index left = 0;                  ///< short edges left: collapsing them was not safe (below)
    double left_share = 0.0;         ///< the smallest length / local size among those left
    Vec3 left_where = Vec3::Zero();  ///< the midpoint of that edge
};

/// \p mesh with every edge shorter than \p ratio times its local size collapsed where that is
/// safe. The local size of an edge is the median length of the other edges of the faces
/// around its two nodes, so a uniformly fine region (a small radius, a graded mesh) is never
/// touched: only edges that are outliers against their own neighbourhood. Shortest first.
///
/// The node that moves is the one on fewer feature lines (edges between two patches, or whose
/// faces' normals differ by more than 40°): a node in a smooth patch moves onto a seam or a
/// corner, never the reverse; on a tie the higher id moves. An edge is left as it is where the
/// node that would move touches a face that is not a triangle or not on a wall patch (a
/// symmetry plane must stay planar), or lies on an open boundary; where the collapse would
/// change the topology (the two nodes share neighbours other than the corners of the two faces
/// on the edge, or a corner would keep fewer than three faces); where a patch would lose its
/// last face; and where a face that stays would turn by more than 45° or get a sharper corner
/// than both its old one and 5°. Faces keep their order, orientation and patch; nodes no face
/// uses are dropped, order kept. \p ratio ≤ 0: \p mesh unchanged. Requires a manifold,
/// consistently oriented mesh (check_surface, orient_surface). Deterministic.
SurfaceMesh collapse_short_edges(const SurfaceMesh& mesh, double ratio, ShortEdgeReport* report = nullptr);

}  // namespace strata
