#include <strata/geometry/primitives.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

namespace strata {

SurfaceMesh icosphere(const Vec3& centre, double radius, int levels, const Patch& patch) {
    const double t = (1.0 + std::sqrt(5.0)) / 2.0;
    std::vector<Vec3> p = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                           {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
    for (Vec3& x : p) x.normalize();
    std::vector<std::array<Index, 3>> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                           {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                           {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                           {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
    for (int level = 0; level < levels; ++level) {
        std::map<std::pair<Index, Index>, Index> mid;  // edge -> its midpoint, shared by both faces
        auto midpoint = [&](Index a, Index b) {
            const auto key = std::minmax(a, b);
            auto it = mid.find(key);
            if (it != mid.end()) return it->second;
            p.push_back((p[static_cast<std::size_t>(a)] + p[static_cast<std::size_t>(b)]).normalized());
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
    }
    SurfaceMesh m;
    m.patches.push_back(patch);
    for (const Vec3& x : p) m.points.push_back(centre + radius * x);
    for (const auto& tri : f) m.add_face({tri[0], tri[1], tri[2]}, 0);
    return m;
}

}  // namespace strata
