// Files read and written through Gmsh (FORMATS.md: never write .msh by hand), so every MSH
// version and encoding Gmsh reads, and every mesh format it writes, is Gmsh's own work. Each
// function is a scratch model in a GmshSession (the caller's current model is untouched) plus
// the one model conversion of gmsh_model.h.

#include <strata/core/error.h>
#include <strata/core/mesh_check.h>
#include <strata/io/cgns.h>
#include <strata/io/vtk_xml.h>
#include <strata/io/cobalt.h>
#include <strata/io/files.h>
#include <strata/io/formats.h>
#include <strata/io/gmsh_model.h>
#include <strata/io/gmsh_session.h>
#include <strata/io/input_file.h>
#include <strata/io/openfoam.h>
#include <strata/io/read_surface.h>
#include <strata/io/write_surface.h>
#include <strata/io/write_volume.h>

#include "msh41_writer.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <cerrno>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <new>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace strata {
namespace {

/// Formats whose Gmsh writer seeks in its file (MED, on HDF5), so they cannot be written
/// through a pipe.
bool seeks_in_its_file(const std::string& path) {
    return lower_extension(path) == ".med";
}

/// Free bytes below which a file Gmsh wrote directly is taken as cut short by a full disk
/// (Gmsh does not check its writes).
constexpr std::int64_t kFullDisk = 1 << 20;

/// What Gmsh writes, copied to a file with every write checked: Gmsh writes into a pipe (a
/// FIFO in a scratch directory, named with the output's extension, from which Gmsh picks the
/// format), and a thread copies the pipe to \p temp with checked write()s, then fsyncs it.
/// Gmsh's own writers check none of their writes, so a full disk would otherwise give a
/// truncated file and no error.
class PipedWrite {
public:
    PipedWrite(const std::string& temp, const std::string& target) : target_(target) {
        std::error_code ec;
        const std::filesystem::path tmp = std::filesystem::temp_directory_path(ec);
        const std::string base = (ec ? std::string("/tmp") : tmp.string()) + "/strata-XXXXXX";
        std::vector<char> name(base.begin(), base.end());
        name.push_back('\0');
        if (!::mkdtemp(name.data())) return;  // no scratch directory: Gmsh writes the file itself
        dir_ = std::make_unique<ScopedTemporary>(std::string(name.data()), true);
        fifo_ = dir_->path() + "/out" + std::filesystem::path(target).extension().string();
        if (::mkfifo(fifo_.c_str(), 0600) != 0) {
            fifo_.clear();
            return;
        }
        in_ = ::open(fifo_.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
        keep_ = in_ < 0 ? -1 : ::open(fifo_.c_str(), O_WRONLY | O_CLOEXEC);  // no EOF before Gmsh is done
        if (keep_ < 0) {
            close_all();
            fifo_.clear();
            return;
        }
        ::fcntl(in_, F_SETFL, ::fcntl(in_, F_GETFL) & ~O_NONBLOCK);
        const int out = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
        if (out < 0) {
            const int err = errno;
            close_all();
            throw OutputError(write_failure(target, err));
        }
        copier_ = std::thread([this, out] { copy(out); });
    }
    ~PipedWrite() { close_all(); }
    PipedWrite(const PipedWrite&) = delete;
    PipedWrite& operator=(const PipedWrite&) = delete;

    /// Where Gmsh is to write: the pipe, or "" if none could be made (then the file itself).
    const std::string& path() const { return fifo_; }

    /// After Gmsh returned: wait for the copy; OutputError if a write failed; the bytes copied.
    std::size_t finish() {
        close_all();
        if (error_ != 0) throw OutputError(write_failure(target_, error_));
        return bytes_;
    }

private:
    void copy(int out) {
        std::vector<char> buf(std::size_t{1} << 16);
        for (;;) {
            const ssize_t n = ::read(in_, buf.data(), buf.size());
            if (n < 0 && errno == EINTR) continue;
            if (n <= 0) break;
            bytes_ += static_cast<std::size_t>(n);
            if (error_ == 0 && !write_all(out, buf.data(), static_cast<std::size_t>(n))) error_ = errno;
        }  // after a failed write the pipe is still drained, so Gmsh is never blocked
        if (error_ == 0 && ::fsync(out) != 0 && errno != EINVAL && errno != EROFS) error_ = errno;
        if (::close(out) != 0 && error_ == 0 && errno != EINTR) error_ = errno;
    }
    void close_all() {
        if (keep_ >= 0) ::close(keep_);
        keep_ = -1;
        if (copier_.joinable()) copier_.join();
        if (in_ >= 0) ::close(in_);
        in_ = -1;
    }

    std::string target_, fifo_;
    std::unique_ptr<ScopedTemporary> dir_;
    int in_ = -1, keep_ = -1;
    std::thread copier_;
    std::size_t bytes_ = 0;
    int error_ = 0;
};

/// Build the mesh in a scratch model with \p add and write it to \p path through a temporary
/// file (AtomicFile, in \p outputs if given), with Strata's output options set for the call only.
template <class Add>
void write_through_gmsh(const std::string& path, MshFormat msh, const char* session_name, Progress* progress,
                        OutputSet* outputs, Add&& add) {
    report(progress, "writing", 0.0);
    OutputSet own;
    AtomicFile& out = (outputs ? *outputs : own).file(path);  // InputError now if the directory does not exist
    GmshSession session(session_name);
    GmshOptionScope options;  // declared after the session: restored before the session ends
    std::optional<PipedWrite> pipe;
    if (!seeks_in_its_file(path)) pipe.emplace(out.temp_path(), path);
    const bool piped = pipe && !pipe->path().empty();
    gmsh_call("writing '" + path + "'", [&] {
        options.set("Mesh.MshFileVersion", msh.version);
        options.set("Mesh.Binary", msh.binary ? 1 : 0);
        options.set("Mesh.SaveAll", 0);  // every element is in a physical group
        options.set("Mesh.ScalingFactor", 1);
        add();
        gmsh::write(piped ? pipe->path() : out.temp_path());
    });
    std::error_code ec;
    const std::size_t bytes = piped ? pipe->finish() : std::filesystem::file_size(out.temp_path(), ec);
    // Gmsh only logs some failures (a format it was built without): say so, not "rename failed".
    if (bytes == 0 || ec) {
        const std::string last = GmshSession::last_error();
        throw BackendError("writing '" + path + "': Gmsh wrote nothing" + (last.empty() ? "" : ": " + last));
    }
    const std::int64_t free = free_bytes_at(path);
    if (!piped && free >= 0 && free < kFullDisk) throw OutputError(write_failure(path, ENOSPC));
    report(progress, "writing", 1.0);  // cancelled here: the temporary file goes, nothing is written
    if (!outputs) own.commit();
}

/// \p path merged into a Gmsh session named \p session_name and converted by \p convert (given the
/// path quoted, for its messages); running out of memory is an InputError naming the file.
template <class Convert>
auto from_msh_file(const char* session_name, const std::string& path, Convert&& convert) {
    GmshSession session(session_name);
    merge_msh_file(path);
    try {
        return convert("'" + path + "'");
    } catch (const std::bad_alloc&) {
        throw out_of_memory(path);
    }
}

}  // namespace

SurfaceMesh read_msh(const std::string& path) {
    return from_msh_file("read_msh", path, [](const std::string& context) { return surface_from_gmsh_model(context); });
}

VolumeMesh read_volume_msh(const std::string& path) {
    return from_msh_file("read_volume_msh", path, volume_from_gmsh_model);
}

void write_surface(const SurfaceMesh& mesh, const std::string& path, MshFormat msh, Progress* progress,
                   OutputSet* outputs) {
    check_surface_output(path, msh);
    require_sound(check_surface_arrays(mesh), "cannot write '" + path + "': ");
    write_through_gmsh(path, msh, "write_surface", progress, outputs, [&] { add_surface_to_gmsh_model(mesh); });
}

void write_volume(const VolumeMesh& mesh, const std::string& path, MshFormat msh, Progress* progress,
                  OutputSet* outputs) {
    check_volume_output(path, msh);
    if (is_cobalt_path(path)) return write_cobalt(mesh, path, progress, outputs);
    if (is_polymesh_path(path)) {
        write_polymesh(mesh, path, progress, outputs);
        return;
    }
    if (is_cgns_path(path)) return write_cgns(mesh, path, progress, outputs);
    if (is_vtu_path(path)) return write_vtu(mesh, path, progress, outputs);
    if (is_vtm_path(path)) return write_vtm(mesh, path, progress, outputs);
    require_sound(check_volume_arrays(mesh), "cannot write '" + path + "': ");
    if (lower_extension(path) == ".msh" && msh.version == 4.1 && !msh.binary)
        return write_msh41_ascii(mesh, path, progress, outputs);  // Strata's own: Gmsh's printf()s took minutes
    write_through_gmsh(path, msh, "write_volume", progress, outputs, [&] { add_volume_to_gmsh_model(mesh); });
}

}  // namespace strata
