// The `strata` program on inputs that are not what their names say (a PNG named .iges, a .msh
// claiming billions of nodes, /dev/zero named .stl, a pipe) and on layers no double holds: one
// line naming the file or the option and what to do, exit code 1, no output file. A pipe named
// .stl is read to its end.

#include <strata/io/read_surface.h>

#include <gtest/gtest.h>

#include "test_support.h"

#include <sys/stat.h>
#include <sys/wait.h>
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

namespace strata {
namespace {

namespace fs = std::filesystem;
using test::example_data;
using test::slurp;

using test::CliResult;

/// Run the strata program with \p args (already shell-quoted) in \p dir, its standard input
/// from \p feed (a shell command piped in) or /dev/null; stopped after 120 s, so that a run
/// waiting for ever on a pipe fails instead of hanging the suite.
CliResult strata_cli(const test::ScratchDir& dir, const std::string& args, const std::string& feed = "") {
    return test::run_program(dir, STRATA_CLI, args, "timeout 120 ", feed);
}

/// \p r failed as a bad input does: exit 1, one line on stderr holding \p message.
void expect_refused(const CliResult& r, const std::string& message) {
    EXPECT_EQ(r.code, 1) << r.err;
    EXPECT_NE(r.err.find(message), std::string::npos) << "'" << message << "' not in: " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

/// `strata surface NAME -o out.msh` in \p dir is refused with \p message and leaves only NAME.
void expect_surface_refused(const test::ScratchDir& dir, const std::string& name, const std::string& message) {
    expect_refused(strata_cli(dir, "surface " + name + " -o out.msh"), message);
    EXPECT_EQ(test::dir_entries(dir.path()), std::vector<std::string>{name});
}

TEST(CliBadInput, PngNamedIges) {
    test::ScratchDir dir("cli_bad_png");
    std::ofstream(dir.file("wing.iges"), std::ios::binary) << std::string("\x89PNG\r\n\x1a\n\0\0\0\rIHDR", 16);
    expect_surface_refused(dir, "wing.iges",
                           "'wing.iges' is not an IGES file: it looks like a PNG image; export the model again as "
                           "IGES, or give the file the extension of its format (.step, .iges, .brep)");
}

TEST(CliBadInput, MshClaimingBillionsOfNodes) {
    test::ScratchDir dir("cli_bad_msh");
    const std::string text =
        "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 3000000000 1 3000000000\n2 1 0 3000000000\n1\n0 0 0\n"
        "$EndNodes\n";
    std::ofstream(dir.file("huge.msh"), std::ios::binary) << text;
    expect_surface_refused(
        dir, "huge.msh",
        "'huge.msh' claims 3000000000 nodes but the file has only " + std::to_string(text.size()) + " bytes");
}

TEST(CliBadInput, MshThatCrashesGmshsReaderIsAnError) {
    // A damaged binary MSH 2.2 file the fuzzer found: Gmsh 4.8's reader crashes on it
    // (SIGSEGV), in the child process Strata reads it in first.
    test::ScratchDir dir("cli_bad_msh_crash");
    fs::copy_file(
        std::string(STRATA_EXAMPLES_DATA) + "/../../fuzz/regressions/msh/msh22_binary_nodes_garbled_segv_1.msh",
        dir.file("damaged.msh"));
    expect_surface_refused(dir, "damaged.msh",
                           "reading 'damaged.msh': Gmsh's MSH reader crashes (signal 11) on it: the file is damaged "
                           "or not MSH 2.2 or 4.1; write it again");
}

TEST(CliBadInput, DeviceNamedStl) {
    test::ScratchDir dir("cli_bad_device");
    fs::create_symlink("/dev/zero", dir.file("x.stl"));
    expect_surface_refused(dir, "x.stl", "'x.stl' is a device, not a file; give the STL file itself");
}

TEST(CliBadInput, PipeNamedMshOrStepIsRefusedWithoutWaiting) {
    test::ScratchDir dir("cli_bad_fifo");
    // No writer: opening either would wait for ever (the runner's timeout would end it: 124).
    for (const char* name : {"p.msh", "p.step"}) {
        ASSERT_EQ(::mkfifo(dir.file(name).c_str(), 0600), 0);
        expect_refused(strata_cli(dir, std::string("surface ") + name + " -o out.msh"),
                       std::string(name) + "' is a pipe, not a file: Gmsh reads it by name");
    }
    EXPECT_EQ(test::dir_entries(dir.path()), (std::vector<std::string>{"p.msh", "p.step"}));
}

TEST(CliBadInput, PipeNamedStlIsReadToItsEnd) {
    test::ScratchDir dir("cli_fifo_stl");
    const std::string fifo = dir.file("sphere.stl");
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    std::thread writer =
        test::fill_fifo(fifo, slurp(example_data("sphere.stl")));  // it waits for the program to open it
    const CliResult r = strata_cli(dir, "surface sphere.stl -o out.msh");
    writer.join();
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(read_msh(dir.file("out.msh")).num_triangles(), 606);

    // And the shell's pipe, through /dev/stdin under an .stl name.
    fs::create_symlink("/dev/stdin", dir.file("stdin.stl"));
    const CliResult s = strata_cli(dir, "surface stdin.stl -o piped.msh", "cat '" + example_data("sphere.stl") + "'");
    ASSERT_EQ(s.code, 0) << s.err;
    EXPECT_EQ(read_msh(dir.file("piped.msh")).num_triangles(), 606);
}

TEST(CliBadInput, LayersNoDoubleHolds) {
    test::ScratchDir dir("cli_bad_layers");
    const CliResult r =
        strata_cli(dir, "layers '" + example_data("sphere.stl") + "' -o out.msh --layers 10000 --first-height 1e-5");
    expect_refused(
        r, "--layers = 10000 with --growth = 1.2: the last layer would be 1.2^9999 ≈ 1e791 times the first layer");
    EXPECT_NE(r.err.find("use fewer layers or a smaller growth"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("inf"), std::string::npos) << r.err;
    EXPECT_TRUE(test::dir_entries(dir.path()).empty());
}

}  // namespace
}  // namespace strata
