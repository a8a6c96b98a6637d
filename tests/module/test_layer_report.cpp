// The coverage report's counting (layer_report.h): one wall patch's or the whole wall's figures
// from its nodes, and layer_report on a small hand-built layer mesh whose figures are known.
#include <strata/module/layer_report.h>
#include <strata/module/layers.h>

#include <gtest/gtest.h>

#include <string>
#include <tuple>
#include <vector>

namespace strata {
namespace {

std::size_t at(Shortfall reason) {
    return static_cast<std::size_t>(reason);
}

/// The counts of a PatchCoverage, in its fields' order.
struct Counts {
    std::string name;
    Index faces, nodes, full_nodes, all_layers, unbound_nodes, unbound_all_layers;
};

void expect_counts(const PatchCoverage& c, const Counts& w) {
    EXPECT_EQ(std::tie(c.name, c.faces, c.nodes, c.full_nodes, c.all_layers, c.unbound_nodes, c.unbound_all_layers),
              std::tie(w.name, w.faces, w.nodes, w.full_nodes, w.all_layers, w.unbound_nodes, w.unbound_all_layers));
}

TEST(LayerReport, CoverageOfNodesCountsSharesAndReasons) {
    // 4 layers asked: two full nodes, one thinned for proximity, one stopped for quality, one
    // lowered by its neighbours, one stopped at the wall for proximity, one thinned for
    // proximity and then lowered by its neighbours.
    const std::vector<NodeCoverage> nodes{{1.0, 4, Shortfall::None, false},       {1.0, 4, Shortfall::None, false},
                                          {0.5, 4, Shortfall::Proximity, true},   {0.25, 1, Shortfall::Quality, false},
                                          {0.5, 2, Shortfall::Neighbours, false}, {0.0, 0, Shortfall::Proximity, true},
                                          {0.75, 3, Shortfall::Neighbours, true}};
    const PatchCoverage c = coverage_of("body", 9, nodes, 4);
    expect_counts(c, {"body", 9, 7, 2, 3, 4, 2});
    EXPECT_DOUBLE_EQ(c.all_layers_share(), 3.0 / 7.0);
    EXPECT_DOUBLE_EQ(c.unbound_all_layers_share(), 0.5);
    EXPECT_DOUBLE_EQ(c.mean_share, 4.0 / 7.0);
    EXPECT_DOUBLE_EQ(c.unbound_mean_share, (1.0 + 1.0 + 0.25 + 0.5) / 4.0);  // the four no proximity limit binds
    EXPECT_DOUBLE_EQ(c.min_share, 0.0);
    EXPECT_DOUBLE_EQ(c.mean_layers, 18.0 / 7.0);
    EXPECT_EQ(c.min_layers, 0);
    EXPECT_EQ(c.short_nodes(Shortfall::None), 2);
    EXPECT_EQ(c.short_nodes(Shortfall::Proximity), 2);
    EXPECT_EQ(c.short_nodes(Shortfall::Quality), 1);
    EXPECT_EQ(c.short_nodes(Shortfall::Neighbours), 2);
    EXPECT_EQ(c.own_reason_nodes(), 3);  // proximity 2, quality 1
}

TEST(LayerReport, CoverageOfNoNodesIsWhole) {
    const PatchCoverage c = coverage_of("none", 0, {}, 5);
    EXPECT_EQ(c.nodes, 0);
    EXPECT_EQ(c.min_layers, 5);
    EXPECT_DOUBLE_EQ(c.mean_share, 1.0);
    EXPECT_DOUBLE_EQ(c.unbound_mean_share, 1.0);
    EXPECT_DOUBLE_EQ(c.all_layers_share(), 1.0);
    EXPECT_DOUBLE_EQ(c.unbound_all_layers_share(), 1.0);
    EXPECT_EQ(c.own_reason_nodes(), 0);
}

TEST(LayerReport, OwnReasonsAreEveryReasonButNoneAndNeighbours) {
    PatchCoverage c;
    for (std::size_t k = 0; k < kShortfalls; ++k) c.short_by[k] = 1;
    EXPECT_EQ(c.own_reason_nodes(), static_cast<Index>(kShortfalls) - 2);
}

TEST(LayerReport, TheWholeWallCountsANodeOnTwoPatchesOnce) {
    // Wall nodes i at (i % 3, i / 3, 0), two layers of height 1 asked; patch "left" faces 0 1 4
    // and 0 4 3, "right" 1 2 5 and 1 5 4 (nodes 1 and 4 on both). Node 2 stopped at the wall
    // for quality, node 4 after one layer by its neighbours, node 5 thinned to half for proximity.
    LayerMesh lm(6, 2);
    lm.asked_thickness = 2.0;
    const std::vector<int> layers{2, 2, 0, 2, 1, 2};
    lm.set_columns(layers);
    const auto height = [](Index i) { return i == 5 ? 0.5 : 1.0; };
    for (int k = 0; k <= 2; ++k)
        for (Index i = 0; i < 6; ++i)
            if (layers[static_cast<std::size_t>(i)] >= k)
                lm.mesh.points.emplace_back(static_cast<double>(i % 3), static_cast<double>(i / 3), k * height(i));
    lm.stop_reason = {Shortfall::None, Shortfall::None,       Shortfall::Quality,
                      Shortfall::None, Shortfall::Neighbours, Shortfall::None};
    lm.scale_reason.assign(6, Shortfall::None);
    lm.scale_reason[5] = Shortfall::Proximity;
    lm.held_back.assign(6, 0);
    for (Index i = 0; i < 6; ++i) lm.top.points.push_back(lm.mesh.points[static_cast<std::size_t>(lm.top_node(i))]);
    lm.top.patches = {{"left", PatchKind::Wall}, {"right", PatchKind::Wall}};
    lm.top.add_face({0, 1, 4}, 0);
    lm.top.add_face({0, 4, 3}, 0);
    lm.top.add_face({1, 2, 5}, 1);
    lm.top.add_face({1, 5, 4}, 1);

    const LayerReport r = layer_report(lm);
    ASSERT_EQ(r.patches.size(), 2u);
    const PatchCoverage &left = r.patches[0], &right = r.patches[1], &wall = r.wall;
    EXPECT_EQ(left.nodes, 4);
    EXPECT_EQ(left.all_layers, 3);
    EXPECT_EQ(right.nodes, 4);
    EXPECT_EQ(right.all_layers, 2);
    EXPECT_EQ(right.unbound_nodes, 3);
    EXPECT_EQ(right.unbound_all_layers, 1);

    expect_counts(wall, {"wall", 4, 6, 3, 4, 5, 3});
    EXPECT_DOUBLE_EQ(wall.all_layers_share(), 4.0 / 6.0);
    EXPECT_DOUBLE_EQ(wall.unbound_all_layers_share(), 0.6);
    EXPECT_DOUBLE_EQ(wall.mean_share, (1.0 + 1.0 + 0.0 + 1.0 + 0.5 + 0.5) / 6.0);
    EXPECT_DOUBLE_EQ(wall.min_share, 0.0);
    EXPECT_DOUBLE_EQ(wall.mean_layers, 9.0 / 6.0);
    EXPECT_EQ(wall.min_layers, 0);
    EXPECT_EQ(wall.short_by[at(Shortfall::Quality)], 1);
    EXPECT_EQ(wall.short_by[at(Shortfall::Neighbours)], 1);
    EXPECT_EQ(wall.short_by[at(Shortfall::Proximity)], 1);
    EXPECT_EQ(wall.own_reason_nodes(), 2);

    // The plots' per-node figures: the short nodes' own, the others full.
    EXPECT_EQ(node_layers(r, 6), layers);
    const std::vector<double> shares = node_shares(r, 6);
    const std::vector<double> expected{1.0, 1.0, 0.0, 1.0, 0.5, 0.5};
    ASSERT_EQ(shares.size(), expected.size());
    for (std::size_t i = 0; i < shares.size(); ++i) EXPECT_DOUBLE_EQ(shares[i], expected[i]) << i;
}

}  // namespace
}  // namespace strata
