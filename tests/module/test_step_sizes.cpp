// Sizes for the steps the layers take at their proximity limits (module/step_sizes.h, and
// proximity_plan in layers.h): a plate under a tilted wall, the gap narrowing towards one end,
// so the columns there have fewer layers, one less per node towards the narrow end.

#include <strata/core/error.h>
#include <strata/core/solver_checks.h>
#include <strata/module/distribution.h>
#include <strata/module/layers.h>
#include <strata/module/step_sizes.h>

#include <gtest/gtest.h>

#include <map>
#include <numbers>

#include "test_support.h"

namespace strata {
namespace {

/// A 1 × 1 plate of 20 × 20 quads at z = 0 facing up and, above it, a wall facing down whose
/// height rises from 0.01 at x = 0 to 0.2 at x = 1, reaching 0.1 past the plate on every side.
SurfaceMesh plate_under_a_tilted_wall() {
    SurfaceMesh m = test::quad_grid(20, 20, 0.05);
    m.patches[0] = Patch{std::string("plate"), PatchKind::Wall};
    const SurfaceMesh top = test::quad_grid(12, 12, 0.1);
    const Index n = m.num_points();
    m.patches.push_back({"lid", PatchKind::Wall});
    for (const Vec3& x : top.points) {
        const Vec3 p = x + Vec3(-0.1, -0.1, 0.0);
        m.points.push_back(Vec3(p.x(), p.y(), 0.01 + 0.19 * p.x()));
    }
    for (Index f = 0; f < top.num_faces(); ++f) {
        const Index* v = top.face_begin(f);
        m.add_face({v[0] + n, v[3] + n, v[2] + n, v[1] + n}, 1);  // reversed: facing down
    }
    return m;
}

LayerParams ten_layers() {
    LayerParams p;
    p.distribution.layers = 10;
    p.distribution.kind = Distribution::Geometric;
    p.distribution.first_height = 1e-3;
    p.distribution.growth = 1.2;
    return p;
}

TEST(StepSizes, PlanStopsTheColumnsWhereTheGapIsNarrowAsTheMarchDoes) {
    const SurfaceMesh m = plate_under_a_tilted_wall();
    const LayerParams p = ten_layers();
    const ProximityPlan plan = proximity_plan(m, p);
    ASSERT_EQ(plan.levels.size(), m.points.size());
    // Thickness 0.026; 0.45 of the gap fits it from x ≈ 0.25 on: the plate's nodes short of
    // that have fewer layers, the fewest at the narrow end, and none beyond x = 0.4.
    int short_nodes = 0;
    for (Index i = 0; i < 441; ++i) {
        const double x = m.points[static_cast<std::size_t>(i)].x();
        if (plan.proximity[static_cast<std::size_t>(i)]) {
            ++short_nodes;
            EXPECT_LT(plan.levels[static_cast<std::size_t>(i)], 10);
            EXPECT_LT(x, 0.4);
        } else {
            EXPECT_EQ(plan.levels[static_cast<std::size_t>(i)], 10) << "node " << i << " at x = " << x;
        }
    }
    EXPECT_GT(short_nodes, 60);
    // The march stops the same columns at the same levels (it may stop more for other reasons).
    const LayerMesh lm = extrude_layers(m, p);
    for (Index w = 0; w < lm.wall_nodes(); ++w) {
        const auto i = static_cast<std::size_t>(lm.input_node[static_cast<std::size_t>(w)]);
        EXPECT_LE(lm.node_layers(w), plan.levels[i]);
        if (lm.stop_reason[static_cast<std::size_t>(w)] == Shortfall::Proximity) {
            EXPECT_EQ(lm.node_layers(w), plan.levels[i]) << "wall node " << w;
        }
    }
}

TEST(StepSizes, EachStepAsksTheSpacingThatGivesItsLayerHeightOverQuality) {
    const SurfaceMesh m = plate_under_a_tilted_wall();
    const LayerParams p = ten_layers();
    const ProximityPlan plan = proximity_plan(m, p);
    const std::vector<double> heights = layer_heights(p.distribution);
    const double quality = 0.5;  // every step here: heights 0.001..0.005 over 0.05
    const std::vector<SizePoint> points = step_sizes(m, plan, heights, quality);
    ASSERT_FALSE(points.empty());
    for (const SizePoint& q : points) {
        // At a node the plan stops for proximity, below a neighbour, asking 0.7 h_k / quality.
        Index at = kNone;
        for (Index i = 0; i < m.num_points(); ++i)
            if (m.points[static_cast<std::size_t>(i)] == q.at) at = i;
        ASSERT_NE(at, kNone);
        const auto i = static_cast<std::size_t>(at);
        EXPECT_TRUE(plan.proximity[i]);
        EXPECT_DOUBLE_EQ(q.size, kStepSizeShare * heights[static_cast<std::size_t>(plan.levels[i])] / quality);
        EXPECT_LT(q.size, 0.05);  // finer than the plate
    }
    // Steps already better than asked ask nothing; neither does a plan with no proximity stop.
    EXPECT_TRUE(step_sizes(m, plan, heights, 0.01).empty());
    ProximityPlan none = plan;
    std::fill(none.proximity.begin(), none.proximity.end(), 0);
    EXPECT_TRUE(step_sizes(m, none, heights, quality).empty());
}

TEST(StepSizes, BadQualityOrPlanIsAnInputError) {
    const SurfaceMesh m = plate_under_a_tilted_wall();
    const ProximityPlan plan = proximity_plan(m, ten_layers());
    const std::vector<double> heights = layer_heights(ten_layers().distribution);
    EXPECT_THROW(step_sizes(m, plan, heights, 0.0), InputError);
    EXPECT_THROW(step_sizes(m, plan, heights, 1.5), InputError);
    ProximityPlan short_plan = plan;
    short_plan.levels.pop_back();
    EXPECT_THROW(step_sizes(m, short_plan, heights, 0.1), InputError);
}

TEST(StepSizes, FanWedgesFlatterThanTheLimitAskForShorterEdges) {
    // A blade whose sharp edge turns 170 degrees (fans at 150), closed by its base (95) and end
    // caps (90), in segments of 0.125 along y: under a first layer of 1e-4 a fan's first wedge
    // along y is about 2L / (h sin w), near 2500, where checkMesh fails above 1000. Each end of
    // such an edge asks the length that brings its wedge to 0.7 of the limit.
    const SurfaceMesh wall = test::blade(8, 10.0);
    LayerParams p = ten_layers();
    p.distribution.first_height = 1e-4;
    p.fan_angle_deg = 150.0;
    const ProximityPlan plan = proximity_plan(wall, p);
    ASSERT_FALSE(plan.fan_wedges.empty());
    const FanWedgeSizes sized = fan_wedge_sizes(wall, plan, 1e-4, 1000.0);
    ASSERT_FALSE(sized.points.empty());
    std::map<Index, double> asked;  // node → the smallest length its wedges ask
    int along_y = 0;
    std::vector<std::pair<Vec3, Vec3>> edges;  // the edges sized, and the length each asks (x)
    std::vector<double> wants;
    for (const ProximityPlan::FanWedge& e : plan.fan_wedges) {
        const Vec3 &a = wall.points[static_cast<std::size_t>(e.a)], &b = wall.points[static_cast<std::size_t>(e.b)];
        const double ar = fan_wedge_aspect_ratio(a, b, e.d1, e.d2, 1e-4);
        if (!(ar > 1000.0)) continue;  // the caps' edges, across the axes, sum to far less
        const double want = (b - a).norm() * 700.0 / ar;
        if (std::abs((b - a).normalized().y()) > 0.999) {
            // Along an axis the figure grows with the edge: at the length asked, 0.7 of the limit.
            ++along_y;
            EXPECT_NEAR(fan_wedge_aspect_ratio(a, a + want * (b - a).normalized(), e.d1, e.d2, 1e-4), 700.0, 1.0);
        }
        for (const Index v : {e.a, e.b}) {
            auto [it, fresh] = asked.emplace(v, want);
            if (!fresh) it->second = std::min(it->second, want);
        }
        edges.emplace_back(a, b);
        wants.push_back(want);
    }
    EXPECT_GE(along_y, 8 * 2 + 16 * 2);  // the sharp edge's two wedges and the base's, per segment
    ASSERT_EQ(static_cast<std::size_t>(sized.nodes), asked.size());
    ASSERT_GT(sized.points.size(), asked.size());
    std::size_t k = 0;
    for (const auto& [v, want] : asked) {  // in node order, one per node
        EXPECT_EQ(sized.points[k].at, wall.points[static_cast<std::size_t>(v)]);
        EXPECT_NEAR(sized.points[k].size, want, 1e-12);
        ++k;
    }
    // Every point of a sized edge is within a quarter of its length of a point asking it, so
    // the size field along the edge stays near the length asked (the ends alone let it rise by
    // the growth over half the edge: here 0.25 · 0.0625 against lengths of about 0.03).
    const PointSizes field(sized.points, 0.25);
    for (std::size_t i = 0; i < edges.size(); ++i)
        for (int s = 0; s <= 20; ++s) {
            const Vec3 x = edges[i].first + (s / 20.0) * (edges[i].second - edges[i].first);
            EXPECT_LE(field(x), wants[i] * (1.0 + 0.25 / 4.0) + 1e-12) << "edge " << i << " at " << s << "/20";
        }
    // A wedge narrower than kFanWedgeMinDeg asks nothing: it is flat whatever its edge (here
    // 5 degrees along y, about 14 times the figure of the 85-degree one) and no spacing mends it.
    ProximityPlan narrow;
    const Vec3 d1(0, 0, 1), d2(std::sin(5.0 * std::numbers::pi / 180.0), 0, std::cos(5.0 * std::numbers::pi / 180.0));
    narrow.fan_wedges.push_back({2, 5, d1, d2});  // along the sharp edge, 0.125 long
    ASSERT_GT(fan_wedge_aspect_ratio(wall.points[2], wall.points[5], d1, d2, 1e-4), 1000.0);
    EXPECT_TRUE(fan_wedge_sizes(wall, narrow, 1e-4, 1000.0).points.empty());
    const Vec3 d3(std::sin(20.0 * std::numbers::pi / 180.0), 0, std::cos(20.0 * std::numbers::pi / 180.0));
    narrow.fan_wedges.front().d2 = d3;  // 20 degrees: sized
    const FanWedgeSizes one = fan_wedge_sizes(wall, narrow, 1e-4, 1000.0);
    EXPECT_EQ(one.nodes, 2);
    EXPECT_GT(one.points.size(), 2u);  // and along it
    // A first layer thick enough, or no limit: nothing asked; no fans: no wedge.
    EXPECT_TRUE(fan_wedge_sizes(wall, plan, 1e-2, 1000.0).points.empty());
    EXPECT_TRUE(fan_wedge_sizes(wall, plan, 1e-4, 0.0).points.empty());
    p.fan_angle_deg = 0.0;
    EXPECT_TRUE(proximity_plan(wall, p).fan_wedges.empty());
}

}  // namespace
}  // namespace strata
