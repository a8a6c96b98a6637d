#pragma once
/// \file
/// Closed surfaces built from formulas: the generated farfield's sphere, and test bodies.

#include <strata/core/surface_mesh.h>

namespace strata {

/// The icosahedron inscribed in the sphere of \p radius about \p centre, each triangle split
/// into four \p levels times (20 · 4^levels triangles, new points projected onto the sphere),
/// one patch \p patch, faces oriented outward. Node and face order depend only on \p levels.
SurfaceMesh icosphere(const Vec3& centre, double radius, int levels, const Patch& patch);

}  // namespace strata
