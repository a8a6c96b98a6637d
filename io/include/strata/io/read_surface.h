#pragma once
/// \file
/// Surface-mesh readers: STL (ASCII and binary) and Gmsh .msh (2.2 and 4.1, via the Gmsh API).
/// They return the mesh as stored (no merging, no orientation): see prepare.h for that.

#include <strata/core/surface_mesh.h>

#include <string>
#include <string_view>

namespace strata {

/// STL, ASCII or binary (detected from the content, not the header word). One patch per
/// ASCII `solid NAME` block (name "wall" if empty); binary: one patch named after the file
/// stem. Nodes are not merged (3 per facet). Throws InputError naming the file and line
/// (ASCII) or facet (binary) on a malformed or truncated file.
SurfaceMesh read_stl(const std::string& path);

/// read_stl on a file's bytes already in memory (a download, a fuzzer's input): the same
/// detection, mesh and errors, with \p source where read_stl names the path (in every message,
/// and its stem as a binary file's patch name).
SurfaceMesh read_stl_bytes(std::string_view data, const std::string& source);

/// Gmsh .msh 2.2 or 4.1 with 3-node triangles and 4-node quadrangles (higher-order or other
/// 2D types are an error; points, lines and volume elements are ignored), read by Gmsh into a
/// scratch model and converted by surface_from_gmsh_model: patches by its rule (one per 2D
/// physical group with faces, one per surface in no group), nodes in the file's order. Throws
/// InputError naming the file if it is missing or unreadable, or holds no triangles or quads.
SurfaceMesh read_msh(const std::string& path);

}  // namespace strata
