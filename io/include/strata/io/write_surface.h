#pragma once
/// \file
/// Surface-mesh writer through the Gmsh API: one discrete surface and one physical group per
/// patch, so every format Gmsh writes is available from the extension.

#include <strata/core/surface_mesh.h>

#include <string>

namespace strata {

/// Write \p mesh to \p path (.msh = MSH 4.1; .msh22 is not an extension: pass \p msh_version 2.2
/// for MSH 2.2; .vtk, .stl, .su2, ... by extension). Atomic: written to a temporary name and
/// renamed. Throws InputError if the directory is not writable, BackendError if Gmsh fails.
void write_surface(const SurfaceMesh& mesh, const std::string& path, double msh_version = 4.1);

}  // namespace strata
