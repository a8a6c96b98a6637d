#include <strata/error.h>
#include <strata/geometry/face_geometry.h>
#include <strata/hybrid/farfield.h>

#include <algorithm>
#include <cctype>
#include <map>
#include <string>

namespace strata {

FarfieldShape parse_farfield_shape(std::string_view text) {
    std::string t(text);
    std::transform(t.begin(), t.end(), t.begin(), [](unsigned char c) { return std::tolower(c); });
    if (t == "box") return FarfieldShape::Box;
    if (t == "sphere") return FarfieldShape::Sphere;
    throw InputError("--farfield " + std::string(text) + ": use box or sphere");
}

namespace {

/// Box [c − h, c + h]³, each side an n × n grid of squares split into triangles, outward.
SurfaceMesh box(const Vec3& c, double h, int n) {
    SurfaceMesh m;
    m.patches.push_back({"farfield", PatchKind::Farfield});
    std::map<std::array<int, 3>, Index> ids;  // lattice coordinates → node (shared edges)
    auto node = [&](int i, int j, int k) {
        const std::array<int, 3> key{i, j, k};
        auto it = ids.find(key);
        if (it != ids.end()) return it->second;
        const Index id = m.num_points();
        m.points.push_back(c + h * Vec3(2.0 * i / n - 1.0, 2.0 * j / n - 1.0, 2.0 * k / n - 1.0));
        ids.emplace(key, id);
        return id;
    };
    // For each axis and side, (u, v) span the face so that u × v points outward.
    for (int axis = 0; axis < 3; ++axis)
        for (int side = 0; side < 2; ++side) {
            const int a = (axis + 1) % 3, b = (axis + 2) % 3;
            for (int i = 0; i < n; ++i)
                for (int j = 0; j < n; ++j) {
                    auto at = [&](int u, int v) {
                        std::array<int, 3> p{};
                        p[axis] = side * n;
                        p[a] = u;
                        p[b] = v;
                        return node(p[0], p[1], p[2]);
                    };
                    Index q[4] = {at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)};
                    if (side == 0) std::swap(q[1], q[3]);  // e_a × e_b = +e_axis: reverse on the low side
                    // Alternate the diagonal for a symmetric triangulation.
                    if ((i + j) % 2 == 0) {
                        m.add_face({q[0], q[1], q[2]}, 0);
                        m.add_face({q[0], q[2], q[3]}, 0);
                    } else {
                        m.add_face({q[0], q[1], q[3]}, 0);
                        m.add_face({q[1], q[2], q[3]}, 0);
                    }
                }
        }
    return m;
}

/// Icosphere of radius r around c, subdivided until edges are about 2r/n.
SurfaceMesh sphere(const Vec3& c, double r, int n) {
    SurfaceMesh m;
    m.patches.push_back({"farfield", PatchKind::Farfield});
    const double t = (1.0 + std::sqrt(5.0)) / 2.0;
    std::vector<Vec3> p = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                           {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    for (Vec3& x : p) x.normalize();
    std::vector<std::array<Index, 3>> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                           {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                           {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                           {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
    // Each level halves the edges (icosahedron edge ≈ 1.05 r); stop once they are ≤ 2r/n.
    double edge = 1.05;
    while (edge > 2.0 / n) {
        std::map<std::pair<Index, Index>, Index> mid;
        auto midpoint = [&](Index a, Index b) {
            const auto key = std::minmax(a, b);
            auto it = mid.find(key);
            if (it != mid.end()) return it->second;
            p.push_back((p[a] + p[b]).normalized());
            const Index id = static_cast<Index>(p.size()) - 1;
            mid.emplace(key, id);
            return id;
        };
        std::vector<std::array<Index, 3>> g;
        for (const auto& tri : f) {
            const Index ab = midpoint(tri[0], tri[1]), bc = midpoint(tri[1], tri[2]), ca = midpoint(tri[2], tri[0]);
            g.push_back({tri[0], ab, ca});
            g.push_back({tri[1], bc, ab});
            g.push_back({tri[2], ca, bc});
            g.push_back({ab, bc, ca});
        }
        f.swap(g);
        edge *= 0.5;
    }
    for (const Vec3& x : p) m.points.push_back(c + r * x);
    for (const auto& tri : f) m.add_face({tri[0], tri[1], tri[2]}, 0);
    return m;
}

}  // namespace

SurfaceMesh make_farfield(const std::vector<Vec3>& body_points, const FarfieldParams& params) {
    if (!(params.size > 1.0))
        throw InputError("--farfield-size " + std::to_string(params.size) +
                         ": the farfield must be larger than the body (a multiple of its size > 1, typically 10 to 50)");
    if (params.divisions < 2) throw InputError("farfield divisions must be at least 2");
    const BoundingBox bb = bounding_box(body_points);
    const Vec3 c = 0.5 * (bb.min + bb.max);
    const double half = 0.5 * params.size * bb.diagonal();
    return params.shape == FarfieldShape::Box ? box(c, half, params.divisions) : sphere(c, half, params.divisions);
}

}  // namespace strata
