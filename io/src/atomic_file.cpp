#include <strata/core/error.h>
#include <strata/io/atomic_file.h>

#include <cstdio>
#include <filesystem>
#include <unistd.h>
#include <utility>

namespace strata {

AtomicFile::AtomicFile(std::string target) : target_(std::move(target)) {
    namespace fs = std::filesystem;
    fs::path t(target_);
    fs::path dir = t.parent_path().empty() ? fs::path(".") : t.parent_path();
    std::error_code ec;
    if (!fs::is_directory(dir, ec))
        throw InputError("cannot write '" + target_ + "': directory '" + dir.string() +
                         "' does not exist; create it or choose another output path");
    // Same directory (so rename is atomic), same extension (writers pick the format from it).
    std::string name = ".";
    name += t.stem().string();
    name += ".tmp";
    name += std::to_string(::getpid());
    name += t.extension().string();
    temp_ = (dir / name).string();
}

AtomicFile::~AtomicFile() {
    if (!committed_) std::remove(temp_.c_str());
}

void AtomicFile::commit() {
    std::error_code ec;
    if (!std::filesystem::exists(temp_, ec))
        throw InputError("writing '" + target_ + "' failed: nothing was written to '" + temp_ + "'");
    std::filesystem::rename(temp_, target_, ec);
    if (ec)
        throw InputError("cannot move '" + temp_ + "' to '" + target_ + "': " + ec.message());
    committed_ = true;
}

}  // namespace strata
