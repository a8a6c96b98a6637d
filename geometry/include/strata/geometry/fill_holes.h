#pragma once
/// \file
/// Holes in a surface mesh: a few triangles missing from an STL (an exporter's or a scan's
/// slip) leave the surface open, which strata mesh refuses (only a half model's symmetry cut
/// may be open). fill_holes closes such loops with triangles, on request (PrepareParams::
/// fill_holes, --fill-holes N): a loop of more edges than asked (a half model's cut, an
/// opening that is meant) is left as it is.

#include <strata/core/surface_mesh.h>
#include <strata/core/types.h>

namespace strata {

/// What fill_holes did.
struct HoleReport {
    Index max_edges = 0;        ///< the largest loop asked to be closed (0: none)
    Index holes = 0;            ///< boundary loops closed
    Index triangles = 0;        ///< triangles added
    Index largest = 0;          ///< edges of the largest loop closed
    Vec3 where = Vec3::Zero();  ///< the centre of that loop
    Index left = 0;             ///< loops left open: more edges than asked, or no triangulation found
    Index largest_left = 0;     ///< edges of the largest of those
    bool caps = false;          ///< closed by cap_holes: each loop its own patch, cap_1, cap_2, ...
};

/// \p mesh (manifold: every edge on at most two faces) with each boundary loop of at most
/// \p max_edges edges closed by triangles: CGAL's triangulate_hole_polyline on the loop's
/// nodes (of the triangulations of the loop's polygon, the one whose worst dihedral angle
/// between neighbouring triangles is smallest, then of least area), each new triangle in the
/// patch most of the loop's edges' faces belong to and oriented as they are. No node is added.
/// A loop CGAL cannot triangulate (a degenerate one) is left, and counted in \p report->left.
/// Deterministic. TopologyError where boundary loops touch (boundary_loops).
SurfaceMesh fill_holes(const SurfaceMesh& mesh, Index max_edges, HoleReport* report = nullptr);

/// The openings of a vessel or a duct (an artery cut at its inlet and outlets) closed as
/// fill_holes closes them, but each loop by a cap of its own: the loop's triangulation refined
/// with nodes inside it (CGAL's refine, Liepa's scheme: spacing as the loop's edges, in the
/// loop's plane where it is planar) in a new patch cap_1, cap_2, ... (in the order of
/// boundary_loops), of kind Other, which layers meet as they meet an outflow plane and a user
/// renames (an inlet, an outlet). \p report->caps is set. Deterministic.
SurfaceMesh cap_holes(const SurfaceMesh& mesh, Index max_edges, HoleReport* report = nullptr);

}  // namespace strata
