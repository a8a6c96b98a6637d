#pragma once
/// \file
/// The whole pipeline after the surface: boundary layers, pyramid transition, tetrahedral
/// fill out to the farfield, assembled into one validated hybrid mesh.

#include <strata/core/progress.h>
#include <strata/core/validate.h>
#include <strata/geometry/point_sizes.h>
#include <strata/hybrid/farfield.h>
#include <strata/hybrid/improve_tets.h>
#include <strata/hybrid/pyramids.h>
#include <strata/hybrid/tetgen_fill.h>
#include <strata/module/layers.h>
#include <strata/module/step_sizes.h>

namespace strata {

struct HybridParams {
    LayerParams layers;  ///< its threads field is set from threads below
    PyramidParams pyramids;
    TetFillParams tets;
    TetImproveParams improve;  ///< the tetrahedra below a scaled Jacobian improved after TetGen
    FarfieldParams farfield;   ///< used when the surface has no farfield patch
    /// Threads of every parallel stage (layers, validation; 0: OpenMP's default; negative:
    /// InputError). The mesh is the same for any count.
    int threads = 0;
};

/// What each stage produced and how long it took, for the CLI's summary.
struct HybridReport {
    LayerCounts layers;    ///< the final layers' figures (LayerMesh's)
    int front_rounds = 0;  ///< rounds of lowering columns where the front intersected itself
    /// Per wall patch, the thickness reached and why not (layer_report), and the wall nodes left
    /// without a fan: its first cells would have been unusable (LayerMesh::fans_dropped) or its
    /// face on the layer top could not take a pyramid.
    LayerReport coverage;
    Index front_lowered_nodes = 0;  ///< column lowerings over those rounds
    /// Rounds where TetGen stopped on one of its internal checks recovering a layer-top face
    /// (fill_with_tets' LocalTopologyError) and the columns around it were lowered.
    int tet_retries = 0;
    /// Rounds where a wall quad could not take a pyramid on the layer top (too warped for an
    /// apex: a quad bent round a small hole), its columns at the wall or lowered for it in a
    /// round before, and was split into two triangles (its columns prisms).
    int split_quads = 0;
    /// The mesh had faces between layer cells checkMesh fails as skewed, and was made again
    /// with their columns capped below them (cap_skewed_columns): they stop for quality.
    bool skew_capped = false;
    std::vector<Index>
        remeshed_patches;  ///< patches (of the result's boundary) re-meshed around the layers' side faces
    /// Non-wall patches the layers end on that are not one plane but a few (a wind tunnel's
    /// single "farfield" group over its inlet, outlet, sides and top): re-meshed plane by plane
    /// round the layers, one patch in the result as in the input. Per such patch (of the
    /// result's boundary), the planes it was made of.
    std::vector<std::pair<Index, int>> planes_of_patches;
    /// The input was a half model (walls open along one plane): a half farfield and a
    /// "symmetry" patch were generated; their patches follow the input's.
    bool closed_half_model = false;
    /// The input's walls enclose the fluid (they point inward: PrepareParams::internal_flow), so
    /// no farfield was generated.
    bool internal_flow = false;
    /// With TetFillParams::mesher Hxt: why HXT could not fill the region, which TetGen then
    /// filled ("" where HXT did, or TetGen was asked).
    std::string tets_fallback;
    TetImproveReport tet_improve;  ///< what improve_tets changed
    ValidationReport validation;
    double seconds_layers = 0.0, seconds_pyramids = 0.0, seconds_tets = 0.0, seconds_validate = 0.0;
};

/// Build the hybrid mesh around the walls of \p surface (oriented; normals into the flow).
/// The fluid domain is closed by the surface's own farfield patches if it has any, or by its
/// walls alone where they point inward (internal flow: a duct, a tunnel), otherwise by a
/// generated box or sphere. Cells: the layers' hexahedra and prisms, pyramids on the
/// quads of the outermost layer, tetrahedra beyond. Patches: the input's (walls, farfield,
/// symmetry). The result passes require_valid_mesh (checked here; a failure throws).
/// Walls may end on planar non-wall patches (a half model's symmetry plane, an outflow plane,
/// a box side): the layers march in those planes and the planes are re-meshed around the
/// layers' side faces (outer_boundary). A half model (walls only, open along one plane) is
/// closed first (close_half_model: half farfield, symmetry plane). Any other open input:
/// InputError. \p progress: stages "layers", "pyramids", "tetrahedra", "validation"; cancelled,
/// Cancelled is thrown at the next check.
VolumeMesh build_hybrid_mesh(const SurfaceMesh& surface, const HybridParams& params, Progress* progress = nullptr,
                             HybridReport* report = nullptr);

/// What the layers of build_hybrid_mesh plan at their proximity limits on a surface (nothing
/// marched: proximity_plan over its closed domain, a half model closed as it closes it).
struct StepPlan {
    /// The sizes that would close their steps with a scaled Jacobian of about the quality
    /// asked (step_sizes); empty where no such step is below it.
    std::vector<SizePoint> points;
    /// The thickness the plan gives the walls, a share of the thickness asked, weighted by the
    /// wall area round each node (1: every column full).
    double thickness_share = 1.0;
    /// The sizes that keep the fans' first wedges under \p max_aspect_ratio (fan_wedge_sizes);
    /// empty where none exceeds it, or \p max_aspect_ratio is 0.
    FanWedgeSizes fans;
};
StepPlan step_plan(const SurfaceMesh& surface, const HybridParams& params, double quality,
                   double max_aspect_ratio = 0.0);

}  // namespace strata
