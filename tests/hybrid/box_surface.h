#pragma once
// The surface of an axis-aligned box as triangles, for the tetrahedral-fill tests.

#include <strata/core/surface_mesh.h>

#include <array>
#include <map>

namespace strata::test {

/// Add the surface of the box [lo, hi] to \p m, each side an n × n grid of squares split into
/// triangles, on \p patch; normals point out of the box if \p outward, into it otherwise.
/// Orientation is decided geometrically (against the side's outward direction).
inline void add_box(SurfaceMesh& m, const Vec3& lo, const Vec3& hi, int n, Index patch, bool outward) {
    std::map<std::array<int, 3>, Index> node;  // grid coordinates → node id (shared edges)
    auto id = [&](int i, int j, int k) {
        auto [it, fresh] = node.try_emplace({i, j, k}, m.num_points());
        if (fresh) {
            const Vec3 t(i, j, k);
            m.points.push_back(lo + (hi - lo).cwiseProduct(t / n));
        }
        return it->second;
    };
    for (int axis = 0; axis < 3; ++axis) {
        const int u = (axis + 1) % 3, v = (axis + 2) % 3;
        for (int side = 0; side < 2; ++side) {
            Vec3 out = Vec3::Zero();
            out[axis] = (side == 1 ? 1.0 : -1.0) * (outward ? 1.0 : -1.0);
            for (int a = 0; a < n; ++a)
                for (int b = 0; b < n; ++b) {
                    std::array<Index, 4> q;
                    const std::array<std::array<int, 2>, 4> uv{{{a, b}, {a + 1, b}, {a + 1, b + 1}, {a, b + 1}}};
                    for (int c = 0; c < 4; ++c) {
                        std::array<int, 3> g{};
                        g[axis] = side * n, g[u] = uv[c][0], g[v] = uv[c][1];
                        q[c] = id(g[0], g[1], g[2]);
                    }
                    for (const auto& t :
                         {std::array<Index, 3>{q[0], q[1], q[2]}, std::array<Index, 3>{q[0], q[2], q[3]}}) {
                        const Vec3 nrm = (m.points[t[1]] - m.points[t[0]]).cross(m.points[t[2]] - m.points[t[0]]);
                        if (nrm.dot(out) > 0)
                            m.add_face({t[0], t[1], t[2]}, patch);
                        else
                            m.add_face({t[0], t[2], t[1]}, patch);
                    }
                }
        }
    }
}

}  // namespace strata::test
