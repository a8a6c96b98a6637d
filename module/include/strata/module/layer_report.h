#pragma once
/// \file
/// The coverage report of the boundary layers: per wall patch, what was asked and what the
/// columns reached, and every wall node that fell short, with where and why. The layer
/// module fills it (layer_report); the report tree (frontend/report.h) carries it to the JSON,
/// Python and the CLI.

#include <strata/core/types.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace strata {

/// Why a column did not reach the thickness asked: it stopped below the layers asked (the
/// reasons a column stops, LayerParams) or its layers were thinned.
/// Quality, Turning, Twist and Neighbours: stopped there, or marched again ending where it
/// stopped with every layer (LayerConstraints::node_stop_limit).
enum class Shortfall : std::uint8_t {
    None,        ///< nothing limited it (smoothing may leave it a few per cent off)
    Proximity,   ///< fewer or thinner layers to fit the distance to a facing wall or patch
    Front,       ///< lowered where the layer front intersected itself or left no room for a pyramid
    HeldBack,    ///< lowered where its cells would have inverted (LayerParams::hold_back)
    Quality,     ///< stopped: a cell it would make falls below LayerParams::min_quality
    Turning,     ///< stopped: its column would turn more than LayerParams::max_turn_deg
    Twist,       ///< stopped: a cell it would make twists more than LayerParams::max_twist_deg
    Neighbours,  ///< stopped: with its neighbours stopped, the cell closing the step would be unusable; or lowered by a neighbour's bound
    NonFinite,   ///< stopped: its next position could not be computed
    SharpEdge,   ///< stopped at the wall: on a convex edge too sharp for one direction, without a fan
    Isotropic,   ///< stopped: its next layer would be taller than the front is wide there (LayerParams::isotropy)
};
inline constexpr std::size_t kShortfalls = 11;
/// "none", "proximity", "front", "held back", "quality", "turning", "twist", "neighbours",
/// "non-finite", "sharp edge", "isotropic".
std::string_view to_string(Shortfall reason);

/// One wall node as the coverage counts it (a node with a fan: its shortest column).
struct NodeCoverage {
    double share = 1.0;  ///< thickness reached / asked
    int layers = 0;      ///< layers reached
    Shortfall reason = Shortfall::None;
    bool proximity = false;  ///< a proximity limit binds it: stopped or thinned for a facing wall
};

/// One wall patch, or the whole wall (LayerReport::wall).
struct PatchCoverage {
    std::string name;
    Index faces = 0;
    Index nodes = 0;               ///< wall nodes on the patch (a node on two patches counts in both)
    Index full_nodes = 0;          ///< nodes whose column nothing limited
    Index all_layers = 0;          ///< nodes with every layer asked (possibly thinner)
    Index unbound_nodes = 0;       ///< nodes no proximity limit binds (NodeCoverage::proximity)
    Index unbound_all_layers = 0;  ///< of those, the nodes with every layer asked
    double mean_share = 1.0;       ///< mean thickness reached / asked over the patch's nodes
    double unbound_mean_share = 1.0;  ///< the same over the nodes no proximity limit binds (1 with none)
    double min_share = 1.0;
    double mean_layers = 0.0;  ///< layers reached, mean over the patch's nodes
    int min_layers = 0;
    std::array<Index, kShortfalls> short_by{};  ///< nodes short, by reason (index: Shortfall)
    Index short_nodes(Shortfall reason) const { return short_by[static_cast<std::size_t>(reason)]; }
    /// Nodes short for a reason of their own: every reason but None and Neighbours.
    Index own_reason_nodes() const;
    /// all_layers / nodes, and unbound_all_layers / unbound_nodes (1 with no such nodes).
    double all_layers_share() const;
    double unbound_all_layers_share() const;
};

/// The coverage of \p nodes (each wall node once) with \p layers asked, named \p name, over
/// \p faces faces: counts, means and minima (mean_share 1 and min_layers \p layers with none).
PatchCoverage coverage_of(std::string name, Index faces, const std::vector<NodeCoverage>& nodes, int layers);

/// A wall node whose column fell short.
struct ShortNode {
    Index node = kNone;  ///< wall node id (the node of the input surface: input_node)
    Vec3 position = Vec3::Zero();
    double share = 1.0;  ///< thickness reached / asked
    int layers = 0;      ///< layers reached
    Shortfall reason = Shortfall::None;
};

/// Why a wall node on a sharp convex edge got no fan (one column instead of several).
enum class NoFan : std::uint8_t {
    Unusable,  ///< the fan's first cells would have been unusable (a needle face or a narrow gap beside it)
    Uncapped,  ///< a fan's face on the layer top could not be capped with a pyramid (its columns twist)
    Skewed,    ///< a fan's cells had faces OpenFOAM's checkMesh would fail as skewed (kFoamSkewness)
    Open,      ///< on the wall's open boundary where no fan ends (its edge's fan ends one node before)
    Unclosed,  ///< its edge's chain could take no fan (a lone edge between two chain ends, a corner's dropped edge)
};
inline constexpr std::size_t kNoFanReasons = 5;
/// "unusable", "uncapped", "skewed", "open", "unclosed".
std::string_view to_string(NoFan reason);

/// A wall node on a sharp convex edge that got no fan.
struct NoFanNode {
    Index node = kNone;  ///< node of the input surface
    Vec3 position = Vec3::Zero();
    NoFan reason = NoFan::Unusable;
};

struct LayerReport {
    int layers = 0;             ///< layers asked
    double first_height = 0.0;  ///< asked
    double thickness = 0.0;     ///< asked: the sum of the layer heights
    std::vector<PatchCoverage> patches;
    PatchCoverage wall;                  ///< the whole wall: its faces, and each node once (named "wall")
    std::vector<ShortNode> short_nodes;  ///< every limited node, by wall node id
    std::vector<NoFanNode> no_fan;       ///< wall nodes with no fan (LayerParams::fan_angle_deg), by node id
    /// The wall nodes of no_fan with \p reason.
    Index no_fan_nodes(NoFan reason) const;
};

/// The layers each of the \p nodes nodes of the surface the layers stand on reached:
/// \p report's short nodes theirs, every other node report.layers.
std::vector<int> node_layers(const LayerReport& report, std::size_t nodes);
/// The share of the thickness asked each of them reached: the short nodes' theirs, every other
/// node 1 (nothing limited its column).
std::vector<double> node_shares(const LayerReport& report, std::size_t nodes);

}  // namespace strata
