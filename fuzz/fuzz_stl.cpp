// Fuzz target "stl": Strata's STL reader (ASCII and binary, told apart by content) on any
// bytes, then the surface chain on what it read. Seeds: fuzz/corpus/stl/ and the STL files
// scripts/fuzz.sh finds (../shared/data, examples/data, tests/data); dictionary fuzz/stl.dict.

#include <strata/core/error.h>
#include <strata/io/read_surface.h>

#include "fuzz_support.h"
#include "fuzz_targets.h"
#include "surface_chain.h"

#include <string_view>

int strata_fuzz_one_stl(const std::uint8_t* data, std::size_t size) {
    using namespace strata;
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    SurfaceMesh mesh;
    try {
        mesh = read_stl_bytes(bytes, "fuzz.stl");
    } catch (const Error&) {
        return 0;  // the expected answer to bad input
    }
    // Every facet is a triangle of 3 new nodes (the reader merges nothing).
    fuzz::require(mesh.num_points() == 3 * mesh.num_faces() &&
                      mesh.face_patch.size() == static_cast<std::size_t>(mesh.num_faces()),
                  "read_stl_bytes gives 3 nodes and a patch per facet");
    fuzz::run_surface_chain(mesh, PrepareParams{}, "fuzz.stl");
    return 0;
}

#ifdef STRATA_LIBFUZZER
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return strata_fuzz_one_stl(data, size);
}
#endif
