#pragma once
/// \file
/// A run's report as a tree: an ordered node of keys to values (a flag, an integer, a number,
/// a text, a list of values, a node). The front end builds it once from the stages' results
/// (frontend/report.h); the JSON writer, the Python dict and the CLI's summary walk it, so a
/// field added to the builder reaches all three.

#include <concepts>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace strata {

class ReportValue;

/// A node: keys to values, in the order they were set.
class ReportNode {
public:
    struct Entry;

    // Out of line, where Entry is complete (a vector of an incomplete type cannot be built or
    // destroyed here).
    ReportNode();
    ~ReportNode();
    ReportNode(const ReportNode&);
    ReportNode(ReportNode&&) noexcept;
    ReportNode& operator=(const ReportNode&);
    ReportNode& operator=(ReportNode&&) noexcept;

    /// Set \p key to \p value: replaced in place if the node has it, else added at the end.
    ReportNode& set(std::string key, ReportValue value);
    /// The value of \p key, or nullptr.
    const ReportValue* find(std::string_view key) const;
    /// The value of \p key; Error naming it if the node has none.
    const ReportValue& at(std::string_view key) const;
    /// at(key) as a node, a flag, an integer, a number (an integer converted) or a text; Error
    /// naming the key if it holds another kind.
    const ReportNode& node(std::string_view key) const;
    bool flag(std::string_view key) const;
    std::int64_t integer(std::string_view key) const;
    double number(std::string_view key) const;
    const std::string& text(std::string_view key) const;
    const std::vector<ReportValue>& list(std::string_view key) const;

    const std::vector<Entry>& entries() const { return entries_; }
    bool empty() const { return entries_.empty(); }

private:
    std::vector<Entry> entries_;
};

/// One value of a report.
class ReportValue {
public:
    enum class Kind : std::uint8_t { Flag, Integer, Number, Text, List, Node };
    using List = std::vector<ReportValue>;

    ReportValue(bool flag) : kind_(Kind::Flag), flag_(flag) {}
    template <std::integral T>
    requires(!std::same_as<T, bool>) ReportValue(T integer)
        : kind_(Kind::Integer), integer_(static_cast<std::int64_t>(integer)) {}
    ReportValue(double number) : kind_(Kind::Number), number_(number) {}
    ReportValue(std::string text) : kind_(Kind::Text), text_(std::move(text)) {}
    ReportValue(const char* text) : kind_(Kind::Text), text_(text) {}
    ReportValue(List list) : kind_(Kind::List), list_(std::move(list)) {}
    ReportValue(ReportNode node) : kind_(Kind::Node), node_(std::move(node)) {}
    /// A list of \p values, each converted to a ReportValue.
    template <class Range>
    static ReportValue list_of(const Range& values) {
        List list;
        for (const auto& v : values) list.emplace_back(v);
        return ReportValue(std::move(list));
    }

    Kind kind() const { return kind_; }
    /// The value as its kind; Error if it is another (number() also takes an integer).
    bool flag() const;
    std::int64_t integer() const;
    double number() const;
    const std::string& text() const;
    const List& list() const;
    const ReportNode& node() const;

private:
    Kind kind_;
    bool flag_ = false;
    std::int64_t integer_ = 0;
    double number_ = 0.0;
    std::string text_;
    List list_;
    ReportNode node_;
};

struct ReportNode::Entry {
    std::string key;
    ReportValue value;
};

/// The name of \p kind: "flag", "integer", "number", "text", "list", "node".
std::string_view to_string(ReportValue::Kind kind);

}  // namespace strata
