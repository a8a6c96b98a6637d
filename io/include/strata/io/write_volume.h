#pragma once
/// \file
/// Volume meshes to and from files: Cobalt60 (cobalt.h), OpenFOAM polyMesh (openfoam.h), CGNS
/// (cgns.h), VTK XML (vtk_xml.h) and every format Gmsh writes.

#include <strata/core/progress.h>
#include <strata/core/volume_mesh.h>
#include <strata/io/files.h>
#include <strata/io/formats.h>

#include <string>

namespace strata {

/// Write \p mesh to \p path, the format from the extension (formats.h): .cgr, .cog or .grd as
/// Cobalt60 with its .bc patch map (write_cobalt); a path whose last component is `polyMesh` as
/// an OpenFOAM polyMesh directory (write_polymesh); .cgns as CGNS (write_cgns); .vtu and .vtm as VTK XML (write_vtu, write_vtm); .msh as MSH \p msh (4.1 or 2.2, ASCII or binary);
/// .vtk, .su2, .unv, ... through Gmsh: one discrete volume with all cells and a physical group "fluid" (3D), one
/// discrete surface and one 2D physical group per boundary patch, named after the patch (add_volume_to_gmsh_model).
/// Atomic (temporary name, then rename; every write checked and synced: OutputError on a full
/// disk), or staged in \p outputs to be committed with the run's other outputs. Does not validate: callers run
/// require_valid_mesh first. InputError for an unknown extension, a missing directory or malformed arrays; BackendError
/// if Gmsh fails. \p progress: stage "writing"; cancelled, nothing is left at \p path.
void write_volume(const VolumeMesh& mesh, const std::string& path, MshFormat msh = {},
                  Progress* progress = nullptr, OutputSet* outputs = nullptr);

/// Read a volume mesh written by write_volume (or any .msh with linear tets, pyramids,
/// prisms and hexes, and 2D physical groups as patches) through the Gmsh API
/// (volume_from_gmsh_model).
VolumeMesh read_volume_msh(const std::string& path);

}  // namespace strata
