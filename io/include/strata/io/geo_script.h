#pragma once
/// \file
/// Reading a Gmsh .geo script more than once in one process. Gmsh 4.8 keeps a script's Macro
/// (Function) definitions for the life of the process: neither gmsh::clear() nor
/// gmsh::finalize() forgets them, and a second read of a script that defines one fails with
/// "Redefinition of function NAME". Strata reads a CAD file again where it meshes the walls
/// finer (the layers' steps, the wall aspect ratio, a quad recombination that folded), and a
/// Python or FreeCAD session meshes the same script again and again; Gmsh's own tutorials
/// define Macros. merge_geo_script reads such a script through a copy whose Macros are renamed.

#include <string>
#include <vector>

namespace strata {

/// The names of the Macros (and Functions, their old spelling) that the script text \p text
/// defines, in order: `Macro NAME` or `Macro "NAME"` at the start of a statement.
std::vector<std::string> geo_macro_names(const std::string& text);

/// \p text with every Macro (Function) it defines, and every `Call` of one, renamed to
/// NAME + \p suffix. Only the names \p text defines; a Call of another script's Macro stays.
std::string rename_geo_macros(const std::string& text, const std::string& suffix);

/// gmsh::merge(\p path) (Gmsh initialised, its current model the target), where \p path is a
/// .geo script whose Macros this process has defined before (read by Strata): its text with
/// those Macros renamed is merged instead, from a hidden copy beside it (so that the script's
/// relative paths, Include and Merge, still resolve) that is removed at once. A directory
/// Strata cannot write to leaves the script as it is (Gmsh then says which Macro it
/// redefines). Throws what gmsh::merge throws.
void merge_geo_script(const std::string& path);

}  // namespace strata
