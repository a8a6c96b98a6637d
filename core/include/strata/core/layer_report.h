#pragma once
/// \file
/// The coverage report of the boundary layers: per wall patch, what was asked and what the
/// columns reached, and every wall node that fell short, with where and why. The layer
/// module fills it (layer_report), the program prints it, io writes it as JSON
/// (write_layer_report) next to the mesh.

#include <strata/core/types.h>

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace strata {

/// Why a column did not reach the thickness asked.
enum class Shortfall : std::uint8_t {
    None,       ///< nothing limited it (smoothing may leave it a few per cent off)
    Proximity,  ///< thinned to fit the distance to a facing wall or patch (LayerParams::proximity)
    Front,      ///< lowered where the layer front intersected itself
    HeldBack,   ///< lowered where its cells would have inverted (LayerParams::hold_back)
};
/// "none", "proximity", "front", "held back".
std::string_view to_string(Shortfall reason);

/// One wall patch.
struct PatchCoverage {
    std::string name;
    Index faces = 0;
    Index nodes = 0;          ///< wall nodes on the patch (a node on two patches counts in both)
    Index full_nodes = 0;     ///< nodes whose column nothing limited
    double mean_share = 1.0;  ///< mean thickness reached / asked over the patch's nodes
    double min_share = 1.0;
    Index proximity = 0, front = 0, held_back = 0;  ///< nodes short, by reason
};

/// A wall node whose column fell short.
struct ShortNode {
    Index node = kNone;  ///< wall node id (the node of the input surface: input_node)
    Vec3 position = Vec3::Zero();
    double share = 1.0;  ///< thickness reached / asked
    Shortfall reason = Shortfall::None;
};

struct LayerReport {
    int layers = 0;             ///< layers asked (every column has them all; some thinner)
    double first_height = 0.0;  ///< asked
    double thickness = 0.0;     ///< asked: the sum of the layer heights
    std::vector<PatchCoverage> patches;
    std::vector<ShortNode> short_nodes;  ///< every limited node, by wall node id
};

}  // namespace strata
