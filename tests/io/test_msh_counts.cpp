// msh_counts.h: a .msh file claiming more nodes or elements than its size holds is refused
// before Gmsh sizes its arrays from the claim; real files, ASCII and binary, pass.

#include "msh_variants.h"
#include "test_support.h"

#include <strata/core/error.h>
#include <strata/io/gmsh_session.h>
#include <strata/io/msh_counts.h>
#include <strata/io/read_surface.h>

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

using namespace strata;
using strata::test::ScratchDir;
namespace fs = std::filesystem;

namespace {

template <class T>
std::string raw(T v, bool swap = false) {
    std::string s(sizeof v, '\0');
    std::memcpy(s.data(), &v, sizeof v);
    if (swap) std::reverse(s.begin(), s.end());
    return s;
}

std::string write(const ScratchDir& dir, const std::string& name, const std::string& bytes) {
    std::ofstream(dir.file(name), std::ios::binary) << bytes;
    return dir.file(name);
}

/// read_msh on \p path fails with the claim and the file's size in its message.
void expect_claim(const std::string& path, const std::string& claim) {
    const std::string size = std::to_string(fs::file_size(path));
    test::expect_error<InputError>([&] { read_msh(path); },
                                   {"'" + path + "' claims " + claim + " but the file has only " + size + " bytes",
                                    "it is truncated or damaged; write it again"});
}

const std::string kAscii41 = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n";
const std::string kAscii22 = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n";

}  // namespace

TEST(MshCounts, Ascii41HugeNodeAndElementCounts) {
    ScratchDir dir("msh_counts_a41");
    expect_claim(write(dir, "nodes.msh",
                       kAscii41 + "$Nodes\n1 3000000000 1 3000000000\n2 1 0 3000000000\n1\n0 0 0\n$EndNodes\n"),
                 "3000000000 nodes");
    expect_claim(write(dir, "elements.msh",
                       kAscii41 + "$Nodes\n1 3 1 3\n2 1 0 3\n1\n2\n3\n0 0 0\n1 0 0\n0 1 0\n$EndNodes\n"
                                  "$Elements\n1 2000000000 1 2000000000\n2 1 2 2000000000\n1 1 2 3\n"
                                  "$EndElements\n"),
                 "2000000000 elements");
}

TEST(MshCounts, Ascii22HugeNodeAndElementCounts) {
    ScratchDir dir("msh_counts_a22");
    expect_claim(write(dir, "nodes.msh", kAscii22 + "$Nodes\n3000000000\n1 0 0 0\n$EndNodes\n"), "3000000000 nodes");
    expect_claim(write(dir, "elements.msh",
                       kAscii22 + "$Nodes\r\n3\r\n1 0 0 0\r\n2 1 0 0\r\n3 0 1 0\r\n$EndNodes\r\n"
                                  "$Elements\r\n4000000000\r\n1 2 0 1 2 3\r\n$EndElements\r\n"),
                 "4000000000 elements");
}

TEST(MshCounts, Binary41And22HugeCountsInEitherByteOrder) {
    ScratchDir dir("msh_counts_bin");
    for (const bool swap : {false, true}) {
        SCOPED_TRACE(swap ? "swapped" : "native");
        const std::string one = raw(std::int32_t{1}, swap);
        std::string b41 = "$MeshFormat\n4.1 1 8\n" + one + "\n$EndMeshFormat\n$Nodes\n";
        for (const std::uint64_t v :
             {std::uint64_t{1}, std::uint64_t{3000000000}, std::uint64_t{1}, std::uint64_t{3000000000}})
            b41 += raw(v, swap);
        b41 += std::string(40, '\0') + "\n$EndNodes\n";
        expect_claim(write(dir, "b41.msh", b41), "3000000000 nodes");

        const std::string b22 = "$MeshFormat\n2.2 1 8\n" + one + "\n$EndMeshFormat\n$Nodes\n5000000000\n" +
                                std::string(28, '\0') + "\n$EndNodes\n";
        expect_claim(write(dir, "b22.msh", b22), "5000000000 nodes");
    }
}

TEST(MshCounts, Msh41NodeTagsBeyondAnIntAreRefused) {
    // Gmsh 4.8 crashed (SIGSEGV in GModel::getMeshVertexByTag(int)) on an element using node 3e9.
    ScratchDir dir("msh_counts_tags");
    const std::string path = write(dir, "tags.msh",
                                   kAscii41 +
                                       "$Nodes\n1 3 1 3000000000\n2 1 0 3\n1\n2\n3000000000\n"
                                       "0 0 0\n1 0 0\n0 1 0\n$EndNodes\n$Elements\n1 1 1 1\n"
                                       "2 1 2 1\n1 1 2 3000000000\n$EndElements\n");
    test::expect_error<InputError>([&] { read_msh(path); },
                                   {"tags.msh': its node tags reach 3000000000, beyond the 2147483647 Gmsh reads"});
    // MSH 2.2 and element tags take them (Gmsh reads those as they are).
    const std::string v22 = write(dir, "tags22.msh",
                                  kAscii22 +
                                      "$Nodes\n3\n1 0 0 0\n2 1 0 0\n3000000000 0 1 0\n$EndNodes\n"
                                      "$Elements\n1\n1 2 2 1 1 1 2 3000000000\n$EndElements\n");
    EXPECT_EQ(read_msh(v22).num_triangles(), 1);
}

TEST(MshCounts, NotAnMshFileSaysWhatItIs) {
    ScratchDir dir("msh_counts_png");
    const std::string png = write(dir, "x.msh", std::string("\x89PNG\r\n\x1a\n\0\0\0\rIHDR", 16));
    test::expect_error<InputError>(
        [&] { read_msh(png); }, {"'" + png + "' is not an MSH file: it looks like a PNG image; write the mesh again"});
    const std::string empty = write(dir, "empty.msh", "");
    test::expect_error<InputError>([&] { read_msh(empty); }, {"'" + empty + "' is not an MSH file: it is empty"});
}

TEST(MshCounts, RealFilesPass) {
    std::vector<std::string> files;
    for (const std::string& dir : {std::string(STRATA_EXAMPLES_DATA), std::string(STRATA_TEST_DATA)})
        for (const auto& e : fs::directory_iterator(dir))
            if (e.path().extension() == ".msh") files.push_back(e.path().string());
    ASSERT_GE(files.size(), 6u);
    // And Gmsh's binary 4.1 and 2.2 (ASCII 2.2 too) of one of them, little-endian like the machine.
    ScratchDir dir("msh_counts_real");
    for (const std::string& f : test::write_msh_variants(test::example_data("sphere_pyhyp_quads.msh"), dir))
        files.push_back(f);
    for (const std::string& f : files) {
        SCOPED_TRACE(f);
        EXPECT_NO_THROW(check_msh_counts(f));
    }
    // Gmsh's own files cut to 3000 bytes: their real node counts (read from binary too) no
    // longer fit.
    for (const char* name : {"b41.msh", "b22.msh", "a22.msh"}) {
        SCOPED_TRACE(name);
        const std::string cut = dir.file(std::string("cut_") + name);
        std::ofstream(cut, std::ios::binary) << test::slurp(dir.file(name)).substr(0, 3000);
        test::expect_error<InputError>([&] { check_msh_counts(cut); },
                                       {"' claims 1538 nodes but the file has only 3000 bytes"});
    }
}
