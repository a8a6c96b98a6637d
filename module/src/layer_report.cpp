#include <strata/core/enum_names.h>
#include <strata/module/layer_report.h>

namespace strata {

std::string_view to_string(Shortfall reason) {
    static constexpr EnumNames<Shortfall, kShortfalls> kNames{{"none", "proximity", "front", "held back", "quality",
                                                               "turning", "twist", "neighbours", "non-finite",
                                                               "sharp edge", "isotropic"}};
    return kNames.name(reason);
}

std::string_view to_string(NoFan reason) {
    static constexpr EnumNames<NoFan, kNoFanReasons> kNames{{"unusable", "uncapped", "skewed", "open", "unclosed"}};
    return kNames.name(reason);
}

Index LayerReport::no_fan_nodes(NoFan reason) const {
    Index n = 0;
    for (const NoFanNode& v : no_fan) n += v.reason == reason ? 1 : 0;
    return n;
}

std::vector<int> node_layers(const LayerReport& report, std::size_t nodes) {
    std::vector<int> layers(nodes, report.layers);
    for (const ShortNode& n : report.short_nodes)
        if (n.node >= 0 && static_cast<std::size_t>(n.node) < nodes)
            layers[static_cast<std::size_t>(n.node)] = n.layers;
    return layers;
}

}  // namespace strata
