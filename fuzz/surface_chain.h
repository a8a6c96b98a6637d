#pragma once
/// \file
/// The surface targets' shared part (fuzz_stl.cpp, fuzz_surface.cpp): the soup format of
/// target "surface" and everything after reading a surface, on any mesh.

#include <strata/core/surface_mesh.h>
#include <strata/surface/prepare.h>

#include <cstddef>
#include <cstdint>
#include <string>

namespace strata::fuzz {

/// A surface mesh and the preparation options for it, decoded from a fuzzer's bytes.
struct Soup {
    SurfaceMesh mesh;
    PrepareParams params;
};

/// Decode \p data as a soup (the format is described at decode_soup's definition in
/// fuzz/fuzz_surface.cpp; fuzz/make_seeds.py writes it). Every byte string decodes to some
/// mesh; short input gives an empty one.
Soup decode_soup(const std::uint8_t* data, std::size_t size);

/// Everything after reading, on any mesh: the pieces alone on the mesh as given (check_surface,
/// vertex_faces, edge_table, boundary_loops, face_components, node_rings; orient_surface and
/// needle_faces once check_surface passed), then prepare_mesh with \p params (assign kinds,
/// merge, remove collapsed faces, check, orient; no fuse or remesh) and, on its result, the
/// check again (which must pass), node_rings, boundary_loops, face_components and needle_faces.
/// strata::Error from any step is expected and caught; an oracle that fails throws
/// std::logic_error. Returns how far it got: 0 nothing passed, 1 prepare_mesh passed, 2 its
/// result also has node rings.
int run_surface_chain(const SurfaceMesh& mesh, const PrepareParams& params, const std::string& source);

}  // namespace strata::fuzz
