#pragma once
/// \file
/// The volume mesh every later stage produces: struct-of-arrays, cells per type in
/// fixed-width blocks, Gmsh node order (FORMATS.md), boundary faces with patches.

#include <strata/core/surface_mesh.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace strata {

enum class CellType { Tet, Pyramid, Prism, Hex };

/// The cell types in the order every stage numbers cells (CellNumbering): tetrahedra,
/// pyramids, prisms, hexahedra.
inline constexpr std::array<CellType, 4> kCellTypes{CellType::Tet, CellType::Pyramid, CellType::Prism, CellType::Hex};

/// Corners per cell type: 4, 5, 6, 8.
constexpr int cell_corners(CellType t) {
    constexpr std::array<int, 4> kCorners{4, 5, 6, 8};
    return kCorners[static_cast<std::size_t>(t)];
}
/// "tetrahedron", "pyramid", "prism", "hexahedron".
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
    /// Per cell in CellNumbering order, the boundary layer it belongs to (1: on the wall), 0 for
    /// cells outside the layers (the pyramids on their top, the tetrahedra beyond); empty where
    /// not known (a mesh read from a file). Writers that carry it (.vtu) use it only when it
    /// has one entry per cell.
    std::vector<std::int32_t> cell_layers;

    Index num_cells() const { return static_cast<Index>(tets.size() + pyramids.size() + prisms.size() + hexes.size()); }
    /// Cells of type \p t.
    std::size_t num_cells(CellType t) const;
    /// The cell_corners(t) corners of cell \p i of type \p t.
    const Index* cell(CellType t, std::size_t i) const;
    /// \p f(cells) on the block of cells of type \p t (a std::vector<std::array<Index, N>>).
    template <class F>
    decltype(auto) with_cells(CellType t, F&& f) const {
        switch (t) {
            case CellType::Tet:
                return f(tets);
            case CellType::Pyramid:
                return f(pyramids);
            case CellType::Prism:
                return f(prisms);
            case CellType::Hex:
                break;
        }
        return f(hexes);
    }
};

/// Global cell numbers, one order for every stage and writer: tetrahedra first, then
/// pyramids, prisms, hexahedra (kCellTypes), each block in VolumeMesh order.
class CellNumbering {
public:
    explicit CellNumbering(const VolumeMesh& mesh);
    std::int64_t count() const { return start_[4]; }
    std::int64_t count(CellType t) const { return start(next(t)) - start(t); }
    /// Global number of the first cell of type \p t.
    std::int64_t start(CellType t) const { return start_[static_cast<std::size_t>(t)]; }

    struct Cell {
        CellType type;
        std::int64_t index;  ///< within the type
    };
    /// The type and index within the type of global cell \p g (0 ≤ g < count()).
    Cell locate(std::int64_t g) const;

private:
    static std::size_t next(CellType t) { return static_cast<std::size_t>(t) + 1; }
    std::int64_t start(std::size_t k) const { return start_[k]; }
    std::array<std::int64_t, 5> start_{};
};

/// "prism 12 at (x, y, z)" (the centroid): how messages name a cell.
std::string describe_cell(const VolumeMesh& mesh, CellType t, std::int64_t i);

/// Append \p from to \p to with every node id mapped through \p map (a callable Index → Index):
/// how assembly moves one stage's cells into the numbering of the whole mesh.
template <std::size_t N, class NodeMap>
void append_cells(std::vector<std::array<Index, N>>& to, const std::vector<std::array<Index, N>>& from, NodeMap&& map) {
    to.reserve(to.size() + from.size());
    for (const std::array<Index, N>& c : from) {
        std::array<Index, N> m;
        for (std::size_t k = 0; k < N; ++k) m[k] = map(c[k]);
        to.push_back(m);
    }
}

}  // namespace strata
