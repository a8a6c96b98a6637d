#include <strata/core/enum_names.h>
#include <strata/module/layer_report.h>

#include <algorithm>
#include <utility>

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

Index PatchCoverage::own_reason_nodes() const {
    Index n = 0;
    for (std::size_t k = 0; k < kShortfalls; ++k) {
        const auto reason = static_cast<Shortfall>(k);
        if (reason != Shortfall::None && reason != Shortfall::Neighbours) n += short_by[k];
    }
    return n;
}

double PatchCoverage::all_layers_share() const {
    return nodes > 0 ? static_cast<double>(all_layers) / static_cast<double>(nodes) : 1.0;
}

double PatchCoverage::unbound_all_layers_share() const {
    return unbound_nodes > 0 ? static_cast<double>(unbound_all_layers) / static_cast<double>(unbound_nodes) : 1.0;
}

PatchCoverage coverage_of(std::string name, Index faces, const std::vector<NodeCoverage>& nodes, int layers) {
    PatchCoverage c;
    c.name = std::move(name);
    c.faces = faces;
    c.min_layers = layers;
    double share_sum = 0.0, unbound_share_sum = 0.0, layer_sum = 0.0;
    for (const NodeCoverage& n : nodes) {
        ++c.nodes;
        share_sum += n.share;
        layer_sum += n.layers;
        c.min_share = std::min(c.min_share, n.share);
        c.min_layers = std::min(c.min_layers, n.layers);
        c.all_layers += n.layers == layers;
        c.full_nodes += n.reason == Shortfall::None;
        c.unbound_nodes += !n.proximity;
        unbound_share_sum += n.proximity ? 0.0 : n.share;
        c.unbound_all_layers += !n.proximity && n.layers == layers;
        ++c.short_by[static_cast<std::size_t>(n.reason)];
    }
    if (c.nodes > 0) {
        c.mean_share = share_sum / static_cast<double>(c.nodes);
        c.mean_layers = layer_sum / static_cast<double>(c.nodes);
    }
    if (c.unbound_nodes > 0) c.unbound_mean_share = unbound_share_sum / static_cast<double>(c.unbound_nodes);
    return c;
}

Index LayerReport::no_fan_nodes(NoFan reason) const {
    Index n = 0;
    for (const NoFanNode& v : no_fan) n += v.reason == reason ? 1 : 0;
    return n;
}

namespace {

/// Per node of the surface (\p nodes of them): \p full, the short nodes' \p field.
template <class T>
std::vector<T> per_node(const LayerReport& report, std::size_t nodes, T full, T ShortNode::*field) {
    std::vector<T> out(nodes, full);
    for (const ShortNode& n : report.short_nodes)
        if (n.node >= 0 && static_cast<std::size_t>(n.node) < nodes) out[static_cast<std::size_t>(n.node)] = n.*field;
    return out;
}

}  // namespace

std::vector<int> node_layers(const LayerReport& report, std::size_t nodes) {
    return per_node(report, nodes, report.layers, &ShortNode::layers);
}

std::vector<double> node_shares(const LayerReport& report, std::size_t nodes) {
    return per_node(report, nodes, 1.0, &ShortNode::share);
}

}  // namespace strata
