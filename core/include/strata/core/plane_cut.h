#pragma once
/// \file
/// The cells of a volume mesh cut by an axis-aligned plane, each as its polygon of
/// intersection in the plane's coordinates: for pictures of a section through the mesh.

#include <strata/core/volume_mesh.h>

#include <array>
#include <vector>

namespace strata {

/// The polygons of a plane cut, in CSR.
struct PlaneCut {
    int axis = 0;                               ///< the plane is x[axis] = value
    double value = 0.0;                         ///< model units
    int u = 1, v = 2;                           ///< the plane's coordinates: the other two axes, in order
    std::vector<CellType> types;                ///< per polygon, the type of the cell it cuts
    std::vector<Index> cells;                   ///< per polygon, the cell's index within its type
    std::vector<Index> offsets{0};              ///< polygon p is points[offsets[p] .. offsets[p + 1])
    std::vector<std::array<double, 2>> points;  ///< (x[u], x[v]) per polygon corner, model units
    Index num_polygons() const { return static_cast<Index>(types.size()); }
};

/// Cut \p mesh by the plane x[\p axis] = \p value (axis 0, 1, 2): every cell with corners on
/// both sides (a corner on the plane counts on the + side; a cell touching it at a corner or
/// an edge only gives none) gives the angle-ordered
/// polygon of the points where its edges cross the plane, kept when all of the cell's corners
/// lie in \p window = {u0, u1, v0, v1} of the plane's coordinates (a cut near the body without
/// the farfield's large cells). Cells in kCellTypes order, each type in mesh order.
PlaneCut cut_cells(const VolumeMesh& mesh, int axis, double value, const std::array<double, 4>& window);

}  // namespace strata
