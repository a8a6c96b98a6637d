#pragma once
/// \file
/// The local faces of each cell type in Gmsh node order, every face's right-hand normal
/// pointing out of the cell. One table for every stage that walks cell faces (the validator,
/// the Cobalt60 writer); tests/module/test_validate.cpp checks it against Gmsh's reference
/// elements.

#include <strata/module/volume_mesh.h>

#include <array>

namespace strata {

struct CellFaceTable {
    int count;                               ///< faces per cell
    std::array<int, 6> size;                 ///< 3 or 4 nodes per face
    std::array<std::array<int, 4>, 6> node;  ///< local corner ids per face
};

inline constexpr CellFaceTable kTetFaces{4, {3, 3, 3, 3, 0, 0}, {{{0, 2, 1, 0}, {0, 1, 3, 0}, {0, 3, 2, 0}, {3, 1, 2, 0}}}};
inline constexpr CellFaceTable kPyramidFaces{
    5, {4, 3, 3, 3, 3, 0}, {{{0, 3, 2, 1}, {0, 1, 4, 0}, {3, 0, 4, 0}, {1, 2, 4, 0}, {2, 3, 4, 0}}}};
inline constexpr CellFaceTable kPrismFaces{
    5, {3, 3, 4, 4, 4, 0}, {{{0, 2, 1, 0}, {3, 4, 5, 0}, {0, 1, 4, 3}, {0, 3, 5, 2}, {1, 2, 5, 4}}}};
inline constexpr CellFaceTable kHexFaces{
    6, {4, 4, 4, 4, 4, 4}, {{{0, 3, 2, 1}, {0, 1, 5, 4}, {0, 4, 7, 3}, {1, 2, 6, 5}, {2, 3, 7, 6}, {4, 5, 6, 7}}}};

/// The cell types in the order every stage numbers cells: tetrahedra, pyramids, prisms, hexahedra.
inline constexpr std::array<CellType, 4> kCellTypes{CellType::Tet, CellType::Pyramid, CellType::Prism, CellType::Hex};

inline const CellFaceTable& cell_faces(CellType t) {
    switch (t) {
        case CellType::Tet: return kTetFaces;
        case CellType::Pyramid: return kPyramidFaces;
        case CellType::Prism: return kPrismFaces;
        case CellType::Hex: return kHexFaces;
    }
    return kTetFaces;
}

}  // namespace strata
