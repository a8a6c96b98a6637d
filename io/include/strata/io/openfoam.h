#pragma once
/// \file
/// OpenFOAM polyMesh writer: the directory `constant/polyMesh` of a case (points, faces, owner,
/// neighbour, boundary), ASCII, as OpenFOAM's own utilities write it.

#include <strata/core/progress.h>
#include <strata/core/volume_mesh.h>
#include <strata/io/files.h>

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace strata {

/// A boundary patch of a PolyMesh: its faces are [start, start + size) of the face list.
struct PolyPatch {
    std::string name;  ///< an OpenFOAM word (foam_patch_names), unique
    PatchKind kind = PatchKind::Wall;
    std::int64_t start = 0;  ///< first face
    std::int64_t size = 0;   ///< number of faces (≥ 1: patches without faces are left out)
};

/// A volume mesh as OpenFOAM's face-based polyMesh. Cells are numbered as CellNumbering does
/// (tetrahedra, pyramids, prisms, hexahedra). Faces: the internal faces first, in
/// upper-triangular order (by owner, then by neighbour; owner < neighbour), then the boundary
/// faces patch by patch (patch-table order, each patch's faces by owner). Every face's nodes are
/// ordered so that its right-hand normal points out of its owner.
struct PolyMesh {
    std::vector<std::int64_t> face_offsets{0};  ///< #faces + 1, CSR into face_nodes
    std::vector<Index> face_nodes;              ///< 3 or 4 node ids per face
    std::vector<Index> owner;                   ///< #faces, the cell each face points out of
    std::vector<Index> neighbour;               ///< #internal faces, the cell on the other side
    std::vector<PolyPatch> patches;             ///< patches with faces, in patch-table order
    std::int64_t num_cells = 0;

    std::int64_t num_faces() const { return static_cast<std::int64_t>(face_offsets.size()) - 1; }
    std::int64_t num_internal_faces() const { return static_cast<std::int64_t>(neighbour.size()); }
};

/// \p mesh as a PolyMesh. Its arrays must be sound and its faces must match (every cell face
/// shared by exactly two cells or lying on one boundary face): InputError or TopologyError
/// naming the first problem otherwise. \p threads for the face matching (0: OpenMP's default);
/// the result is the same for any count.
PolyMesh to_polymesh(const VolumeMesh& mesh, int threads = 0);

/// The OpenFOAM patch type of a patch kind: "wall", "symmetry", or "patch" (farfield, other).
std::string_view openfoam_patch_type(PatchKind kind);

/// Patch names as OpenFOAM words, one per name (patch_word, surface_mesh.h), a name already
/// taken getting "_2", "_3", ... appended.
std::vector<std::string> foam_patch_names(const std::vector<std::string>& names);

/// Write \p mesh as the OpenFOAM polyMesh directory \p path (its last component is normally
/// `polyMesh`, e.g. "case/constant/polyMesh"): the files points, faces, owner, neighbour and
/// boundary (wall patches of type `wall`, symmetry patches `symmetry`, farfield and other
/// patches `patch`), ASCII, with the FoamFile headers OpenFOAM writes. The directory is built
/// under a temporary name next to \p path and put in place only once complete; an existing
/// directory is replaced as a whole. Does not validate: callers run require_valid_mesh first.
/// InputError (missing parent directory, \p path a file, malformed arrays), TopologyError
/// (faces that do not match). \p progress: stage "writing"; cancelled, nothing is left. Returns
/// the patches written (the boundary file's, for a case's fields: openfoam_case.h).
std::vector<PolyPatch> write_polymesh(const VolumeMesh& mesh, const std::string& path, Progress* progress = nullptr,
                                      OutputSet* outputs = nullptr);

}  // namespace strata
