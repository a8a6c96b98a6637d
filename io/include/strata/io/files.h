#pragma once
/// \file
/// Paths and files, the same way for every reader and writer: the check that an input file
/// can be read, write-then-rename for outputs, extensions.

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace strata {

/// Refuse \p path before any reader opens it: InputError "cannot open '<path>': no such file;
/// check the path" (or: it is a directory, or the system's reason it cannot be read).
void check_input_file(const std::string& path);

/// Refuse \p path as an output before anything is written: InputError "cannot write '<path>':
/// directory '<dir>' does not exist; ..." or "...: it is a directory; choose a file name", and
/// OutputError when the file cannot be created there: the directory is not writable or on a
/// read-only file system, or the name (or the temporary name it is written under) is too long
/// for the file system. Found by creating and removing the temporary file the writer will use.
void check_output_path(const std::string& path);

/// Refuse \p path as an output directory (a polyMesh) before anything is written: InputError
/// "cannot write '<path>': directory '<parent>' does not exist; ..." or "...: it is a file, not a
/// directory; ...", OutputError if the temporary directory cannot be created beside it. An
/// existing directory is fine: it is replaced as a whole (AtomicDirectory).
void check_output_directory(const std::string& path);

/// Refuse, before any work, a run whose outputs would replace one of its inputs: InputError
/// naming both when an output in \p outputs is the same file as an input in \p inputs (the same
/// path once links are resolved, or the same device and inode), or when an input lies inside
/// an output that is a directory (a polyMesh replaced whole).
void check_outputs_are_not_inputs(const std::vector<std::string>& outputs, const std::vector<std::string>& inputs);

/// The message for a write to \p target that failed with \p err (an errno): "disk full writing
/// '<target>'" for ENOSPC, the quota, the file size limit, an I/O error, or the system's text,
/// each saying what to do and that the previous '<target>' is as it was.
std::string write_failure(const std::string& target, int err);

/// fsync \p path (a file just written for \p target) to its device: OutputError
/// (write_failure) if the device reports an error (a delayed "disk full", an I/O error).
void sync_file(const std::string& path, const std::string& target);

/// write() all of \p data to the file descriptor \p fd, again after EINTR and short writes;
/// false with errno set on failure.
bool write_all(int fd, const char* data, std::size_t size);

/// Write \p data to the new file \p path for \p target, checked to the end (every write(),
/// fsync, close): OutputError (write_failure) on any failure.
void write_whole_file(const std::string& path, const std::string& target, std::string_view data);

/// Free bytes for this user on the file system that holds \p path's directory; -1 if unknown.
std::int64_t free_bytes_at(const std::string& path);

/// A temporary file or directory of this process (a scratch directory, a pipe) removed when this
/// is destroyed, and by remove_temporaries() until then.
class ScopedTemporary {
public:
    ScopedTemporary(std::string path, bool directory);
    ~ScopedTemporary();
    ScopedTemporary(const ScopedTemporary&) = delete;
    ScopedTemporary& operator=(const ScopedTemporary&) = delete;
    const std::string& path() const { return path_; }

private:
    std::string path_;
    bool directory_;
    int slot_;
};

/// Remove every temporary output this process has not committed, now: for a signal or crash
/// handler (only unlink, rmdir and directory reads by system call; async-signal-safe).
void remove_temporaries() noexcept;

/// The extension of \p path in lower case, with its dot (".step"); "" if it has none.
std::string lower_extension(const std::string& path);

/// The bytes of the file at \p path, "" if it cannot be opened (check_input_file first where
/// that must be an error).
std::string read_whole_file(const std::string& path);

/// Write-then-rename, so a failed or interrupted write never leaves a partial output file:
/// a temporary path next to \p target with the same extension (writers such as Gmsh pick the
/// format from it), ".<stem>.tmp<pid><ext>" (the stem shortened, with a hash of the name, where
/// that would pass the file system's 255 bytes). commit() renames it onto the target;
/// destruction without commit() removes it, and so does remove_temporaries().
class AtomicFile {
public:
    /// InputError naming the directory if it does not exist, or if \p target is a directory.
    explicit AtomicFile(std::string target);
    ~AtomicFile();
    AtomicFile(const AtomicFile&) = delete;
    AtomicFile& operator=(const AtomicFile&) = delete;

    const std::string& temp_path() const { return temp_; }
    const std::string& target() const { return target_; }
    /// fsync the temporary file, rename it onto the target, fsync the directory; OutputError
    /// (write_failure) if the file did not reach the device, InputError naming both if the
    /// rename fails.
    void commit();

private:
    friend class OutputSet;
    std::string target_;
    std::string temp_;
    int slot_ = -1;  ///< in the registry of remove_temporaries
    bool committed_ = false;
};

/// Build-then-rename for an output that is a directory of files (an OpenFOAM polyMesh): the
/// files go into a temporary directory next to \p target; commit() puts it in place of the
/// target in one step (Linux renameat2 RENAME_EXCHANGE swaps it with an existing target, whose
/// old contents are then removed), so a reader never sees a half-written or half-replaced
/// directory. Destruction without commit() removes the temporary directory and everything in it.
class AtomicDirectory {
public:
    /// InputError naming the directory if the parent does not exist or \p target is a file;
    /// creates the (empty) temporary directory.
    explicit AtomicDirectory(std::string target);
    ~AtomicDirectory();
    AtomicDirectory(const AtomicDirectory&) = delete;
    AtomicDirectory& operator=(const AtomicDirectory&) = delete;

    const std::string& temp_path() const { return temp_; }
    const std::string& target() const { return target_; }
    /// A file of the temporary directory: temp_path()/\p name.
    std::string file(const std::string& name) const;
    /// fsync the files in the temporary directory, put it in place of the target; throws
    /// OutputError or InputError naming both on failure (the target is then as it was).
    void commit();

private:
    std::string target_;
    std::string temp_;
    int slot_ = -1;  ///< in the registry of remove_temporaries
    bool committed_ = false;
};

/// The outputs of one run (a mesh, its Cobalt60 patch map, its report), committed together or
/// not at all: each is written under its temporary name first; commit() makes every one reach
/// the device (fsync) before any is renamed into place, and if a rename fails puts back the
/// files it had already replaced. Destroyed without commit(), every temporary goes.
class OutputSet {
public:
    OutputSet() = default;
    ~OutputSet();
    OutputSet(const OutputSet&) = delete;
    OutputSet& operator=(const OutputSet&) = delete;

    /// A new file output for \p target (AtomicFile: the target checked now).
    AtomicFile& file(const std::string& target);
    /// A new directory output for \p target (AtomicDirectory); committed after the files.
    AtomicDirectory& directory(const std::string& target);
    /// Create the directory \p path, for outputs of this set to go in, if it does not exist yet
    /// (an OpenFOAM case's `system/`): kept by commit(); removed again when the set is destroyed
    /// without commit(), and by remove_temporaries(), if nothing else was put in it. An existing
    /// directory is left as it is. InputError if its parent does not exist or \p path is a file,
    /// OutputError (write_failure) if it cannot be created.
    void make_directory(const std::string& path);
    /// Put every output in place, or none (see the class).
    void commit();

private:
    /// The directories made, each with its slot in remove_temporaries' registry.
    std::vector<std::pair<std::string, int>> made_;
    std::vector<std::unique_ptr<AtomicFile>> files_;
    std::vector<std::unique_ptr<AtomicDirectory>> directories_;
    bool committed_ = false;
};

}  // namespace strata
