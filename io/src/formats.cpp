#include <strata/core/error.h>
#include <strata/io/files.h>
#include <strata/io/formats.h>

#include <array>

namespace strata {
namespace {

/// Mesh formats Gmsh 4.8 writes a surface to, from a file extension
/// (GuessFileFormatFromFileName). Images, .geo and post-processing formats are left out: they
/// are not meshes.
constexpr std::array<const char*, 20> kSurfaceExtensions = {".msh",  ".vtk",  ".stl",  ".su2", ".unv",  ".mesh", ".bdf",
                                                            ".nas",  ".inp",  ".cgns", ".med", ".mail", ".p3d",  ".wrl",
                                                            ".vrml", ".ply2", ".off",  ".x3d", ".neu",  ".key"};

/// Formats Gmsh 4.8 writes volume meshes to (.cgns and .med only if this Gmsh was built with
/// them: BackendError at writing otherwise). Surface-only formats (.stl, .off, .ply2, .wrl, ...)
/// are left out, and so is Gambit .neu: Gmsh 4.8's writer corrupts the heap (the process aborts)
/// on a mesh mixing cell types.
constexpr std::array<const char*, 11> kGmshVolumeExtensions = {".msh", ".vtk", ".su2",  ".unv", ".mesh", ".bdf",
                                                               ".nas", ".inp", ".cgns", ".med", ".key"};
constexpr std::array<const char*, 3> kCobaltExtensions = {".cgr", ".cog", ".grd"};

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

void check_msh_version(const std::string& path, double version) {
    if (version != 2.2 && version != 4.1)
        throw InputError("cannot write '" + path + "': MSH version " + std::to_string(version) +
                         " is not written; use 4.1 (default) or 2.2");
}

}  // namespace

double parse_msh_version(std::string_view text) {
    if (text == "4.1") return 4.1;
    if (text == "2.2") return 2.2;
    throw InputError("MSH version '" + std::string(text) + "': use 4.1 or 2.2");
}

void check_surface_output(const std::string& path, double msh_version) {
    const std::string ext = lower_extension(path);
    if (!listed(ext, kSurfaceExtensions))
        throw InputError("cannot write '" + path + "': unknown mesh extension '" + ext + "'; use one of " +
                         join(kSurfaceExtensions));
    if (ext == ".msh") check_msh_version(path, msh_version);
    check_output_path(path);
}

void check_volume_output(const std::string& path, double msh_version) {
    const std::string ext = lower_extension(path);
    if (!listed(ext, kGmshVolumeExtensions) && !listed(ext, kCobaltExtensions))
        throw InputError("cannot write '" + path + "': unknown volume-mesh extension '" + ext + "'; use one of " +
                         join(kCobaltExtensions) + " (Cobalt60) or " + join(kGmshVolumeExtensions));
    if (ext == ".msh") check_msh_version(path, msh_version);
    check_output_path(path);
}

bool is_cobalt_path(const std::string& path) {
    return listed(lower_extension(path), kCobaltExtensions);
}

std::vector<std::string> volume_output_files(const std::string& path) {
    if (is_cobalt_path(path)) return {path, path + ".bc"};
    return {path};
}

}  // namespace strata
