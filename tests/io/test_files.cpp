// files.h: the output-directory check and AtomicDirectory (build next to the target, put in
// place whole, remove on failure). AtomicFile is exercised by every writer's tests.

#include "test_support.h"

#include <strata/core/error.h>
#include <strata/io/files.h>

#include <gtest/gtest.h>

#include <algorithm>
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
