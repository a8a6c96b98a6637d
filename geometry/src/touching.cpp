// Faces where closed bodies touch along a common face: touching.h.

#include <strata/geometry/cgal_kernel.h>

#include <strata/core/face_geometry.h>
#include <strata/geometry/intersections.h>
#include <strata/geometry/topology.h>
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

/// Where a body touches only part of another's face (a cabin box on a longer body's top), the
/// covered side would go and the other stay, leaving an edge with one face: such faces are not
/// back to back over their whole extent, and only a Boolean union (fuse.h) can join the bodies
/// there. Every connected group of \p drop (across edges) with an edge that removing it would
/// leave with an odd number of faces is kept.
void keep_where_partial(const SurfaceMesh& mesh, std::vector<char>& drop) {
    const EdgeTable et = edge_table(mesh);
    const auto ne = et.nodes.size();
    // Groups: union-find over the edges two dropped faces share.
    std::vector<Index> parent(drop.size());
    for (std::size_t f = 0; f < drop.size(); ++f) parent[f] = static_cast<Index>(f);
    auto find = [&](Index f) {
        while (parent[static_cast<std::size_t>(f)] != f)
            f = parent[static_cast<std::size_t>(f)] =
                parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(f)])];
        return f;
    };
    std::vector<char> odd(ne, 0);
    for (std::size_t e = 0; e < ne; ++e) {
        const Index* fs = et.faces.row_begin(static_cast<Index>(e));
        const Index n = et.faces.row_size(static_cast<Index>(e));
        Index dropped = 0, first = kNone;
        for (Index k = 0; k < n; ++k) {
            if (!drop[static_cast<std::size_t>(fs[k])]) continue;
            ++dropped;
            if (first == kNone)
                first = fs[k];
            else
                parent[static_cast<std::size_t>(find(fs[k]))] = find(first);
        }
        odd[e] = dropped > 0 && (n - dropped) % 2 == 1;
    }
    std::vector<char> partial(drop.size(), 0);
    for (std::size_t e = 0; e < ne; ++e) {
        if (!odd[e]) continue;
        const Index* fs = et.faces.row_begin(static_cast<Index>(e));
        for (Index k = 0; k < et.faces.row_size(static_cast<Index>(e)); ++k)
            if (drop[static_cast<std::size_t>(fs[k])]) partial[static_cast<std::size_t>(find(fs[k]))] = 1;
    }
    for (std::size_t f = 0; f < drop.size(); ++f)
        if (drop[f] && partial[static_cast<std::size_t>(find(static_cast<Index>(f)))]) drop[f] = 0;
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
    const auto nf = static_cast<std::size_t>(mesh.num_faces());
    std::vector<char> drop(nf, 0);
    for (std::size_t f = 0; f < nf; ++f) drop[f] = face_all[f] && !face_any_open[f];
    keep_where_partial(mesh, drop);
    std::vector<Index> out;
    for (std::size_t f = 0; f < nf; ++f)
        if (drop[f]) out.push_back(static_cast<Index>(f));
    return out;
}

}  // namespace strata
