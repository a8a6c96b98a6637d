#pragma once
/// \file
/// Where the layers will step low at a proximity limit, the wall spacing that would make the
/// cells closing the steps usable: the sizes a front-end meshes a CAD model's walls again with
/// (CadParams::size_points, prepare_for_layers).

#include <strata/geometry/point_sizes.h>
#include <strata/module/layers.h>

#include <vector>

namespace strata {

/// Gmsh's edges run up to about 1.4 times the size asked; a size asks this share of the spacing
/// it needs.
inline constexpr double kStepSizeShare = 0.7;

/// The cells closing a step (ALGORITHM.md, "The cells that close a step") have a corner at the
/// stopped column's top that sees the taller column's next segment edge-on: its scaled Jacobian
/// is about that segment's height s over the wall distance L between the two columns. For every
/// wall node i that \p plan stops at its proximity limit below a neighbour j across a wall face
/// of \p wall (levels[i] < levels[j]) where s / L < \p quality (s = \p heights[levels[i]], the
/// layer heights asked), the size that gives s / L = quality: a point at i with kStepSizeShare ·
/// s / quality, the smallest over i's neighbours. In node order, one per such node.
///
/// Only proximity steps: their place follows the gap, so a finer wall there gives the same
/// steps, better closed; round columns stopped at a sharp edge or a junction the new nodes stop
/// too, and finer walls there make the layers fold (docs/DESIGN_NOTES.md). \p quality in (0, 1]
/// (InputError otherwise).
std::vector<SizePoint> step_sizes(const SurfaceMesh& wall, const ProximityPlan& plan,
                                  const std::vector<double>& heights, double quality);

/// The sizes fan_wedge_sizes asks.
struct FanWedgeSizes {
    /// At the \p nodes wall nodes first (in node order, the smallest a node's wedges ask), then
    /// along the edges between them.
    std::vector<SizePoint> points;
    Index nodes = 0;  ///< wall nodes at the ends of the edges sized
};

/// A fan's first wedge along a wall edge of length L is a prism whose end triangles are about
/// h² against sides of L · h, OpenFOAM's aspect ratio about 2L / (h sin w)
/// (fan_wedge_aspect_ratio): fans want edges four times shorter than faces do. For every wedge
/// of \p plan (ProximityPlan::fan_wedges, the fans the layers would build on \p wall) whose
/// aspect ratio under a first layer of \p first_height exceeds \p max_aspect_ratio, the length
/// that gives kStepSizeShare of the limit, asked at each end of its edge (the smallest at a
/// node) and at points along it half that length apart. The CAD wall sizing
/// (CadParams::max_aspect_ratio) forecasts the fan curves before the surface is meshed; this
/// sees the fans the layers build on it: a chain closed through a curve that touches no fan
/// curve (a delta wing's blunt base) is sized here, and a chain the fans drop (one ending at a
/// concave junction) is not. Empty when \p max_aspect_ratio or \p first_height is 0.
FanWedgeSizes fan_wedge_sizes(const SurfaceMesh& wall, const ProximityPlan& plan, double first_height,
                              double max_aspect_ratio);

/// fan_wedge_sizes skips wedges whose columns are closer than this (degrees): the narrowest a
/// chain's closing curve of 30 degrees gets in a run of two wedges; the sizes narrower wedges
/// ask make needles of a thin fin's faces (docs/DESIGN_NOTES.md).
inline constexpr double kFanWedgeMinDeg = 15.0;

}  // namespace strata
