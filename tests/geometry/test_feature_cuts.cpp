// Cuts that put every long sharp edge between two regions (geometry/feature_cuts.h): a wing-like
// tube, round at its leading edge and sharp at its trailing edge, capped at both ends. Its
// trailing edge has the same smooth region on both sides (round the leading edge), which Gmsh's
// classifySurfaces drops; with the cuts, the two sides are apart and the cut runs along the
// leading edge. Surfaces without such an edge get no cut.

#include <strata/core/union_find.h>
#include <strata/geometry/feature_cuts.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace strata {
namespace {

constexpr double kPi = 3.141592653589793;

struct Soup {
    std::vector<Vec3> points;
    std::vector<std::array<Index, 3>> triangles;
};

/// A wing section: a half circle of radius 1 about the origin (the leading edge, x ≤ 0) and two
/// straight sides meeting at the trailing edge (chord, 0, 0), a wedge of about 2 atan(1 / chord);
/// counter-clockwise from the trailing edge. Extruded over y in [0, span] in \p stations
/// steps, each end closed by a fan round its centre; normals out.
Soup wing(double chord, double span, int stations, int arc = 12) {
    std::vector<std::array<double, 2>> section{{chord, 0.0}};
    for (int i = 0; i <= arc; ++i) {
        const double t = kPi / 2 + kPi * i / arc;
        section.push_back({std::cos(t), std::sin(t)});
    }
    std::reverse(section.begin() + 1, section.end());  // trailing edge, upper side, lower side
    Soup s;
    const auto n = static_cast<Index>(section.size());
    for (int j = 0; j <= stations; ++j)
        for (const auto& [x, z] : section) s.points.emplace_back(x, span * j / stations, z);
    auto node = [&](int j, Index i) { return static_cast<Index>(j) * n + (i % n); };
    for (int j = 0; j < stations; ++j)
        for (Index i = 0; i < n; ++i) {
            s.triangles.push_back({node(j, i), node(j + 1, i), node(j + 1, i + 1)});
            s.triangles.push_back({node(j, i), node(j + 1, i + 1), node(j, i + 1)});
        }
    for (const int j : {0, stations}) {
        const auto centre = static_cast<Index>(s.points.size());
        s.points.emplace_back(0.0, span * j / stations, 0.0);
        for (Index i = 0; i < n; ++i)
            if (j == 0)
                s.triangles.push_back({centre, node(j, i), node(j, i + 1)});
            else
                s.triangles.push_back({centre, node(j, i + 1), node(j, i)});
    }
    return s;
}

Vec3 normal(const Soup& s, Index t) {
    const auto& tri = s.triangles[static_cast<std::size_t>(t)];
    const Vec3 &a = s.points[static_cast<std::size_t>(tri[0])], &b = s.points[static_cast<std::size_t>(tri[1])],
               &c = s.points[static_cast<std::size_t>(tri[2])];
    return (b - a).cross(c - a).normalized();
}

/// The regions of \p s with edges sharper than \p angle_deg and \p cuts as walls.
std::vector<Index> regions(const Soup& s, const std::vector<std::array<Index, 2>>& cuts, double angle_deg) {
    std::vector<std::pair<std::array<Index, 2>, Index>> halves;
    for (std::size_t t = 0; t < s.triangles.size(); ++t)
        for (int i = 0; i < 3; ++i) {
            const Index a = s.triangles[t][static_cast<std::size_t>(i)],
                        b = s.triangles[t][static_cast<std::size_t>((i + 1) % 3)];
            halves.push_back({{std::min(a, b), std::max(a, b)}, static_cast<Index>(t)});
        }
    std::sort(halves.begin(), halves.end());
    UnionFind uf(s.triangles.size());
    for (std::size_t i = 0; i + 1 < halves.size(); ++i)
        if (halves[i].first == halves[i + 1].first &&
            normal(s, halves[i].second).dot(normal(s, halves[i + 1].second)) >= std::cos(angle_deg * kPi / 180) &&
            !std::binary_search(cuts.begin(), cuts.end(), halves[i].first))
            uf.unite(halves[i].second, halves[i + 1].second);
    std::vector<Index> r(s.triangles.size());
    for (std::size_t t = 0; t < r.size(); ++t) r[t] = uf.find(static_cast<Index>(t));
    return r;
}

/// The two triangles on the trailing-edge edge between stations j and j + 1 (node i = 0).
std::pair<Index, Index> trailing_edge_sides(const Soup& s, int j, Index n) {
    std::vector<Index> on;
    for (std::size_t t = 0; t < s.triangles.size(); ++t) {
        int hits = 0;
        for (Index v : s.triangles[t]) hits += v == j * n || v == (j + 1) * n;
        if (hits == 2) on.push_back(static_cast<Index>(t));
    }
    EXPECT_EQ(on.size(), 2u);
    return {on.at(0), on.at(1)};
}

TEST(FeatureCuts, SeparateTheSidesOfAWingsTrailingEdgeAlongItsLeadingEdge) {
    const Soup s = wing(6.0, 10.0, 8);
    const Index n = 14;  // section nodes
    // Without cuts, the trailing edge (a wedge of 19 degrees) has one region on both sides.
    const std::vector<Index> before = regions(s, {}, 40.0);
    const auto [u0, l0] = trailing_edge_sides(s, 3, n);
    ASSERT_EQ(before[static_cast<std::size_t>(u0)], before[static_cast<std::size_t>(l0)]);

    const auto cuts = feature_cuts(s.points, s.triangles, {}, 40.0, 1.0);
    ASSERT_FALSE(cuts.empty());
    EXPECT_TRUE(std::is_sorted(cuts.begin(), cuts.end()));
    const std::vector<Index> after = regions(s, cuts, 40.0);
    for (int j = 0; j < 8; ++j) {
        const auto [u, l] = trailing_edge_sides(s, j, n);
        EXPECT_NE(after[static_cast<std::size_t>(u)], after[static_cast<std::size_t>(l)]) << "station " << j;
    }
    // The cut runs along the leading edge (the section's middle node, x = -1, z = 0): every cut
    // edge that is not the trailing edge itself lies within the half circle's front half.
    for (const auto& [a, b] : cuts) {
        const Vec3 mid = 0.5 * (s.points[static_cast<std::size_t>(a)] + s.points[static_cast<std::size_t>(b)]);
        if (mid.x() > 5.9) continue;  // the trailing edge
        EXPECT_LT(mid.x(), -0.5) << a << "-" << b;
        EXPECT_GT(mid.y(), -1e-12);
        EXPECT_LT(mid.y(), 10.0 + 1e-12);
    }
    // The caps were regions of their own already: no cut edge touches a cap centre.
    const auto caps = static_cast<Index>(s.points.size()) - 2;
    for (const auto& [a, b] : cuts) EXPECT_LT(b, caps);
}

TEST(FeatureCuts, LeaveShortChainsBluntWedgesBarriersAndSmoothSurfaces) {
    const Soup s = wing(6.0, 10.0, 8);
    // The trailing edge is 10 long: a minimum of 11 leaves it to Gmsh.
    EXPECT_TRUE(feature_cuts(s.points, s.triangles, {}, 40.0, 11.0).empty());
    // At 60 degrees the trailing edge is still sharp and inside one region: cut.
    EXPECT_FALSE(feature_cuts(s.points, s.triangles, {}, 60.0, 1.0).empty());
    // A blunt one: chord 1 makes a right-angled wedge, its faces' normals 90 degrees apart,
    // sharp at 60 and inside one region (the sides turn 52.5 degrees into the half circle), but
    // a face across it does not fold: left to Gmsh.
    const Soup blunt = wing(1.0, 10.0, 8);
    EXPECT_TRUE(feature_cuts(blunt.points, blunt.triangles, {}, 60.0, 1.0).empty());
    // Patch seams along the leading edge already split the tube: nothing to add.
    std::vector<std::array<Index, 2>> seams;
    const Index n = 14, middle = 7;  // the leading edge's node in each section
    for (Index j = 0; j < 8; ++j) seams.push_back({j * n + middle, (j + 1) * n + middle});
    EXPECT_TRUE(feature_cuts(s.points, s.triangles, seams, 40.0, 1.0).empty());
    // A closed smooth surface: a coarse sphere of latitude-longitude triangles.
    Soup sphere;
    const int rings = 8, segments = 16;
    sphere.points.emplace_back(0, 0, 1);
    for (int r = 1; r < rings; ++r)
        for (int k = 0; k < segments; ++k) {
            const double th = kPi * r / rings, ph = 2 * kPi * k / segments;
            sphere.points.emplace_back(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th));
        }
    sphere.points.emplace_back(0, 0, -1);
    auto ring = [&](int r, int k) { return static_cast<Index>(1 + (r - 1) * segments + (k % segments)); };
    const auto south = static_cast<Index>(sphere.points.size()) - 1;
    for (int k = 0; k < segments; ++k) {
        sphere.triangles.push_back({0, ring(1, k), ring(1, k + 1)});
        for (int r = 1; r + 1 < rings; ++r) {
            sphere.triangles.push_back({ring(r, k), ring(r + 1, k), ring(r + 1, k + 1)});
            sphere.triangles.push_back({ring(r, k), ring(r + 1, k + 1), ring(r, k + 1)});
        }
        sphere.triangles.push_back({south, ring(rings - 1, k + 1), ring(rings - 1, k)});
    }
    EXPECT_TRUE(feature_cuts(sphere.points, sphere.triangles, {}, 40.0, 0.0).empty());
}

TEST(FeatureCuts, DoNotDependOnTheTrianglesOrder) {
    Soup s = wing(6.0, 10.0, 8);
    const auto cuts = feature_cuts(s.points, s.triangles, {}, 40.0, 1.0);
    std::reverse(s.triangles.begin(), s.triangles.end());
    for (auto& t : s.triangles) std::rotate(t.begin(), t.begin() + 1, t.end());
    EXPECT_EQ(feature_cuts(s.points, s.triangles, {}, 40.0, 1.0), cuts);
}

}  // namespace
}  // namespace strata
