#pragma once
// Boundaries to fill and the checks of a fill, independent of the code under test: shared by
// test_tetgen_fill.cpp and test_hxt_fill.cpp.

#include <strata/core/cell_quality.h>
#include <strata/core/validate.h>
#include <strata/hybrid/tetgen_fill.h>

#include <gtest/gtest.h>

#include "box_surface.h"

#include <algorithm>
#include <array>
#include <map>
#include <vector>

namespace strata::test {


inline SurfaceMesh unit_cube(int n = 1) {
    SurfaceMesh m;
    m.patches.push_back({"farfield", PatchKind::Farfield});
    add_box(m, Vec3::Zero(), Vec3::Ones(), n, 0, true);
    return m;
}

/// Outer box [−2, 3]³ (farfield, n_out per side) around the unit cube (wall, n_in per side,
/// oriented into the cube, i.e. out of the region to fill). Hole point: the cube's centre.
inline SurfaceMesh cube_in_box(int n_in, int n_out, bool inner_outward = false, double outer = 2.0) {
    SurfaceMesh m;
    m.patches.push_back({"farfield", PatchKind::Farfield});
    m.patches.push_back({"wall", PatchKind::Wall});
    add_box(m, Vec3::Constant(-outer), Vec3::Constant(1.0 + outer), n_out, 0, true);
    add_box(m, Vec3::Zero(), Vec3::Ones(), n_in, 1, inner_outward);
    return m;
}
inline const std::vector<Vec3> kCubeHole{Vec3(0.5, 0.5, 0.5)};

inline double total_volume(const TetFill& f) {
    double v = 0.0;
    for (const auto& t : f.tets)
        v += (f.points[t[1]] - f.points[t[0]])
                 .cross(f.points[t[2]] - f.points[t[0]])
                 .dot(f.points[t[3]] - f.points[t[0]]) /
             6.0;
    return v;
}

/// For each boundary triangle, the number of tets having it as a face (independent of the
/// code under test: a map keyed by sorted node triples).
inline std::vector<int> tets_per_boundary_triangle(const SurfaceMesh& b, const TetFill& f) {
    std::map<std::array<Index, 3>, int> count;
    auto key = [](Index a, Index c, Index d) {
        std::array<Index, 3> k{a, c, d};
        std::sort(k.begin(), k.end());
        return k;
    };
    for (const auto& t : f.tets)
        for (int o = 0; o < 4; ++o) {
            std::array<Index, 3> k;
            int j = 0;
            for (int i = 0; i < 4; ++i)
                if (i != o) k[j++] = t[i];
            ++count[key(k[0], k[1], k[2])];
        }
    std::vector<int> r;
    for (Index i = 0; i < b.num_faces(); ++i) {
        const auto it = count.find(key(b.face_node(i, 0), b.face_node(i, 1), b.face_node(i, 2)));
        r.push_back(it == count.end() ? 0 : it->second);
    }
    return r;
}

inline double mean_edge(const TetFill& f, const std::array<Index, 4>& t) {
    double s = 0.0;
    for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j) s += (f.points[t[i]] - f.points[t[j]]).norm();
    return s / 6.0;
}

/// Common checks of a fill of \p b: boundary points unchanged and first, positive tets,
/// every boundary triangle a face of exactly one tet, volume = \p volume.
inline void expect_valid_fill(const SurfaceMesh& b, const TetFill& f, double volume) {
    ASSERT_GE(f.points.size(), b.points.size());
    for (std::size_t i = 0; i < b.points.size(); ++i) ASSERT_EQ(f.points[i], b.points[i]) << "boundary node " << i;
    ASSERT_FALSE(f.tets.empty());
    double min_j = 1.0;
    for (const auto& t : f.tets) min_j = std::min(min_j, tet_min_scaled_jacobian(f.points, t));
    EXPECT_GT(min_j, 0.0);
    const auto per_face = tets_per_boundary_triangle(b, f);
    for (std::size_t i = 0; i < per_face.size(); ++i) EXPECT_EQ(per_face[i], 1) << "boundary triangle " << i;
    EXPECT_NEAR(total_volume(f), volume, 1e-12 * std::max(1.0, volume));
}

inline VolumeMesh as_volume_mesh(const SurfaceMesh& b, const TetFill& f) {
    VolumeMesh m;
    m.points = f.points;
    m.tets = f.tets;
    m.boundary = b;
    m.boundary.points.clear();
    return m;
}

}  // namespace strata::test
