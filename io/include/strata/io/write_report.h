#pragma once
/// \file
/// The layer coverage report as JSON, next to the mesh (OUT.report.json): what was asked, per
/// wall patch what was reached, and every node that fell short with its position and reason,
/// so that a picture of the layers achieved can be drawn.

#include <strata/core/layer_report.h>
#include <strata/core/surface_mesh.h>
#include <strata/core/validate.h>
#include <strata/core/volume_mesh.h>
#include <strata/io/files.h>

#include <string>

namespace strata {

/// The report file of a mesh written to \p mesh_path: mesh_path + ".report.json".
std::string report_path(const std::string& mesh_path);

/// Write \p report to \p path as JSON (UTF-8; numbers with 17 significant digits):
/// {"layers": n, "first_height": h, "thickness": t,
///  "layer_stats": [{"layer", "height", "min_scaled_jacobian", "mean_scaled_jacobian",
///                   "max_orthogonality_deg", "columns", "stopped_nodes", "held_nodes"}],
///  "patches": [{"name", "faces", "nodes", "full_nodes", "mean_share", "min_share",
///               "short": {"proximity", "front", "held_back"}}],
///  "short_nodes": [{"node", "position": [x, y, z], "share", "layers", "reason"}],
///  "no_fan_nodes": [{"node", "position": [x, y, z], "reason": "unusable" | "uncapped" | "skewed" |
///   "open" | "unclosed"}]}.
/// Atomic (temporary name, then rename), or staged in \p outputs to be committed with the mesh;
/// OutputError naming the path if it cannot be written.
void write_layer_report(const LayerReport& report, const std::string& path, OutputSet* outputs = nullptr);

/// write_layer_report with the mesh's figures after "thickness": "nodes", "cells" (per cell
/// type, all four), and "quality": {"min_scaled_jacobian": {"all", and per type with cells},
/// "bin_edges": the kQualityBins + 1 edges of the histograms' bins (0, then quality_bin_edge:
/// 1e-6 ... 1; bin 0 also holds anything ≤ 0), "histograms": {per type with cells: kQualityBins
/// counts summing to its cells}}. Small whatever the mesh: what `strata report` plots.
void write_mesh_report(const LayerReport& report, const VolumeMesh& mesh, const ValidationReport& quality,
                       const std::string& path, OutputSet* outputs = nullptr);

/// The file of the plots' geometry beside the mesh \p mesh_path: mesh_path + ".plot.json".
std::string plot_data_path(const std::string& mesh_path);

/// Write what the plots of `strata report` draw beyond the report, as JSON (7 significant
/// digits: for pictures), to \p path:
/// {"wall": {"points": [[x, y, z]], "faces": [[a, b, c(, d)]], "patches": [names],
///           "face_patch": [i], "layers": [layers reached per point]},
///  "cut": {"axis": "x" | "y" | "z", "value": c, "u": axis, "v": axis,
///          "window": [u0, u1, v0, v1], "types": [cell type name per polygon],
///          "polygons": [[u, v, u, v, ...]]}}.
/// wall: the wall patches of \p surface (the surface the layers were marched from; its node
/// ids are the report's), each point with the layers its column reached (\p report's short
/// nodes, every other wall node all of them). cut: the cells of \p mesh crossed by the plane
/// axis = value, each as its polygon of intersection, within the wall's box widened by half its
/// size in the plane (the layers and the first tetrahedra, not the farfield). The plane is
/// through the wall box's centre across its longest side (a wing's section, a missile's cross
/// section) unless \p cut_axis is 0, 1 or 2 (then at \p cut_value). Atomic, or staged in
/// \p outputs; OutputError naming the path if it cannot be written.
void write_plot_data(const LayerReport& report, const SurfaceMesh& surface, const VolumeMesh& mesh,
                     const std::string& path, int cut_axis = -1, double cut_value = 0.0, OutputSet* outputs = nullptr);

}  // namespace strata
