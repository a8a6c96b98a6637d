// Target "writers"' decoder: the fuzzer's bytes as a small volume mesh of every cell type with
// boundary patches (volume_soup.h).

#include <strata/core/cell_faces.h>

#include "fuzz_support.h"
#include "volume_soup.h"

#include <array>
#include <map>
#include <string>
#include <vector>

namespace strata::fuzz {
namespace {

constexpr std::array<const char*, 4> kPlainNames = {"wall", "farfield", "symmetry", "outlet"};
/// Names the writers must change: a CGNS section's name, a '/' and control characters, a blank
/// name, one over CGNS's 32 characters.
constexpr std::array<const char*, 4> kAwkwardNames = {"Hexahedra", "inlet/left\twall", " ",
                                                      "a patch name longer than thirty-two characters"};
constexpr std::array<PatchKind, 4> kKinds = {PatchKind::Wall, PatchKind::Farfield, PatchKind::Symmetry,
                                             PatchKind::Other};

/// Every cell face that no other cell face and no boundary face has (the same node set) becomes a
/// boundary face, as its cell lists it, on the patches in turn.
void complete_boundary(VolumeMesh& m) {
    std::map<std::array<Index, 4>, int> count;
    for (Index f = 0; f < m.boundary.num_faces(); ++f)
        ++count[sorted_face_key(m.boundary.face_begin(f), static_cast<int>(m.boundary.face_size(f)))];
    auto each_face = [&m](auto&& f) {
        for (CellType t : kCellTypes) {
            const CellFaceTable& table = cell_faces(t);
            for (std::size_t i = 0; i < m.num_cells(t); ++i)
                for (std::size_t k = 0; k < static_cast<std::size_t>(table.count); ++k) {
                    std::array<Index, 4> v{};
                    for (std::size_t j = 0; j < static_cast<std::size_t>(table.size[k]); ++j)
                        v[j] = m.cell(t, i)[table.node[k][j]];
                    f(v, table.size[k]);
                }
        }
    };
    each_face([&](const std::array<Index, 4>& v, int n) { ++count[sorted_face_key(v.data(), n)]; });
    Index patch = 0;
    const auto npatches = static_cast<Index>(m.boundary.patches.size());
    each_face([&](const std::array<Index, 4>& v, int n) {
        if (count[sorted_face_key(v.data(), n)] != 1) return;
        m.boundary.add_face(v.data(), n, patch);
        patch = (patch + 1) % npatches;
    });
}

/// Break the arrays the way a caller's own code might (what: bits 0-2 which array, bits 3-7 a
/// position; value: the new value): each writer must refuse the mesh, not index through it.
void corrupt(VolumeMesh& m, std::uint8_t what, std::uint8_t value) {
    const std::size_t at = what >> 3;
    SurfaceMesh& b = m.boundary;
    std::vector<Index*> corners;
    for (CellType t : kCellTypes)
        for (std::size_t i = 0; i < m.num_cells(t); ++i)
            for (int k = 0; k < cell_corners(t); ++k) corners.push_back(const_cast<Index*>(m.cell(t, i)) + k);
    switch (what & 7) {
        case 0:  // malformed CSR: the offsets from one on shifted by value - 128, all but the last
        case 1:  // a patch entry too few or too many
            corrupt_faces(b, what & 7, at, value);
            break;
        case 2:  // a negative cell corner
            if (!corners.empty()) *corners[at % corners.size()] = Index{value} - 256;
            break;
        case 3:  // nodes dropped from the end
            m.points.resize(value % (m.points.size() + 1));
            break;
        case 4:  // patches dropped from the end
            b.patches.resize(value % (b.patches.size() + 1));
            break;
        case 5:  // a negative boundary node
            corrupt_faces(b, 2, at, value);
            break;
        case 6:  // a cell corner set to value, in range or not
            if (!corners.empty()) *corners[at % corners.size()] = Index{value};
            break;
        default:  // the last offset off the number of face nodes
            b.face_offsets.back() += Index{value} - 128;
            break;
    }
}

}  // namespace

/// The volume soup format, byte by byte (every byte string decodes to something):
///
///   flags      bits 0-1  number of patches - 1
///              bit 2     awkward patch names (kAwkwardNames) instead of kPlainNames
///              bit 3     complete the boundary (complete_boundary above) after the records
///              bits 4-5  patch p has kind kKinds[(p + bits) % 4]
///              bit 6     every patch named as patch 0
///              bit 7     corrupt the arrays after decoding: two more bytes, what and value
///                        (corrupt() above)
///   N          number of nodes, 0-255
///   N nodes    each a byte and what follows it (decode_point, fuzz_support.h)
///   records    until the end, a header byte h and the node ids of a cell or a boundary face:
///              bit 2 clear: a cell, of type kCellTypes[bits 0-1] (tetrahedron, pyramid, prism,
///                           hexahedron), with its corners in Gmsh order
///              bit 2 set:   a boundary face, a triangle (bit 0 clear) or a quadrilateral
///              bit 3        ids taken as they are (may be out of range) instead of modulo N
///              bits 4-7     a boundary face's patch: modulo the number of patches, or with
///                           bit 3 set (h >> 4) - 1, which may be out of range
///              A record cut short by the end is left out.
VolumeMesh decode_volume(const std::uint8_t* data, std::size_t size) {
    VolumeMesh m;
    Bytes in(data, size);
    std::uint8_t flags = 0, what = 0, value = 0;
    if (!in.byte(flags)) return m;
    const bool corrupted = (flags & 0x80) && in.byte(what) && in.byte(value);
    const unsigned num_patches = (flags & 3u) + 1;
    const auto& names = (flags & 4) ? kAwkwardNames : kPlainNames;
    for (unsigned p = 0; p < num_patches; ++p)
        m.boundary.patches.push_back({names[(flags & 0x40) ? 0 : p], kKinds[(p + ((flags >> 4) & 3u)) % 4]});

    if (!decode_points(in, m.points)) return m;
    const auto n = static_cast<Index>(m.points.size());

    for (std::uint8_t h = 0; in.byte(h);) {
        const bool face = h & 4;
        const CellType type = kCellTypes[h & 3u];
        const int k = face ? 3 + (h & 1) : cell_corners(type);
        std::array<Index, 8> v{};
        if (!decode_ids(in, k, h & 8, n, v.data())) break;
        if (face) {
            const Index patch = (h & 8) ? Index{h >> 4} - 1 : Index{h >> 4} % static_cast<Index>(num_patches);
            m.boundary.add_face(v.data(), k, patch);
            continue;
        }
        switch (type) {
            case CellType::Tet:
                m.tets.push_back({v[0], v[1], v[2], v[3]});
                break;
            case CellType::Pyramid:
                m.pyramids.push_back({v[0], v[1], v[2], v[3], v[4]});
                break;
            case CellType::Prism:
                m.prisms.push_back({v[0], v[1], v[2], v[3], v[4], v[5]});
                break;
            case CellType::Hex:
                m.hexes.push_back({v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7]});
                break;
        }
    }
    if (flags & 8) complete_boundary(m);
    if (corrupted) corrupt(m, what, value);
    return m;
}

}  // namespace strata::fuzz
