#pragma once
/// \file
/// Output formats, decided by a path's extension, and checked before the work that produces
/// the mesh starts (a typo in the output name should not cost a meshing run).

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace strata {

/// The MSH versions the writers produce, "4.1" (default) or "2.2"; InputError naming \p text
/// otherwise.
double parse_msh_version(std::string_view text);

/// How a .msh file is written: its version (4.1 or 2.2) and whether in binary (Gmsh's
/// Mesh.Binary: the same mesh with every coordinate's bits, where ASCII keeps 16 digits,
/// written in about half the time; 1M prisms: 1.8 -> 0.8 s, 94 -> 83 MB).
struct MshFormat {
    double version = 4.1;
    bool binary = false;
    MshFormat(double v = 4.1, bool b = false) : version(v), binary(b) {}  // NOLINT: a version alone is ASCII
};

/// A surface output Gmsh writes (.msh, .vtk, .stl, .su2, ...; \p msh's version 4.1 or 2.2 for
/// .msh, binary for .msh only) in a directory that exists: InputError naming the path and the
/// choices otherwise.
void check_surface_output(const std::string& path, MshFormat msh = {});

/// A volume output: Cobalt60 (.cgr, .cog, .grd, with its .bc patch map), CGNS (.cgns), VTK XML
/// (.vtu; .vtm, whose blocks' directory may hold only .vtu and .vtp files if it exists), an
/// OpenFOAM polyMesh directory (a path whose last component is `polyMesh`: a directory that
/// does not exist yet or is replaced whole) or a format Gmsh writes volume meshes to (.msh, .vtk,
/// .su2, .unv, ...; \p msh as for check_surface_output), in a directory that exists: InputError
/// naming the path and the choices otherwise.
void check_volume_output(const std::string& path, MshFormat msh = {});

/// Cobalt60 grid extensions: .cgr, .cog, .grd (any case).
bool is_cobalt_path(const std::string& path);

/// CGNS: .cgns (any case).
bool is_cgns_path(const std::string& path);

/// VTK XML: .vtu (one UnstructuredGrid) and .vtm (a MultiBlock dataset), any case.
bool is_vtu_path(const std::string& path);
bool is_vtm_path(const std::string& path);

/// The directory of a .vtm's datasets, replaced whole when it is written: "<path without its
/// extension>_blocks" ("out/wing.vtm" -> "out/wing_blocks").
std::string vtm_block_directory(const std::string& path);

/// An OpenFOAM polyMesh directory: the last component of \p path (trailing slashes aside) is
/// `polyMesh` (e.g. "case/constant/polyMesh").
bool is_polymesh_path(const std::string& path);

/// The files write_volume writes for \p path: the grid and, for Cobalt60, "<path>.bc"; for a
/// .vtm, its blocks' directory.
std::vector<std::string> volume_output_files(const std::string& path);

/// About how many bytes a mesh of \p nodes nodes and \p cells cells (or faces, for a surface)
/// takes in the format of \p path: for a warning when the disk has less free space.
std::int64_t estimate_output_bytes(const std::string& path, std::size_t nodes, std::size_t cells);

}  // namespace strata
