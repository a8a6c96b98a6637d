#include <strata/core/error.h>
#include <strata/core/volume_mesh.h>

#include <string>

namespace strata {

int cell_corners(CellType t) {
    switch (t) {
        case CellType::Tet: return 4;
        case CellType::Pyramid: return 5;
        case CellType::Prism: return 6;
        case CellType::Hex: return 8;
    }
    return 0;
}

std::string_view to_string(CellType t) {
    switch (t) {
        case CellType::Tet: return "tetrahedron";
        case CellType::Pyramid: return "pyramid";
        case CellType::Prism: return "prism";
        case CellType::Hex: return "hexahedron";
    }
    return "cell";
}

void check_volume_mesh(const VolumeMesh& mesh, const std::string& where) {
    if (mesh.num_cells() == 0) throw InputError(where + "the mesh has no cells");
    const Index num_points = static_cast<Index>(mesh.points.size());
    for (std::size_t i = 0; i < mesh.points.size(); ++i)
        if (!mesh.points[i].allFinite())
            throw TopologyError(where + "node " + std::to_string(i) + " has a non-finite coordinate");
    auto check_cells = [&](const auto& cells, CellType type) {
        for (std::size_t c = 0; c < cells.size(); ++c)
            for (Index v : cells[c])
                if (v < 0 || v >= num_points)
                    throw InputError(where + std::string(to_string(type)) + " " + std::to_string(c) + " uses node " +
                                     std::to_string(v) + " but the mesh has " + std::to_string(num_points) + " nodes");
    };
    check_cells(mesh.tets, CellType::Tet);
    check_cells(mesh.pyramids, CellType::Pyramid);
    check_cells(mesh.prisms, CellType::Prism);
    check_cells(mesh.hexes, CellType::Hex);

    const SurfaceMesh& b = mesh.boundary;
    if (b.face_offsets.empty() || b.face_offsets.front() != 0 ||
        static_cast<std::size_t>(b.face_offsets.back()) != b.face_nodes.size())
        throw InputError(where + "boundary.face_offsets is malformed");
    if (b.face_patch.size() != static_cast<std::size_t>(b.num_faces()))
        throw InputError(where + "boundary.face_patch has " + std::to_string(b.face_patch.size()) + " entries for " +
                         std::to_string(b.num_faces()) + " boundary faces");
    for (Index f = 0; f < b.num_faces(); ++f) {
        const Index n = b.face_size(f);
        if (n != 3 && n != 4)
            throw InputError(where + "boundary face " + std::to_string(f) + " has " + std::to_string(n) +
                             " nodes; only triangles and quadrangles can be written");
        for (const Index* v = b.face_begin(f); v != b.face_end(f); ++v)
            if (*v < 0 || *v >= num_points)
                throw InputError(where + "boundary face " + std::to_string(f) + " uses node " + std::to_string(*v) +
                                 " but the mesh has " + std::to_string(num_points) + " nodes");
        const Index p = b.face_patch[f];
        if (p < 0 || p >= static_cast<Index>(b.patches.size()))
            throw InputError(where + "boundary face " + std::to_string(f) + " is on patch " + std::to_string(p) +
                             " but the mesh has " + std::to_string(b.patches.size()) + " patches");
    }
}

}  // namespace strata
