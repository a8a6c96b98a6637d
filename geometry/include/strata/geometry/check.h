#pragma once
/// \file
/// Validity checks on a surface mesh and its orientation. Each failure throws a
/// strata::Error whose one-line message names the source, the face/edge/node and where it is.

#include <strata/core/surface_mesh.h>

#include <string>
#include <vector>

namespace strata {

/// First the arrays (check_surface_arrays, require_sound): InputError for an empty mesh, a face
/// that is not a triangle or quadrilateral, a node or patch id out of range; TopologyError for
/// a NaN or infinite coordinate (naming the node), and for nodes that span 1e100 or more (the
/// bounding-box diagonal from which areas and volumes overflow; the message gives the box).
/// Then TopologyError for a face with a repeated node or (near) zero area (relative to the
/// bounding box), and for an edge shared by more than two faces (naming the edge's nodes,
/// coordinates and faces). \p source names the input. \p small_faces_ok: only a face of no
/// area at all is refused (a surface that is to be meshed again: remeshing rebuilds it).
void check_surface(const SurfaceMesh& mesh, const std::string& source, bool small_faces_ok = false);

/// What orient_surface did.
struct OrientReport {
    Index components = 0;         ///< connected components
    Index flipped_faces = 0;      ///< faces whose order was reversed
    Index closed_components = 0;  ///< of which closed (no boundary edge)
};

/// Make every connected component consistently oriented (breadth-first from its lowest face),
/// then orient closed components so normals point into the flow domain: a closed body that
/// lies in no other component points outward; a closed surface that holds other components,
/// or carries a farfield patch, points inward. With \p internal_flow (the fluid is inside the
/// walls: a duct, a wind tunnel) every closed component that lies in no other one points
/// inward too, and the bodies inside it outward. An open component keeps the majority
/// orientation of its faces. Throws TopologyError (naming an edge) where a component is not
/// orientable (e.g. a Möbius strip), InputError when \p internal_flow is asked of a surface
/// with no closed component. Requires check_surface to have passed.
SurfaceMesh orient_surface(const SurfaceMesh& mesh, OrientReport* report = nullptr, bool internal_flow = false);

/// Needle faces: faces with a corner sharper than a bound. A layer cell on a face can be no
/// better than the sine of the face's sharpest corner (its scaled Jacobian at that corner), so
/// such faces cap the layers whatever the marching does; a CAD tool's coarse STL export is
/// full of them. Remeshing the surface is the remedy.
struct NeedleReport {
    Index faces = 0;              ///< faces counted (on the patches asked)
    Index needles = 0;            ///< of which with a corner below the bound
    double sharpest_deg = 180.0;  ///< the sharpest corner of all faces counted
    Index worst_face = kNone;     ///< the face that has it
    Vec3 where = Vec3::Zero();    ///< its corner's position
};

/// Below this corner angle (degrees) a face is a needle: a layer cell on it is below sin 5° = 0.09.
inline constexpr double kNeedleCornerDeg = 5.0;

/// The needle faces of \p mesh among those on patches of a kind in \p kinds (all if empty):
/// a corner below \p min_angle_deg degrees. Corners with an edge of zero length (a fan's faces
/// on the layer module's wall) have no angle and are left out.
NeedleReport needle_faces(const SurfaceMesh& mesh, double min_angle_deg, const std::vector<PatchKind>& kinds = {});

}  // namespace strata
