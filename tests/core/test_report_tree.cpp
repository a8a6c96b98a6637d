// The report tree (core/report_tree.h): values of every kind, in order, read back by kind.

#include <strata/core/error.h>
#include <strata/core/report_tree.h>

#include <gtest/gtest.h>

#include "test_support.h"

namespace strata {
namespace {

TEST(ReportTree, TypedReadsAndWrongKinds) {
    ReportNode n;
    n.set("count", Index{4}).set("share", 0.5).set("name", "wall").set("on", true);
    n.set("child", ReportNode().set("x", 1));
    EXPECT_EQ(n.integer("count"), 4);
    EXPECT_EQ(n.number("count"), 4.0);  // an integer reads as a number
    EXPECT_EQ(n.number("share"), 0.5);
    EXPECT_EQ(n.text("name"), "wall");
    EXPECT_TRUE(n.flag("on"));
    EXPECT_EQ(n.node("child").integer("x"), 1);
    EXPECT_EQ(n.find("missing"), nullptr);
    test::expect_error<Error>([&] { (void)n.integer("share"); }, {"number read as integer"});
    test::expect_error<Error>([&] { (void)n.at("missing"); }, {"no value 'missing'"});
    ASSERT_EQ(n.entries().size(), 5u);
    EXPECT_EQ(n.entries()[2].key, "name");
}

TEST(ReportTree, SetAgainReplacesInPlace) {
    ReportNode n;
    n.set("a", 1).set("b", 2).set("a", "one");
    ASSERT_EQ(n.entries().size(), 2u);
    EXPECT_EQ(n.entries()[0].key, "a");
    EXPECT_EQ(n.text("a"), "one");
    const ReportValue list = ReportValue::list_of(std::vector<int>{1, 2});
    EXPECT_EQ(list.kind(), ReportValue::Kind::List);
    EXPECT_EQ(list.list()[1].integer(), 2);
}

}  // namespace
}  // namespace strata
