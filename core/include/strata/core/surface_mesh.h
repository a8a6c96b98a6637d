#pragma once
/// \file
/// The in-memory surface mesh: struct-of-arrays, triangles and quadrilaterals mixed in CSR.

#include <strata/core/types.h>

#include <initializer_list>
#include <string>
#include <utility>
#include <string_view>
#include <vector>

namespace strata {

/// What a patch is to the flow solver and to the layer generator.
enum class PatchKind { Wall, Symmetry, Farfield, Other };

/// "wall", "symmetry", "farfield", "other".
std::string_view to_string(PatchKind kind);
/// Inverse of to_string (case-insensitive); throws InputError naming \p text otherwise.
PatchKind parse_patch_kind(std::string_view text);

/// A named group of faces (a Gmsh physical group, an STL solid, a CAD surface).
struct Patch {
    Patch() = default;
    Patch(std::string name_, PatchKind kind_ = PatchKind::Wall, std::string body_ = {})
        : name(std::move(name_)), kind(kind_), body(std::move(body_)) {}

    std::string name;
    PatchKind kind = PatchKind::Wall;
    /// The CAD body (a solid the file names, as STEP's products) whose faces the patch holds
    /// (empty: none, several, or a name-less one): PrepareParams::patch_kinds and patch_names
    /// take it for all of that body's patches at once.
    std::string body;
};

/// Surface mesh of arbitrary topology. Faces are triangles or quadrilaterals, nodes
/// counter-clockwise so that the right-hand normal points into the flow domain once the
/// mesh has been oriented (orient_surface, geometry/check.h).
struct SurfaceMesh {
    std::vector<Vec3> points;            ///< #nodes, model units
    std::vector<Index> face_offsets{0};  ///< #faces + 1; face f is face_nodes[offsets[f], offsets[f+1])
    std::vector<Index> face_nodes;       ///< node ids, 3 or 4 per face
    std::vector<Index> face_patch;       ///< #faces, index into patches
    std::vector<Patch> patches;          ///< patch table

    Index num_points() const { return static_cast<Index>(points.size()); }
    Index num_faces() const { return static_cast<Index>(face_offsets.size()) - 1; }
    Index face_size(Index f) const { return face_offsets[f + 1] - face_offsets[f]; }
    const Index* face_begin(Index f) const { return face_nodes.data() + face_offsets[f]; }
    const Index* face_end(Index f) const { return face_nodes.data() + face_offsets[f + 1]; }
    Index face_node(Index f, Index i) const { return face_nodes[face_offsets[f] + i]; }

    /// Append a face of 3 or 4 nodes on \p patch.
    void add_face(std::initializer_list<Index> nodes, Index patch);
    void add_face(const Index* nodes, Index n, Index patch);

    Index num_triangles() const;
    Index num_quads() const;
};

/// Reverse the orientation of every face of \p mesh, keeping its first node first (a triangle
/// a b c becomes a c b, a quad a b c d becomes a d c b).
void flip_faces(SurfaceMesh& mesh);

/// Index of the patch called \p name, or kNone.
Index find_patch(const SurfaceMesh& mesh, std::string_view name);

/// \p name as a word every format Strata writes takes as it is (an OpenFOAM word): characters
/// other than letters, digits, '_', '-' and '.' become '_' (a run of them one '_', none at the
/// end), and a name that does not start with a letter or '_' gets "patch_" in front (OpenFOAM
/// would read a number); an empty one is "patch_<index + 1>".
std::string patch_word(std::string_view name, std::size_t index);

}  // namespace strata
