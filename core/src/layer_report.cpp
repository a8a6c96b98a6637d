#include <strata/core/enum_names.h>
#include <strata/core/layer_report.h>

namespace strata {

std::string_view to_string(Shortfall reason) {
    static constexpr EnumNames<Shortfall, kShortfalls> kNames{
        {"none", "proximity", "front", "held back", "quality", "turning", "twist", "neighbours", "non-finite"}};
    return kNames.name(reason);
}

}  // namespace strata
