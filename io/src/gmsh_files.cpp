// Files read and written through Gmsh (FORMATS.md: never write .msh by hand), so every MSH
// version and encoding Gmsh reads, and every mesh format it writes, is Gmsh's own work. Each
// function is a scratch model in a GmshSession (the caller's current model is untouched) plus
// the one model conversion of gmsh_model.h.

#include <strata/core/error.h>
#include <strata/core/mesh_check.h>
#include <strata/io/cgns.h>
#include <strata/io/cobalt.h>
#include <strata/io/files.h>
#include <strata/io/formats.h>
#include <strata/io/gmsh_model.h>
#include <strata/io/gmsh_session.h>
#include <strata/io/openfoam.h>
#include <strata/io/read_surface.h>
#include <strata/io/write_surface.h>
#include <strata/io/write_volume.h>

#include <filesystem>
#include <string>

namespace strata {
namespace {

/// Build the mesh in a scratch model with \p add and write it to \p path through a temporary
/// file (AtomicFile), with Strata's output options set for the call only.
template <class Add>
void write_through_gmsh(const std::string& path, double msh_version, const char* session_name, Progress* progress,
                        Add&& add) {
    report(progress, "writing", 0.0);
    AtomicFile out(path);  // InputError now if the directory does not exist
    GmshSession session(session_name);
    GmshOptionScope options;  // declared after the session: restored before the session ends
    gmsh_call("writing '" + path + "'", [&] {
        options.set("Mesh.MshFileVersion", msh_version);
        options.set("Mesh.Binary", 0);
        options.set("Mesh.SaveAll", 0);  // every element is in a physical group
        options.set("Mesh.ScalingFactor", 1);
        add();
        gmsh::write(out.temp_path());
    });
    // Gmsh only logs some failures (a format it was built without): say so, not "rename failed".
    std::error_code ec;
    if (!std::filesystem::exists(out.temp_path(), ec)) {
        const std::string last = GmshSession::last_error();
        throw BackendError("writing '" + path + "': Gmsh wrote nothing" + (last.empty() ? "" : ": " + last));
    }
    report(progress, "writing", 1.0);  // cancelled here: the temporary file goes, nothing is written
    out.commit();
}

}  // namespace

SurfaceMesh read_msh(const std::string& path) {
    GmshSession session("read_msh");
    merge_msh_file(path);
    return surface_from_gmsh_model("'" + path + "'");
}

VolumeMesh read_volume_msh(const std::string& path) {
    GmshSession session("read_volume_msh");
    merge_msh_file(path);
    return volume_from_gmsh_model("'" + path + "'");
}

void write_surface(const SurfaceMesh& mesh, const std::string& path, double msh_version, Progress* progress) {
    check_surface_output(path, msh_version);
    require_sound(check_surface_arrays(mesh), "cannot write '" + path + "': ");
    write_through_gmsh(path, msh_version, "write_surface", progress, [&] { add_surface_to_gmsh_model(mesh); });
}

void write_volume(const VolumeMesh& mesh, const std::string& path, double msh_version, Progress* progress) {
    check_volume_output(path, msh_version);
    if (is_cobalt_path(path)) return write_cobalt(mesh, path, progress);
    if (is_polymesh_path(path)) return write_polymesh(mesh, path, progress);
    if (is_cgns_path(path)) return write_cgns(mesh, path, progress);
    require_sound(check_volume_arrays(mesh), "cannot write '" + path + "': ");
    write_through_gmsh(path, msh_version, "write_volume", progress, [&] { add_volume_to_gmsh_model(mesh); });
}

}  // namespace strata
