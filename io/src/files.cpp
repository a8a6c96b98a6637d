#include <strata/core/error.h>
#include <strata/io/files.h>

#include <dirent.h>
#include <fcntl.h>  // AT_FDCWD, open
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <sys/syscall.h>
#include <unistd.h>
#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <sstream>
#include <utility>

namespace strata {

namespace fs = std::filesystem;

void check_input_file(const std::string& path) {
    std::error_code ec;
    const fs::file_status st = fs::status(path, ec);
    if (!fs::exists(st)) throw InputError("cannot open '" + path + "': no such file; check the path");
    if (fs::is_directory(st)) throw InputError("cannot open '" + path + "': it is a directory; give the file itself");
    // Opening a FIFO waits for its writer and closing it loses what the writer sent: readers take
    // pipes through check_input_source and read_input (input_file.h).
    if (fs::is_fifo(st)) return;
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(path.c_str(), "rb"), &std::fclose);
    if (!f) throw InputError("cannot open '" + path + "': " + std::strerror(errno));
}

std::string read_whole_file(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

std::string lower_extension(const std::string& path) {
    std::string ext = fs::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext;
}

// ---------------------------------------------------------------------------------------
// The registry of temporaries that remove_temporaries() removes from a signal handler: fixed
// slots (no allocation in the handler), each a path and whether it is a directory.

namespace {

constexpr int kSlots = 64;
constexpr std::size_t kSlotPath = 4096;

/// What a slot holds: a file, a directory removed with its files, or a directory made for
/// outputs (OutputSet::make_directory), removed only once empty.
enum class SlotKind { File, Tree, Made };

struct Slot {
    std::atomic<int> state{0};  // 0 free, 1 being filled, 2 registered
    SlotKind kind = SlotKind::File;
    char path[kSlotPath] = {};
};

Slot g_slots[kSlots];

int register_temporary(const std::string& path, SlotKind kind) {
    if (path.size() >= kSlotPath) return -1;
    for (int i = 0; i < kSlots; ++i) {
        int expected = 0;
        if (!g_slots[i].state.compare_exchange_strong(expected, 1)) continue;
        std::memcpy(g_slots[i].path, path.c_str(), path.size() + 1);
        g_slots[i].kind = kind;
        g_slots[i].state.store(2);
        return i;
    }
    return -1;  // more than kSlots outputs at once: removed by the destructors only
}

int register_temporary(const std::string& path, bool directory) {
    return register_temporary(path, directory ? SlotKind::Tree : SlotKind::File);
}

void unregister_temporary(int slot) {
    if (slot >= 0) g_slots[slot].state.store(0);
}

/// Remove the files of directory \p path and the directory itself, with system calls only.
void remove_directory_now(const char* path) noexcept {
    const int fd = ::open(path, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd >= 0) {
        alignas(8) char buf[4096];
        for (;;) {
            const long n = ::syscall(SYS_getdents64, fd, buf, sizeof buf);
            if (n <= 0) break;
            for (long at = 0; at < n;) {
                const auto* d = reinterpret_cast<const struct dirent64*>(buf + at);
                const char* name = d->d_name;
                const bool dots = name[0] == '.' && (name[1] == '\0' || (name[1] == '.' && name[2] == '\0'));
                if (!dots) ::unlinkat(fd, name, 0);
                at += d->d_reclen;
            }
        }
        ::close(fd);
    }
    ::rmdir(path);
}

}  // namespace

ScopedTemporary::ScopedTemporary(std::string path, bool directory)
    : path_(std::move(path)), directory_(directory), slot_(register_temporary(path_, directory)) {}

ScopedTemporary::~ScopedTemporary() {
    std::error_code ec;
    if (directory_)
        fs::remove_all(path_, ec);
    else
        fs::remove(path_, ec);
    unregister_temporary(slot_);
}

void remove_temporaries() noexcept {
    for (Slot& s : g_slots) {
        if (s.state.load() != 2 || s.kind == SlotKind::Made) continue;
        if (s.kind == SlotKind::Tree)
            remove_directory_now(s.path);
        else
            ::unlink(s.path);
    }
    // Then the directories made for outputs, once the temporaries in them are gone: a directory
    // inside another is emptied by an earlier pass, whatever the slots' order.
    for (int pass = 0; pass < kSlots; ++pass) {
        bool removed = false;
        for (Slot& s : g_slots)
            if (s.state.load() == 2 && s.kind == SlotKind::Made && ::rmdir(s.path) == 0) removed = true;
        if (!removed) break;
    }
}

// ---------------------------------------------------------------------------------------
// Checked writes.

namespace {

/// The longest file name the file system of directory \p dir takes.
std::size_t name_max(const std::string& dir) {
    const long n = ::pathconf(dir.c_str(), _PC_NAME_MAX);
    return n > 0 ? static_cast<std::size_t>(n) : std::size_t{NAME_MAX};
}

}  // namespace

std::string write_failure(const std::string& target, int err) {
    const std::string kept = "; '" + target + "' was left as it was";
    const fs::path t(target);
    const std::string dir = t.parent_path().empty() ? "." : t.parent_path().string();
    switch (err) {
        case ENOSPC:
            return "disk full writing '" + target + "': no space left on the file system of '" + dir +
                   "'; free some space or write elsewhere" + kept;
        case EDQUOT:
            return "disk quota exceeded writing '" + target + "'; free some space or write elsewhere" + kept;
        case EFBIG:
            return "file too large writing '" + target +
                   "': over the file size limit (ulimit -f) or the file system's largest file; raise the limit "
                   "or write elsewhere" +
                   kept;
        case EIO:
            return "I/O error writing '" + target + "': the device reported a failure; check the disk" + kept;
        case EROFS:
            return "cannot write '" + target + "': '" + dir + "' is on a read-only file system; write elsewhere" + kept;
        case EACCES:
        case EPERM:
            return "cannot write '" + target + "': permission denied in '" + dir +
                   "'; choose a directory you can write to" + kept;
        case ENAMETOOLONG:
            return "cannot write '" + target + "': the name '" + t.filename().string() + "' (" +
                   std::to_string(t.filename().string().size()) + " bytes) is too long for the file system (" +
                   std::to_string(name_max(dir)) + " bytes at most); choose a shorter output name";
        default:
            return "writing '" + target + "' failed: " + std::strerror(err) + kept;
    }
}

void sync_file(const std::string& path, const std::string& target) {
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) throw OutputError(write_failure(target, errno));
    const int synced = ::fsync(fd);
    const int err = errno;
    ::close(fd);
    if (synced != 0 && err != EINVAL && err != EROFS) throw OutputError(write_failure(target, err));
}

namespace {

/// fsync the directory \p dir, so a rename in it is on the device (best effort: some file
/// systems cannot sync a directory; the data itself was synced before).
void sync_directory(const fs::path& dir) {
    const int fd = ::open(dir.empty() ? "." : dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) return;
    ::fsync(fd);
    ::close(fd);
}

}  // namespace

bool write_all(int fd, const char* data, std::size_t size) {
    while (size > 0) {
        const ssize_t w = ::write(fd, data, size);
        if (w < 0) {
            if (errno == EINTR) continue;
            return false;
        }
        data += w;
        size -= static_cast<std::size_t>(w);
    }
    return true;
}

void write_whole_file(const std::string& path, const std::string& target, std::string_view data) {
    const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
    if (fd < 0) throw OutputError(write_failure(target, errno));
    bool ok = write_all(fd, data.data(), data.size());
    int err = errno;
    if (ok && ::fsync(fd) != 0 && errno != EINVAL) ok = false, err = errno;
    if (::close(fd) != 0 && ok && errno != EINTR) ok = false, err = errno;
    if (!ok) throw OutputError(write_failure(target, err));
}

std::int64_t free_bytes_at(const std::string& path) {
    const fs::path t(path);
    const fs::path dir = t.parent_path().empty() ? fs::path(".") : t.parent_path();
    struct statvfs s {};
    if (::statvfs(dir.c_str(), &s) != 0) return -1;
    return static_cast<std::int64_t>(s.f_bavail) * static_cast<std::int64_t>(s.f_frsize);
}

// ---------------------------------------------------------------------------------------
// Output paths.

namespace {

/// The directory \p path is in ("." for a bare name).
fs::path parent_of(const std::string& path) {
    const fs::path t(path);
    return t.parent_path().empty() ? fs::path(".") : t.parent_path();
}

/// InputError unless the directory \p path is to go in exists.
void require_parent_directory(const std::string& path) {
    const fs::path dir = parent_of(path);
    std::error_code ec;
    if (!fs::is_directory(dir, ec))
        throw InputError("cannot write '" + path + "': directory '" + dir.string() +
                         "' does not exist; create it or choose another output path");
}

/// The temporary name beside \p target: "." + stem + ".tmp<pid>" + ext, the stem shortened
/// (and a hash of the whole name added, so two long names stay apart) where the name would pass
/// NAME_MAX.
std::string temporary_name(const std::string& target, const std::string& ext) {
    const fs::path t(target);
    std::string stem = ext.empty() ? t.filename().string() : t.stem().string();
    const std::string tag = ".tmp" + std::to_string(::getpid());
    const std::size_t room = NAME_MAX;
    if (1 + stem.size() + tag.size() + ext.size() > room) {
        char hash[24];
        std::snprintf(hash, sizeof hash, "-%016zx", std::hash<std::string>{}(t.filename().string()));
        const std::size_t fixed = 1 + tag.size() + ext.size() + std::strlen(hash);
        stem = stem.substr(0, fixed < room ? room - fixed : 0) + hash;
    }
    return (parent_of(target) / ("." + stem + tag + ext)).string();
}

/// Create and remove the file \p temp (what a writer will create for \p target): OutputError
/// naming the cause if it cannot be created.
void probe_file(const std::string& temp, const std::string& target) {
    int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
    if (fd < 0 && errno == EEXIST) {  // left by a killed run that had our pid
        ::unlink(temp.c_str());
        fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
    }
    if (fd < 0) throw OutputError(write_failure(target, errno));
    ::close(fd);
    ::unlink(temp.c_str());
}

}  // namespace

void check_output_path(const std::string& path) {
    require_parent_directory(path);
    std::error_code ec;
    if (fs::is_directory(fs::path(path), ec))
        throw InputError("cannot write '" + path + "': it is a directory; choose a file name");
    if (fs::path(path).filename().string().size() > name_max(parent_of(path).string()))
        throw OutputError(write_failure(path, ENAMETOOLONG));
    probe_file(temporary_name(path, fs::path(path).extension().string()), path);
}

namespace {

/// \p path without trailing slashes ("case/constant/polyMesh/" names the same directory).
std::string without_trailing_slash(std::string path) {
    while (path.size() > 1 && path.back() == '/') path.pop_back();
    return path;
}

}  // namespace

void check_output_directory(const std::string& path) {
    require_parent_directory(path);
    const fs::path t(path);
    std::error_code ec;
    if (fs::exists(t, ec) && !fs::is_directory(t, ec))
        throw InputError("cannot write '" + path +
                         "': it is a file, not a directory; remove it or choose another output path");
    const std::string temp = temporary_name(without_trailing_slash(path), "");
    fs::remove_all(temp, ec);
    if (::mkdir(temp.c_str(), 0777) != 0) throw OutputError(write_failure(path, errno));
    ::rmdir(temp.c_str());
}

namespace {

/// \p path with links and ".." resolved as far as it exists (weakly_canonical), or as given.
fs::path resolved(const std::string& path) {
    std::error_code ec;
    fs::path p = fs::weakly_canonical(fs::absolute(path), ec);
    return ec ? fs::path(path) : p;
}

/// Whether \p inner is \p outer or lies inside it (both resolved).
bool inside(const fs::path& inner, const fs::path& outer) {
    auto i = inner.begin(), o = outer.begin();
    for (; o != outer.end() && !o->empty(); ++i, ++o)
        if (i == inner.end() || *i != *o) return false;
    return true;
}

}  // namespace

void check_outputs_are_not_inputs(const std::vector<std::string>& outputs, const std::vector<std::string>& inputs) {
    for (const std::string& out : outputs) {
        const fs::path o = resolved(without_trailing_slash(out));
        std::error_code ec;
        const bool out_dir = fs::is_directory(o, ec);
        for (const std::string& in : inputs) {
            const fs::path i = resolved(in);
            const bool same = i == o || (fs::exists(o, ec) && fs::equivalent(i, o, ec));
            if (same)
                throw InputError("the output '" + out + "' is the input '" + in +
                                 "': writing it would destroy the input; choose another output name");
            if (out_dir && inside(i, o))
                throw InputError("the output directory '" + out + "' holds the input '" + in +
                                 "' and would be replaced whole; choose another output directory");
        }
    }
}

// ---------------------------------------------------------------------------------------
// AtomicFile, AtomicDirectory, OutputSet.

AtomicFile::AtomicFile(std::string target) : target_(std::move(target)) {
    check_output_path(target_);
    // Same directory (so rename is atomic), same extension (writers pick the format from it).
    temp_ = temporary_name(target_, fs::path(target_).extension().string());
    slot_ = register_temporary(temp_, false);
}

AtomicFile::~AtomicFile() {
    if (!committed_) std::remove(temp_.c_str());
    unregister_temporary(slot_);
}

void AtomicFile::commit() {
    std::error_code ec;
    if (!fs::exists(temp_, ec))
        throw OutputError("writing '" + target_ + "' failed: nothing was written to '" + temp_ + "'");
    sync_file(temp_, target_);
    fs::rename(temp_, target_, ec);
    if (ec) throw OutputError("cannot move '" + temp_ + "' to '" + target_ + "': " + ec.message());
    committed_ = true;
    unregister_temporary(slot_);
    slot_ = -1;
    sync_directory(parent_of(target_));
}

AtomicDirectory::AtomicDirectory(std::string target) : target_(without_trailing_slash(std::move(target))) {
    check_output_directory(target_);
    // Same parent (so the rename is atomic); the pid keeps concurrent runs apart.
    temp_ = temporary_name(target_, "");
    std::error_code ec;
    fs::remove_all(temp_, ec);  // left by an earlier run of this pid that was killed
    if (::mkdir(temp_.c_str(), 0777) != 0) throw OutputError(write_failure(target_, errno));
    slot_ = register_temporary(temp_, true);
}

AtomicDirectory::~AtomicDirectory() {
    std::error_code ec;
    if (!committed_) fs::remove_all(temp_, ec);
    unregister_temporary(slot_);
}

std::string AtomicDirectory::file(const std::string& name) const {
    return (fs::path(temp_) / name).string();
}

void AtomicDirectory::commit() {
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(temp_, ec))
        sync_file(e.path().string(), target_ + "/" + e.path().filename().string());
    sync_directory(temp_);
    unregister_temporary(slot_);  // from here the temporary may hold the old directory
    slot_ = -1;
    if (!fs::exists(target_, ec)) {
        fs::rename(temp_, target_, ec);
        if (ec) throw OutputError("cannot move '" + temp_ + "' to '" + target_ + "': " + ec.message());
        committed_ = true;
        sync_directory(parent_of(target_));
        return;
    }
    if (!fs::is_directory(target_, ec))
        throw InputError("cannot write '" + target_ + "': it is a file, not a directory; remove it");
    // An existing directory: swap the two in one step, then remove the old one (now at temp_).
    if (::renameat2(AT_FDCWD, temp_.c_str(), AT_FDCWD, target_.c_str(), RENAME_EXCHANGE) == 0) {
        committed_ = true;
        sync_directory(parent_of(target_));
        fs::remove_all(temp_, ec);
        return;
    }
    if (errno != EINVAL && errno != ENOSYS)
        throw OutputError("cannot move '" + temp_ + "' to '" + target_ + "': " + std::strerror(errno));
    // A file system without RENAME_EXCHANGE: move the old directory aside, the new one in, and the
    // old one back if that fails; a reader may find no directory for that moment, never a partial one.
    const std::string old = temp_ + ".old";
    fs::remove_all(old, ec);
    fs::rename(target_, old, ec);
    if (ec) throw OutputError("cannot replace '" + target_ + "': " + ec.message());
    fs::rename(temp_, target_, ec);
    if (ec) {
        std::error_code ignored;
        fs::rename(old, target_, ignored);
        throw OutputError("cannot move '" + temp_ + "' to '" + target_ + "': " + ec.message());
    }
    committed_ = true;
    fs::remove_all(old, ec);
}

OutputSet::~OutputSet() {
    files_.clear();  // their temporaries first, then the directories they were in
    directories_.clear();
    for (auto m = made_.rbegin(); m != made_.rend(); ++m) {
        if (!committed_) ::rmdir(m->first.c_str());  // only if nothing else was put in it
        unregister_temporary(m->second);
    }
}

void OutputSet::make_directory(const std::string& path) {
    const std::string dir = without_trailing_slash(path);
    std::error_code ec;
    if (fs::is_directory(dir, ec)) return;
    require_parent_directory(dir);
    if (fs::exists(dir, ec))
        throw InputError("cannot write into '" + dir +
                         "': it is a file, not a directory; remove it or choose another output path");
    // Registered before it exists, so that a signal between the two still finds it.
    const int slot = register_temporary(dir, SlotKind::Made);
    if (::mkdir(dir.c_str(), 0777) != 0) {
        const int err = errno;
        unregister_temporary(slot);
        throw OutputError(write_failure(dir, err));
    }
    made_.emplace_back(dir, slot);
}

AtomicFile& OutputSet::file(const std::string& target) {
    files_.push_back(std::make_unique<AtomicFile>(target));
    return *files_.back();
}

AtomicDirectory& OutputSet::directory(const std::string& target) {
    directories_.push_back(std::make_unique<AtomicDirectory>(target));
    return *directories_.back();
}

namespace {

/// A target replaced by OutputSet::commit, and the hard link that keeps its old contents.
struct Replaced {
    std::string target, backup;  // backup empty: there was no file at target
};

/// Put back what \p done replaced (the newest first); best effort, the commit is failing.
void roll_back(const std::vector<Replaced>& done) {
    for (auto r = done.rbegin(); r != done.rend(); ++r) {
        if (r->backup.empty())
            ::unlink(r->target.c_str());
        else
            ::rename(r->backup.c_str(), r->target.c_str());
    }
}

}  // namespace

void OutputSet::commit() {
    // Every file on the device before any is renamed: a failure here replaces nothing.
    for (const auto& f : files_) {
        std::error_code ec;
        if (!fs::exists(f->temp_, ec))
            throw OutputError("writing '" + f->target_ + "' failed: nothing was written to '" + f->temp_ + "'");
        sync_file(f->temp_, f->target_);
    }
    std::vector<Replaced> done;
    try {
        for (const auto& f : files_) {
            Replaced r{f->target_, ""};
            std::error_code ec;
            if (fs::is_regular_file(f->target_, ec)) {
                r.backup = f->temp_ + ".old";
                ::unlink(r.backup.c_str());
                if (::link(f->target_.c_str(), r.backup.c_str()) != 0) r.backup.clear();
            }
            if (::rename(f->temp_.c_str(), f->target_.c_str()) != 0)
                throw OutputError("cannot move '" + f->temp_ + "' to '" + f->target_ + "': " + std::strerror(errno));
            f->committed_ = true;
            unregister_temporary(f->slot_);
            f->slot_ = -1;
            done.push_back(std::move(r));
        }
        for (const auto& d : directories_) d->commit();
    } catch (...) {
        roll_back(done);
        throw;
    }
    for (const Replaced& r : done)
        if (!r.backup.empty()) ::unlink(r.backup.c_str());
    for (const auto& f : files_) sync_directory(parent_of(f->target_));
    committed_ = true;  // the directories made for the outputs stay
    for (const auto& m : made_) sync_directory(parent_of(m.first));
}

}  // namespace strata
