#include <strata/core/enum_names.h>
#include <strata/core/error.h>
#include <strata/core/report_tree.h>

namespace strata {

ReportNode::ReportNode() = default;
ReportNode::~ReportNode() = default;
ReportNode::ReportNode(const ReportNode&) = default;
ReportNode::ReportNode(ReportNode&&) noexcept = default;
ReportNode& ReportNode::operator=(const ReportNode&) = default;
ReportNode& ReportNode::operator=(ReportNode&&) noexcept = default;

namespace {

[[noreturn]] void wrong_kind(ReportValue::Kind has, ReportValue::Kind asked) {
    throw Error("report value: " + std::string(to_string(has)) + " read as " + std::string(to_string(asked)));
}

}  // namespace

std::string_view to_string(ReportValue::Kind kind) {
    static constexpr EnumNames<ReportValue::Kind, 6> kNames{{"flag", "integer", "number", "text", "list", "node"}};
    return kNames.name(kind);
}

ReportNode& ReportNode::set(std::string key, ReportValue value) {
    for (Entry& e : entries_)
        if (e.key == key) {
            e.value = std::move(value);
            return *this;
        }
    entries_.push_back({std::move(key), std::move(value)});
    return *this;
}

const ReportValue* ReportNode::find(std::string_view key) const {
    for (const Entry& e : entries_)
        if (e.key == key) return &e.value;
    return nullptr;
}

const ReportValue& ReportNode::at(std::string_view key) const {
    if (const ReportValue* v = find(key)) return *v;
    throw Error("report: no value '" + std::string(key) + "'");
}

const ReportNode& ReportNode::node(std::string_view key) const {
    return at(key).node();
}
bool ReportNode::flag(std::string_view key) const {
    return at(key).flag();
}
std::int64_t ReportNode::integer(std::string_view key) const {
    return at(key).integer();
}
double ReportNode::number(std::string_view key) const {
    return at(key).number();
}
const std::string& ReportNode::text(std::string_view key) const {
    return at(key).text();
}
const std::vector<ReportValue>& ReportNode::list(std::string_view key) const {
    return at(key).list();
}

bool ReportValue::flag() const {
    if (kind_ != Kind::Flag) wrong_kind(kind_, Kind::Flag);
    return flag_;
}

std::int64_t ReportValue::integer() const {
    if (kind_ != Kind::Integer) wrong_kind(kind_, Kind::Integer);
    return integer_;
}

double ReportValue::number() const {
    if (kind_ == Kind::Integer) return static_cast<double>(integer_);
    if (kind_ != Kind::Number) wrong_kind(kind_, Kind::Number);
    return number_;
}

const std::string& ReportValue::text() const {
    if (kind_ != Kind::Text) wrong_kind(kind_, Kind::Text);
    return text_;
}

const ReportValue::List& ReportValue::list() const {
    if (kind_ != Kind::List) wrong_kind(kind_, Kind::List);
    return list_;
}

const ReportNode& ReportValue::node() const {
    if (kind_ != Kind::Node) wrong_kind(kind_, Kind::Node);
    return node_;
}

}  // namespace strata
