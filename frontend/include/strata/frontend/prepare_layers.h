#pragma once
/// \file
/// The surface for a hybrid mesh: prepare_surfaces, then, for CAD input, the walls meshed
/// again finer where the layers would step low (CadParams::step_quality).

#include <strata/hybrid/hybrid_mesh.h>
#include <strata/surface/prepare.h>

#include <functional>

namespace strata {

/// The surface meshed again for the steps has at most this many times the faces it had (the
/// sizes raised until the estimate fits): finer walls at a gap are a gain in quality, not a
/// need, and two bodies 3 mm apart over a wide face took 80 times the cells without it.
inline constexpr double kStepFacesGrowth = 3.0;

/// The walls meshed again for the steps are kept only if the layers' plan on them keeps the
/// thickness it had within this share of what was asked (StepSizeReport::kept otherwise).
inline constexpr double kStepThicknessLoss = 0.02;

/// How a surface is made with some PrepareParams, its report filled: prepare_surfaces on the
/// input files, or prepare_mesh on a surface given. prepare_for_layers calls it again with
/// other parameters.
using SurfaceSource = std::function<SurfaceMesh(const PrepareParams&, PrepareReport*)>;

/// \p source(\p params). Then, when \p cad (some input is a CAD file) and
/// params.cad.step_quality > 0: the layers build_hybrid_mesh would march on it (first_layers
/// with \p mesh), the sizes their steps ask (step_sizes), and, if any, the surface made again
/// with those sizes as CadParams::size_points (in the CAD's unit: over PrepareParams::scale),
/// raised where needed so that the surface stays within about CadParams::wall_faces_budget
/// faces and kStepFacesGrowth times its own; the first surface stays if the new one's plan
/// gives the walls less thickness (kStepThicknessLoss). report->steps says what was done; the
/// rest of \p report is the final surface's. If the layers cannot be marched, the first surface
/// is returned (build_hybrid_mesh then reports why). Where Blossom's quads (CAD, or a remeshed
/// surface) fold, the surface is made again with Gmsh's simple recombination if that does not.
SurfaceMesh prepare_for_layers(const SurfaceSource& source, bool cad, const PrepareParams& params,
                               const HybridParams& mesh, PrepareReport* report = nullptr);

}  // namespace strata
