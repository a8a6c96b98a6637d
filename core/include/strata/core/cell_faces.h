#pragma once
/// \file
/// The local faces of each cell type in Gmsh node order, every face's right-hand normal
/// pointing out of the cell: the one table for everything that walks cell faces (the face
/// matcher, cell volumes, the writers); tests/core/test_validate.cpp checks it against the
/// geometry of Gmsh's reference elements.

#include <strata/core/volume_mesh.h>

#include <algorithm>
#include <array>
#include <utility>

namespace strata {

struct CellFaceTable {
    int count;                               ///< faces per cell
    std::array<int, 6> size;                 ///< 3 or 4 nodes per face
    std::array<std::array<int, 4>, 6> node;  ///< local corner ids per face
};

inline constexpr CellFaceTable kTetFaces{
    4, {3, 3, 3, 3, 0, 0}, {{{0, 2, 1, 0}, {0, 1, 3, 0}, {0, 3, 2, 0}, {3, 1, 2, 0}}}};
inline constexpr CellFaceTable kPyramidFaces{
    5, {4, 3, 3, 3, 3, 0}, {{{0, 3, 2, 1}, {0, 1, 4, 0}, {3, 0, 4, 0}, {1, 2, 4, 0}, {2, 3, 4, 0}}}};
inline constexpr CellFaceTable kPrismFaces{
    5, {3, 3, 4, 4, 4, 0}, {{{0, 2, 1, 0}, {3, 4, 5, 0}, {0, 1, 4, 3}, {0, 3, 5, 2}, {1, 2, 5, 4}}}};
inline constexpr CellFaceTable kHexFaces{
    6, {4, 4, 4, 4, 4, 4}, {{{0, 3, 2, 1}, {0, 1, 5, 4}, {0, 4, 7, 3}, {1, 2, 6, 5}, {2, 3, 7, 6}, {4, 5, 6, 7}}}};

/// The faces of cell type \p t (indexed in CellType order).
inline const CellFaceTable& cell_faces(CellType t) {
    static constexpr std::array<const CellFaceTable*, 4> kTables{&kTetFaces, &kPyramidFaces, &kPrismFaces, &kHexFaces};
    return *kTables[static_cast<std::size_t>(t)];
}

/// The node set of a face (3 or 4 nodes) as a sorted key, a triangle's 4th entry kNone: two
/// faces are the same face exactly when their keys are equal. A sorting network, as this runs
/// once per cell face.
inline std::array<Index, 4> sorted_face_key(const Index* v, int n) {
    std::array<Index, 4> k{v[0], v[1], v[2], n == 4 ? v[3] : kNone};
    auto order = [&k](int i, int j) {
        if (k[j] < k[i]) std::swap(k[i], k[j]);
    };
    if (n == 3) {
        order(0, 1);
        order(1, 2);
        order(0, 1);
    } else {
        order(0, 1);
        order(2, 3);
        order(0, 2);
        order(1, 3);
        order(1, 2);
    }
    return k;
}

/// Whether two faces with the same \p n nodes list them in the same cyclic order (+1),
/// reversed (−1), or neither, or are not the same nodes (0).
inline int relative_orientation(const Index* f, const Index* g, int n) {
    int k = 0;
    while (k < n && g[k] != f[0]) ++k;
    if (k == n) return 0;
    bool same = true, reversed = true;
    for (int i = 0; i < n; ++i) {
        same = same && g[(k + i) % n] == f[i];
        reversed = reversed && g[(k - i + n) % n] == f[i];
    }
    return same ? 1 : reversed ? -1 : 0;
}

}  // namespace strata
