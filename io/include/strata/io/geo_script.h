#pragma once
/// \file
/// Reading a Gmsh .geo script more than once in one process. Gmsh 4.8 keeps a script's Macro
/// (Function) definitions for the life of the process: neither gmsh::clear() nor
/// gmsh::finalize() forgets them, and a second read of a script that defines one fails with
/// "Redefinition of function NAME". Strata reads a CAD file again where it meshes the walls
/// finer (the layers' steps, the wall aspect ratio, a quad recombination that folded), and a
/// Python or FreeCAD session meshes the same script again and again; Gmsh's own tutorials
/// define Macros. merge_geo_script reads such a script through a copy whose Macros are renamed.
///
/// A .geo script is also a program: Gmsh 4.8 runs the shell commands it gives (SystemCall),
/// starts programs (OnelabRun) and writes the files it names (Save, Printf > file) with the
/// rights of whoever reads it. check_geo_script refuses such a script (and one that Includes or
/// Merges such a script) before Gmsh reads it, unless its author is trusted.

#include <string>
#include <vector>

namespace strata {

/// The names of the Macros (and Functions, their old spelling) that the script text \p text
/// defines, in order: `Macro NAME` or `Macro "NAME"` at the start of a statement.
std::vector<std::string> geo_macro_names(const std::string& text);

/// \p text with every Macro (Function) it defines, and every `Call` of one, renamed to
/// NAME + \p suffix. Only the names \p text defines; a Call of another script's Macro stays.
std::string rename_geo_macros(const std::string& text, const std::string& suffix);

/// A statement of a .geo script that reaches outside Gmsh's model (scan_geo_text).
struct GeoHazard {
    std::string file;       ///< the script it is in (empty from scan_geo_text)
    int line = 0;           ///< 1-based line of its command
    std::string command;    ///< as written: "SystemCall", "Printf(...) >", "Plugin(Bubbles).Run"
    std::string what;       ///< what it does: "runs a shell command"
    std::string read_from;  ///< the Include or Merge that reads \p file ("main.geo, line 3"); empty: the script itself
};

/// A script that a script reads as it runs: `Include "PATH";` or `Merge "PATH";`
/// (MergeWithBoundingBox too), PATH a plain string.
struct GeoRead {
    int line = 0;
    std::string command;  ///< "Include", "Merge" or "MergeWithBoundingBox"
    std::string path;     ///< as written (relative paths are Gmsh's: to the reading script's directory)
};

struct GeoScan {
    std::vector<GeoHazard> hazards;  ///< in the order of the text
    std::vector<GeoRead> reads;
};

/// The statements of the Gmsh 4.8 script \p text that run a shell command or a program
/// (SystemCall, System, NonBlockingSystemCall, OnelabRun), talk to a ONELAB server (SendToServer),
/// write or create files (Save, Print, Printf(...) > or >> a file, CreateDir, Plugin(...).Run:
/// several plugins write files), end the process (Exit), or read a file named by a string
/// expression (Include, Merge: Strata cannot tell which); and the files read by a plain name
/// (\p reads). Comments and the contents of strings are skipped; keywords are case-sensitive,
/// as Gmsh's lexer reads them. Every statement counts, in a Macro or an If branch that never
/// runs too. Reads nothing but \p text.
GeoScan scan_geo_text(const std::string& text);

/// Whether Gmsh 4.8 runs the file at \p path as a script when a script Merges it: not for the
/// extensions it reads with a reader of their own (.step, .stl, ... as Gmsh spells them: lower
/// or upper case), nor for a mesh or view file (its first line $MeshFormat, $Comments,
/// $PostFormat or $View); every other file it parses as a .geo script. An Include always is.
bool merged_as_script(const std::string& path);

/// The hazards (scan_geo_text) of the script at \p path and of every script it reads (Include,
/// and Merge where merged_as_script), depth first, each named by its file; a read file that
/// does not exist has none (Gmsh fails on it), and each file is scanned once.
std::vector<GeoHazard> geo_script_hazards(const std::string& path);

/// InputError naming the file, the line, the command, what it does and what to do
/// (CadParams::trust_geo), for the first of geo_script_hazards(\p path), and the lines of
/// the others; nothing if it has none.
void check_geo_script(const std::string& path);

/// gmsh::merge(\p path) (Gmsh initialised, its current model the target), where \p path is a
/// .geo script whose Macros this process has defined before (read by Strata): its text with
/// those Macros renamed is merged instead, from a hidden copy beside it (so that the script's
/// relative paths, Include and Merge, still resolve) that is removed at once. A directory
/// Strata cannot write to leaves the script as it is (Gmsh then says which Macro it
/// redefines). Unless \p trusted, check_geo_script(\p path) first. Throws what gmsh::merge
/// throws.
void merge_geo_script(const std::string& path, bool trusted);

}  // namespace strata
