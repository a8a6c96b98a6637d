// The fuzz targets' bodies (fuzz/fuzz_targets.h) in the normal build: every seed of
// fuzz/corpus/<target>/ and every reproducer of a past finding in fuzz/regressions/<target>/
// runs through its target without a crash or an exception other than Strata's own; the seeds
// are valid meshes that get all the way through (so the fuzzer starts deep); the soup decoders
// do what their formats say.

#include <strata/core/error.h>
#include <strata/core/face_match.h>
#include <strata/core/mesh_check.h>
#include <strata/core/validate.h>
#include <strata/io/read_surface.h>
#include <strata/io/write_volume.h>

#include <gtest/gtest.h>

#include "fuzz_targets.h"
#include "surface_chain.h"
#include "test_support.h"
#include "volume_soup.h"

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

TEST(FuzzRegressions, MshSeedsAndReproducers) {
    replay("msh", &strata_fuzz_one_msh);
}

TEST(FuzzRegressions, WritersSeedsAndReproducers) {
    replay("writers", &strata_fuzz_one_writers);
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

TEST(FuzzSeeds, MshSeedsAreRead) {
    for (const fs::path& file : inputs("corpus", "msh")) {
        SCOPED_TRACE(file.string());
        const SurfaceMesh surface = read_msh(file.string());
        EXPECT_GT(surface.num_faces(), 0);
        EXPECT_TRUE(check_surface_arrays(surface).ok());
        if (file.filename().string().rfind("every_type", 0) != 0) continue;
        // One cell of each type but the prism, of which two; two patches.
        const VolumeMesh volume = read_volume_msh(file.string());
        EXPECT_TRUE(check_volume_arrays(volume).ok());
        EXPECT_EQ(volume.tets.size() + volume.pyramids.size() + volume.hexes.size(), 3u);
        EXPECT_EQ(volume.prisms.size(), 2u);
        EXPECT_EQ(volume.boundary.patches.size(), 2u);
    }
}

TEST(FuzzSeeds, WritersSeedsDecodeToValidMeshes) {
    for (const fs::path& file : inputs("corpus", "writers")) {
        SCOPED_TRACE(file.string());
        const std::string data = slurp(file);
        const VolumeMesh mesh = fuzz::decode_volume(bytes(data), data.size());
        EXPECT_GT(mesh.num_cells(), 0);
        // Valid, so both writers must write it (and the target reads it back).
        const ValidationReport report = validate_mesh(mesh);
        EXPECT_TRUE(report.ok()) << (report.problems.empty() ? "" : report.problems.front());
    }
}

TEST(FuzzVolumeSoup, DecodesTheDocumentedFormat) {
    // Flags: 2 patches, awkward names, kinds rotated by 1, both named as patch 0. Nodes: grid
    // points 0, 1 (x = 1), 4 (y = 1), 16 (z = 1), the last moved 0.5 in z.
    const std::string data = {0x01 | 0x04 | 0x10 | 0x40, 4, 0, 1, 4, '\x90',
                              // a tetrahedron with ids modulo 4 (5 is 1)
                              0x00, 0, 5, 2, 3,
                              // a triangle on patch 3 modulo 2 = 1, a quad on patch (0x2D >> 4) - 1 = 1
                              // with raw ids, a hexahedron cut short (left out)
                              0x34, 0, 2, 1, 0x2D, 0, 1, 2, 9, 0x03, 1, 2};
    const VolumeMesh m = fuzz::decode_volume(bytes(data), data.size());
    ASSERT_EQ(m.boundary.patches.size(), 2u);
    EXPECT_EQ(m.boundary.patches[0].name, "Hexahedra");
    EXPECT_EQ(m.boundary.patches[1].name, "Hexahedra");
    EXPECT_EQ(m.boundary.patches[0].kind, PatchKind::Farfield);
    EXPECT_EQ(m.boundary.patches[1].kind, PatchKind::Symmetry);
    ASSERT_EQ(m.points.size(), 4u);
    EXPECT_EQ(m.points[3], Vec3(0, 0, 1.5));
    ASSERT_EQ(m.tets.size(), 1u);
    EXPECT_EQ(m.tets[0], (std::array<Index, 4>{0, 1, 2, 3}));
    EXPECT_EQ(m.num_cells(), 1);
    ASSERT_EQ(m.boundary.num_faces(), 2);
    EXPECT_EQ(std::vector<Index>(m.boundary.face_begin(0), m.boundary.face_end(0)), (std::vector<Index>{0, 2, 1}));
    EXPECT_EQ(m.boundary.face_patch[0], 1);
    EXPECT_EQ(std::vector<Index>(m.boundary.face_begin(1), m.boundary.face_end(1)), (std::vector<Index>{0, 1, 2, 9}));
    EXPECT_EQ(m.boundary.face_patch[1], 1);
    // Completing the boundary (flag bit 3) adds the tetrahedron's faces, outward, patches in turn.
    std::string completed = data;
    completed[0] = 0x08 | 0x01;
    completed.resize(11);
    const VolumeMesh c = fuzz::decode_volume(bytes(completed), completed.size());
    ASSERT_EQ(c.boundary.num_faces(), 4);
    EXPECT_EQ(std::vector<Index>(c.boundary.face_begin(3), c.boundary.face_end(3)), (std::vector<Index>{3, 1, 2}));
    EXPECT_EQ(c.boundary.face_patch, (std::vector<Index>{0, 1, 0, 1}));
    EXPECT_TRUE(match_faces(c).ok());
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
