#pragma once
/// \file
/// The fuzz targets' bodies, one function per target, so that the same code runs under
/// libFuzzer (STRATA_FUZZ=ON: fuzz_stl, fuzz_surface, built with clang's sanitizers and driven
/// by scripts/fuzz.sh) and in the regression test (tests/fuzz/test_fuzz_regressions.cpp, the
/// normal build), which replays the seed corpus and every reproducer in fuzz/regressions/.
///
/// Strata's own exceptions (strata::Error and its subclasses) are the expected answer to bad
/// input and are caught; anything else escapes: a crash, a sanitizer report, an assertion, a
/// non-Strata exception (std::bad_alloc, std::out_of_range, the oracles' std::logic_error) or a
/// hang is a finding.

#include <strata/core/surface_mesh.h>
#include <strata/geometry/prepare.h>

#include <cstddef>
#include <cstdint>
#include <string>

/// Target "stl": the bytes as an STL file (read_stl_bytes, ASCII or binary); a mesh read is
/// then put through run_surface_chain. Returns 0 (libFuzzer's convention).
int strata_fuzz_one_stl(const std::uint8_t* data, std::size_t size);

/// Target "surface": the bytes decoded into a triangle/quad soup (decode_soup), which is put
/// through run_surface_chain. Returns 0.
int strata_fuzz_one_surface(const std::uint8_t* data, std::size_t size);

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
