#pragma once
/// \file
/// A run's report as JSON next to the mesh (OUT.report.json): the report tree (report_tree.h)
/// written as it is, whatever it holds; and the data of the plots `strata report` draws.

#include <strata/core/report_tree.h>
#include <strata/core/surface_mesh.h>
#include <strata/core/volume_mesh.h>
#include <strata/io/files.h>

#include <string>
#include <vector>

namespace strata {

/// The report file of a mesh written to \p mesh_path: mesh_path + ".report.json".
std::string report_path(const std::string& mesh_path);

/// \p report as JSON (UTF-8): a node an object with its keys in order, a list an array, a
/// number with 17 significant digits (null where not finite), an integer, a flag or a text as
/// themselves. Rows of a table (a list of nodes) one per line.
std::string report_json(const ReportNode& report);

/// Write report_json(\p report) to \p path. Atomic (temporary name, then rename), or staged in
/// \p outputs to be committed with the mesh; OutputError naming the path if it cannot be written.
void write_report(const ReportNode& report, const std::string& path, OutputSet* outputs = nullptr);

/// The file of the plots' geometry beside the mesh \p mesh_path: mesh_path + ".plot.json".
std::string plot_data_path(const std::string& mesh_path);

/// Write what the plots of `strata report` draw beyond the report, as JSON (7 significant
/// digits: for pictures), to \p path:
/// {"wall": {"points": [[x, y, z]], "faces": [[a, b, c(, d)]], "patches": [names],
///           "face_patch": [i], "layers": [layers reached per point],
///           "share": [thickness reached / asked per point]},
///  "cut": {"axis": "x" | "y" | "z", "value": c, "u": axis, "v": axis,
///          "window": [u0, u1, v0, v1], "types": [cell type name per polygon],
///          "polygons": [[u, v, u, v, ...]]}}.
/// wall: the wall patches of \p surface (the surface the layers were marched from; its node
/// ids are the report's), each point with the layers its column reached (\p node_layers) and
/// its share of the thickness asked (\p node_share), one per node of \p surface (Error if
/// not). cut: the cells of \p mesh crossed by the plane
/// axis = value, each as its polygon of intersection, within the wall's box widened by half its
/// size in the plane (the layers and the first tetrahedra, not the farfield). The plane is
/// through the wall box's centre across its longest side (a wing's section, a missile's cross
/// section) unless \p cut_axis is 0, 1 or 2 (then at \p cut_value). Atomic, or staged in
/// \p outputs; OutputError naming the path if it cannot be written.
void write_plot_data(const std::vector<int>& node_layers, const std::vector<double>& node_share,
                     const SurfaceMesh& surface, const VolumeMesh& mesh, const std::string& path, int cut_axis = -1,
                     double cut_value = 0.0, OutputSet* outputs = nullptr);

}  // namespace strata
