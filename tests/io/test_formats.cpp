// formats.h: which writer an output path picks, and the check that refuses a bad one before
// any work, naming the path and the choices.

#include "test_support.h"

#include <strata/core/error.h>
#include <strata/io/formats.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

using namespace strata;
using strata::test::ScratchDir;

TEST(Formats, PathsPickTheirWriter) {
    EXPECT_TRUE(is_polymesh_path("case/constant/polyMesh"));
    EXPECT_TRUE(is_polymesh_path("case/constant/polyMesh/"));
    EXPECT_TRUE(is_polymesh_path("polyMesh"));
    EXPECT_FALSE(is_polymesh_path("case/constant/polyMesh.msh"));
    EXPECT_FALSE(is_polymesh_path("case/polyMesh/mesh.cgr"));
    EXPECT_FALSE(is_polymesh_path("mypolyMesh"));
    EXPECT_TRUE(is_cgns_path("wing.cgns"));
    EXPECT_TRUE(is_cgns_path("WING.CGNS"));
    EXPECT_FALSE(is_cgns_path("wing.cgr"));
    EXPECT_TRUE(is_cobalt_path("wing.cgr"));
    EXPECT_EQ(volume_output_files("case/constant/polyMesh"), std::vector<std::string>{"case/constant/polyMesh"});
    EXPECT_EQ(volume_output_files("m.cgns"), std::vector<std::string>{"m.cgns"});
    EXPECT_TRUE(is_vtu_path("m.VTU"));
    EXPECT_TRUE(is_vtm_path("out/m.vtm"));
    EXPECT_FALSE(is_vtm_path("m.vtu"));
    EXPECT_EQ(vtm_block_directory("out/m.VTM"), "out/m_blocks");
    EXPECT_EQ(volume_output_files("m.vtm"), (std::vector<std::string>{"m.vtm", "m_blocks"}));
}

TEST(Formats, VolumeOutputsAreCheckedBeforeTheWork) {
    ScratchDir dir("formats_check");
    EXPECT_NO_THROW(check_volume_output(dir.file("m.cgns")));
    EXPECT_NO_THROW(check_volume_output(dir.file("polyMesh")));
    std::filesystem::create_directory(dir.file("polyMesh"));
    EXPECT_NO_THROW(check_volume_output(dir.file("polyMesh")));  // replaced whole when written
    test::expect_error<InputError>([&] { check_volume_output(dir.file("m.xyz")); },
                                   {"m.xyz", ".cgr", ".cgns (CGNS)", ".vtu, .vtm (VTK XML", "polyMesh (OpenFOAM", ".msh"});
    EXPECT_NO_THROW(check_volume_output(dir.file("m.vtu")));
    EXPECT_NO_THROW(check_volume_output(dir.file("m.vtm")));
    test::expect_error<InputError>([&] { check_volume_output(dir.file("missing/constant/polyMesh")); },
                                   {"missing/constant", "does not exist"});
    test::expect_error<InputError>([&] { check_volume_output(dir.file("missing/m.cgns")); }, {"does not exist"});
    std::filesystem::create_directory(dir.file("case"));
    std::ofstream(dir.file("case/polyMesh")) << "x";
    test::expect_error<InputError>([&] { check_volume_output(dir.file("case/polyMesh")); }, {"is a file"});
}
