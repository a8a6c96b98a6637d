// The report tree of a run (frontend/report.h): the keys OUT.report.json has always had, the
// rest of the stages' figures, provenance; and every value of the tree in the JSON.

#include <strata/core/validate.h>
#include <strata/frontend/report.h>
#include <strata/io/write_report.h>

#include <gtest/gtest.h>

#include "core/box_mesh.h"
#include "test_support.h"

#include <cctype>
#include <string>

namespace strata {
namespace {

/// A hybrid run's report as build_hybrid_mesh would fill it, on the mixed box.
HybridReport hybrid_fixture(const VolumeMesh& mesh) {
    HybridReport h;
    LayerReport& r = h.coverage;
    r.layers = 30, r.first_height = 1e-4, r.thickness = 0.125;
    PatchCoverage c;
    c.name = "wing \"upper\"\\tip\n";
    c.faces = 10, c.nodes = 12, c.full_nodes = 9, c.mean_share = 0.9, c.min_share = 0.25;
    c.short_by[static_cast<std::size_t>(Shortfall::Proximity)] = 2;
    c.short_by[static_cast<std::size_t>(Shortfall::Front)] = 1;
    c.short_by[static_cast<std::size_t>(Shortfall::Quality)] = 3;
    c.min_layers = 4, c.mean_layers = 12.5, c.all_layers = 8;
    r.patches.push_back(c);
    c.name = "wall", c.nodes = 10, c.full_nodes = 6, c.all_layers = 7, c.unbound_nodes = 8, c.unbound_all_layers = 6;
    c.short_by[static_cast<std::size_t>(Shortfall::Neighbours)] = 1;
    c.short_by[static_cast<std::size_t>(Shortfall::Quality)] = 1;
    r.wall = c;  // with proximity 2, front 1: 4 short for their own reason, 1 for a neighbour
    r.short_nodes.push_back({7, Vec3(1, 2, 3), 0.25, 30, Shortfall::Proximity});
    r.short_nodes.push_back({8, Vec3(1, 2, 4), 0.5, 4, Shortfall::HeldBack});
    r.no_fan.push_back({5, Vec3(0.5, 0, 1), NoFan::Unusable});
    r.no_fan.push_back({9, Vec3(0, 0, 2), NoFan::Uncapped});
    LayerStats s;
    s.height = 1e-3, s.min_scaled_jacobian = 0.5, s.mean_scaled_jacobian = 0.75, s.max_orthogonality_deg = 12.5;
    s.columns = 40, s.stopped_nodes = 0, s.held_nodes = 1, s.sweeps = 10;
    h.layers.stats = {s, s};
    h.layers.stats[1].height = 1.2e-3;
    h.layers.fan_edges = 6, h.layers.fan_nodes = 8, h.layers.fan_plane_nodes = 2;
    h.planes_of_patches = {{0, 3}};
    h.remeshed_patches = {0};
    h.front_rounds = 2, h.tet_improve.flips = 5;
    h.validation = validate_mesh(mesh);
    h.seconds_layers = 1.5;
    return h;
}

/// Every scalar of \p v written as `"key": value`, and every list or node's key, found in \p json.
void expect_in_json(const ReportNode& n, const std::string& json, const std::string& path) {
    for (const ReportNode::Entry& e : n.entries()) {
        const std::string at = path + "/" + e.key;
        std::string text = report_json(ReportNode().set(e.key, e.value));  // {\n  "key": value\n}\n
        text = text.substr(4, text.size() - 7);
        if (e.value.kind() == ReportValue::Kind::Node)
            expect_in_json(e.value.node(), json, at);
        else if (e.value.kind() == ReportValue::Kind::List)
            text = text.substr(0, text.find(": ") + 2);
        EXPECT_NE(json.find(text), std::string::npos) << at << ": " << text;
    }
}

TEST(MeshReport, TheJsonKeepsItsKeysAndCarriesEveryValueOfTheTree) {
    const VolumeMesh mesh = test::mixed_box().build();
    const HybridReport h = hybrid_fixture(mesh);
    Options o;
    o.surface.inputs = {"wing.stl", "tail.step"};
    o.layers.params.distribution.layers = 30;
    const ReportNode report = mesh_run_report(&mesh, h, nullptr, nullptr, o, {{"surface", 0.25}});
    const std::string json = report_json(report);
    // The keys and layout strata.report and earlier readers know.
    for (const std::string& part :
         {std::string("{\n  \"layers\": 30,\n  \"first_height\": 0.0001,\n  \"thickness\": 0.125,\n"),
          "  \"nodes\": " + std::to_string(mesh.points.size()) + ",\n",
          std::string("\"cells\": {\"tetrahedron\": 10, \"pyramid\": 16, \"prism\": 4, \"hexahedron\": 21}"),
          std::string("\"quality\": {\n    \"min_scaled_jacobian\": {\"all\": "), std::string("\"bin_edges\": [0, "),
          std::string("{\"layer\": 1, \"height\": 0.001, \"min_scaled_jacobian\": 0.5, \"mean_scaled_jacobian\": "
                      "0.75, \"max_orthogonality_deg\": 12.5, \"columns\": 40, \"stopped_nodes\": 0, "
                      "\"held_nodes\": 1"),
          std::string("{\"layer\": 2, \"height\": 0.0011999999999999999, "),
          std::string("{\"name\": \"wing \\\"upper\\\"\\\\tip\\n\", \"faces\": 10, \"nodes\": 12, \"full_nodes\": 9, "
                      "\"all_layers\": 8, \"unbound_nodes\": 0, \"unbound_all_layers\": 0, "
                      "\"mean_share\": 0.90000000000000002, \"unbound_mean_share\": 1, \"min_share\": 0.25, "
                      "\"mean_layers\": 12.5, \"min_layers\": 4, \"short\": {\"proximity\": 2, \"front\": 1, "
                      "\"held back\": 0, \"quality\": 3, \"turning\": 0, \"twist\": 0, \"neighbours\": 0, "
                      "\"non-finite\": 0, \"sharp edge\": 0, \"isotropic\": 0}}"),
          std::string(
              "\"coverage\": {\"faces\": 10, \"nodes\": 10, \"full_nodes\": 6, \"all_layers\": 7, "
              "\"unbound_nodes\": 8, \"unbound_all_layers\": 6, \"mean_share\": 0.90000000000000002, "
              "\"unbound_mean_share\": 1, \"min_share\": 0.25, \"mean_layers\": 12.5, \"min_layers\": 4, \"short\": {\"proximity\": 2, "
              "\"front\": 1, \"held back\": 0, \"quality\": 1, \"turning\": 0, \"twist\": 0, "
              "\"neighbours\": 1, \"non-finite\": 0, \"sharp edge\": 0, \"isotropic\": 0}, \"all_layers_share\": 0.69999999999999996, "
              "\"unbound_all_layers_share\": 0.75, \"own_reason_nodes\": 4, \"neighbour_nodes\": 1}"),
          std::string("{\"node\": 7, \"position\": [1, 2, 3], \"share\": 0.25, \"layers\": 30, "
                      "\"reason\": \"proximity\"}"),
          std::string("\"no_fan_nodes\": [\n    {\"node\": 5, \"position\": [0.5, 0, 1], \"reason\": \"unusable\"},\n"
                      "    {\"node\": 9, \"position\": [0, 0, 2], \"reason\": \"uncapped\"}\n  ]")})
        EXPECT_NE(json.find(part), std::string::npos) << part << "\n" << json;
    // The rest of the run: the layers' counters, the hybrid stages', the times, provenance.
    EXPECT_EQ(report.integer("fan_plane_nodes"), 2);
    EXPECT_EQ(report.node("planes_of_patches").integer(mesh.boundary.patches[0].name), 3);
    EXPECT_EQ(report.node("tet_improve").integer("flips"), 5);
    EXPECT_EQ(report.node("times").number("surface"), 0.25);
    EXPECT_EQ(report.node("times").number("layers"), 1.5);
    const ReportNode& p = report.node("provenance");
    EXPECT_EQ(p.text("strata_version"), strata_version());
    const std::string commit = p.text("git_commit");
    EXPECT_TRUE(commit == "unknown" || (commit.size() == 40 && std::isxdigit(static_cast<unsigned char>(commit[0]))))
        << commit;
    ASSERT_EQ(p.list("inputs").size(), 2u);
    EXPECT_EQ(p.list("inputs")[1].text(), "tail.step");
    EXPECT_EQ(p.node("options").integer("layers"), 30);    // given
    EXPECT_EQ(p.node("options").find("sweeps"), nullptr);  // the default
    // Whatever the builder adds reaches the JSON.
    expect_in_json(report, json, "");
}

TEST(MeshReport, AGmshModelsReportHasItsCellsWithoutTheMesh) {
    const VolumeMesh mesh = test::mixed_box().build();
    const ReportNode report = mesh_run_report(nullptr, hybrid_fixture(mesh), nullptr, nullptr, Options{}, {});
    EXPECT_EQ(report.find("nodes"), nullptr);
    EXPECT_EQ(report.node("cells").integer("hexahedron"), 21);
    EXPECT_EQ(report.node("planes_of_patches").integer("0"), 3);  // the patch by its index
}

}  // namespace
}  // namespace strata
