#pragma once
/// \file
/// The one sanity check of a mesh's arrays, run before anything indexes them: by the surface
/// checks of the geometry stage, the validator, every writer and the TetGen adapter. It finds
/// what would make indexing undefined or an output meaningless; whether the mesh is a valid
/// surface or volume (manifold, oriented, conforming, positive cells) is for check_surface and
/// validate_mesh.

#include <strata/core/surface_mesh.h>
#include <strata/core/volume_mesh.h>

#include <cstddef>
#include <string>
#include <vector>

namespace strata {

/// What is wrong with a mesh's arrays: each problem one line naming the entity.
struct MeshProblems {
    static constexpr std::size_t kMaxLines = 5;
    std::vector<std::string> lines;  ///< the first kMaxLines problems, in the order found
    std::size_t count = 0;           ///< every problem found
    bool indexable = true;           ///< false: malformed CSR or an id out of range; do not index the arrays
    bool first_non_finite = false;   ///< the first problem is a NaN or infinite coordinate

    bool ok() const { return count == 0; }
    void add(std::string line, bool non_finite = false);
};

/// What check_face_arrays asks of the faces.
struct FaceRules {
    bool require_faces = true;    ///< no faces is a problem
    bool triangles_only = false;  ///< a quadrilateral is a problem (TetGen's input)
    bool coordinates = true;      ///< a non-finite coordinate in the points is a problem
    bool patches = true;          ///< face_patch must hold a patch of mesh.patches per face
    const char* word = "face";    ///< how messages name a face ("face", "boundary face")
};

/// The faces of a surface mesh, indexing \p points (mesh.points, or a volume mesh's points for
/// its boundary): no faces, malformed CSR (face_offsets that do not rise from 0 to the number of
/// face nodes, a face_patch not one per face), a face of other than 3 or
/// 4 nodes (or 3), a node id outside \p points, a patch id outside mesh.patches, a non-finite
/// coordinate in \p points, as \p rules ask.
MeshProblems check_face_arrays(const SurfaceMesh& mesh, const std::vector<Vec3>& points, const FaceRules& rules = {});
/// A surface mesh's own faces and points.
inline MeshProblems check_surface_arrays(const SurfaceMesh& mesh, const FaceRules& rules = {}) {
    return check_face_arrays(mesh, mesh.points, rules);
}
/// A volume mesh: no cells, a cell corner outside points, then its boundary faces
/// (check_face_arrays, "boundary face") and its coordinates.
MeshProblems check_volume_arrays(const VolumeMesh& mesh);

/// Throw the first problem as "<where><problem>": TopologyError if it is a non-finite
/// coordinate (the geometry is broken), InputError otherwise (the arrays are); nothing if ok.
void require_sound(const MeshProblems& problems, const std::string& where);

}  // namespace strata
