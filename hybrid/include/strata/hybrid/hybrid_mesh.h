#pragma once
/// \file
/// The whole pipeline after the surface: boundary layers, pyramid transition, tetrahedral
/// fill out to the farfield, assembled into one validated hybrid mesh.

#include <strata/hybrid/farfield.h>
#include <strata/hybrid/pyramids.h>
#include <strata/hybrid/tetgen_fill.h>
#include <strata/module/layers.h>
#include <strata/module/validate.h>
#include <strata/progress.h>

namespace strata {

struct HybridParams {
    LayerParams layers;
    PyramidParams pyramids;
    TetFillParams tets;
    FarfieldParams farfield;  ///< used when the surface has no farfield patch
};

/// What each stage produced and how long it took, for the CLI's summary.
struct HybridReport {
    std::vector<LayerStats> layer_stats;
    Index unsmoothed_nodes = 0;
    ValidationReport validation;
    double seconds_layers = 0.0, seconds_pyramids = 0.0, seconds_tets = 0.0, seconds_validate = 0.0;
};

/// Build the hybrid mesh around the walls of \p surface (oriented; normals into the flow).
/// The fluid domain is closed by the surface's own farfield patches if it has any, otherwise
/// by a generated box or sphere. Cells: the layers' hexahedra and prisms, pyramids on the
/// quads of the outermost layer, tetrahedra beyond. Patches: the input's (walls, farfield,
/// symmetry). The result passes require_valid_mesh (checked here; a failure throws).
/// Surfaces whose layers end on a symmetry or outflow plane (open walls) are not supported
/// yet: InputError.
VolumeMesh build_hybrid_mesh(const SurfaceMesh& surface, const HybridParams& params, Progress* progress = nullptr,
                             HybridReport* report = nullptr);

}  // namespace strata
