#include <strata/core/error.h>
#include <strata/io/files.h>

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

void check_output_path(const std::string& path) {
    namespace fs = std::filesystem;
    const fs::path t(path);
    const fs::path dir = t.parent_path().empty() ? fs::path(".") : t.parent_path();
    std::error_code ec;
    if (!fs::is_directory(dir, ec))
        throw InputError("cannot write '" + path + "': directory '" + dir.string() +
                         "' does not exist; create it or choose another output path");
    if (fs::is_directory(t, ec)) throw InputError("cannot write '" + path + "': it is a directory; choose a file name");
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

}  // namespace strata
