#pragma once
/// \file
/// Volume-mesh writer through the Gmsh API: every format Gmsh writes, by extension.

#include <strata/core/volume_mesh.h>

#include <string>

namespace strata {

/// Write \p mesh to \p path (.msh as MSH \p msh_version 4.1 or 2.2; .vtk, .su2, .unv, ... by
/// extension): one discrete volume with all cells and a physical group "fluid" (3D), one
/// discrete surface and one 2D physical group per boundary patch, named after the patch.
/// Atomic (temporary name, then rename). Does not validate: callers run require_valid_mesh first.
void write_volume(const VolumeMesh& mesh, const std::string& path, double msh_version = 4.1);

/// Add \p mesh to the CURRENT Gmsh model, as write_volume lays it out before writing: one
/// discrete volume holding every node and cell with a 3D physical group "fluid", one discrete
/// surface and one 2D physical group per non-empty boundary patch, named after the patch.
/// Entity, physical-group, node and element tags start past the largest in use (in an empty
/// model: volume 1, surface = patch index + 1, nodes = index + 1, elements = cell index + 1
/// then #cells + boundary face index + 1). For a Gmsh user: Gmsh must be initialised
/// (InputError otherwise); a malformed mesh is an InputError naming the cell or face, Gmsh's
/// failures a BackendError. Does not validate: callers run require_valid_mesh first.
void add_volume_to_gmsh_model(const VolumeMesh& mesh);

/// Read a volume mesh written by write_volume (or any .msh with linear tets, pyramids,
/// prisms and hexes, and 2D physical groups as patches) through the Gmsh API.
VolumeMesh read_volume_msh(const std::string& path);

}  // namespace strata
