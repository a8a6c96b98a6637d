#pragma once
/// \file
/// VTK's XML formats, written by Strata for ParaView: a volume mesh as one UnstructuredGrid
/// (.vtu) with cell fields to colour by, or as a MultiBlock dataset (.vtm) that adds one PolyData
/// (.vtp) per boundary patch, each block named after its patch. Binary: the arrays raw in one
/// appended block, little-endian, header_type UInt64. The same mesh gives the same bytes on every
/// run and for any thread count.

#include <strata/core/progress.h>
#include <strata/core/volume_mesh.h>
#include <strata/io/files.h>

#include <string>

namespace strata {

/// Write \p mesh to \p path as a VTK XML UnstructuredGrid: every cell in CellNumbering order
/// (tetrahedra as VTK_TETRA 10, pyramids VTK_PYRAMID 14, prisms VTK_WEDGE 13 with their
/// triangles reversed to VTK's order, hexahedra VTK_HEXAHEDRON 12), points Float64, and the
/// cell data
///   cell_type          Int32    the VTK cell type above
///   scaled_jacobian    Float64  min_scaled_jacobian (cell_quality.h), as the report's plots
///   non_orthogonality  Float64  checkMesh's, degrees, the largest over the cell's interior faces
///   skewness           Float64  checkMesh's, the largest over the cell's faces
///   aspect_ratio       Float64  checkMesh's
///   layer              Int32    VolumeMesh::cell_layers (1 on the wall; 0 outside the layers),
///                               where the mesh has one per cell
/// (cell_solver_figures, solver_checks.h).
/// Atomic (temporary name, then rename), or staged in \p outputs. Does not validate (callers run
/// require_valid_mesh first); InputError for malformed arrays or a missing directory, OutputError
/// on a failed write (a full disk). \p progress: stage "writing".
void write_vtu(const VolumeMesh& mesh, const std::string& path, Progress* progress = nullptr,
               OutputSet* outputs = nullptr);

/// Write \p mesh to \p path as a VTK XML MultiBlock dataset: block "volume" (the .vtu of
/// write_vtu) and block "boundary" holding one PolyData per patch with faces (patch-table
/// order), named after the patch, with the cell data `patch` (Int32, the patch's index) and the
/// field data `patch_name` and `patch_kind` (String: wall, symmetry, farfield, other). The
/// datasets are files in the directory vtm_block_directory(path) (formats.h), which is replaced whole; the
/// .vtm and the directory are committed together (with \p outputs if given) or not at all.
void write_vtm(const VolumeMesh& mesh, const std::string& path, Progress* progress = nullptr,
               OutputSet* outputs = nullptr);

}  // namespace strata
