#pragma once
/// \file
/// Unit node normals of a surface mesh.

#include <strata/geometry/surface_mesh.h>
#include <strata/types.h>

#include <string_view>

namespace strata {

enum class NormalMethod {
    AreaWeighted,   ///< sum of incident face area vectors (the paper's)
    AngleWeighted,  ///< incident unit face normals weighted by the face's corner angle at the node
    MaxMinDot,      ///< the unit vector maximising the minimum dot product with the incident
                    ///< face normals (robust at sharp edges and corners)
};
std::string_view to_string(NormalMethod m);
/// "area", "angle", "robust" (throws InputError otherwise).
NormalMethod parse_normal_method(std::string_view text);

/// One unit normal per node for the node positions \p points (#nodes, may differ from
/// mesh.points: the module calls this on every layer). A node no face uses gets (0,0,0).
std::vector<Vec3> node_normals(const SurfaceMesh& mesh, const std::vector<Vec3>& points,
                               NormalMethod method);
/// Same, with the node → face adjacency (vertex_faces(mesh)) precomputed by the caller.
std::vector<Vec3> node_normals(const SurfaceMesh& mesh, const std::vector<Vec3>& points,
                               const Csr& vertex_faces, NormalMethod method);
inline std::vector<Vec3> node_normals(const SurfaceMesh& mesh, NormalMethod method) {
    return node_normals(mesh, mesh.points, method);
}

}  // namespace strata
