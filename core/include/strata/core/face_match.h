#pragma once
/// \file
/// How the faces of a volume mesh meet: every local face of every cell and every boundary face,
/// grouped by node set. The one face matcher of Strata: the validator judges the mesh by it,
/// the writers (Cobalt60's face list) number faces by it.

#include <strata/core/volume_mesh.h>

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace strata {

/// Every local face of every cell, numbered in (global cell, local face) order: the slots of
/// cell g's faces are consecutive, g in CellNumbering order, faces in cell_faces order.
class FaceSlots {
public:
    explicit FaceSlots(const VolumeMesh& mesh);

    const VolumeMesh& mesh() const { return *mesh_; }
    const CellNumbering& cells() const { return cells_; }
    /// Number of slots (Σ cells × faces per cell).
    std::uint64_t count() const { return start_[4]; }
    /// First slot of the cells of type \p t.
    std::uint64_t start(CellType t) const { return start_[static_cast<std::size_t>(t)]; }

    struct Slot {
        CellType type;
        std::int64_t index;  ///< cell index within the type
        int face;            ///< local face (cell_faces)
    };
    Slot locate(std::uint64_t slot) const;
    /// Global cell number (CellNumbering) of the cell owning \p slot.
    std::int64_t cell(std::uint64_t slot) const;
    /// The nodes of the face in \p slot, outward from its cell; returns their count (3 or 4).
    int nodes(std::uint64_t slot, Index* out) const;

private:
    const VolumeMesh* mesh_;
    CellNumbering cells_;
    std::array<std::uint64_t, 5> start_{};
};

/// Why a group of faces with one node set is not a clean match (an interior face shared by
/// two cells with opposite orientations, or a cell face with its boundary face).
enum class FaceIssue {
    SharedByThreeOrMoreCells,  ///< three or more cell faces: duplicated or overlapping cells
    NotOpposite,               ///< two cells list the face in the same orientation, or not reversed
    SameCell,                  ///< two faces of one cell have the same nodes (a degenerate cell)
    InteriorOnBoundary,        ///< a face between two cells is also listed in the boundary
    BoundaryDuplicated,        ///< a boundary face listed two or more times
    BoundaryMisoriented,       ///< the boundary face is not its cell's face in the same orientation
    QuadAgainstTriangles,      ///< an unmatched quad whose halves are two unmatched triangles
    Hole,                      ///< a cell face with no neighbouring cell and no boundary face
    StrayBoundary,             ///< a boundary face that is no face of any cell
};

/// The match of every face of a volume mesh. Faces are referred to by code: a slot (below
/// slots.count()) or slots.count() + a boundary face index.
struct FaceMatch {
    FaceSlots slots;
    /// Per slot: the slot across it (an interior face: two cells' faces with one node set and no
    /// boundary face, in whatever orientation), −1 − f for boundary face f (one cell's face and
    /// boundary face f, the first of them), or kUnmatched.
    std::vector<std::int64_t> across;
    static constexpr std::int64_t kUnmatched = std::numeric_limits<std::int64_t>::min();
    std::int64_t interior = 0;  ///< node sets of exactly two cell faces and no boundary face
    std::int64_t boundary = 0;  ///< node sets of one cell face and one or more boundary faces

    /// A group of faces that is not a clean match, with its members' codes: the faces of one
    /// node set, cell faces first (ascending), then boundary faces; for QuadAgainstTriangles the
    /// quad, then the two triangles.
    struct Problem {
        FaceIssue issue;
        std::vector<std::uint64_t> faces;
    };
    /// Every problem, in a fixed order: by node set (smallest node first), then the
    /// QuadAgainstTriangles, Hole and StrayBoundary groups in the order of their faces' node sets.
    std::vector<Problem> problems;

    bool ok() const { return problems.empty(); }
    bool is_slot(std::uint64_t code) const { return code < slots.count(); }
    Index boundary_face(std::uint64_t code) const { return static_cast<Index>(code - slots.count()); }
};

/// Match the faces of \p mesh. Its arrays must be sound (check_volume_arrays: every node and
/// patch id in range, faces of 3 or 4 nodes). Faces are bucketed by their smallest node and
/// sorted by node set within a bucket, O(n log n) and a few bytes per face; buckets are
/// processed in fixed chunks on \p threads threads (0: OpenMP's default) and merged in chunk
/// order, so the result does not depend on the thread count.
FaceMatch match_faces(const VolumeMesh& mesh, int threads = 0);

/// One line for \p problem naming the faces and cells and where they are, e.g. "face (1 4 10 7)
/// is shared by 3 cells: hexahedron 0 at (0.5, 0.5, 0.5), ... (a face joins at most two cells:
/// duplicated or overlapping cells)".
std::string describe(const FaceMatch& match, const FaceMatch::Problem& problem);

}  // namespace strata
