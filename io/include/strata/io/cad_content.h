#pragma once
/// \file
/// The check that a CAD file holds what its extension says, before Gmsh and OpenCASCADE read
/// it: they take a PNG named .iges for a model with nothing in it ("no surfaces"), which says
/// nothing about the real mistake.

#include <string>
#include <string_view>

namespace strata {

/// The CAD formats whose content can be recognised from their first bytes.
enum class CadContent { Step, Iges, Brep };

/// Whether \p head, a file's first bytes (a few kB), starts as a \p kind file does:
/// - STEP: `ISO-10303-21;` (any case), after an optional UTF-8 byte-order mark, white space and
///   comments;
/// - IGES: the first record, after blank lines, has its section letter in column 73 (`S`, `G`,
///   `C` or `F` for a compressed file's flag section, `B` for binary) and a sequence number;
///   a first record whose padding was lost ("...text S      1") is taken too, as OpenCASCADE
///   reads it;
/// - BREP (OpenCASCADE's text format): `DBRep_DrawableShape` or a first line with
///   `CASCADE Topology`.
bool holds_cad_content(std::string_view head, CadContent kind);

/// InputError unless \p path (a regular file) starts as a \p kind file: "'x.iges' is not an
/// IGES file: it looks like a PNG image; export the model again as IGES, or give the file the
/// extension of its format (.step, .iges, .brep)".
void check_cad_content(const std::string& path, CadContent kind);

}  // namespace strata
