#pragma once
/// \file
/// Unit node normals of a surface mesh.

#include <strata/core/enum_names.h>
#include <strata/core/surface_mesh.h>
#include <strata/core/types.h>

#include <string_view>

namespace strata {

/// How a node's normal is made from its incident faces. All four skip degenerate faces
/// (vector area ≤ 1e-12 × the sum of squared edge lengths) and assume the faces are
/// consistently oriented (orient_surface).
///
/// Which to use: on smooth walls, Max. It is exact for nodes on a sphere, however irregular
/// the mesh (the unit sphere meshed by Gmsh at size 0.05: max error 2.6e-15, against 1.5e-2
/// area, 5.3e-3 angle, 7.4e-3 robust), and elsewhere its leading error, O(h) at irregular
/// nodes, is proportional to the difference of the principal curvatures rather than to the
/// curvature, so it is smallest on rounded, near-umbilic walls. The three averages of face
/// normals are first-order accurate wherever the fan around a node is lopsided (O(h) times
/// the curvature), and second-order only on centrally symmetric stencils. Caveat: on strongly
/// anisotropic walls (thin cylinders, saddles) meshed irregularly Max is also first order and
/// no better than AngleWeighted. At sharp edges and corners use MaxMinDot (robust) or
/// AngleWeighted, which give the exact bisector there; Max leans towards the side with the
/// smaller faces, AreaWeighted towards the larger. AreaWeighted stays the default elsewhere.
enum class NormalMethod {
    AreaWeighted,   ///< sum of incident face area vectors, normalised (the paper's); leans
                    ///< towards large faces at sharp edges and corners
    AngleWeighted,  ///< incident unit face normals weighted by the face's interior angle at the
                    ///< node; exact bisector at an edge or corner between planar sides
    MaxMinDot,      ///< the unit vector maximising the minimum dot product with the incident
                    ///< face normals (axis of their smallest enclosing cone): the bisector /
                    ///< diagonal at any sharp edge or corner, however the sides are meshed.
                    ///< Where the face normals span a hemisphere or more (no direction has a
                    ///< positive dot product with all) it falls back to the angle-weighted normal
    Max,            ///< Nelson Max's weights ("Weights for computing vertex normals from facet
                    ///< normals", J. Graphics Tools 4(2), 1999): the sum over incident faces of
                    ///< (e1 × e2) / (|e1|² |e2|²), e1 and e2 the face's two edges leaving the node
                    ///< in counter-clockwise order (for a quad or polygon, the two edges at the
                    ///< node, never a diagonal), normalised. The weight of a face's unit normal is
                    ///< sin(corner angle) / (|e1| |e2|): small faces count more. Exact when the
                    ///< node and its edge neighbours lie on a sphere (inversion about the node maps
                    ///< the sphere to a plane normal to it there, and the terms add up to twice
                    ///< the area vector of the inverted ring of neighbours); this needs a closed
                    ///< fan, so at a mesh boundary or next to a skipped face it is approximate.
                    ///< On other smooth surfaces: O(h |k1 - k2|) at irregular nodes, second order
                    ///< or better on symmetric stencils and at umbilic points. Corners with a
                    ///< zero-length edge are skipped (a node with no other corner gets (0,0,0))
};
/// The methods' names, in enum order: "area", "angle", "robust", "max".
inline constexpr EnumNames<NormalMethod, 4> kNormalMethodNames{{"area", "angle", "robust", "max"}};
inline std::string_view to_string(NormalMethod m) {
    return kNormalMethodNames.name(m);
}
/// Inverse of to_string (case-insensitive); throws InputError naming \p text and the choices.
inline NormalMethod parse_normal_method(std::string_view text) {
    return kNormalMethodNames.parse(text, "LayerParams::normals");
}

/// The unit vector maximising the minimum dot product with \p directions (unit vectors; zero
/// vectors are ignored): the axis of their smallest enclosing cone, computed as MaxMinDot does
/// for face normals, but for any set (the module uses the corner normals of the cells at a
/// node). \p min_dot receives that minimum; it is ≤ 0 when the directions span a hemisphere
/// or more, and then no direction has a positive dot product with all of them and the axis
/// returned means nothing. With no nonzero direction: (0,0,0) and min_dot = −1.
Vec3 max_min_dot_direction(const std::vector<Vec3>& directions, double* min_dot = nullptr);

/// One unit normal per node for the node positions \p points (#nodes, model units; may differ
/// from mesh.points: the module calls this on every layer). A node no usable face touches gets
/// (0,0,0), as does a node whose face normals cancel (a folded surface). Nodes are independent
/// of each other, computed on \p threads threads (0: OpenMP's default; the result is the same
/// for any count). Throws InputError if \p points does not have one entry per mesh node.
std::vector<Vec3> node_normals(const SurfaceMesh& mesh, const std::vector<Vec3>& points, NormalMethod method,
                               int threads = 0);
/// Same, with the node → face adjacency (vertex_faces(mesh)) precomputed by the caller; it
/// allocates nothing but the result, so it suits a loop over smoothing sweeps. Throws
/// InputError if \p vertex_faces does not have one row per node.
std::vector<Vec3> node_normals(const SurfaceMesh& mesh, const std::vector<Vec3>& points, const Csr& vertex_faces,
                               NormalMethod method, int threads = 0);

/// Scratch space node_normals_at keeps between calls, so that a loop calling it allocates
/// nothing once it has grown.
struct NormalScratch {
    std::vector<Vec3> areas;       ///< per face: its vector area (zero where degenerate)
    std::vector<Vec3> units;       ///< per face: areas normalised (zero where degenerate)
    std::vector<Index> faces;      ///< the faces evaluated by the last call
    std::vector<char> face_marked; ///< per face: 0 between calls
    std::vector<char> node_marked; ///< per node: 0 between calls

    void set(Index f, const Vec3& area) {
        areas[static_cast<std::size_t>(f)] = area;
        units[static_cast<std::size_t>(f)] = area.normalized();
    }
};

/// node_normals at \p nodes only (node ids, each once), for a loop that moves the points and
/// needs the normals where something moved (the layers' smoothing sweeps): \p normals (resized
/// to one per node) gets those nodes' normals, its other entries are left as they are. Each
/// face round them is evaluated once, not once per corner. Node for node the same values as
/// node_normals, for any thread count.
void node_normals_at(const SurfaceMesh& mesh, const std::vector<Vec3>& points, const Csr& vertex_faces,
                     NormalMethod method, const std::vector<Index>& nodes, NormalScratch& scratch,
                     std::vector<Vec3>& normals, int threads = 0);

inline std::vector<Vec3> node_normals(const SurfaceMesh& mesh, NormalMethod method) {
    return node_normals(mesh, mesh.points, method);
}

}  // namespace strata
