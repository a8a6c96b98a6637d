#pragma once
/// \file
/// CGNS writer (.cgns, HDF5) through the CGNS mid-level library (Debian's libcgns-dev).

#include <strata/core/progress.h>
#include <strata/core/volume_mesh.h>
#include <strata/io/files.h>

#include <string>
#include <vector>

namespace strata {

/// Write \p mesh to \p path as CGNS: one base "Base" (cell and physical dimension 3) with one
/// unstructured zone "Fluid". Coordinates CoordinateX/Y/Z (double). Elements numbered from 1:
/// the cells first, one section per cell type present, in CellNumbering order ("Tetrahedra"
/// TETRA_4, "Pyramids" PYRA_5, "Prisms" PENTA_6, "Hexahedra" HEXA_8; the node orders of
/// FORMATS.md are CGNS's for these types), then the boundary faces patch by patch
/// (patch-table order, patches without faces left out), one section per patch named after it
/// (TRI_3 or QUAD_4; a patch holding both gets two sections, "<name>" with its triangles then
/// "<name>_quads", so that its faces stay one element range). Per patch a boundary condition
/// in ZoneBC: PointRange over its elements, GridLocation FaceCenter, BCWall (wall),
/// BCSymmetryPlane (symmetry), BCFarfield (farfield) or BCTypeUserDefined (other), with a
/// FamilyName naming a family of the base that carries the same BC type (FamilyBC). Names are
/// cgns_names of the patch names. Written to a temporary file and renamed. Does not validate:
/// callers run require_valid_mesh first. InputError (missing directory, malformed arrays, more
/// elements than CGNS's 32-bit sizes hold), BackendError (the CGNS library failed, with its
/// message). \p progress: stage "writing"; cancelled, nothing is left at \p path.
void write_cgns(const VolumeMesh& mesh, const std::string& path, Progress* progress = nullptr,
                OutputSet* outputs = nullptr);

/// Patch names as CGNS node names: '/' and control characters become '_', at most 32
/// characters (CGNS's limit), an empty name "patch_<i+1>", and a name that is taken (by an
/// earlier one or by \p reserved) shortened if need be and given "_2", "_3", ...
std::vector<std::string> cgns_names(const std::vector<std::string>& names, const std::vector<std::string>& reserved);

}  // namespace strata
