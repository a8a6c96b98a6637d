#pragma once
/// \file
/// Where closed bodies touch along a common face: a model split into halves at a plane, two
/// solids exported together whose faces coincide (OpenCASCADE's tessellation of the glider
/// wing_fuselage.step writes its fuselage as two halves, each closed by a disc at y = 0). Each
/// body's tessellation closes itself there, so the surface holds two walls back to back inside
/// the union, and the edges round them are shared by four faces. Their union (PrepareParams::
/// fuse) has neither: touching_faces finds them, geometry/topology.h's remove_faces removes
/// them.

#include <strata/core/surface_mesh.h>

#include <vector>

namespace strata {

/// The faces of \p mesh that lie on a face facing the other way: every corner of each within
/// \p rel_tol × the model's bounding-box diagonal of the other's plane, their normals opposed,
/// and the centre of each triangle of the face inside such a face (quads as two triangles).
/// Sorted; empty if none. Exact duplicates of the same orientation are not touching faces.
/// Where the faces lie back to back over only part of one of them (a small body on a large
/// one's side), removing them would leave an edge with one face: such a connected group is not
/// returned, and only a Boolean union (fuse.h) joins the bodies there.
/// Deterministic.
std::vector<Index> touching_faces(const SurfaceMesh& mesh, double rel_tol = 1e-6);

}  // namespace strata
