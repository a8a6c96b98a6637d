#pragma once
/// \file
/// The outer part of the fluid domain's boundary, for the tetrahedral fill: the input's
/// non-wall patches (farfield, symmetry, outflow), where every planar patch that the layers
/// end on is re-meshed around the layers' side faces.

#include <strata/module/layers.h>

#include <vector>

namespace strata {

struct OuterBoundary {
    SurfaceMesh mesh;             ///< triangles on the input's patches, oriented as the input (normals into the fluid)
    std::vector<Index> top_node;  ///< per point of mesh: the layer-top node it is (a wall node id), or kNone
    std::vector<Index> remeshed;  ///< the input patches that were re-meshed, ascending
};

/// The non-wall faces of \p surface (the fluid domain: walls plus farfield, symmetry, outflow
/// patches, closed) joined to the layers \p layers grown from its walls.
///
/// A non-wall patch P that touches the walls holds the layers' side faces (extrude_layers
/// keeps those nodes in P's plane). P is re-meshed with Gmsh outside them: its boundary is
/// P's own, with each run of wall-contact edges replaced by the corresponding edges of the
/// layer top, and each edge between P and another non-wall patch Q that starts at the walls
/// (a corner, where the layers march along the line of the two planes) cut at the top of the
/// layers, with points graded from the layer-top spacing to the original one (the same points
/// on P and Q, so the two stay conforming). No point is added on that boundary. Untouched
/// patches keep their faces (quads split into triangles).
///
/// Throws InputError when such a patch is not planar, and TopologyError when the layers are
/// too thick for the patch edge they march along (naming the patches and the position).
/// \p growth: the re-meshed patches' size grows from their boundary at this rate at most
/// (mesh_plane_region; pass TetFillParams::growth), 0 as Gmsh grades it.
OuterBoundary outer_boundary(const SurfaceMesh& surface, const LayerMesh& layers, double growth = 0.0);

}  // namespace strata
