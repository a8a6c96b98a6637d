// Faces where closed bodies touch along a common face: touching.h.

#include "cgal_kernel.h"

#include <strata/core/face_geometry.h>
#include <strata/geometry/intersections.h>
#include <strata/geometry/touching.h>

#include <CGAL/box_intersection_d.h>

#include <algorithm>

namespace strata {
namespace {

using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, std::size_t>;

/// Whether \p p lies within \p tol of the plane of triangle \p t (unit normal \p n).
bool near_plane(const Vec3& p, const std::array<Vec3, 3>& t, const Vec3& n, double tol) {
    return std::abs((p - t[0]).dot(n)) <= tol;
}

/// Whether \p p, projected along \p n onto triangle \p t's plane, lies inside \p t (its
/// boundary included, within \p tol).
bool inside(const Vec3& p, const std::array<Vec3, 3>& t, const Vec3& n, double tol) {
    for (int i = 0; i < 3; ++i) {
        const Vec3& a = t[static_cast<std::size_t>(i)];
        const Vec3& b = t[static_cast<std::size_t>((i + 1) % 3)];
        const Vec3 e = b - a;
        const double len = e.norm();
        // Signed distance of p from edge a-b, positive inside.
        if (!(len > 0.0) || n.cross(e).dot(p - a) / len < -tol) return false;
    }
    return true;
}

}  // namespace

std::vector<Index> touching_faces(const SurfaceMesh& mesh, double rel_tol) {
    const std::vector<SurfaceTriangle> tris = surface_triangles(mesh);
    if (tris.empty()) return {};
    const double tol = rel_tol * bounding_box(mesh.points).diagonal();
    std::vector<std::array<Vec3, 3>> x(tris.size());
    std::vector<Vec3> normal(tris.size());
    std::vector<Box> boxes;
    boxes.reserve(tris.size());
    for (std::size_t i = 0; i < tris.size(); ++i) {
        for (int c = 0; c < 3; ++c)
            x[i][static_cast<std::size_t>(c)] = mesh.points[static_cast<std::size_t>(tris[i].v[c])];
        normal[i] = (x[i][1] - x[i][0]).cross(x[i][2] - x[i][0]).normalized();
        Vec3 lo = x[i][0].cwiseMin(x[i][1]).cwiseMin(x[i][2]), hi = x[i][0].cwiseMax(x[i][1]).cwiseMax(x[i][2]);
        lo.array() -= tol;
        hi.array() += tol;
        boxes.emplace_back(CGAL::Bbox_3(lo.x(), lo.y(), lo.z(), hi.x(), hi.y(), hi.z()), i);
    }
    std::vector<char> covered(tris.size(), 0);
    auto centre = [&](std::size_t i) { return Vec3((x[i][0] + x[i][1] + x[i][2]) / 3.0); };
    auto back_to_back = [&](std::size_t a, std::size_t b) {
        if (!(normal[a].dot(normal[b]) < 0.0)) return false;
        for (const Vec3& p : x[a])
            if (!near_plane(p, x[b], normal[b], tol)) return false;
        for (const Vec3& p : x[b])
            if (!near_plane(p, x[a], normal[a], tol)) return false;
        return true;
    };
    // Each candidate pair marks only its own two triangles: the result does not depend on the
    // order CGAL reports the pairs in.
    CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), [&](const Box& p, const Box& q) {
        const std::size_t a = p.info(), b = q.info();
        if (tris[a].face == tris[b].face || !back_to_back(a, b)) return;
        if (inside(centre(a), x[b], normal[b], tol)) covered[a] = 1;
        if (inside(centre(b), x[a], normal[a], tol)) covered[b] = 1;
    });
    // A face touches where every one of its triangles does.
    std::vector<char> face_all(static_cast<std::size_t>(mesh.num_faces()), 0);
    std::vector<char> face_any_open(static_cast<std::size_t>(mesh.num_faces()), 0);
    for (std::size_t i = 0; i < tris.size(); ++i) {
        const auto f = static_cast<std::size_t>(tris[i].face);
        face_all[f] = 1;
        if (!covered[i]) face_any_open[f] = 1;
    }
    std::vector<Index> out;
    for (Index f = 0; f < mesh.num_faces(); ++f)
        if (face_all[static_cast<std::size_t>(f)] && !face_any_open[static_cast<std::size_t>(f)]) out.push_back(f);
    return out;
}

}  // namespace strata
