#pragma once
/// \file
/// Paths and files, the same way for every reader and writer: the check that an input file
/// can be read, write-then-rename for outputs, extensions.

#include <string>

namespace strata {

/// Refuse \p path before any reader opens it: InputError "cannot open '<path>': no such file;
/// check the path" (or: it is a directory, or the system's reason it cannot be read).
void check_input_file(const std::string& path);

/// Refuse \p path as an output before anything is written: InputError "cannot write '<path>':
/// directory '<dir>' does not exist; ..." or "...: it is a directory; choose a file name".
void check_output_path(const std::string& path);

/// Refuse \p path as an output directory (a polyMesh) before anything is written: InputError
/// "cannot write '<path>': directory '<parent>' does not exist; ..." or "...: it is a file, not a
/// directory; ...". An existing directory is fine: it is replaced as a whole (AtomicDirectory).
void check_output_directory(const std::string& path);

/// The extension of \p path in lower case, with its dot (".step"); "" if it has none.
std::string lower_extension(const std::string& path);

/// Write-then-rename, so a failed or interrupted write never leaves a partial output file:
/// a temporary path next to \p target with the same extension (writers such as Gmsh pick the
/// format from it). commit() renames it onto the target; destruction without commit() removes
/// it.
class AtomicFile {
public:
    /// InputError naming the directory if it does not exist, or if \p target is a directory.
    explicit AtomicFile(std::string target);
    ~AtomicFile();
    AtomicFile(const AtomicFile&) = delete;
    AtomicFile& operator=(const AtomicFile&) = delete;

    const std::string& temp_path() const { return temp_; }
    const std::string& target() const { return target_; }
    /// Rename the temporary file onto the target; throws InputError naming both on failure.
    void commit();

private:
    std::string target_;
    std::string temp_;
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
    /// Put the temporary directory in place of the target; throws InputError naming both on failure
    /// (the target is then as it was).
    void commit();

private:
    std::string target_;
    std::string temp_;
    bool committed_ = false;
};

}  // namespace strata
