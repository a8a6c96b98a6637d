#pragma once
/// \file
/// The current Gmsh model ↔ Strata's meshes: the one place that turns Gmsh's elements and
/// physical groups into patches and back (gmsh_session.h is the lock and error side of the
/// adapter). Gmsh's 1-based size_t tags appear here and in the few .cpp files that call Gmsh;
/// what leaves these functions is 0-based strata::Index.
///
/// Every function works on the CURRENT model and takes Gmsh's lock (GmshLock): call it inside
/// a GmshSession (Strata's readers, writers and CAD import), or with Gmsh initialised by the
/// user (the Gmsh-API entry point); InputError otherwise.
///
/// Patches, one rule for every reader (a .msh file, a CAD model Gmsh meshed, a user's model):
/// one patch per 2D physical group that holds faces, in group-tag order, named after the group
/// ("physical_<tag>" if unnamed; groups of the same name share one patch); a surface in several
/// groups belongs to the lowest-tagged one; then one patch "surface_<tag>" per surface with
/// faces in no group, in surface-tag order. So a model without physical groups gives one patch
/// per surface entity.

#include <strata/core/error.h>
#include <strata/core/surface_mesh.h>
#include <strata/core/volume_mesh.h>

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace strata {

/// Every node of the current model, sorted by Gmsh tag, and the map from a tag to its 0-based
/// position. The lookup is dense when the tags are compact (the usual case), a binary search
/// when they are very sparse.
class GmshNodes {
public:
    /// Read the current model's nodes. \p context names the model in errors ("'wing.msh'");
    /// Gmsh's failures are BackendError "reading <context>: ...", more nodes than Index holds
    /// an InputError.
    explicit GmshNodes(const std::string& context);

    /// #nodes, model units, in ascending tag order.
    const std::vector<Vec3>& points() const { return points_; }
    std::vector<Vec3> take_points() { return std::move(points_); }
    /// 0-based position of the node tagged \p tag, or kNone if the model has none.
    Index index_of(std::size_t tag) const;

private:
    std::vector<Vec3> points_;
    std::vector<std::size_t> tags_;  // ascending
    std::vector<Index> dense_;       // tag -> position, when dense
};

/// How surface_from_gmsh_model numbers the nodes its faces use.
enum class NodeOrder {
    Tags,      ///< ascending Gmsh tag: a file's or a user's own numbering is kept
    FirstUse,  ///< in order of first use by the faces: a mesh Gmsh has just made from CAD, whose
               ///< tags follow its meshing order (points, curves, surfaces), gets nodes numbered
               ///< surface by surface
};

/// The current model's surface mesh: its 3-node triangles and 4-node quadrangles (higher-order
/// or other 2D types are an InputError naming the surface; points, lines and volume elements
/// are ignored), patches as the file comment says, faces in Gmsh element-tag order, only the
/// nodes the faces use, numbered as \p order says. As stored: no merging, no orientation
/// (surface/prepare.h). \p face_surface, if given, receives the Gmsh surface entity of each
/// face. \p context names the model in errors ("'wing.msh'", "Gmsh model 'sphere'"); InputError
/// "<context> holds no triangles or quadrangles: ..." if it has none.
SurfaceMesh surface_from_gmsh_model(const std::string& context, NodeOrder order = NodeOrder::Tags,
                                    std::vector<int>* face_surface = nullptr);

/// The patch each of \p surfaces would belong to by the rule above, before they are meshed
/// (the same names surface_from_gmsh_model gives once they have faces): surface tag → patch
/// name. For a CAD model's surfaces, all of which get faces.
std::vector<std::pair<int, std::string>> surface_patch_names(const std::vector<int>& surfaces);

/// The current model's volume mesh: its 4-node tetrahedra, 5-node pyramids, 6-node prisms and
/// 8-node hexahedra (other 3D types: InputError naming the volume), each type in element-tag
/// order, every node of the model in tag order, and its 2D elements as the boundary with
/// patches as the file comment says (what add_volume_to_gmsh_model put there comes back in the
/// same order). InputError if the model has no cells.
VolumeMesh volume_from_gmsh_model(const std::string& context);

/// Add \p mesh to the CURRENT Gmsh model: one discrete surface and one 2D physical group per
/// patch with faces (tag = patch index + 1, named after the patch), element tag = face index + 1
/// (so surface_from_gmsh_model restores the face order), node tag = node index + 1, each node
/// on the lowest-numbered patch that uses it; unused nodes are left out. For an empty model
/// (write_surface's scratch model). No checks: check_surface_arrays first.
void add_surface_to_gmsh_model(const SurfaceMesh& mesh);

/// Add \p mesh to the CURRENT Gmsh model: one discrete volume holding every node and cell with
/// a 3D physical group "fluid", one discrete surface and one 2D physical group per non-empty
/// boundary patch, named after the patch. Entity, physical-group, node and element tags start
/// past the largest in use (in an empty model: volume 1, surface = patch index + 1, nodes =
/// index + 1, elements = cell index + 1 in CellNumbering order, then #cells + boundary face
/// index + 1). For a Gmsh user: Gmsh must be initialised (InputError otherwise); a malformed mesh
/// is an InputError naming the cell or face, a patch whose name is a group the model already
/// has an InputError, Gmsh's failures a BackendError. Does not validate: callers run
/// require_valid_mesh first.
void add_volume_to_gmsh_model(const VolumeMesh& mesh);

/// Merge the .msh file \p path into the current model (gmsh::merge, not gmsh::open, which may
/// replace the current model). InputError for a missing or unreadable file, a pipe or device
/// (Gmsh reads files by name), a file that is not MSH or claims more nodes or elements than its
/// size holds (check_msh_counts), a file Gmsh cannot parse (with Gmsh's reason) and one whose
/// mesh does not fit in memory.
void merge_msh_file(const std::string& path);

}  // namespace strata
