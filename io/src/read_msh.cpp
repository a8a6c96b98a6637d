// Gmsh .msh reader through the Gmsh API, so every MSH version and encoding Gmsh reads
// (2.2, 4.1, ASCII, binary) is handled by Gmsh itself. The conversion of the model into a
// SurfaceMesh (patches from physical groups) is gmsh_model.cpp's, shared with the Gmsh-API
// entry point.

#include <strata/io/gmsh_model.h>
#include <strata/io/gmsh_session.h>
#include <strata/io/read_surface.h>

#include <string>

namespace strata {

SurfaceMesh read_msh(const std::string& path) {
    GmshSession session("read_msh");  // a scratch model: the caller's current model is untouched
    merge_msh_file(path);
    return surface_from_gmsh_model("'" + path + "'");
}

}  // namespace strata
