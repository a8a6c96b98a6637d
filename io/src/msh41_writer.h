#pragma once
// Private to strata_io: a volume mesh as ASCII MSH 4.1 written by Strata itself (numbers through
// std::to_chars, BufferedFile), the same entities, physical groups, node and element tags as
// add_volume_to_gmsh_model gives Gmsh's own writer (which printf()s each number and took half of
// `strata layers` on a 10M-prism sphere). MSH 2.2 and binary MSH still go through Gmsh.

#include <strata/core/progress.h>
#include <strata/core/volume_mesh.h>
#include <strata/io/files.h>

#include <string>

namespace strata {

/// \p mesh (arrays checked by the caller) to \p path through a temporary file (in \p outputs if
/// given): surfaces 1.. (patch index + 1, patches with faces), volume 1 bounded by them, physical
/// group 3/1 "fluid" and one 2D group per patch name (tag: its first patch's index + 1); every
/// node on the volume, tags 1..; cells tagged 1.. in the order tets, pyramids, prisms, hexahedra;
/// boundary faces tagged after them by face index. Coordinates in the shortest form that reads
/// back exactly.
void write_msh41_ascii(const VolumeMesh& mesh, const std::string& path, Progress* progress, OutputSet* outputs);

}  // namespace strata
