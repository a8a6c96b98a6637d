#pragma once
// The layer parameters and level heights the layer tests share (test_layers.cpp on synthetic
// walls, test_layer_cases.cpp on prepared geometries).

#include <strata/module/layers.h>

#include <vector>

namespace strata::test {

inline LayerParams geometric(int layers, double h1, double q) {
    LayerParams p;
    p.distribution.layers = layers;
    p.distribution.kind = Distribution::Geometric;
    p.distribution.first_height = h1;
    p.distribution.growth = q;
    return p;
}

/// Height of level k above the wall: Σ_{j<k} δ_j.
inline std::vector<double> level_heights(const LayerParams& p) {
    const std::vector<double> d = layer_heights(p.distribution);
    std::vector<double> h{0.0};
    for (int k = 0; k < p.distribution.layers; ++k) h.push_back(h.back() + d[static_cast<std::size_t>(k)]);
    return h;
}

}  // namespace strata::test
