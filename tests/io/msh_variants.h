#pragma once
// The .msh file \p src converted by Gmsh itself to binary 4.1, binary 2.2 and ASCII 2.2, for
// the readers' tests (test_read_surface, test_msh_counts).

#include "test_support.h"

#include <strata/io/gmsh_session.h>

#include <gmsh.h>

#include <string>
#include <tuple>
#include <vector>

namespace strata::test {

/// Writes b41.msh, b22.msh and a22.msh into \p dir; their paths, in that order.
inline std::vector<std::string> write_msh_variants(const std::string& src, const ScratchDir& dir) {
    std::vector<std::string> files;
    GmshSession session("test_msh_variants");
    gmsh::merge(src);
    double version = 0, binary = 0;
    gmsh::option::getNumber("Mesh.MshFileVersion", version);
    gmsh::option::getNumber("Mesh.Binary", binary);
    for (auto [v, b, name] :
         {std::tuple{4.1, 1, "b41.msh"}, std::tuple{2.2, 1, "b22.msh"}, std::tuple{2.2, 0, "a22.msh"}}) {
        gmsh::option::setNumber("Mesh.MshFileVersion", v);
        gmsh::option::setNumber("Mesh.Binary", b);
        gmsh::write(dir.file(name));
        files.push_back(dir.file(name));
    }
    gmsh::option::setNumber("Mesh.MshFileVersion", version);
    gmsh::option::setNumber("Mesh.Binary", binary);
    return files;
}

}  // namespace strata::test
