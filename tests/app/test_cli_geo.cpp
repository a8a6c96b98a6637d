// End-to-end tests of the `strata` program on what its options let run: a .geo script is a
// program, refused where it reaches outside Gmsh's model unless --trust-geo; a thread count the
// library refuses is refused by its flag's name, before any work.

#include <gtest/gtest.h>

#include "test_support.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace strata {
namespace {

namespace fs = std::filesystem;

test::CliResult strata_cli(const test::ScratchDir& dir, const std::string& args) {
    return test::run_program(dir, STRATA_CLI, args);
}

/// A unit box (a valid model) that then runs `touch pwned` in the directory it is read in.
void write_evil_script(const test::ScratchDir& dir) {
    std::ofstream(dir.file("evil.geo")) << "SetFactory(\"OpenCASCADE\");\n"
                                           "Box(1) = {0, 0, 0, 1, 1, 1};\n"
                                           "SystemCall \"touch pwned\";\n";
}

TEST(CliGeo, AScriptRunningAShellCommandIsRefusedAndNothingRuns) {
    test::ScratchDir dir("cli_geo_refused");
    write_evil_script(dir);
    const test::CliResult r = strata_cli(dir, "surface evil.geo -o out.msh");
    EXPECT_EQ(r.code, 1) << r.err;
    for (const char* part :
         {"evil.geo, line 3: `SystemCall` runs a shell command", "a .geo file is a program", "give --trust-geo"})
        EXPECT_NE(r.err.find(part), std::string::npos) << "'" << part << "' not in: " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(fs::exists(dir.file("pwned")));
    EXPECT_EQ(test::dir_entries(dir.path()), std::vector<std::string>{"evil.geo"});  // no output
}

TEST(CliGeo, ATrustedScriptRuns) {
    test::ScratchDir dir("cli_geo_trusted");
    write_evil_script(dir);
    const test::CliResult r = strata_cli(dir, "surface evil.geo -o out.msh --trust-geo");
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(fs::exists(dir.file("pwned")));  // Gmsh ran it, as asked
    EXPECT_TRUE(fs::exists(dir.file("out.msh")));
}

TEST(CliOptions, ANegativeThreadCountIsRefusedByItsFlag) {
    test::ScratchDir dir("cli_negative_threads");
    for (const char* command : {"layers", "mesh"}) {
        const test::CliResult r = strata_cli(dir, std::string(command) + " '" + test::example_data("sphere.stl") +
                                                      "' -o out.msh --layers 2 --first-height 0.01 --threads -1");
        EXPECT_EQ(r.code, 1) << command << ": " << r.err;
        EXPECT_NE(r.err.find("--threads is -1: give 0 (all cores) or a positive count"), std::string::npos)
            << command << ": " << r.err;
        EXPECT_TRUE(test::dir_entries(dir.path()).empty()) << command;
    }
}

}  // namespace
}  // namespace strata
