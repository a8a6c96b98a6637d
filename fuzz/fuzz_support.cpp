// The scratch directory of the targets that go through files (fuzz_support.h).

#include "fuzz_support.h"

#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>

#include <unistd.h>

namespace strata::fuzz {
namespace {

/// A directory made with mkdtemp, removed with what it holds when the process exits normally
/// (a crash leaves it: the input that caused it is libFuzzer's artifact, not this).
class ScratchDir {
public:
    ScratchDir() {
        namespace fs = std::filesystem;
        std::error_code ec;
        // /dev/shm is memory: the targets write a file or three per input.
        const fs::path base = fs::is_directory("/dev/shm", ec) ? fs::path("/dev/shm") : fs::temp_directory_path();
        std::string pattern = (base / "strata-fuzz-XXXXXX").string();
        if (!mkdtemp(pattern.data())) throw std::runtime_error("fuzz: cannot make a scratch directory in " + base.string());
        path_ = pattern;
    }
    ~ScratchDir() {
        std::error_code ec;
        std::filesystem::remove_all(path_, ec);
    }
    ScratchDir(const ScratchDir&) = delete;
    ScratchDir& operator=(const ScratchDir&) = delete;
    const std::string& path() const { return path_; }

private:
    std::string path_;
};

}  // namespace

std::string scratch_path(const std::string& name) {
    static const ScratchDir dir;
    return dir.path() + "/" + name;
}

}  // namespace strata::fuzz
