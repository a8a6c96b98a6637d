// Fuzz target "msh": the bytes as a .msh file read by read_msh (surface) and read_volume_msh
// (volume), every MSH version and encoding Gmsh reads (4.1 and 2.2, ASCII and binary). Gmsh
// reads files, not memory, so the bytes go to a file in the scratch directory (memory, under
// /dev/shm) named .msh, which makes Gmsh use its MSH reader and nothing else. Oracle: a mesh
// returned passes the array checks (core/mesh_check.h), or the reader throws strata::Error.
// Gmsh is initialised once for the process, as by a program that calls Gmsh itself (GmshLock
// records it, so each reader's session neither initialises nor finalises Gmsh): five times the
// inputs per second of a Gmsh initialised per read.
// Seeds: fuzz/corpus/msh/ (fuzz/make_seeds.py), dictionary fuzz/msh.dict.

#include <strata/core/error.h>
#include <strata/core/mesh_check.h>
#include <strata/io/gmsh_session.h>
#include <strata/io/read_surface.h>
#include <strata/io/write_volume.h>

#include "fuzz_support.h"
#include "fuzz_targets.h"

#include <cstdio>
#include <memory>
#include <string>

namespace {

/// Initialise Gmsh, quiet, on the first call (GmshSession's options), and record it as the
/// program's own initialisation.
void keep_gmsh_initialised() {
    static const bool initialised = [] {
        gmsh::initialize();
        gmsh::option::setNumber("General.Terminal", 0);
        gmsh::option::setNumber("General.Verbosity", 2);
        const strata::GmshLock record("fuzz target msh");
        return true;
    }();
    (void)initialised;
}

}  // namespace

int strata_fuzz_one_msh(const std::uint8_t* data, std::size_t size) {
    using namespace strata;
    keep_gmsh_initialised();
    const std::string path = fuzz::scratch_path("fuzz.msh");
    {
        const std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(path.c_str(), "wb"), &std::fclose);
        fuzz::require(f && std::fwrite(data, 1, size, f.get()) == size, "the input is written to " + path);
    }
    try {
        const SurfaceMesh mesh = read_msh(path);
        const MeshProblems problems = check_surface_arrays(mesh);
        fuzz::require(problems.ok(), "read_msh returns sound arrays: " + (problems.ok() ? "" : problems.lines[0]));
    } catch (const Error&) {
        // the expected answer to bad input
    }
    try {
        const VolumeMesh mesh = read_volume_msh(path);
        const MeshProblems problems = check_volume_arrays(mesh);
        fuzz::require(problems.ok(),
                      "read_volume_msh returns sound arrays: " + (problems.ok() ? "" : problems.lines[0]));
    } catch (const Error&) {
    }
    return 0;
}

#ifdef STRATA_LIBFUZZER
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return strata_fuzz_one_msh(data, size);
}
#endif
