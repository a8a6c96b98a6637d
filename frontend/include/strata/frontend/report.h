#pragma once
/// \file
/// The report of a run, built once from the stages' results as a tree (report_tree.h): the
/// JSON beside the mesh (write_report), the Python dict and the CLI's summary all walk it, so a
/// field added here reaches the three. Its keys, for a hybrid mesh in order: the coverage head
/// ("layers" asked, "first_height", "thickness"), the mesh ("nodes", "cells", "quality"), the
/// layers ("layer_stats"), the coverage ("coverage": the whole wall, "patches", "short_nodes",
/// "no_fan_nodes"), the layers' counters (LayerCounts: "unsmoothed_nodes", "thinned_nodes",
/// "fan_edges", ...), the hybrid stages' ("internal_flow", "front_rounds", "tet_improve", ...),
/// "surface" (PrepareReport), "times" (seconds per stage) and "provenance" (Strata's version and
/// commit, the inputs, the options given).

#include <strata/core/report_tree.h>
#include <strata/core/surface_mesh.h>
#include <strata/core/validate.h>
#include <strata/core/volume_mesh.h>
#include <strata/frontend/options.h>
#include <strata/hybrid/hybrid_mesh.h>
#include <strata/module/layer_report.h>
#include <strata/module/layers.h>
#include <strata/surface/prepare.h>

#include <string>
#include <utility>
#include <vector>

namespace strata {

/// Seconds per stage, in the order they ran ("surface", "layers", ...).
using StageTimes = std::vector<std::pair<std::string, double>>;

/// Strata's version ("0.1.0") and the git commit it was built from ("unknown" outside a
/// git checkout).
std::string strata_version();
std::string strata_commit();

/// "provenance": {"strata_version", "git_commit", "inputs": [the input files], "options":
/// {keyword (the flag without "--" where there is none): value} for every option of the table
/// (option_table) whose value in \p options differs from the default}.
ReportNode provenance_report(const Options& options);

/// "surface": the surface (\p surface: its counts, "patch_table", "open_loops", its wall's
/// "needles"), whether it came from CAD (\p cad_input) and what prepare_surfaces did (\p report).
/// A layers or mesh run's also has "wall_aspect" where the surface was kept as it is: its wall
/// faces against the first layer (--max-aspect-ratio).
ReportNode surface_report(const SurfaceMesh& surface, const PrepareReport& report, bool cad_input);

/// The mesh's figures: "nodes" (when \p mesh is given), "cells" per type, and "quality": per
/// type with cells its "min_scaled_jacobian" (and "all"), "worst_cell", the "bin_edges" and
/// "histograms" of the quality bins, "cell_volume", "boundary_volume", and "openfoam" (checkMesh's
/// figures). The cells per type are the histograms' sums, so a report without the mesh (the
/// Gmsh model's) has them too.
ReportNode quality_report(const ValidationReport& validation, const VolumeMesh* mesh);

/// The report of `strata surface`: surface_report's keys at the root, then "times" and
/// "provenance".
ReportNode surface_run_report(const SurfaceMesh& surface, const PrepareReport& report, const Options& options,
                              const StageTimes& times);

/// The report of `strata layers`: the layers \p lm, their \p coverage (layer_report) and their
/// \p validation; "surface", "times" and "provenance" when \p surface and \p prepared are given.
ReportNode layers_run_report(const LayerMesh& lm, const LayerReport& coverage, const ValidationReport& validation,
                             const SurfaceMesh* surface, const PrepareReport* prepared, const Options& options,
                             const StageTimes& times);

/// The report of `strata mesh`: the hybrid mesh \p mesh (nullptr: a mesh handed to Gmsh, whose
/// node count and patch names are then left out) and \p hybrid; "surface" when \p surface and
/// \p prepared are given.
ReportNode mesh_run_report(const VolumeMesh* mesh, const HybridReport& hybrid, const SurfaceMesh* surface,
                           const PrepareReport* prepared, const Options& options, const StageTimes& times);

/// \p report's "times" with \p stage set to \p seconds (a stage timed after the report was
/// built: writing the files).
void set_time(ReportNode& report, const std::string& stage, double seconds);

}  // namespace strata
