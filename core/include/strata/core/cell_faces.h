#pragma once
/// \file
/// The local faces of each cell type in Gmsh node order, every face's right-hand normal
/// pointing out of the cell. One table for every stage that walks cell faces (the validator,
/// the Cobalt60 writer); tests/module/test_validate.cpp checks it against Gmsh's reference
/// elements.

#include <strata/core/volume_mesh.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

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

/// The cell types in the order every stage numbers cells: tetrahedra, pyramids, prisms, hexahedra.
inline constexpr std::array<CellType, 4> kCellTypes{CellType::Tet, CellType::Pyramid, CellType::Prism, CellType::Hex};

inline const CellFaceTable& cell_faces(CellType t) {
    switch (t) {
        case CellType::Tet:
            return kTetFaces;
        case CellType::Pyramid:
            return kPyramidFaces;
        case CellType::Prism:
            return kPrismFaces;
        case CellType::Hex:
            return kHexFaces;
    }
    return kTetFaces;
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

/// Faces grouped by a key (e.g. their smallest node): group k is codes[offsets[k], offsets[k+1]).
template <class Code>
struct FaceBuckets {
    std::vector<std::size_t> offsets;  ///< #keys + 1
    std::vector<Code> codes;
};

/// Counting sort of face codes into \p num_keys groups. \p for_each_face(visit) must call
/// visit(key, code) for every face, the same way on both of its two calls; codes keep that
/// visiting order within a group, so the result is deterministic.
template <class Code, class ForEachFace>
FaceBuckets<Code> bucket_faces_by_key(std::size_t num_keys, ForEachFace&& for_each_face) {
    FaceBuckets<Code> b;
    b.offsets.assign(num_keys + 1, 0);
    for_each_face([&](Index key, std::uint64_t) { ++b.offsets[static_cast<std::size_t>(key) + 1]; });
    for (std::size_t i = 1; i < b.offsets.size(); ++i) b.offsets[i] += b.offsets[i - 1];
    b.codes.resize(b.offsets.back());
    std::vector<std::size_t> fill(b.offsets.begin(), b.offsets.end() - 1);
    for_each_face([&](Index key, std::uint64_t code) {
        b.codes[fill[static_cast<std::size_t>(key)]++] = static_cast<Code>(code);
    });
    return b;
}

/// Every face of \p mesh grouped by its smallest node (bucket_faces_by_key): the faces of the
/// cells (types in kCellTypes order, cells in order, faces in cell_faces order) with code
/// \p cell_code(type, cell, face), then the boundary faces with code \p boundary_code(face).
template <class Code, class CellCode, class BoundaryCode>
FaceBuckets<Code> bucket_faces_by_min_node(const VolumeMesh& mesh, CellCode&& cell_code, BoundaryCode&& boundary_code) {
    const SurfaceMesh& bnd = mesh.boundary;
    const std::array<std::int64_t, 4> counts{
        static_cast<std::int64_t>(mesh.tets.size()), static_cast<std::int64_t>(mesh.pyramids.size()),
        static_cast<std::int64_t>(mesh.prisms.size()), static_cast<std::int64_t>(mesh.hexes.size())};
    auto for_each_face = [&](auto&& visit) {
        for (int t = 0; t < 4; ++t) {
            const CellFaceTable& table = cell_faces(kCellTypes[static_cast<std::size_t>(t)]);
            for (std::int64_t i = 0; i < counts[static_cast<std::size_t>(t)]; ++i) {
                const Index* v = cell_nodes(mesh, t, i);
                for (int f = 0; f < table.count; ++f) {
                    Index m = v[table.node[f][0]];
                    for (int k = 1; k < table.size[f]; ++k) m = std::min(m, v[table.node[f][k]]);
                    visit(m, cell_code(t, i, f));
                }
            }
        }
        for (Index f = 0; f < bnd.num_faces(); ++f)
            visit(*std::min_element(bnd.face_begin(f), bnd.face_end(f)), boundary_code(f));
    };
    return bucket_faces_by_key<Code>(mesh.points.size(), for_each_face);
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

/// A face for sorting: its nodes sorted (a triangle's 4th entry kNone), then its code.
struct KeyedFace {
    std::array<Index, 4> key;
    std::uint64_t code;
    bool operator<(const KeyedFace& o) const { return key != o.key ? key < o.key : code < o.code; }
};

}  // namespace strata
