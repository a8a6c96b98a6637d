#pragma once
/// \file
/// A generated outer boundary for a body that comes without one.

#include <strata/geometry/surface_mesh.h>

#include <string_view>

namespace strata {

enum class FarfieldShape { Box, Sphere };
/// "box" or "sphere" (InputError otherwise).
FarfieldShape parse_farfield_shape(std::string_view text);

struct FarfieldParams {
    FarfieldShape shape = FarfieldShape::Sphere;
    double size = 20.0;     ///< extent as a multiple of the body's bounding-box diagonal
    int divisions = 16;     ///< triangles along a box edge / icosphere refinement level control
};

/// A closed triangulated box or sphere around \p body_points, centred on their bounding box,
/// with half-extent (box) or radius (sphere) = size × diagonal / 2, one patch "farfield" of
/// kind Farfield, normals pointing outward (out of the fluid domain it bounds).
SurfaceMesh make_farfield(const std::vector<Vec3>& body_points, const FarfieldParams& params);

}  // namespace strata
