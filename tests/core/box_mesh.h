#pragma once
// Test helper: boxes of unit cubes, each cube meshed as one hexahedron, two prisms, six
// tetrahedra (Kuhn split along the c0–c6 diagonal), six pyramids meeting at its centre, or six
// pyramids with one of them split into two tetrahedra. Every triangulated cube side uses the
// diagonal through the cube's corner c0 or c6, so neighbouring cubes conform whenever both
// sides are triangulated or both are quads. Orientation is decided geometrically here (signed
// volumes, outward directions), independently of the validator's face tables.

#include <strata/core/volume_mesh.h>

#include <algorithm>
#include <array>
#include <map>
#include <vector>

namespace strata::test {

enum class CubeSplit { Hex, Prisms, Kuhn, Pyramids, PyramidsTets };

/// Cube sides: 0 x−, 1 x+, 2 y−, 3 y+, 4 z−, 5 z+.
struct Cube {
    CubeSplit split = CubeSplit::Hex;
    int tet_side = -1;  ///< PyramidsTets: the side whose pyramid is two tetrahedra
};

class BoxMesh {
public:
    /// nx × ny × nz cubes of size h starting at origin, all hexahedra until set().
    BoxMesh(int nx, int ny, int nz, double h = 1.0, Vec3 origin = Vec3::Zero())
        : nx_(nx), ny_(ny), nz_(nz), h_(h), origin_(origin) {
        for (int k = 0; k < nz; ++k)
            for (int j = 0; j < ny; ++j)
                for (int i = 0; i < nx; ++i) cubes_[{i, j, k}] = Cube{};
    }
    void set(int i, int j, int k, CubeSplit split, int tet_side = -1) { cubes_[{i, j, k}] = Cube{split, tet_side}; }
    void remove(int i, int j, int k) { cubes_.erase({i, j, k}); }

    /// Cells of every cube and boundary faces (patches "xmin", "xmax", "ymin", "ymax", "zmin",
    /// "zmax" by outward direction) on every cube side without a neighbouring cube.
    VolumeMesh build() const {
        VolumeMesh m;
        for (int k = 0; k <= nz_; ++k)
            for (int j = 0; j <= ny_; ++j)
                for (int i = 0; i <= nx_; ++i) m.points.push_back(origin_ + h_ * Vec3(i, j, k));
        for (const char* name : {"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"})
            m.boundary.patches.push_back({name, PatchKind::Wall});

        for (const auto& [ijk, cube] : cubes_) {
            const auto [i, j, k] = ijk;
            std::array<Index, 8> c;
            for (int l = 0; l < 8; ++l) {
                const auto o = kCorner[l];
                c[l] = node(i + o[0], j + o[1], k + o[2]);
            }
            add_cells(m, c, cube);
            for (int s = 0; s < 6; ++s) {
                const std::array<int, 3> nb{i + kDir[s][0], j + kDir[s][1], k + kDir[s][2]};
                if (cubes_.count(nb)) continue;
                const Vec3 out(kDir[s][0], kDir[s][1], kDir[s][2]);
                const auto side = side_nodes(c, s);
                if (triangulated(cube, s)) {
                    const auto [t1, t2] = split_side(c, s);
                    add_boundary(m, oriented(m, t1, out), s);
                    add_boundary(m, oriented(m, t2, out), s);
                } else {
                    add_boundary(m, oriented(m, std::vector<Index>(side.begin(), side.end()), out), s);
                }
            }
        }
        return m;
    }

    /// Local hex corners (Gmsh order) as offsets.
    static constexpr std::array<std::array<int, 3>, 8> kCorner{
        {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}}};
    static constexpr std::array<std::array<int, 3>, 6> kDir{
        {{-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}, {0, 0, -1}, {0, 0, 1}}};
    /// Corners of each side, cyclic (orientation irrelevant: oriented() fixes it).
    static constexpr std::array<std::array<int, 4>, 6> kSide{
        {{0, 3, 7, 4}, {1, 2, 6, 5}, {0, 1, 5, 4}, {3, 2, 6, 7}, {0, 1, 2, 3}, {4, 5, 6, 7}}};

    /// Reorder \p nodes so that their right-hand normal points along \p dir.
    static std::vector<Index> oriented(const VolumeMesh& m, std::vector<Index> nodes, const Vec3& dir) {
        Vec3 a = Vec3::Zero();
        for (std::size_t l = 1; l + 1 < nodes.size(); ++l)
            a += (m.points[nodes[l]] - m.points[nodes[0]]).cross(m.points[nodes[l + 1]] - m.points[nodes[0]]);
        if (a.dot(dir) < 0) std::reverse(nodes.begin(), nodes.end());
        return nodes;
    }
    static double det(const VolumeMesh& m, Index a, Index b, Index c, Index d) {
        const Vec3& o = m.points[a];
        return (m.points[b] - o).cross(m.points[c] - o).dot(m.points[d] - o);
    }
    /// Tet with positive det(v1−v0, v2−v0, v3−v0).
    static void add_tet(VolumeMesh& m, Index a, Index b, Index c, Index d) {
        if (det(m, a, b, c, d) < 0) std::swap(b, c);
        m.tets.push_back({a, b, c, d});
    }

private:
    Index node(int i, int j, int k) const { return static_cast<Index>((k * (ny_ + 1) + j) * (nx_ + 1) + i); }

    static std::array<Index, 4> side_nodes(const std::array<Index, 8>& c, int s) {
        return {c[kSide[s][0]], c[kSide[s][1]], c[kSide[s][2]], c[kSide[s][3]]};
    }
    static bool triangulated(const Cube& cube, int s) {
        switch (cube.split) {
            case CubeSplit::Prisms:
                return s >= 4;
            case CubeSplit::Kuhn:
                return true;
            case CubeSplit::PyramidsTets:
                return s == cube.tet_side;
            default:
                return false;
        }
    }
    /// The side's two triangles, split along the diagonal through local corner 0 or 6.
    static std::pair<std::vector<Index>, std::vector<Index>> split_side(const std::array<Index, 8>& c, int s) {
        std::array<int, 4> l = kSide[s];
        const auto d = std::find_if(l.begin(), l.end(), [](int x) { return x == 0 || x == 6; });
        std::rotate(l.begin(), d, l.end());
        return {{c[l[0]], c[l[1]], c[l[2]]}, {c[l[0]], c[l[2]], c[l[3]]}};
    }
    static void add_boundary(VolumeMesh& m, const std::vector<Index>& f, int s) {
        m.boundary.add_face(f.data(), static_cast<Index>(f.size()), s);
    }

    void add_cells(VolumeMesh& m, const std::array<Index, 8>& c, const Cube& cube) const {
        switch (cube.split) {
            case CubeSplit::Hex:
                m.hexes.push_back(c);
                return;
            case CubeSplit::Prisms:
                m.prisms.push_back({c[0], c[1], c[2], c[4], c[5], c[6]});
                m.prisms.push_back({c[0], c[2], c[3], c[4], c[6], c[7]});
                return;
            case CubeSplit::Kuhn: {
                // c0 -> c6 along the axes in every order: c0, c0+ea, c0+ea+eb, c6.
                const std::array<std::array<int, 3>, 6> perms{
                    {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}}};
                for (const auto& p : perms) {
                    std::array<int, 3> o{0, 0, 0};
                    const Index a = corner(c, o);
                    o[p[0]] = 1;
                    const Index b = corner(c, o);
                    o[p[1]] = 1;
                    const Index d = corner(c, o);
                    add_tet(m, a, b, d, c[6]);
                }
                return;
            }
            case CubeSplit::Pyramids:
            case CubeSplit::PyramidsTets: {
                Vec3 centre = Vec3::Zero();
                for (Index v : c) centre += m.points[v];
                m.points.push_back(centre / 8.0);
                const Index apex = static_cast<Index>(m.points.size()) - 1;
                for (int s = 0; s < 6; ++s) {
                    if (cube.split == CubeSplit::PyramidsTets && s == cube.tet_side) {
                        const auto [t1, t2] = split_side(c, s);
                        add_tet(m, t1[0], t1[1], t1[2], apex);
                        add_tet(m, t2[0], t2[1], t2[2], apex);
                        continue;
                    }
                    const Vec3 in = -Vec3(kDir[s][0], kDir[s][1], kDir[s][2]);
                    const auto side = side_nodes(c, s);
                    const auto base = oriented(m, std::vector<Index>(side.begin(), side.end()), in);
                    m.pyramids.push_back({base[0], base[1], base[2], base[3], apex});
                }
                return;
            }
        }
    }
    static Index corner(const std::array<Index, 8>& c, const std::array<int, 3>& o) {
        for (int l = 0; l < 8; ++l)
            if (kCorner[l] == o) return c[l];
        return kNone;
    }

    int nx_, ny_, nz_;
    double h_;
    Vec3 origin_;
    std::map<std::array<int, 3>, Cube> cubes_;
};

/// The 3 × 3 × 3 box with every cell type and every junction: prisms / Kuhn tets / prisms
/// stacked in the corner column (triangles against triangles), pyramid cubes with one
/// pyramid split into two tets against the Kuhn cube's sides, a six-pyramid cube among
/// hexahedra, hexahedra against prism sides. 51 cells, volume 27 h³.
inline BoxMesh mixed_box(double h = 1.0, Vec3 origin = Vec3::Zero()) {
    BoxMesh box(3, 3, 3, h, origin);
    box.set(0, 0, 0, CubeSplit::Prisms);
    box.set(0, 0, 1, CubeSplit::Kuhn);
    box.set(0, 0, 2, CubeSplit::Prisms);
    box.set(1, 0, 1, CubeSplit::PyramidsTets, 0);  // its x− side faces the Kuhn cube
    box.set(0, 1, 1, CubeSplit::PyramidsTets, 2);  // its y− side faces the Kuhn cube
    box.set(2, 2, 2, CubeSplit::Pyramids);
    return box;
}

}  // namespace strata::test
