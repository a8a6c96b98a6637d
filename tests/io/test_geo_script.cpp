// Tests for io/geo_script.h: a .geo script with Macros read more than once in one process.

#include <strata/io/geo_script.h>
#include <strata/io/gmsh_session.h>

#include <gmsh.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "test_support.h"

using namespace strata;

namespace {

// Gmsh's tutorial t5 in miniature: a Macro that adds a sphere, called twice.
constexpr const char* kScript =
    "SetFactory(\"OpenCASCADE\");\n"
    "// Call Bore inside a comment is renamed too, harmlessly\n"
    "Macro Bore\n"
    "  Sphere(newv) = {x, 0, 0, 0.1};\n"
    "Return\n"
    "Function \"Old\"\n"
    "  y = 1;\n"
    "Return\n"
    "x = 0;\n"
    "Call Bore;\n"
    "x = 1;\n"
    "Call \"Bore\";\n"
    "Call Old;\n"
    "Bores = 2; CallBore = 3;\n";

}  // namespace

TEST(GeoScript, MacroNamesAreThoseDefinedBareOrQuoted) {
    EXPECT_EQ(geo_macro_names(kScript), (std::vector<std::string>{"Bore", "Old"}));
    EXPECT_TRUE(geo_macro_names("MyMacro Foo;\nx = 1;\n").empty());  // part of a longer word
}

TEST(GeoScript, RenamingTouchesTheDefinitionsAndCallsOnly) {
    const std::string r = rename_geo_macros(kScript, "_s1");
    EXPECT_NE(r.find("Macro Bore_s1\n"), std::string::npos) << r;
    EXPECT_NE(r.find("Function \"Old_s1\"\n"), std::string::npos) << r;
    EXPECT_NE(r.find("Call Bore_s1;\nx = 1;\nCall \"Bore_s1\";\nCall Old_s1;\n"), std::string::npos) << r;
    EXPECT_NE(r.find("Bores = 2; CallBore = 3;"), std::string::npos) << r;  // other words stay
    EXPECT_EQ(rename_geo_macros("Call Other;\n", "_s1"), "Call Other;\n");  // another script's Macro
}

TEST(GeoScript, AScriptWithMacrosIsReadTwiceInOneProcess) {
    // Gmsh 4.8 keeps Macros for the life of the process: gmsh::merge of the same script a
    // second time failed with "Redefinition of function Bore".
    test::ScratchDir dir("geo_script_twice");
    const std::string path = dir.file("holes.geo");
    std::ofstream(path) << kScript;
    for (int round = 0; round < 3; ++round) {
        GmshSession session("geo_script_test");
        gmsh_call("reading " + path, [&] { merge_geo_script(path); });
        gmsh::model::occ::synchronize();
        gmsh::vectorpair volumes;
        gmsh::model::getEntities(volumes, 3);
        EXPECT_EQ(volumes.size(), 2u) << "round " << round;
    }
    // The renamed copies beside the script are gone.
    int files = 0;
    for (const auto& e : std::filesystem::directory_iterator(dir.path())) files += e.is_regular_file() ? 1 : 0;
    EXPECT_EQ(files, 1);
}
