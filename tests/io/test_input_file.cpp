// input_file.h: devices refused, pipes read to their end without being opened twice, and what
// a wrong file looks like said in words.

#include "test_support.h"

#include <strata/core/error.h>
#include <strata/io/input_file.h>

#include <gtest/gtest.h>

#include <sys/resource.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

using namespace strata;
using strata::test::ScratchDir;
namespace fs = std::filesystem;

namespace {

/// \p bytes written into the FIFO \p path by another thread (the open waits for the reader).
std::thread write_fifo(const std::string& path, std::string bytes) {
    return std::thread([path, bytes = std::move(bytes)] {
        std::FILE* f = std::fopen(path.c_str(), "wb");
        if (!f) return;
        std::fwrite(bytes.data(), 1, bytes.size(), f);
        std::fclose(f);
    });
}

}  // namespace

TEST(CheckInputSource, RegularFilePipeDeviceSocketMissing) {
    ScratchDir dir("input_source");
    std::ofstream(dir.file("a.stl")) << "solid a\nendsolid a\n";
    EXPECT_EQ(check_input_source(dir.file("a.stl")), InputSource::File);
    ASSERT_EQ(::mkfifo(dir.file("p.stl").c_str(), 0600), 0);
    EXPECT_EQ(check_input_source(dir.file("p.stl")), InputSource::Stream);  // returns: the FIFO is not opened
    fs::create_symlink("/dev/zero", dir.file("zero.stl"));
    test::expect_error<InputError>([&] { check_input_source(dir.file("zero.stl")); },
                                   {dir.file("zero.stl") + "' is a device, not a file; give the STL file itself"});
    test::expect_error<InputError>([&] { check_input_source("/dev/null"); }, {"is a device, not a file"});
    test::expect_error<InputError>([&] { check_input_source(dir.file("missing.stl")); }, {"no such file"});
    test::expect_error<InputError>([&] { check_input_source(dir.path().string()); }, {"it is a directory"});

    const int s = ::socket(AF_UNIX, SOCK_STREAM, 0);
    ASSERT_GE(s, 0);
    sockaddr_un addr{};
    addr.sun_family = AF_UNIX;
    const std::string sock = dir.file("s.step");
    ASSERT_LT(sock.size(), sizeof addr.sun_path);
    std::strcpy(addr.sun_path, sock.c_str());
    ASSERT_EQ(::bind(s, reinterpret_cast<const sockaddr*>(&addr), sizeof addr), 0);
    test::expect_error<InputError>([&] { check_input_source(sock); },
                                   {"is a socket, not a file; give the STEP file itself"});
    ::close(s);
}

TEST(RequireRegularInput, RefusesAPipe) {
    ScratchDir dir("input_regular");
    ASSERT_EQ(::mkfifo(dir.file("p.msh").c_str(), 0600), 0);
    test::expect_error<InputError>([&] { require_regular_input(dir.file("p.msh"), "Gmsh"); },
                                   {"p.msh' is a pipe, not a file: Gmsh reads it by name; save it to a file"});
}

TEST(ReadInput, ReadsAPipeToItsEnd) {
    ScratchDir dir("input_pipe");
    const std::string fifo = dir.file("p.stl");
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    std::string bytes(3 << 20, '\0');  // far more than a pipe's buffer (64 kB)
    for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<char>(i * 7919 % 251);
    std::thread writer = write_fifo(fifo, bytes);
    const std::string got = read_input(fifo);
    writer.join();
    EXPECT_EQ(got, bytes);
}

TEST(ReadInput, RegularFileWhole) {
    ScratchDir dir("input_regular_read");
    std::string bytes(100000, 'x');
    bytes[99999] = '\n';
    std::ofstream(dir.file("a.stl"), std::ios::binary) << bytes;
    EXPECT_EQ(read_input(dir.file("a.stl")), bytes);
    std::ofstream(dir.file("empty.stl"), std::ios::binary).flush();
    EXPECT_EQ(read_input(dir.file("empty.stl")), "");
    test::expect_error<InputError>([&] { read_input("/dev/zero"); }, {"'/dev/zero' is a device"});
}

TEST(OutOfMemory, NamesTheFile) {
    const std::string msg = out_of_memory("big.msh").what();
    EXPECT_EQ(msg.rfind("not enough memory to read 'big.msh' (", 0), 0u) << msg;

    // A 1 GB (sparse) file read where only 64 MB more can be allocated: a child process, its
    // address space limited, gets the InputError naming the file, not std::bad_alloc.
    ScratchDir dir("input_oom");
    const std::string big = dir.file("big.stl");
    std::ofstream(big).flush();
    fs::resize_file(big, std::uintmax_t{1} << 30);
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
        long pages = 0;
        std::ifstream("/proc/self/statm") >> pages;
        const rlim_t limit = static_cast<rlim_t>(pages) * static_cast<rlim_t>(::sysconf(_SC_PAGESIZE)) + (64u << 20);
        const rlimit rl{limit, limit};
        ::setrlimit(RLIMIT_AS, &rl);
        try {
            (void)read_input(big);
        } catch (const InputError& e) {
            const std::string what = e.what();
            ::_exit(what.rfind("not enough memory to read '" + big + "'", 0) == 0 ? 0 : 2);
        } catch (...) {
            ::_exit(3);
        }
        ::_exit(4);
    }
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 0) << "2: another message, 3: another exception, 4: no exception";
}

TEST(DescribeContent, CommonFormatsBinaryAndText) {
    using namespace std::string_literals;
    EXPECT_EQ(describe_content(""), "is empty");
    EXPECT_EQ(describe_content("\x89PNG\r\n\x1a\n\0\0\0\rIHDR"s), "looks like a PNG image");
    EXPECT_EQ(describe_content("PK\x03\x04\x14\0\0\0"s), "looks like a ZIP archive (or a file format built on one)");
    EXPECT_EQ(describe_content("%PDF-1.7\n"), "looks like a PDF document");
    EXPECT_EQ(describe_content("\x1f\x8b\x08\0"s), "looks like gzip-compressed data (decompress it first)");
    EXPECT_EQ(describe_content("\xFF\xD8\xFF\xE0"), "looks like a JPEG image");
    EXPECT_EQ(describe_content("ISO-10303-21;\nHEADER;\n"), "looks like a STEP file");
    EXPECT_EQ(describe_content("DBRep_DrawableShape\n\nCASCADE Topology V1"), "looks like an OpenCASCADE BREP file");
    EXPECT_EQ(describe_content("$MeshFormat\n4.1 0 8\n"), "looks like a Gmsh MSH mesh");
    EXPECT_EQ(describe_content("solid wing\n facet normal 0 0 1\n"), "looks like an ASCII STL mesh");
    EXPECT_EQ(describe_content("  <!DOCTYPE html>\n<html>"),
              "looks like a web page (HTML): a download that saved the page, not the file?");
    EXPECT_EQ(describe_content(" \n\t\n"), "holds only white space");
    EXPECT_EQ(describe_content("\0\x01\x02\x03\x04\x05\x06\x07\x08\x09"s),
              "starts with binary data (bytes 00 01 02 03 04 05 06 07 ...)");
    EXPECT_EQ(describe_content("hello world\nsecond line"), "starts with the text 'hello world'");
    EXPECT_EQ(describe_content(std::string(60, 'a')), "starts with the text '" + std::string(40, 'a') + "...'");
}
