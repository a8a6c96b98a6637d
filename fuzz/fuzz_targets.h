#pragma once
/// \file
/// The fuzz targets' bodies, one function per target, so that the same code runs under
/// libFuzzer (STRATA_FUZZ=ON: fuzz_<target>, built with clang's sanitizers and driven by
/// scripts/fuzz.sh) and in the regression test (tests/fuzz/test_fuzz_regressions.cpp, the
/// normal build), which replays the seed corpus and every reproducer in fuzz/regressions/.
///
/// Strata's own exceptions (strata::Error and its subclasses) are the expected answer to bad
/// input and are caught; anything else escapes: a crash, a sanitizer report, an assertion, a
/// non-Strata exception (std::bad_alloc, std::out_of_range, the oracles' std::logic_error) or a
/// hang is a finding. Each returns 0 (libFuzzer's convention).

#include <cstddef>
#include <cstdint>

/// Target "stl": the bytes as an STL file (read_stl_bytes, ASCII or binary); a mesh read is
/// then put through run_surface_chain (surface_chain.h).
int strata_fuzz_one_stl(const std::uint8_t* data, std::size_t size);

/// Target "surface": the bytes decoded into a triangle/quad soup (decode_soup), which is put
/// through run_surface_chain.
int strata_fuzz_one_surface(const std::uint8_t* data, std::size_t size);

/// Target "msh": the bytes as a .msh file (any MSH version and encoding Gmsh reads) through
/// read_msh and read_volume_msh; what they return must pass the array checks (mesh_check.h).
int strata_fuzz_one_msh(const std::uint8_t* data, std::size_t size);

/// Target "writers": a volume mesh decoded from the bytes (decode_volume, volume_soup.h)
/// written as Cobalt60 and as CGNS and read back; the files must hold the mesh, or the writer
/// refuses it (only a mesh with unsound arrays, or for Cobalt60 unmatched faces) and leaves the
/// previous files as they were.
int strata_fuzz_one_writers(const std::uint8_t* data, std::size_t size);
