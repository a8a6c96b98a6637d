#pragma once
/// \file
/// Surface-mesh writer through the Gmsh API: one discrete surface and one physical group per
/// patch, so every format Gmsh writes is available from the extension.

#include <strata/core/progress.h>
#include <strata/core/surface_mesh.h>
#include <strata/io/files.h>
#include <strata/io/formats.h>

#include <string>

namespace strata {

/// Write \p mesh to \p path (.msh as MSH \p msh (4.1 or 2.2, ASCII or binary); .vtk, .stl, .su2, ... by
/// extension, formats.h) as add_surface_to_gmsh_model lays it out, so read_msh gives the nodes,
/// faces and patches back in order. Atomic: written to a temporary name (every write checked and
/// synced: OutputError on a full disk) and renamed, or staged in \p outputs. Throws
/// InputError for an unknown extension, a missing directory or malformed arrays, BackendError if
/// Gmsh fails. \p progress: stage "writing"; cancelled, nothing is left at \p path.
void write_surface(const SurfaceMesh& mesh, const std::string& path, MshFormat msh = {},
                   Progress* progress = nullptr, OutputSet* outputs = nullptr);

}  // namespace strata
