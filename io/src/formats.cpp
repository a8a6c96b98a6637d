#include <strata/core/error.h>
#include <strata/io/files.h>
#include <strata/io/formats.h>

#include <array>
#include <filesystem>

namespace strata {
namespace {

/// Mesh formats Gmsh 4.8 writes a surface to, from a file extension
/// (GuessFileFormatFromFileName). Images, .geo and post-processing formats are left out: they
/// are not meshes.
constexpr std::array<const char*, 20> kSurfaceExtensions = {".msh",  ".vtk",  ".stl",  ".su2", ".unv",  ".mesh", ".bdf",
                                                            ".nas",  ".inp",  ".cgns", ".med", ".mail", ".p3d",  ".wrl",
                                                            ".vrml", ".ply2", ".off",  ".x3d", ".neu",  ".key"};

/// Formats Gmsh 4.8 writes volume meshes to (.med only if this Gmsh was built with it:
/// BackendError at writing otherwise). Surface-only formats (.stl, .off, .ply2, .wrl, ...) are
/// left out, and so is Gambit .neu: Gmsh 4.8's writer corrupts the heap (the process aborts) on a
/// mesh mixing cell types. .cgns is Strata's own writer for volumes (cgns.h).
constexpr std::array<const char*, 10> kGmshVolumeExtensions = {".msh", ".vtk", ".su2", ".unv", ".mesh",
                                                               ".bdf", ".nas", ".inp", ".med", ".key"};
constexpr std::array<const char*, 3> kCobaltExtensions = {".cgr", ".cog", ".grd"};
constexpr std::array<const char*, 1> kCgnsExtensions = {".cgns"};
/// VTK's XML formats, Strata's own writer (vtk_xml.h): one UnstructuredGrid, or a MultiBlock
/// dataset with a directory of blocks beside it.
constexpr std::array<const char*, 2> kVtkXmlExtensions = {".vtu", ".vtm"};
/// The last component of an OpenFOAM mesh directory.
constexpr std::string_view kPolyMesh = "polyMesh";

template <std::size_t N>
bool listed(const std::string& ext, const std::array<const char*, N>& list) {
    for (const char* e : list)
        if (ext == e) return true;
    return false;
}

template <std::size_t N>
std::string join(const std::array<const char*, N>& list) {
    std::string s;
    for (const char* e : list) s += (s.empty() ? "" : ", ") + std::string(e);
    return s;
}

/// \p msh for an output with extension \p ext.
void check_msh_format(const std::string& path, const std::string& ext, MshFormat msh) {
    if (ext != ".msh") {
        if (msh.binary)
            throw InputError("cannot write '" + path + "' in binary: binary output (--binary) is for .msh files; "
                             "leave it out or name a .msh output");
        return;
    }
    if (msh.version != 2.2 && msh.version != 4.1)
        throw InputError("cannot write '" + path + "': MSH version " + std::to_string(msh.version) +
                         " is not written; use 4.1 (default) or 2.2");
}

/// The blocks' directory \p dir of the .vtm \p path, replaced whole when written: refused
/// (InputError) if it holds anything but .vtu and .vtp files, so that a name that clashes with
/// a directory of other data never costs that data.
void check_vtm_block_directory(const std::string& dir, const std::string& path) {
    check_output_directory(dir);
    std::error_code ec;
    for (const auto& e : std::filesystem::directory_iterator(dir, ec)) {
        const std::string ext = lower_extension(e.path().string());
        if (e.is_regular_file() && (ext == ".vtu" || ext == ".vtp")) continue;
        throw InputError("cannot write '" + path + "': its blocks go in '" + dir + "', which is replaced whole, and '" +
                         e.path().string() + "' there is not a block of a .vtm; move it or choose another name");
    }
}

}  // namespace

double parse_msh_version(std::string_view text) {
    if (text == "4.1") return 4.1;
    if (text == "2.2") return 2.2;
    throw InputError("MSH version '" + std::string(text) + "': use 4.1 or 2.2");
}

void check_surface_output(const std::string& path, MshFormat msh) {
    const std::string ext = lower_extension(path);
    if (!listed(ext, kSurfaceExtensions))
        throw InputError("cannot write '" + path + "': unknown mesh extension '" + ext + "'; use one of " +
                         join(kSurfaceExtensions));
    check_msh_format(path, ext, msh);
    check_output_path(path);
}

void check_volume_output(const std::string& path, MshFormat msh) {
    if (is_polymesh_path(path)) {
        check_msh_format(path, "", msh);
        return check_output_directory(path);
    }
    const std::string ext = lower_extension(path);
    if (!listed(ext, kGmshVolumeExtensions) && !listed(ext, kCobaltExtensions) && !listed(ext, kCgnsExtensions) &&
        !listed(ext, kVtkXmlExtensions))
        throw InputError("cannot write '" + path + "': unknown volume-mesh extension '" + ext + "'; use one of " +
                         join(kCobaltExtensions) + " (Cobalt60), " + join(kCgnsExtensions) + " (CGNS), " +
                         join(kVtkXmlExtensions) + " (VTK XML, for ParaView), a directory named polyMesh (OpenFOAM, e.g. case/constant/polyMesh) or " +
                         join(kGmshVolumeExtensions) + " (through Gmsh)");
    check_msh_format(path, ext, msh);
    check_output_path(path);
    if (ext == ".vtm") check_vtm_block_directory(vtm_block_directory(path), path);
}

bool is_cobalt_path(const std::string& path) {
    return listed(lower_extension(path), kCobaltExtensions);
}

bool is_cgns_path(const std::string& path) {
    return listed(lower_extension(path), kCgnsExtensions);
}

bool is_vtu_path(const std::string& path) {
    return lower_extension(path) == ".vtu";
}

bool is_vtm_path(const std::string& path) {
    return lower_extension(path) == ".vtm";
}

std::string vtm_block_directory(const std::string& path) {
    const std::string ext = lower_extension(path);
    return path.substr(0, path.size() - ext.size()) + "_blocks";
}

bool is_polymesh_path(const std::string& path) {
    std::string_view p = path;
    while (p.size() > 1 && p.back() == '/') p.remove_suffix(1);
    const std::size_t slash = p.rfind('/');
    return p.substr(slash == std::string_view::npos ? 0 : slash + 1) == kPolyMesh;
}

std::vector<std::string> volume_output_files(const std::string& path) {
    if (is_cobalt_path(path)) return {path, path + ".bc"};
    if (is_vtm_path(path)) return {path, vtm_block_directory(path)};
    return {path};
}

std::int64_t estimate_output_bytes(const std::string& path, std::size_t nodes, std::size_t cells) {
    // Bytes per node and per cell, rounded up from meshes written in each format.
    std::size_t per_node = 80, per_cell = 35;  // ASCII through Gmsh (.msh, .vtk, ...)
    if (is_cgns_path(path))
        per_node = 24, per_cell = 20;  // binary: 3 doubles a node, the cells' ids
    else if (is_vtu_path(path) || is_vtm_path(path))
        per_node = 30, per_cell = 90;  // binary: the points, 6-8 Int64 ids and 5 fields a cell, the patches
    else if (is_cobalt_path(path) || is_polymesh_path(path))
        per_node = 70, per_cell = 70;  // ASCII faces: about 2.5 faces a cell, with their cells
    return static_cast<std::int64_t>(per_node * nodes + per_cell * cells);
}

}  // namespace strata
