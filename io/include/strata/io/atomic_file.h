#pragma once
/// \file
/// Write-then-rename, so a failed or interrupted write never leaves a partial output file.

#include <string>

namespace strata {

/// A temporary path next to \p target with the same extension (writers such as Gmsh pick
/// the format from it). commit() renames it onto the target; destruction without commit()
/// removes it.
class AtomicFile {
public:
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

}  // namespace strata
