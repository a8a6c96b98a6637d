// Sizes for the steps the layers take at their proximity limits (module/step_sizes.h, and
// proximity_plan in layers.h): a plate under a tilted wall, the gap narrowing towards one end,
// so the columns there have fewer layers, one less per node towards the narrow end.

#include <strata/core/error.h>
#include <strata/module/distribution.h>
#include <strata/module/layers.h>
#include <strata/module/step_sizes.h>

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace strata
