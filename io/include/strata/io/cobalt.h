#pragma once
/// \file
/// Cobalt60 ASCII writer (FORMATS.md): every face once, 1-based ids, boundary faces with
/// −patch in the second cell slot, face normals from the first cell to the second.

#include <strata/core/progress.h>
#include <strata/core/volume_mesh.h>
#include <strata/io/files.h>

#include <string>

namespace strata {

/// Write \p mesh as Cobalt60 to \p path (.cgr, .cog or .grd) and its patch map to
/// `<path>.bc` ("<number> <name> <kind>" per line, numbers 1..npatches in the file's order).
/// Only patches with faces are numbered. Both files are written atomically. Throws
/// InputError (unwritable path) or TopologyError (a face shared by more than two cells).
void write_cobalt(const VolumeMesh& mesh, const std::string& path, Progress* progress = nullptr,
                  OutputSet* outputs = nullptr);

}  // namespace strata
