#include <strata/core/face_geometry.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <limits>

namespace strata {

Vec3 face_area_vector(const SurfaceMesh& mesh, const std::vector<Vec3>& points, Index f) {
    const Index* v = mesh.face_begin(f);
    if (mesh.face_size(f) == 3) return 0.5 * (points[v[1]] - points[v[0]]).cross(points[v[2]] - points[v[0]]);
    // Quad: half the cross product of the diagonals is the exact vector area of the
    // (possibly non-planar) bilinear quad's boundary loop.
    return 0.5 * (points[v[2]] - points[v[0]]).cross(points[v[3]] - points[v[1]]);
}

Vec3 face_centroid(const SurfaceMesh& mesh, const std::vector<Vec3>& points, Index f) {
    Vec3 c = Vec3::Zero();
    for (const Index* v = mesh.face_begin(f); v != mesh.face_end(f); ++v) c += points[*v];
    return c / static_cast<double>(mesh.face_size(f));
}

int quad_shorter_diagonal(const SurfaceMesh& mesh, Index f) {
    const Index* n = mesh.face_begin(f);
    const auto at = [&](int i) -> const Vec3& { return mesh.points[static_cast<std::size_t>(n[i])]; };
    return (at(0) - at(2)).squaredNorm() <= (at(1) - at(3)).squaredNorm() ? 0 : 1;
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

double walls_length(const SurfaceMesh& m) {
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (Index f = 0; f < m.num_faces(); ++f) {
        if (m.patches[static_cast<std::size_t>(m.face_patch[static_cast<std::size_t>(f)])].kind != PatchKind::Wall)
            continue;
        for (Index i = 0, k = m.face_size(f); i < k; ++i) {
            const Vec3& p = m.points[static_cast<std::size_t>(m.face_node(f, i))];
            lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
        }
    }
    return hi.x() >= lo.x() ? (hi - lo).maxCoeff() : 0.0;
}

double median_edge_length(const SurfaceMesh& m) {
    std::vector<double> len;
    for (Index f = 0; f < m.num_faces(); ++f)
        for (Index i = 0, k = m.face_size(f); i < k; ++i)
            len.push_back((m.points[static_cast<std::size_t>(m.face_node(f, (i + 1) % k))] -
                           m.points[static_cast<std::size_t>(m.face_node(f, i))])
                              .norm());
    if (len.empty()) return 0.0;
    const auto mid = len.begin() + static_cast<std::ptrdiff_t>(len.size() / 2);
    std::nth_element(len.begin(), mid, len.end());
    return *mid;
}

PatchPlane fit_plane(const std::vector<Vec3>& pts) {
    PatchPlane pl;
    if (pts.size() < 3) {
        pl.deviation = std::numeric_limits<double>::infinity();
        return pl;
    }
    for (const Vec3& p : pts) pl.point += p;
    pl.point /= static_cast<double>(pts.size());
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    for (const Vec3& p : pts) cov += (p - pl.point) * (p - pl.point).transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(cov);
    pl.normal = es.eigenvectors().col(0).normalized();
    for (const Vec3& p : pts) pl.deviation = std::max(pl.deviation, std::abs((p - pl.point).dot(pl.normal)));
    pl.size = bounding_box(pts).diagonal();
    return pl;
}

PatchPlane patch_plane(const SurfaceMesh& mesh, Index patch) {
    std::vector<char> used(static_cast<std::size_t>(mesh.num_points()), 0);
    std::vector<Vec3> pts;
    Vec3 area = Vec3::Zero();
    for (Index f = 0; f < mesh.num_faces(); ++f) {
        if (mesh.face_patch[f] != patch) continue;
        area += face_area_vector(mesh, f);
        for (const Index* v = mesh.face_begin(f); v != mesh.face_end(f); ++v)
            if (!used[static_cast<std::size_t>(*v)]) {
                used[static_cast<std::size_t>(*v)] = 1;
                pts.push_back(mesh.points[*v]);
            }
    }
    PatchPlane pl = fit_plane(pts);
    if (pl.normal.dot(area) < 0.0) pl.normal = -pl.normal;
    return pl;
}

double signed_volume(const SurfaceMesh& mesh) {
    Vec3 ref = Vec3::Zero();
    for (const Vec3& p : mesh.points) ref += p;
    if (!mesh.points.empty()) ref /= static_cast<double>(mesh.points.size());
    double volume = 0.0;
    for (Index f = 0; f < mesh.num_faces(); ++f)
        volume += (face_centroid(mesh, mesh.points, f) - ref).dot(face_area_vector(mesh, f)) / 3.0;
    return volume;
}

}  // namespace strata
