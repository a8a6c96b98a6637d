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
/// steps, better closed. Refining around columns stopped at a sharp edge or a junction (Quality,
/// SharpEdge, Neighbours) was tried (2026-11-24): the new nodes stop too, and on the body-fin
/// box, the NACA tunnel and the wing-fuselage the finer walls at those junctions made the layers
/// fold there, the lowering spreading over most of the body (coverage 90 % -> 18 %, 92 % -> 20 %,
/// 36 % -> 16 %). \p quality in (0, 1] (InputError otherwise).
std::vector<SizePoint> step_sizes(const SurfaceMesh& wall, const ProximityPlan& plan,
                                  const std::vector<double>& heights, double quality);

}  // namespace strata
