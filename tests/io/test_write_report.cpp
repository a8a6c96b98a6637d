// The layer coverage report as JSON (io/write_report.h): content, escaping, atomic writing.

#include <strata/core/error.h>
#include <strata/core/format.h>
#include <strata/core/validate.h>
#include <strata/io/write_report.h>

#include <gtest/gtest.h>

#include "core/box_mesh.h"
#include "test_support.h"

#include <fstream>
#include <sstream>

namespace strata {
namespace {

using strata::test::slurp;

TEST(WriteLayerReport, PatchesAndShortNodesWithEscapedNames) {
    LayerReport r;
    r.layers = 30;
    r.first_height = 1e-4;
    r.thickness = 0.125;
    PatchCoverage c;
    c.name = "wing \"upper\"\\tip\n";
    c.faces = 10, c.nodes = 12, c.full_nodes = 9, c.mean_share = 0.9, c.min_share = 0.25;
    c.short_by[static_cast<std::size_t>(Shortfall::Proximity)] = 2;
    c.short_by[static_cast<std::size_t>(Shortfall::Front)] = 1;
    c.short_by[static_cast<std::size_t>(Shortfall::Quality)] = 3;
    c.min_layers = 4, c.mean_layers = 12.5, c.all_layers = 8;
    r.patches.push_back(c);
    r.short_nodes.push_back({7, Vec3(1, 2, 3), 0.25, 30, Shortfall::Proximity});
    r.short_nodes.push_back({8, Vec3(1, 2, 4), 0.5, 4, Shortfall::HeldBack});
    r.no_fan.push_back({5, Vec3(0.5, 0, 1), NoFan::Unusable});
    r.no_fan.push_back({9, Vec3(0, 0, 2), NoFan::Uncapped});
    test::ScratchDir dir("write_report");
    const std::string path = report_path(dir.file("m.cgr"));
    EXPECT_EQ(path, dir.file("m.cgr.report.json"));
    write_layer_report(r, path);
    const std::string json = slurp(path);
    for (const char* part :
         {"\"layers\": 30", "\"first_height\": 0.0001", "\"thickness\": 0.125",
          "\"name\": \"wing \\\"upper\\\"\\\\tip\\n\"", "\"faces\": 10", "\"full_nodes\": 9", "\"min_share\": 0.25",
          "\"short\": {\"proximity\": 2, \"front\": 1, \"held back\": 0, \"quality\": 3, \"turning\": 0, "
          "\"twist\": 0, \"neighbours\": 0, \"non-finite\": 0, \"sharp edge\": 0}",
          "\"min_layers\": 4", "\"mean_layers\": 12.5", "\"all_layers\": 8",
          "{\"node\": 7, \"position\": [1, 2, 3], \"share\": 0.25, \"layers\": 30, "
          "\"reason\": \"proximity\"}",
          "\"reason\": \"held back\"",
          "\"no_fan_nodes\": [\n    {\"node\": 5, \"position\": [0.5, 0, 1], \"reason\": \"unusable\"},\n"
          "    {\"node\": 9, \"position\": [0, 0, 2], \"reason\": \"uncapped\"}\n  ]"})
        EXPECT_NE(json.find(part), std::string::npos) << part << "\n" << json;
    // Balanced brackets: one object, three arrays, each patch and node an object.
    int depth = 0, objects = 0;
    bool in_string = false;
    for (std::size_t i = 0; i < json.size(); ++i) {
        const char ch = json[i];
        if (in_string) {
            if (ch == '\\')
                ++i;
            else if (ch == '"')
                in_string = false;
            continue;
        }
        if (ch == '"') in_string = true;
        if (ch == '{' || ch == '[') ++depth, objects += ch == '{';
        if (ch == '}' || ch == ']') --depth;
        ASSERT_GE(depth, 0);
    }
    EXPECT_EQ(depth, 0);
    EXPECT_EQ(objects, 1 + 2 + 2 + 2);  // the report, the patch and its "short", two short nodes, two without fan
}

TEST(WriteLayerReport, MissingDirectoryIsAnInputErrorAndLeavesNothing) {
    test::expect_error<InputError>([] { write_layer_report({}, "/nonexistent_dir_for_strata/m.report.json"); },
                                   {"/nonexistent_dir_for_strata"});
}

TEST(WriteMeshReport, CellsQualityHistogramsAndLayerStats) {
    // The mixed box (every cell type): its cell counts, each type's min scaled Jacobian and
    // histogram (the counts summing to its cells), the bins' edges, and the layers' figures.
    const VolumeMesh m = test::mixed_box().build();
    const ValidationReport v = validate_mesh(m);
    LayerReport r;
    r.layers = 2;
    r.per_layer.push_back({1e-3, 0.5, 0.75, 12.5, 40, 0, 1});
    r.per_layer.push_back({1.2e-3, 0.25, 0.7, 20, 38, 2, 0});
    test::ScratchDir dir("write_mesh_report");
    const std::string path = dir.file("m.report.json");
    write_mesh_report(r, m, v, path);
    const std::string json = slurp(path);
    std::string hex = "\"hexahedron\": [";
    for (int b = 0; b + 1 < kQualityBins; ++b) hex += "0, ";
    hex += "21]";  // unit cubes: all right-angled
    for (const std::string& part :
         {std::string("\"nodes\": ") + std::to_string(m.points.size()),
          std::string("\"cells\": {\"tetrahedron\": 10, \"pyramid\": 16, \"prism\": 4, \"hexahedron\": 21}"),
          "\"min_scaled_jacobian\": {\"all\": " + format_number(v.min_scaled_jacobian, 17), hex,
          std::string("\"bin_edges\": [0, "), std::string(", 1],"),
          std::string("{\"layer\": 1, \"height\": 0.001, \"min_scaled_jacobian\": 0.5, \"mean_scaled_jacobian\": "
                      "0.75, \"max_orthogonality_deg\": 12.5, \"columns\": 40, \"stopped_nodes\": 0, "
                      "\"held_nodes\": 1}"),
          std::string("{\"layer\": 2, \"height\": 0.0011999999999999999, ")})
        EXPECT_NE(json.find(part), std::string::npos) << part << "\n" << json;
    // Each type's histogram sums to its cells.
    for (const CellType t : kCellTypes) {
        const std::string key = "\"" + std::string(to_string(t)) + "\": [";
        const std::size_t at = json.find(key, json.find("\"histograms\""));
        ASSERT_NE(at, std::string::npos) << key;
        std::istringstream in(json.substr(at + key.size(), json.find(']', at) - at - key.size()));
        long sum = 0, count = 0;
        std::string item;
        while (std::getline(in, item, ',')) sum += std::stol(item), ++count;
        EXPECT_EQ(count, kQualityBins) << key;
        EXPECT_EQ(sum, static_cast<long>(m.num_cells(t))) << key;
    }
    // The coverage-only report has no figures.
    write_layer_report(r, path);
    EXPECT_EQ(slurp(path).find("\"quality\""), std::string::npos);
}

}  // namespace
}  // namespace strata
