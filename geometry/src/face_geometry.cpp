#include <strata/geometry/face_geometry.h>

namespace strata {

Vec3 face_area_vector(const SurfaceMesh& mesh, const std::vector<Vec3>& points, Index f) {
    const Index* v = mesh.face_begin(f);
    if (mesh.face_size(f) == 3)
        return 0.5 * (points[v[1]] - points[v[0]]).cross(points[v[2]] - points[v[0]]);
    // Quad: half the cross product of the diagonals is the exact vector area of the
    // (possibly non-planar) bilinear quad's boundary loop.
    return 0.5 * (points[v[2]] - points[v[0]]).cross(points[v[3]] - points[v[1]]);
}

Vec3 face_centroid(const SurfaceMesh& mesh, const std::vector<Vec3>& points, Index f) {
    Vec3 c = Vec3::Zero();
    for (const Index* v = mesh.face_begin(f); v != mesh.face_end(f); ++v) c += points[*v];
    return c / static_cast<double>(mesh.face_size(f));
}

BoundingBox bounding_box(const std::vector<Vec3>& points) {
    BoundingBox b;
    if (points.empty()) return b;
    b.min = b.max = points.front();
    for (const Vec3& p : points) {
        b.min = b.min.cwiseMin(p);
        b.max = b.max.cwiseMax(p);
    }
    return b;
}

}  // namespace strata
