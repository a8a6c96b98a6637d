#pragma once
/// \file
/// A generated outer boundary for a body that comes without one.

#include <strata/core/surface_mesh.h>

#include <string_view>

namespace strata {

enum class FarfieldShape { Box, Sphere };
/// "box", "sphere".
std::string_view to_string(FarfieldShape shape);
/// Inverse of to_string (case-insensitive); InputError naming \p text otherwise.
FarfieldShape parse_farfield_shape(std::string_view text);

struct FarfieldParams {
    FarfieldShape shape = FarfieldShape::Sphere;
    double size = 20.0;  ///< extent as a multiple of the body's bounding-box diagonal
    int divisions = 16;  ///< triangles along a box edge / icosphere refinement level control
};

/// A closed triangulated box or sphere around \p body_points, centred on their bounding box,
/// with half-extent (box) or radius (sphere) = size × diagonal / 2, one patch "farfield" of
/// kind Farfield, normals pointing outward (out of the fluid domain it bounds).
SurfaceMesh make_farfield(const std::vector<Vec3>& body_points, const FarfieldParams& params);

/// The farfield of a half model whose symmetry plane is (\p plane_point, \p plane_normal; the
/// normal points to the body's side): the half of a box or sphere sized and centred as
/// make_farfield would for the body and its mirror image, on the normal's side of the plane,
/// open there (its boundary loop lies in the plane). The half sphere is the half box
/// projected onto it. Patch "farfield", normals outward.
SurfaceMesh make_half_farfield(const std::vector<Vec3>& body_points, const Vec3& plane_point, const Vec3& plane_normal,
                               const FarfieldParams& params);

/// A half model closed into a fluid domain: \p walls (oriented, normals into the flow, open
/// along the plane it was cut at: every open edge in one plane, the body on one side of it)
/// plus make_half_farfield's half box or sphere (patch "farfield") and the part of the plane
/// between the two, meshed with Gmsh around the walls' open edges (patch "symmetry"). The
/// result is closed and oriented like \p walls. InputError if the open edges are not in one
/// plane or the body lies on both sides of it.
SurfaceMesh close_half_model(const SurfaceMesh& walls, const FarfieldParams& params);

}  // namespace strata
