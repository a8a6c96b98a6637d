#pragma once
/// \file
/// The current Gmsh model as Strata meshes: the model side of the Gmsh adapter (gmsh_session.h
/// is its lock and error side). Gmsh's 1-based size_t tags appear here and in the few .cpp
/// files that call Gmsh; what leaves these functions is 0-based strata::Index.
///
/// Every function works on the CURRENT model and takes Gmsh's lock (GmshLock): call it inside
/// a GmshSession (Strata's readers), or with Gmsh initialised by the user (the Gmsh-API entry
/// point); InputError otherwise.

#include <strata/core/error.h>
#include <strata/core/surface_mesh.h>

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

/// The current model's 2D elements with every node numbered as in \p nodes (so points stay
/// empty and faces index nodes.points()): how a volume reader gets its boundary faces.
/// Patches and checks as surface_from_gmsh_model, except that a model without triangles or
/// quadrangles gives an empty mesh instead of an error.
SurfaceMesh surface_faces_from_gmsh_model(const std::string& context, const GmshNodes& nodes);

/// The current model's surface mesh: its 3-node triangles and 4-node quadrangles (higher-order
/// or other 2D types are an InputError naming the surface; points, lines and volume elements
/// are ignored). One patch per 2D physical group in tag order, named after it ("physical_<tag>"
/// if unnamed; groups of the same name share a patch); a surface in several groups goes to the
/// lowest-tagged one; a surface in no group gets a patch "surface_<tag>"; so with no physical
/// groups at all, one patch per surface entity. Faces in Gmsh element-tag order; nodes in tag
/// order, only those the faces use. As stored: no merging, no orientation (prepare.h).
/// \p context names the model in errors ("'wing.msh'", "Gmsh model 'sphere'"); InputError
/// "<context> holds no triangles or quadrangles: ..." if it has none.
SurfaceMesh surface_from_gmsh_model(const std::string& context);

/// Merge the .msh file \p path into the current model (gmsh::merge, not gmsh::open, which may
/// replace the current model). InputError for a missing or unreadable file and for a file Gmsh
/// cannot parse (with Gmsh's reason).
void merge_msh_file(const std::string& path);

/// The error for an element type a reader does not take: "<context>: volume 3 holds 'Tetrahedron
/// 10' elements (Gmsh type 11, 10 nodes): only <supported> are supported; convert the mesh to
/// first order ...". \p dim is the entity's dimension (2 or 3). Call with Gmsh's lock held.
InputError unsupported_gmsh_element(const std::string& context, int dim, int entity, int type,
                                    const std::string& supported);

}  // namespace strata
