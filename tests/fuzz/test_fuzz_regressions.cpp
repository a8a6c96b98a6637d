// The fuzz targets' bodies (fuzz/fuzz_targets.h) in the normal build: every seed of
// fuzz/corpus/<target>/ and every reproducer of a past finding in fuzz/regressions/<target>/
// runs through its target without a crash or an exception other than Strata's own; the seeds
// are valid meshes that get all the way through (so the fuzzer starts deep); the soup decoder
// does what its format says.

#include <strata/core/error.h>
#include <strata/io/read_surface.h>

#include <gtest/gtest.h>

#include "fuzz_targets.h"
#include "test_support.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace strata {
namespace {

namespace fs = std::filesystem;

using strata::test::slurp;

/// The files of fuzz/<kind>/<target>/, sorted (none if the folder does not exist).
std::vector<fs::path> inputs(const std::string& kind, const std::string& target) {
    const fs::path dir = fs::path(STRATA_FUZZ_DIR) / kind / target;
    std::vector<fs::path> files;
    if (fs::is_directory(dir))
        for (const auto& e : fs::directory_iterator(dir))
            if (e.is_regular_file()) files.push_back(e.path());
    std::sort(files.begin(), files.end());
    return files;
}

const std::uint8_t* bytes(const std::string& s) {
    return reinterpret_cast<const std::uint8_t*>(s.data());
}

using Target = int (*)(const std::uint8_t*, std::size_t);

/// Every seed and reproducer of \p target through \p run: returns 0, throws nothing (Strata's
/// errors are caught inside), does not crash.
void replay(const std::string& target, Target run) {
    std::size_t seeds = inputs("corpus", target).size();
    EXPECT_GT(seeds, 0u) << "no seeds in " << STRATA_FUZZ_DIR << "/corpus/" << target;
    for (const std::string kind : {"corpus", "regressions"})
        for (const fs::path& file : inputs(kind, target)) {
            SCOPED_TRACE(file.string());
            const std::string data = slurp(file);
            EXPECT_NO_THROW(EXPECT_EQ(run(bytes(data), data.size()), 0));
        }
}

TEST(FuzzRegressions, StlSeedsAndReproducers) {
    replay("stl", &strata_fuzz_one_stl);
}

TEST(FuzzRegressions, SurfaceSeedsAndReproducers) {
    replay("surface", &strata_fuzz_one_surface);
}

TEST(FuzzSeeds, StlSeedsAreReadPreparedAndHaveRings) {
    for (const fs::path& file : inputs("corpus", "stl")) {
        SCOPED_TRACE(file.string());
        const SurfaceMesh mesh = read_stl_bytes(slurp(file), file.string());
        EXPECT_EQ(fuzz::run_surface_chain(mesh, PrepareParams{}, file.string()), 2);
    }
}

TEST(FuzzSeeds, SurfaceSeedsDecodeToPreparedSurfacesWithRings) {
    for (const fs::path& file : inputs("corpus", "surface")) {
        SCOPED_TRACE(file.string());
        const std::string data = slurp(file);
        const fuzz::Soup soup = fuzz::decode_soup(bytes(data), data.size());
        EXPECT_GT(soup.mesh.num_faces(), 0);
        EXPECT_EQ(fuzz::run_surface_chain(soup.mesh, soup.params, file.string()), 2);
    }
}

TEST(FuzzSoup, DecodesTheDocumentedFormat) {
    // Flags: internal flow, tolerance 0 (bits 1-2 = 1), 2 patches, scale 1000. Nodes: grid
    // point 21 (1, 1, 1); grid point 3 moved 1e-10 in x; grid point 48 with y infinite (0xD1:
    // coordinate 1, special 1); three raw doubles.
    std::string data = {0x01 | 0x02 | 0x10 | 0x40, 4, 21, 0x40 | 3, '\xD1', 48, '\xF0'};
    for (double x : {0.5, -2.0, 7.25}) data.append(reinterpret_cast<const char*>(&x), sizeof x);
    // Faces: a triangle on patch (0xF0 >> 5) - 1 = 6 (bit 4 asks for it) with ids modulo 4; a
    // quad on patch 1 with raw ids (5 is out of range); a triangle cut short (left out).
    const char faces[] = {'\xF0', 1, 6, 2, 0x01 | 0x02 | 0x08, 0, 1, 2, 5, 0x00, 1};
    data.append(faces, sizeof faces);
    const fuzz::Soup soup = fuzz::decode_soup(bytes(data), data.size());
    const SurfaceMesh& m = soup.mesh;
    EXPECT_TRUE(soup.params.internal_flow);
    EXPECT_EQ(soup.params.merge_tolerance, 0.0);
    EXPECT_EQ(soup.params.scale, 1000.0);
    ASSERT_EQ(m.patches.size(), 2u);
    EXPECT_EQ(m.patches[1].name, "farfield");
    ASSERT_EQ(m.num_points(), 4);
    EXPECT_EQ(m.points[0], Vec3(1, 1, 1));
    EXPECT_EQ(m.points[1], Vec3(3 + 1e-10, 0, 0));
    EXPECT_EQ(m.points[2].x(), 0.0);
    EXPECT_TRUE(std::isinf(m.points[2].y()));
    EXPECT_EQ(m.points[2].z(), 3.0);
    EXPECT_EQ(m.points[3], Vec3(0.5, -2.0, 7.25));
    ASSERT_EQ(m.num_faces(), 2);
    EXPECT_EQ(std::vector<Index>(m.face_begin(0), m.face_end(0)), (std::vector<Index>{1, 2, 2}));
    EXPECT_EQ(m.face_patch[0], 6);
    EXPECT_EQ(std::vector<Index>(m.face_begin(1), m.face_end(1)), (std::vector<Index>{0, 1, 2, 5}));
    EXPECT_EQ(m.face_patch[1], 1);
    // Such a mesh is refused with Strata's own errors, nothing else.
    EXPECT_EQ(fuzz::run_surface_chain(m, soup.params, "soup"), 0);
}

}  // namespace
}  // namespace strata
