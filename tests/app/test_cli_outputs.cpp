// The `strata` program never loses a user's data: a full disk, a file size limit, an output
// named as the input, SIGTERM and SIGHUP while writing, and outputs that cannot be written each
// give a non-zero exit and a message with the cause, and leave the previous output byte for
// byte as it was, with no temporary file beside it.

#include "test_support.h"

#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

namespace strata {
namespace {

namespace fs = std::filesystem;
using test::CliResult;
using test::ScratchDir;
using test::slurp;

const std::string kSphere = test::example_data("sphere.stl");
const std::string kLayers = " --layers 3 --first-height 0.01";

/// `strata ARGS` in \p dir under \p prefix (shell commands before it, e.g. "ulimit -f 100;").
CliResult strata(const ScratchDir& dir, const std::string& args, const std::string& prefix = "") {
    return test::run_program(dir, STRATA_CLI, args, prefix);
}

/// The previous outputs of a run: each file with its old bytes, to compare after a failure.
struct Previous {
    std::vector<std::pair<std::string, std::string>> files;
    void add(const std::string& path, const std::string& bytes) {
        fs::create_directories(fs::path(path).parent_path());
        std::ofstream(path, std::ios::binary) << bytes;
        files.emplace_back(path, bytes);
    }
    void expect_unchanged() const {
        for (const auto& [path, bytes] : files) EXPECT_EQ(slurp(path), bytes) << path << " was changed";
    }
};

/// Names in \p dir starting with '.' (Strata's temporaries), recursively.
std::vector<std::string> hidden_files(const fs::path& dir) {
    std::vector<std::string> out;
    for (const auto& e : fs::recursive_directory_iterator(dir))
        if (e.path().filename().string()[0] == '.') out.push_back(e.path().string());
    return out;
}

/// The previous outputs of `-o NAME` in \p dir: the mesh (each file of a polyMesh, Cobalt60's
/// .bc) and its report.
Previous previous_outputs(const std::string& dir, const std::string& name) {
    Previous p;
    if (name == "polyMesh") {
        for (const char* f : {"points", "faces", "owner", "neighbour", "boundary"})
            p.add(dir + "/polyMesh/" + f, std::string("old ") + f);
    } else {
        p.add(dir + "/" + name, "old mesh " + name);
    }
    if (name.ends_with(".cgr")) p.add(dir + "/" + name + ".bc", "old patch map");
    if (name == "out.vtm") p.add(dir + "/out_blocks/volume.vtu", "old volume block");
    if (name != "out.stl") p.add(dir + "/" + name + ".report.json", "old report");
    return p;
}

TEST(CliOutputs, AFullDiskFailsWithTheCauseAndKeepsThePreviousOutputOfEveryFormat) {
    ScratchDir dir("cli_full_disk");
    test::SmallFilesystem full(dir.path() / "full", "size=200k");
    if (!full.mounted()) GTEST_SKIP() << "mounting a tmpfs needs root (the file size limit test runs for anyone)";
    const std::vector<std::pair<std::string, std::string>> runs{{"mesh", "out.msh"},
                                                                {"mesh", "out.msh --msh-version 2.2"},
                                                                {"mesh", "out.msh --binary"},
                                                                {"mesh", "out.vtk"},
                                                                {"mesh", "out.cgr"},
                                                                {"mesh", "out.cgns"},
                                                                {"mesh", "out.vtu"},
                                                                {"mesh", "out.vtm"},
                                                                {"mesh", "polyMesh"},
                                                                {"layers", "out.su2 --layers 20 --first-height 1e-3"},
                                                                {"surface", "out.stl"}};
    for (const auto& [command, output] : runs) {
        const std::string name = output.substr(0, output.find(' '));
        const Previous before = previous_outputs(full.file(""), name);
        const std::string args = command + " '" + kSphere + "' -o full/" + output;
        // The surface alone fits in 200 KB: a file fills most of the disk first.
        const CliResult r = command == "surface"  ? strata(dir, args, "head -c 150000 /dev/zero >full/filler;")
                            : command == "layers" ? strata(dir, args)
                                                  : strata(dir, args + kLayers);
        EXPECT_EQ(r.code, 1) << args << "\n" << r.err;
        EXPECT_NE(r.err.find("disk full writing 'full/"), std::string::npos) << args << "\n" << r.err;
        EXPECT_NE(r.err.find("was left as it was"), std::string::npos) << r.err;
        before.expect_unchanged();
        EXPECT_TRUE(hidden_files(full.file("")).empty()) << args;
        fs::remove_all(full.file(name));
        for (const auto& e : fs::directory_iterator(full.file(""))) fs::remove_all(e.path());
    }
}

TEST(CliOutputs, AFileSizeLimitFailsWithTheCauseAndKeepsThePreviousOutput) {
    ScratchDir dir("cli_file_size_limit");
    for (const std::string name : {"out.msh", "out.cgr", "polyMesh"}) {
        const Previous before = previous_outputs(dir.path().string(), name);
        // 100 blocks of 1024 bytes: the mesh takes megabytes.
        const CliResult r = strata(dir, "mesh '" + kSphere + "' -o " + name + kLayers, "ulimit -f 100;");
        EXPECT_EQ(r.code, 1) << name << "\n" << r.err;
        EXPECT_NE(r.err.find("file too large writing '"), std::string::npos) << r.err;
        before.expect_unchanged();
        EXPECT_TRUE(hidden_files(dir.path()).empty()) << name;
    }
}

TEST(CliOutputs, AnOutputNamedAsTheInputIsRefusedBeforeAnyWork) {
    ScratchDir dir("cli_output_is_input");
    fs::copy_file(kSphere, dir.file("in.stl"));
    const std::string sphere = slurp(dir.file("in.stl"));
    CliResult r = strata(dir, "surface in.stl -o in.stl");
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("the output 'in.stl' is the input 'in.stl': writing it would destroy the input"),
              std::string::npos)
        << r.err;
    ASSERT_EQ(strata(dir, "surface in.stl -o in.msh").code, 0);
    const std::string msh = slurp(dir.file("in.msh"));
    fs::create_symlink("in.msh", dir.file("link.msh"));
    for (const std::string out : {"in.msh", "./in.msh", "link.msh"}) {
        r = strata(dir, "mesh in.msh -o " + out + kLayers);
        EXPECT_EQ(r.code, 1) << out;
        EXPECT_NE(r.err.find("is the input 'in.msh'"), std::string::npos) << r.err;
        EXPECT_EQ(r.out, "");  // before the work: no summary
    }
    EXPECT_EQ(slurp(dir.file("in.stl")), sphere);
    EXPECT_EQ(slurp(dir.file("in.msh")), msh);
}

TEST(CliOutputs, OutputsThatCannotBeWrittenAreRefusedBeforeAnyWork) {
    ScratchDir dir("cli_unwritable");
    const std::string mesh = "mesh '" + kSphere + "' -o ";
    CliResult r = strata(dir, mesh + "missing/out.msh" + kLayers);
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("directory 'missing' does not exist"), std::string::npos) << r.err;
    // A legal mesh name whose report name is over the file system's 255 bytes.
    const std::string long_name(245, 'n');
    r = strata(dir, mesh + long_name + ".msh" + kLayers);
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find(".msh.report.json' (261 bytes) is too long for the file system (255 bytes at most)"),
              std::string::npos)
        << r.err;
    // A report name that is a directory: refused before the mesh is made, the old mesh kept.
    const Previous before = previous_outputs(dir.path().string(), "out.msh");
    fs::remove(dir.file("out.msh.report.json"));
    fs::create_directory(dir.file("out.msh.report.json"));
    r = strata(dir, mesh + "out.msh" + kLayers);
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("out.msh.report.json': it is a directory"), std::string::npos) << r.err;
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(slurp(dir.file("out.msh")), "old mesh out.msh");
    test::SmallFilesystem ro(dir.path() / "ro", "size=64k", true);
    if (!ro.mounted()) GTEST_SKIP() << "mounting a read-only tmpfs needs root";
    r = strata(dir, mesh + "ro/out.cgns" + kLayers);
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("cannot write 'ro/out.cgns': 'ro' is on a read-only file system"), std::string::npos) << r.err;
    EXPECT_EQ(r.out, "");
}

TEST(CliOutputs, TimeoutAndItsValuesAreChecked) {
    ScratchDir dir("cli_timeout_values");
    for (const std::string bad : {"nan", "-1", "inf", "soon"}) {
        const CliResult r = strata(dir, "surface '" + kSphere + "' -o out.msh --timeout " + bad);
        EXPECT_EQ(r.code, 2) << bad;
        EXPECT_NE(r.err.find("expected a number of seconds, 0 or more"), std::string::npos) << r.err;
    }
}

/// Run `strata ARGS` in \p dir, and when its first temporary output has data (the writers have
/// started), stop it (SIGSTOP), send \p sig, and let it go on: its exit code, stderr in \p err.
int signalled_while_writing(const ScratchDir& dir, const std::vector<std::string>& args, int sig, std::string* err) {
    test::Argv argv(STRATA_CLI, args);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
    const std::string err_path = dir.file("..stderr");
    posix_spawn_file_actions_addopen(&actions, 2, err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const fs::path cwd = fs::current_path();
    fs::current_path(dir.path());
    pid_t pid = -1;
    const int spawned = posix_spawn(&pid, argv.data()[0], &actions, nullptr, argv.data(), environ);
    fs::current_path(cwd);
    posix_spawn_file_actions_destroy(&actions);
    if (spawned != 0) return -2;
    const auto writing = [&] {
        const auto temporary = [](const fs::path& p) {
            const std::string n = p.filename().string();
            return n.starts_with(".") && n.find(".tmp") != std::string::npos;
        };
        // Files come and go while the program runs (the outputs' probes): an entry gone
        // between listing and reading is no temporary being written.
        std::error_code ec;
        for (auto it = fs::recursive_directory_iterator(dir.path(), ec); !ec && it != fs::end(it); it.increment(ec)) {
            const fs::path& p = it->path();  // a file, or a file of a polyMesh being written
            std::error_code size_ec;
            if ((temporary(p) || temporary(p.parent_path())) && fs::file_size(p, size_ec) > 0 && !size_ec) return true;
        }
        return false;
    };
    const auto t0 = std::chrono::steady_clock::now();
    int status = 0;
    while (!writing() && std::chrono::steady_clock::now() - t0 < std::chrono::seconds(120)) {
        if (::waitpid(pid, &status, WNOHANG) == pid) return -3;  // ended before writing
        std::this_thread::sleep_for(std::chrono::microseconds(300));
    }
    ::kill(pid, SIGSTOP);
    ::kill(pid, sig);
    ::kill(pid, SIGCONT);
    ::waitpid(pid, &status, 0);
    *err = slurp(err_path);
    fs::remove(err_path);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(CliOutputs, SigtermAndSighupWhileWritingRemoveEveryTemporaryAndKeepThePreviousOutput) {
    ScratchDir dir("cli_signals_writing");
    const std::vector<std::string> layers{"--layers", "20", "--first-height", "1e-3"};
    for (const auto& [sig, name] : std::vector<std::pair<int, std::string>>{{SIGTERM, "out.msh"},
                                                                            {SIGHUP, "out.msh"},
                                                                            {SIGTERM, "out.cgr"},
                                                                            {SIGHUP, "out.cgns"},
                                                                            {SIGTERM, "polyMesh"},
                                                                            {SIGTERM, "out.vtm"},
                                                                            {SIGHUP, "out.vtk"}}) {
        const Previous before = previous_outputs(dir.path().string(), name);
        std::vector<std::string> args{"mesh", kSphere, "-o", name};
        args.insert(args.end(), layers.begin(), layers.end());
        std::string err;
        const int code = signalled_while_writing(dir, args, sig, &err);
        EXPECT_EQ(code, 128 + sig) << name << " " << err;
        EXPECT_NE(err.find(sig == SIGTERM ? "cancelled by SIGTERM" : "cancelled by SIGHUP"), std::string::npos) << err;
        EXPECT_NE(err.find("the previous output is as it was"), std::string::npos) << err;
        before.expect_unchanged();
        EXPECT_TRUE(hidden_files(dir.path()).empty()) << name;
    }
}

}  // namespace
}  // namespace strata
