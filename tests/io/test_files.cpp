// files.h: the output-directory check and AtomicDirectory (build next to the target, put in
// place whole, remove on failure). AtomicFile is exercised by every writer's tests.

#include "test_support.h"

#include <strata/core/error.h>
#include <strata/io/files.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cerrno>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

using namespace strata;
using strata::test::ScratchDir;
namespace fs = std::filesystem;

namespace {

using strata::test::slurp;

}  // namespace

TEST(CheckOutputDirectory, MissingParentAndFileAreRefused) {
    ScratchDir dir("files_check_dir");
    EXPECT_NO_THROW(check_output_directory(dir.file("polyMesh")));
    fs::create_directory(dir.file("existing"));
    EXPECT_NO_THROW(check_output_directory(dir.file("existing")));
    test::expect_error<InputError>([&] { check_output_directory(dir.file("case/constant/polyMesh")); },
                                   {"cannot write", "case/constant", "does not exist"});
    std::ofstream(dir.file("file")) << "x";
    test::expect_error<InputError>([&] { check_output_directory(dir.file("file")); }, {"is a file, not a directory"});
}

TEST(AtomicDirectory, NewTargetExistingTargetAndNoCommit) {
    ScratchDir dir("files_atomic_dir");
    const std::string target = dir.file("out");
    {
        AtomicDirectory d(target);
        EXPECT_TRUE(fs::is_directory(d.temp_path()));
        EXPECT_EQ(fs::path(d.temp_path()).parent_path(), dir.path());
        std::ofstream(d.file("a")) << "first";
        EXPECT_FALSE(fs::exists(target));  // nothing at the target before commit
        d.commit();
    }
    EXPECT_EQ(test::dir_entries(dir.path()), std::vector<std::string>{"out"});
    EXPECT_EQ(slurp(target + "/a"), "first");
    {
        AtomicDirectory d(target);
        std::ofstream(d.file("b")) << "second";
        EXPECT_EQ(slurp(target + "/a"), "first");  // the old one stays whole until commit
        d.commit();
    }
    EXPECT_EQ(test::dir_entries(dir.path()), std::vector<std::string>{"out"});
    EXPECT_EQ(test::dir_entries(target), std::vector<std::string>{"b"});  // replaced whole, not merged
    {
        AtomicDirectory d(target);
        std::ofstream(d.file("c")) << "never committed";
    }
    EXPECT_EQ(test::dir_entries(dir.path()), std::vector<std::string>{"out"});
    EXPECT_EQ(test::dir_entries(target), std::vector<std::string>{"b"});
    EXPECT_THROW(AtomicDirectory(dir.file("missing/out")), InputError);
    EXPECT_EQ(test::dir_entries(dir.path()), std::vector<std::string>{"out"});
}

TEST(AtomicFile, LongNamesGetTemporaryNamesThatFitAndDiffer) {
    ScratchDir dir("files_long_names");
    const std::string stem(235, 'a');  // 251 and 249 bytes with their extensions
    AtomicFile a(dir.file(stem + ".msh.report.json"));
    AtomicFile b(dir.file(stem + ".msh.plot.json"));
    EXPECT_LE(fs::path(a.temp_path()).filename().string().size(), 255u);
    EXPECT_NE(a.temp_path(), b.temp_path());
    std::ofstream(a.temp_path()) << "report";
    a.commit();
    EXPECT_EQ(slurp(dir.file(stem + ".msh.report.json")), "report");
}

TEST(CheckOutputPath, NamesOverTheFileSystemsLimitAreRefusedBeforeAnyWork) {
    ScratchDir dir("files_name_limit");
    test::expect_error<OutputError>(
        [&] { check_output_path(dir.file(std::string(252, 'b') + ".msh")); },
        {"(256 bytes) is too long for the file system (255 bytes at most)", "choose a shorter output name"});
    EXPECT_NO_THROW(check_output_path(dir.file(std::string(251, 'b') + ".msh")));
    EXPECT_TRUE(test::dir_entries(dir.path()).empty());  // the probe left nothing
}

TEST(CheckOutputPath, AReadOnlyFileSystemIsRefusedBeforeAnyWork) {
    ScratchDir dir("files_read_only");
    test::SmallFilesystem ro(dir.path() / "ro", "size=64k", true);
    if (!ro.mounted()) GTEST_SKIP() << "mounting a tmpfs needs root";
    test::expect_error<OutputError>([&] { check_output_path(ro.file("out.msh")); },
                                    {"cannot write '", "out.msh", "read-only file system"});
    test::expect_error<OutputError>([&] { check_output_directory(ro.file("polyMesh")); },
                                    {"polyMesh", "read-only file system"});
}

TEST(OutputSet, CommitsEveryOutputOrNone) {
    ScratchDir dir("files_output_set");
    std::ofstream(dir.file("mesh")) << "old mesh";
    {
        OutputSet set;
        std::ofstream(set.file(dir.file("mesh")).temp_path()) << "new mesh";
        std::ofstream(set.file(dir.file("report")).temp_path()) << "new report";
    }  // not committed: the temporaries go, the old mesh stays
    EXPECT_EQ(test::dir_entries(dir.path()), std::vector<std::string>{"mesh"});
    EXPECT_EQ(slurp(dir.file("mesh")), "old mesh");
    {
        OutputSet set;
        std::ofstream(set.file(dir.file("mesh")).temp_path()) << "new mesh";
        std::ofstream(set.file(dir.file("report")).temp_path()) << "new report";
        // The report's target turns into a directory that a file cannot replace: its rename
        // fails after the mesh's, and the mesh goes back to what it was.
        fs::create_directories(dir.file("report/inside"));
        EXPECT_THROW(set.commit(), Error);
    }
    EXPECT_EQ(slurp(dir.file("mesh")), "old mesh");
    fs::remove_all(dir.file("report"));
    EXPECT_EQ(test::dir_entries(dir.path()), std::vector<std::string>{"mesh"});
    {
        OutputSet set;
        std::ofstream(set.file(dir.file("mesh")).temp_path()) << "new mesh";
        AtomicDirectory& d = set.directory(dir.file("polyMesh"));
        std::ofstream(d.file("points")) << "points";
        set.commit();
    }
    EXPECT_EQ(slurp(dir.file("mesh")), "new mesh");
    EXPECT_EQ(slurp(dir.file("polyMesh/points")), "points");
    EXPECT_EQ(test::dir_entries(dir.path()), (std::vector<std::string>{"mesh", "polyMesh"}));
}

TEST(CheckOutputsAreNotInputs, SameFileByPathLinkOrInodeAndInputsInsideAnOutputDirectory) {
    ScratchDir dir("files_output_input");
    std::ofstream(dir.file("in.msh")) << "input";
    fs::create_symlink(dir.file("in.msh"), dir.file("link.msh"));
    fs::create_hard_link(dir.file("in.msh"), dir.file("hard.msh"));
    fs::create_directories(dir.file("case/polyMesh"));
    std::ofstream(dir.file("case/polyMesh/wall.stl")) << "input";
    const std::vector<std::string> in{dir.file("in.msh")};
    for (const std::string& out :
         {dir.file("in.msh"), dir.file("./in.msh"), dir.file("link.msh"), dir.file("hard.msh")})
        test::expect_error<InputError>([&] { check_outputs_are_not_inputs({out}, in); },
                                       {"the output '" + out + "' is the input", "would destroy the input"});
    test::expect_error<InputError>(
        [&] { check_outputs_are_not_inputs({dir.file("case/polyMesh/")}, {dir.file("case/polyMesh/wall.stl")}); },
        {"holds the input", "would be replaced whole"});
    EXPECT_NO_THROW(check_outputs_are_not_inputs({dir.file("out.msh"), dir.file("in.msh.report.json")}, in));
    EXPECT_EQ(slurp(dir.file("in.msh")), "input");
}

TEST(WriteFailure, SaysTheCauseAndThatTheOldFileStays) {
    EXPECT_EQ(write_failure("d/out.msh", ENOSPC),
              "disk full writing 'd/out.msh': no space left on the file system of 'd'; free some space or write "
              "elsewhere; 'd/out.msh' was left as it was");
    EXPECT_NE(write_failure("out.msh", EFBIG).find("file too large writing 'out.msh'"), std::string::npos);
    EXPECT_NE(write_failure("out.msh", EDQUOT).find("disk quota exceeded"), std::string::npos);
    EXPECT_NE(write_failure("out.msh", EIO).find("I/O error"), std::string::npos);
}

TEST(WriteWholeFile, AFullDiskIsAnOutputErrorNamingTheTarget) {
    ScratchDir dir("files_full");
    test::SmallFilesystem full(dir.path() / "full", "size=64k");
    if (!full.mounted()) GTEST_SKIP() << "mounting a tmpfs needs root";
    test::expect_error<OutputError>([&] { write_whole_file(full.file(".tmp"), "out.json", std::string(1 << 20, 'x')); },
                                    {"disk full writing 'out.json'"});
    fs::remove(full.file(".tmp"));  // what the AtomicFile of a real writer removes
    EXPECT_NO_THROW(write_whole_file(full.file("small"), "small", "fits"));
    EXPECT_EQ(slurp(full.file("small")), "fits");
}

TEST(ReadWholeFile, EveryByteAndNothingForAMissingFile) {
    ScratchDir dir("files_read_whole");
    const std::string bytes = std::string("a\0b\r\n\xff", 6) + std::string(100000, 'x');
    std::ofstream(dir.file("f.bin"), std::ios::binary) << bytes;
    EXPECT_EQ(read_whole_file(dir.file("f.bin")), bytes);
    EXPECT_EQ(read_whole_file(dir.file("missing.bin")), "");
}

TEST(RemoveTemporaries, RemovesUncommittedFilesAndDirectoriesAtOnce) {
    ScratchDir dir("files_remove_temporaries");
    std::ofstream(dir.file("kept")) << "old";
    AtomicFile file(dir.file("kept"));
    std::ofstream(file.temp_path()) << "new";
    AtomicDirectory poly(dir.file("polyMesh"));
    std::ofstream(poly.file("points")) << "points";
    std::ofstream(poly.file("faces")) << "faces";
    ScopedTemporary scratch(dir.file("scratch"), true);
    fs::create_directory(scratch.path());
    std::ofstream(scratch.path() + "/out.msh") << "x";
    EXPECT_EQ(test::dir_entries(dir.path()).size(), 4u);
    remove_temporaries();  // what a signal handler calls
    EXPECT_EQ(test::dir_entries(dir.path()), std::vector<std::string>{"kept"});
    EXPECT_EQ(slurp(dir.file("kept")), "old");
}

TEST(OutputSet, DirectoriesMadeForTheOutputsStayOnlyWithThem) {
    ScratchDir dir("files_made_directories");
    {
        OutputSet set;
        set.make_directory(dir.file("case"));
        set.make_directory(dir.file("case/system/"));
        set.make_directory(dir.file("case"));  // made already: nothing more
        std::ofstream(set.file(dir.file("case/system/controlDict")).temp_path()) << "dict";
        AtomicDirectory& d = set.directory(dir.file("case/0"));
        std::ofstream(d.file("U")) << "U";
        EXPECT_EQ(test::dir_entries(dir.file("case")).size(), 2u);  // system/ and 0/'s temporary
    }  // not committed: the temporaries go, then the directories made for them
    EXPECT_TRUE(test::dir_entries(dir.path()).empty());
    test::expect_error<InputError>([&] { OutputSet().make_directory(dir.file("no/case")); },
                                   {"no/case", "directory '" + dir.file("no") + "' does not exist"});
    std::ofstream(dir.file("file")) << "x";
    test::expect_error<InputError>([&] { OutputSet().make_directory(dir.file("file")); }, {"file", "is a file"});
    fs::remove(dir.file("file"));
    {
        OutputSet set;
        set.make_directory(dir.file("case"));
        set.make_directory(dir.file("case/system"));
        std::ofstream(set.file(dir.file("case/system/controlDict")).temp_path()) << "dict";
        set.commit();
    }
    EXPECT_EQ(slurp(dir.file("case/system/controlDict")), "dict");
    // A directory that was there is never removed, even empty.
    fs::create_directory(dir.file("case/constant"));
    { OutputSet().make_directory(dir.file("case/constant")); }
    EXPECT_EQ(test::dir_entries(dir.file("case")), (std::vector<std::string>{"constant", "system"}));
}

TEST(RemoveTemporaries, RemovesTheDirectoriesMadeForOutputsInnermostFirst) {
    ScratchDir dir("files_remove_made");
    OutputSet set;
    set.make_directory(dir.file("case"));
    set.make_directory(dir.file("case/constant"));
    AtomicDirectory& poly = set.directory(dir.file("case/constant/polyMesh"));
    std::ofstream(poly.file("points")) << "points";
    std::ofstream(set.file(dir.file("case/constant/transportProperties")).temp_path()) << "nu";
    remove_temporaries();  // what a signal handler calls
    EXPECT_TRUE(test::dir_entries(dir.path()).empty());
}
