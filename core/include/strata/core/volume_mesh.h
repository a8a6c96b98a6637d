#pragma once
/// \file
/// The volume mesh every later stage produces: struct-of-arrays, cells per type in
/// fixed-width blocks, Gmsh node order (FORMATS.md), boundary faces with patches.

#include <strata/core/surface_mesh.h>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace strata {

enum class CellType { Tet, Pyramid, Prism, Hex };
/// Corners per cell type: 4, 5, 6, 8.
int cell_corners(CellType t);
std::string_view to_string(CellType t);

struct VolumeMesh {
    std::vector<Vec3> points;                    ///< #nodes, model units
    std::vector<std::array<Index, 4>> tets;      ///< 0-1-2-3, positive det(v1−v0, v2−v0, v3−v0)
    std::vector<std::array<Index, 5>> pyramids;  ///< base 0-1-2-3, apex 4
    std::vector<std::array<Index, 6>> prisms;    ///< bottom 0-1-2, top 3-4-5 (3 above 0)
    std::vector<std::array<Index, 8>> hexes;     ///< bottom 0-1-2-3, top 4-5-6-7 (4 above 0)
    /// Boundary faces (3 or 4 nodes) in CSR with a patch each, right-hand normals pointing out
    /// of the meshed region.
    SurfaceMesh boundary;  ///< boundary.points unused (faces index `points`)

    Index num_cells() const {
        return static_cast<Index>(tets.size() + pyramids.size() + prisms.size() + hexes.size());
    }
};

/// The corners of cell \p i of type \p type (0 tet, 1 pyramid, 2 prism, 3 hexahedron: the
/// order of CellType) in \p m.
inline const Index* cell_nodes(const VolumeMesh& m, int type, std::int64_t i) {
    const auto k = static_cast<std::size_t>(i);
    switch (type) {
        case 0:
            return m.tets[k].data();
        case 1:
            return m.pyramids[k].data();
        case 2:
            return m.prisms[k].data();
        default:
            return m.hexes[k].data();
    }
}

/// Refuse a malformed mesh before a writer hands it on: no cells, a node id out of range, a
/// non-finite coordinate, malformed boundary CSR, a boundary face that is not a triangle or a
/// quad, a patch id out of range. \p where prefixes every message ("cannot write 'm.msh': ").
/// Throws InputError (TopologyError for a non-finite coordinate).
void check_volume_mesh(const VolumeMesh& mesh, const std::string& where);

}  // namespace strata
