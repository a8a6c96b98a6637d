#pragma once
/// \file
/// The layer coverage report as JSON, next to the mesh (OUT.report.json): what was asked, per
/// wall patch what was reached, and every node that fell short with its position and reason,
/// so that a picture of the layers achieved can be drawn.

#include <strata/core/layer_report.h>

#include <string>

namespace strata {

/// The report file of a mesh written to \p mesh_path: mesh_path + ".report.json".
std::string report_path(const std::string& mesh_path);

/// Write \p report to \p path as JSON (UTF-8; numbers with 17 significant digits):
/// {"layers": n, "first_height": h, "thickness": t,
///  "patches": [{"name", "faces", "nodes", "full_nodes", "mean_share", "min_share",
///               "short": {"proximity", "front", "held_back"}}],
///  "short_nodes": [{"node", "position": [x, y, z], "share", "layers", "reason"}],
///  "no_fan_nodes": [{"node", "position": [x, y, z], "reason": "unusable" | "uncapped"}]}.
/// Atomic (temporary name, then rename); InputError naming the path if it cannot be written.
void write_layer_report(const LayerReport& report, const std::string& path);

}  // namespace strata
