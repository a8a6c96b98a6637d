// The boundary-layer module on synthetic walls: exact heights and orthogonality on a flat
// plate, needle triangles, thread counts. Real geometries: test_layer_cases.cpp.

#include <strata/core/error.h>
#include <strata/core/validate.h>
#include <strata/geometry/check.h>
#include <strata/geometry/normals.h>
#include <strata/module/layers.h>

#include <gtest/gtest.h>

#include "layer_params.h"
#include "test_support.h"

#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <utility>

namespace strata {
namespace {

using test::closed_manifold;
using test::geometric;
using test::level_heights;

/// \p corner_jacobian: the scaled Jacobian of the wall faces' sharpest corner (1 for
/// rectangles, 1/√2 for right isosceles triangles), which orthogonal layers keep exactly.
void expect_flat_plate_exact(const SurfaceMesh& wall, const LayerParams& p, double corner_jacobian) {
    const LayerMesh lm = extrude_layers(wall, p);
    const std::vector<double> h = level_heights(p);
    const Index nw = lm.wall_nodes();
    ASSERT_EQ(lm.mesh.points.size(), static_cast<std::size_t>(nw) * (p.distribution.layers + 1));
    ASSERT_EQ(lm.layers(), p.distribution.layers);
    for (int k = 0; k <= p.distribution.layers; ++k)
        for (Index i = 0; i < nw; ++i) {
            const Vec3& x = lm.mesh.points[static_cast<std::size_t>(lm.level_node(k, i))];
            const Vec3& x0 = wall.points[i];
            EXPECT_NEAR(x.z(), h[static_cast<std::size_t>(k)], 1e-12 * h.back()) << "level " << k << " node " << i;
            EXPECT_NEAR(x.x(), x0.x(), 1e-12) << "level " << k << " node " << i;
            EXPECT_NEAR(x.y(), x0.y(), 1e-12) << "level " << k << " node " << i;
        }
    for (const LayerStats& s : lm.stats) {
        EXPECT_NEAR(s.min_scaled_jacobian, corner_jacobian, 1e-9);
        EXPECT_LT(s.max_orthogonality_deg, 1e-6);
    }
    EXPECT_TRUE(validate_mesh(lm.mesh).ok());
}

TEST(Layers, FlatPlateQuadsGeometric) {
    expect_flat_plate_exact(test::quad_grid(8, 6, 0.1), geometric(10, 1e-3, 1.3), 1.0);
}

TEST(Layers, FlatPlateTrianglesAllDistributions) {
    const SurfaceMesh wall = test::split_into_triangles(test::quad_grid(8, 8, 0.1), true);
    expect_flat_plate_exact(wall, geometric(12, 1e-3, 1.2), std::sqrt(0.5));
    LayerParams t = geometric(12, 1e-3, 0.0);  // no growth ratio: the thickness determines it
    t.distribution.kind = Distribution::Thickness;
    t.distribution.thickness = 0.05;
    expect_flat_plate_exact(wall, t, std::sqrt(0.5));
    LayerParams th = t;
    th.distribution.kind = Distribution::Tanh;
    expect_flat_plate_exact(wall, th, std::sqrt(0.5));
    LayerParams y = geometric(12, 0.0, 1.2);
    y.distribution.yplus = 1.0;
    y.distribution.reynolds = 1e6;
    y.distribution.reference_length = 1.0;
    expect_flat_plate_exact(wall, y, std::sqrt(0.5));
}

/// A closed 0.9 m cube whose top and front faces are fans of \p count needle triangles, \p h
/// wide along the top front edge from one corner and 0.9 m long, as CAD tessellators make,
/// then one triangle over the rest of the edge.
SurfaceMesh needle_cube(double h, int count) {
    constexpr double L = 0.9;
    SurfaceMesh m;
    m.patches.push_back({"needles", PatchKind::Wall});
    std::map<std::array<double, 3>, Index> id;
    auto node = [&](double x, double y, double z) {
        const auto [it, fresh] = id.emplace(std::array<double, 3>{x, y, z}, static_cast<Index>(m.points.size()));
        if (fresh) m.points.emplace_back(x, y, z);
        return it->second;
    };
    auto tri = [&](Index a, Index b, Index c) { m.add_face({a, b, c}, 0); };
    const Index b0 = node(0, 0, 0), b1 = node(0, L, 0), b2 = node(L, L, 0), b3 = node(L, 0, 0);
    const Index t1 = node(0, L, L), t2 = node(L, L, L), t3 = node(L, 0, L), t0 = node(0, 0, L);
    const Index apex = node(L / 2, L, L);
    tri(b0, b1, b2), tri(b0, b2, b3);                       // bottom
    tri(b3, b2, t2), tri(b3, t2, t3);                       // x = L
    tri(b1, b0, t0), tri(b1, t0, t1);                       // x = 0
    tri(b2, b1, t1), tri(b2, t1, apex), tri(b2, apex, t2);  // y = L, split at the apex
    std::vector<Index> edge{t0};                            // the top front edge
    for (int i = 1; i <= count && i * h < L; ++i) edge.push_back(node(i * h, 0, L));
    if (edge.back() != t3) edge.push_back(t3);
    const int n = static_cast<int>(edge.size()) - 1;
    for (int i = 0; i < n; ++i) tri(b0, edge[i + 1], edge[i]);  // y = 0: needles from b0
    tri(b0, b3, t3);
    for (int i = 0; i < n; ++i) tri(edge[i], edge[i + 1], apex);  // top: needles to the apex
    tri(t0, apex, t1), tri(t3, t2, apex);
    return orient_surface(m);
}

TEST(Layers, NeedleTrianglesNeverGiveANonFiniteCoordinate) {
    // Needles 0.4 mm wide (aspect ratio 2250) along the whole edge, and ten of 1e-7 m (aspect
    // ratio 9e6; their smoothing update once divided by a K that underflowed, and the second
    // layer had infinite coordinates). Every normal method, smoothing on: each position
    // finite, the layers valid.
    for (const auto& [h, count] : {std::pair{4e-4, 2250}, std::pair{1e-7, 10}}) {
        const SurfaceMesh wall = needle_cube(h, count);
        ASSERT_TRUE(closed_manifold(wall));
        for (const NormalMethod method :
             {NormalMethod::MaxMinDot, NormalMethod::AreaWeighted, NormalMethod::AngleWeighted, NormalMethod::Max}) {
            LayerParams p = geometric(10, 1e-4 * 0.9, 1.2);
            p.normals = method;
            p.min_quality = 0.0;  // every column marches: the positions themselves are under test
            const LayerMesh lm = extrude_layers(wall, p);
            for (const Vec3& x : lm.mesh.points) ASSERT_TRUE(x.allFinite()) << h << " " << to_string(method);
            const ValidationReport vr = validate_mesh(lm.mesh);
            EXPECT_TRUE(vr.ok()) << h << " " << to_string(method) << (vr.problems.empty() ? "" : vr.problems[0]);
        }
        // With local stopping: the columns whose cells stay as good as their needles allow
        // grow (the smoothing held within reach of the extrusion, kMaxSmoothingMove), the others
        // stop; valid layers, or, where no column can grow, a clear error naming the needles
        // and the remedy. Never garbage.
        try {
            const LayerMesh lm = extrude_layers(wall, geometric(10, 1e-4 * 0.9, 1.2));
            for (const Vec3& x : lm.mesh.points) ASSERT_TRUE(x.allFinite()) << h;
            const ValidationReport vr = validate_mesh(lm.mesh);
            EXPECT_TRUE(vr.ok()) << h << (vr.problems.empty() ? "" : vr.problems[0]);
            Index grown = 0;
            for (Index i = 0; i < lm.wall_nodes(); ++i) grown += lm.node_layers(i) > 0 ? 1 : 0;
            std::printf("needles of %g: %d of %d wall nodes grew, min scaled Jacobian %.2e\n", h,
                        static_cast<int>(grown), static_cast<int>(lm.wall_nodes()), vr.min_scaled_jacobian);
            EXPECT_GT(grown, 0);
        } catch (const TopologyError& e) {
            const std::string msg = e.what();
            for (const char* part : {"no wall node could grow", "needle faces", "remesh the surface"})
                EXPECT_NE(msg.find(part), std::string::npos) << part << " not in: " << msg;
        }
    }
}

TEST(Layers, ColumnsLeanAtMostThirtyDegreesOffTheNormalOfTheFrontTheyGrowFrom) {
    // A flat tube (a thin wing with round edges, 0.02 by 0.005, meshed square round its edges)
    // under layers to five times its chord: the front's faces stretch round the edges and the
    // smoothing pulls the columns there towards the edges' tips. Each segment stays within 30°
    // of the max-min normal of the level it grows from (the marching's own normals, a little
    // slack for the normal of the whole level against the marcher's).
    const SurfaceMesh wall = test::thin_torus(0.25, 0.01, 24, 400, 0.25);
    LayerParams p = geometric(16, 0.1 * 0.2 / (std::pow(1.2, 16) - 1.0), 1.2);
    p.proximity = ProximityMode::Off;
    p.min_quality = 0.0;  // every column every layer: the lean is what is measured
    const LayerMesh lm = extrude_layers(wall, p);
    ASSERT_EQ(lm.layers(), 16);
    const Index nw = lm.wall_nodes();
    double worst = 0.0;
    SurfaceMesh level = wall;
    for (int k = 0; k < lm.layers(); ++k) {
        for (Index i = 0; i < nw; ++i) level.points[i] = lm.mesh.points[static_cast<std::size_t>(lm.level_node(k, i))];
        const std::vector<Vec3> n = node_normals(level, NormalMethod::MaxMinDot);
        for (Index i = 0; i < nw; ++i) {
            const Vec3 seg = lm.mesh.points[static_cast<std::size_t>(lm.level_node(k + 1, i))] - level.points[i];
            worst = std::max(worst, std::acos(std::clamp(seg.normalized().dot(n[i]), -1.0, 1.0)) * 180.0 / std::numbers::pi);
        }
    }
    EXPECT_LT(worst, 30.0 + 1e-6);
    EXPECT_GT(worst, 20.0);  // the limit is what holds them
}

TEST(Layers, ANegativeThreadCountIsRefusedByName) {
    // thread_count took any count below 1 for all cores: -1 was a typo run silently.
    LayerParams p = geometric(3, 1e-2, 1.2);
    p.threads = -1;
    const SurfaceMesh wall = test::quad_grid(4, 4, 0.1);
    test::expect_error<InputError>([&] { (void)extrude_layers(wall, p); },
                                   {"LayerParams::threads is -1: give 0 (all cores) or a positive count"});
    test::expect_error<InputError>([&] { (void)proximity_plan(wall, p); }, {"LayerParams::threads is -1"});
}

}  // namespace
}  // namespace strata
