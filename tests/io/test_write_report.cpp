// A report tree as JSON (io/write_report.h): every kind of value, the order of keys, escaping,
// the layout, atomic writing.

#include <strata/core/error.h>
#include <strata/io/write_report.h>

#include <gtest/gtest.h>

#include "test_support.h"

#include <limits>

namespace strata {
namespace {

using strata::test::slurp;

TEST(WriteReport, EveryKindInOrderWithEscapedTextAndNullForNonFinite) {
    ReportNode patch, root;
    patch.set("name", "wing \"upper\"\\tip\n").set("faces", 10).set("short", ReportNode().set("proximity", 2));
    root.set("layers", 30).set("first_height", 1e-4).set("thickness", 0.125).set("ok", true).set("bad", false);
    root.set("inf", std::numeric_limits<double>::infinity()).set("nan", std::nan(""));
    root.set("position", ReportValue::list_of(std::vector<double>{1, 2.5, -3}));
    root.set("patches", ReportValue::List{patch, patch}).set("empty", ReportValue::List{});
    root.set("none", ReportNode()).set("layers", 31);  // set again: replaced in place
    const std::string json = report_json(root);
    EXPECT_EQ(json,
              "{\n"
              "  \"layers\": 31,\n"
              "  \"first_height\": 0.0001,\n"
              "  \"thickness\": 0.125,\n"
              "  \"ok\": true,\n"
              "  \"bad\": false,\n"
              "  \"inf\": null,\n"
              "  \"nan\": null,\n"
              "  \"position\": [1, 2.5, -3],\n"
              "  \"patches\": [\n"
              "    {\"name\": \"wing \\\"upper\\\"\\\\tip\\n\", \"faces\": 10, \"short\": {\"proximity\": 2}},\n"
              "    {\"name\": \"wing \\\"upper\\\"\\\\tip\\n\", \"faces\": 10, \"short\": {\"proximity\": 2}}\n"
              "  ],\n"
              "  \"empty\": [],\n"
              "  \"none\": {}\n"
              "}\n");
    // 17 significant digits: a double reads back as itself.
    EXPECT_NE(report_json(ReportNode().set("h", 1.2e-3)).find("\"h\": 0.0011999999999999999"), std::string::npos);
    // Three levels deep: the inner nodes on lines of their own.
    const std::string deep = report_json(ReportNode().set(
        "quality", ReportNode().set("openfoam", ReportNode().set("failures", ReportValue::List{"a"}))));
    EXPECT_EQ(deep, "{\n  \"quality\": {\n    \"openfoam\": {\"failures\": [\"a\"]}\n  }\n}\n");
}

TEST(WriteReport, WrittenAtomicallyBesideTheMesh) {
    test::ScratchDir dir("write_report");
    const std::string path = report_path(dir.file("m.cgr"));
    EXPECT_EQ(path, dir.file("m.cgr.report.json"));
    EXPECT_EQ(report_path(dir.file("polyMesh/")), dir.file("polyMesh.report.json"));
    const ReportNode r = ReportNode().set("layers", 3);
    write_report(r, path);
    EXPECT_EQ(slurp(path), report_json(r));
}

TEST(WriteReport, MissingDirectoryIsAnInputErrorAndLeavesNothing) {
    test::expect_error<InputError>([] { write_report({}, "/nonexistent_dir_for_strata/m.report.json"); },
                                   {"/nonexistent_dir_for_strata"});
}

}  // namespace
}  // namespace strata
