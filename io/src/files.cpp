#include <strata/core/error.h>
#include <strata/io/files.h>

#include <fcntl.h>  // AT_FDCWD
#include <unistd.h>
#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <utility>

namespace strata {

void check_input_file(const std::string& path) {
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::file_status st = fs::status(path, ec);
    if (!fs::exists(st)) throw InputError("cannot open '" + path + "': no such file; check the path");
    if (fs::is_directory(st)) throw InputError("cannot open '" + path + "': it is a directory; give the file itself");
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(path.c_str(), "rb"), &std::fclose);
    if (!f) throw InputError("cannot open '" + path + "': " + std::strerror(errno));
}

std::string lower_extension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext;
}

namespace {

/// InputError unless the directory \p path is to go in exists.
void require_parent_directory(const std::string& path) {
    namespace fs = std::filesystem;
    const fs::path t(path);
    const fs::path dir = t.parent_path().empty() ? fs::path(".") : t.parent_path();
    std::error_code ec;
    if (!fs::is_directory(dir, ec))
        throw InputError("cannot write '" + path + "': directory '" + dir.string() +
                         "' does not exist; create it or choose another output path");
}

}  // namespace

void check_output_path(const std::string& path) {
    namespace fs = std::filesystem;
    require_parent_directory(path);
    const fs::path t(path);
    std::error_code ec;
    if (fs::is_directory(t, ec)) throw InputError("cannot write '" + path + "': it is a directory; choose a file name");
}

void check_output_directory(const std::string& path) {
    namespace fs = std::filesystem;
    require_parent_directory(path);
    const fs::path t(path);
    std::error_code ec;
    if (fs::exists(t, ec) && !fs::is_directory(t, ec))
        throw InputError("cannot write '" + path +
                         "': it is a file, not a directory; remove it or choose another output path");
}

AtomicFile::AtomicFile(std::string target) : target_(std::move(target)) {
    namespace fs = std::filesystem;
    check_output_path(target_);
    const fs::path t(target_);
    const fs::path dir = t.parent_path().empty() ? fs::path(".") : t.parent_path();
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
    if (ec) throw InputError("cannot move '" + temp_ + "' to '" + target_ + "': " + ec.message());
    committed_ = true;
}

namespace {

/// \p path without trailing slashes ("case/constant/polyMesh/" names the same directory).
std::string without_trailing_slash(std::string path) {
    while (path.size() > 1 && path.back() == '/') path.pop_back();
    return path;
}

}  // namespace

AtomicDirectory::AtomicDirectory(std::string target) : target_(without_trailing_slash(std::move(target))) {
    namespace fs = std::filesystem;
    check_output_directory(target_);
    const fs::path t(target_);
    const fs::path dir = t.parent_path().empty() ? fs::path(".") : t.parent_path();
    // Same parent (so the rename is atomic); the pid keeps concurrent runs apart.
    std::string name = ".";  // appended, not "." + ...: GCC 12 warns falsely (-Wrestrict) on that
    name += t.filename().string();
    name += ".tmp";
    name += std::to_string(::getpid());
    temp_ = (dir / name).string();
    std::error_code ec;
    fs::remove_all(temp_, ec);  // left by an earlier run of this pid that was killed
    if (!fs::create_directory(temp_, ec) || ec)
        throw InputError("cannot write '" + target_ + "': cannot create '" + temp_ + "': " + ec.message() +
                         "; check that the directory is writable");
}

AtomicDirectory::~AtomicDirectory() {
    std::error_code ec;
    if (!committed_) std::filesystem::remove_all(temp_, ec);
}

std::string AtomicDirectory::file(const std::string& name) const {
    return (std::filesystem::path(temp_) / name).string();
}

void AtomicDirectory::commit() {
    namespace fs = std::filesystem;
    std::error_code ec;
    if (!fs::exists(target_, ec)) {
        fs::rename(temp_, target_, ec);
        if (ec) throw InputError("cannot move '" + temp_ + "' to '" + target_ + "': " + ec.message());
        committed_ = true;
        return;
    }
    if (!fs::is_directory(target_, ec))
        throw InputError("cannot write '" + target_ + "': it is a file, not a directory; remove it");
    // An existing directory: swap the two in one step, then remove the old one (now at temp_).
    if (::renameat2(AT_FDCWD, temp_.c_str(), AT_FDCWD, target_.c_str(), RENAME_EXCHANGE) == 0) {
        committed_ = true;
        fs::remove_all(temp_, ec);
        return;
    }
    if (errno != EINVAL && errno != ENOSYS)
        throw InputError("cannot move '" + temp_ + "' to '" + target_ + "': " + std::strerror(errno));
    // A file system without RENAME_EXCHANGE: move the old directory aside, the new one in, and the
    // old one back if that fails; a reader may find no directory for that moment, never a partial one.
    const std::string old = temp_ + ".old";
    fs::remove_all(old, ec);
    fs::rename(target_, old, ec);
    if (ec) throw InputError("cannot replace '" + target_ + "': " + ec.message());
    fs::rename(temp_, target_, ec);
    if (ec) {
        std::error_code ignored;
        fs::rename(old, target_, ignored);
        throw InputError("cannot move '" + temp_ + "' to '" + target_ + "': " + ec.message());
    }
    committed_ = true;
    fs::remove_all(old, ec);
}

}  // namespace strata
