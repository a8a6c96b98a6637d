#pragma once
/// \file
/// Geometry of single faces: area vector, unit normal, centroid. Quads use the
/// cross product of their diagonals (exact vector area of a non-planar quad).

#include <strata/core/surface_mesh.h>

namespace strata {

/// Vector area of face \p f with node positions \p points (#nodes): |a| = area,
/// direction = right-hand normal of the node order.
Vec3 face_area_vector(const SurfaceMesh& mesh, const std::vector<Vec3>& points, Index f);
inline Vec3 face_area_vector(const SurfaceMesh& mesh, Index f) {
    return face_area_vector(mesh, mesh.points, f);
}
/// Centroid (mean of the corners) of face \p f.
Vec3 face_centroid(const SurfaceMesh& mesh, const std::vector<Vec3>& points, Index f);
/// The corner of quad face \p f where its shorter diagonal starts: 0 for the diagonal 0–2 (also
/// on a tie), 1 for 1–3. A quad split into two triangles is split along it.
int quad_shorter_diagonal(const SurfaceMesh& mesh, Index f);

/// Volume a closed surface encloses, signed by its orientation (positive for normals outward),
/// measured from the centroid of its points so that a body far from the origin keeps it.
double signed_volume(const SurfaceMesh& mesh);

/// Axis-aligned bounding box of \p points; diagonal() of an empty set is 0.
struct BoundingBox {
    Vec3 min = Vec3::Constant(0.0), max = Vec3::Constant(0.0);
    double diagonal() const { return (max - min).norm(); }
};
BoundingBox bounding_box(const std::vector<Vec3>& points);

/// The walls' length: the largest side of the bounding box of the nodes of the faces on wall
/// patches (PatchKind::Wall); 0 without wall faces. A body's length, a wing's span.
double walls_length(const SurfaceMesh& mesh);

/// The median length of the faces' edges (each counted once per face using it); 0 without faces.
double median_edge_length(const SurfaceMesh& mesh);

/// Least-squares plane through the nodes of the faces of one patch.
struct PatchPlane {
    Vec3 point = Vec3::Zero();    ///< centroid of the patch's nodes
    Vec3 normal = Vec3::UnitZ();  ///< unit, on the side the faces' normals point to
    double deviation = 0.0;       ///< largest distance of a node from the plane
    double size = 0.0;            ///< bounding-box diagonal of the patch's nodes
    /// Flat to within \p rel_tol of the patch's size (CAD planes and STL planes are flat to
    /// round-off).
    bool planar(double rel_tol = 1e-6) const { return deviation <= rel_tol * size; }
};
/// The plane of the faces of \p mesh on patch \p patch (no faces: size 0, not planar).
PatchPlane patch_plane(const SurfaceMesh& mesh, Index patch);
/// The least-squares plane through \p points (fewer than 3: not planar); the normal's sign is
/// arbitrary.
PatchPlane fit_plane(const std::vector<Vec3>& points);

}  // namespace strata
