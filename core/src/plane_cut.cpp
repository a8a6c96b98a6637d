// The cells cut by an axis-aligned plane: plane_cut.h.

#include <strata/core/cell_faces.h>
#include <strata/core/error.h>
#include <strata/core/plane_cut.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

namespace strata {
namespace {

/// The edges of cell type \p t as local corner pairs: each face's sides, once each.
std::vector<std::pair<int, int>> cell_edges(CellType t) {
    const CellFaceTable& table = cell_faces(t);
    std::vector<std::pair<int, int>> edges;
    for (int f = 0; f < table.count; ++f) {
        const auto& nodes = table.node[static_cast<std::size_t>(f)];
        const int n = table.size[static_cast<std::size_t>(f)];
        for (int j = 0; j < n; ++j) {
            const int a = nodes[static_cast<std::size_t>(j)], b = nodes[static_cast<std::size_t>((j + 1) % n)];
            edges.emplace_back(std::min(a, b), std::max(a, b));
        }
    }
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    return edges;
}

}  // namespace

PlaneCut cut_cells(const VolumeMesh& mesh, int axis, double value, const std::array<double, 4>& window) {
    if (axis < 0 || axis > 2) throw InputError("cut_cells: axis " + std::to_string(axis) + " is not 0, 1 or 2");
    PlaneCut cut;
    cut.axis = axis;
    cut.value = value;
    cut.u = axis == 0 ? 1 : 0;
    cut.v = axis == 2 ? 1 : 2;
    std::vector<std::array<double, 2>> poly;
    for (const CellType t : kCellTypes) {
        const int nc = cell_corners(t);
        const std::vector<std::pair<int, int>> edges = cell_edges(t);
        for (std::size_t i = 0; i < mesh.num_cells(t); ++i) {
            const Index* c = mesh.cell(t, i);
            bool below = false, above = false, inside = true;
            for (int k = 0; k < nc; ++k) {
                const Vec3& p = mesh.points[static_cast<std::size_t>(c[k])];
                (p[axis] - value < 0.0 ? below : above) = true;
                inside = inside && p[cut.u] >= window[0] && p[cut.u] <= window[1] && p[cut.v] >= window[2] &&
                         p[cut.v] <= window[3];
            }
            if (!below || !above || !inside) continue;
            poly.clear();
            for (const auto& [a, b] : edges) {
                const Vec3& p = mesh.points[static_cast<std::size_t>(c[a])];
                const Vec3& q = mesh.points[static_cast<std::size_t>(c[b])];
                const double dp = p[axis] - value, dq = q[axis] - value;
                if ((dp < 0.0) == (dq < 0.0)) continue;
                // A corner on the plane is taken as it is, so that cells touching the plane at a
                // corner or an edge give repeated points (dropped below), not slivers.
                const double s = dp / (dp - dq);  // dp and dq differ in sign: no division by 0
                const Vec3 x = dp == 0.0 ? p : dq == 0.0 ? q : Vec3(p + s * (q - p));
                poly.push_back({x[cut.u], x[cut.v]});
            }
            std::sort(poly.begin(), poly.end());
            poly.erase(std::unique(poly.begin(), poly.end()), poly.end());
            if (poly.size() < 3) continue;  // touching only
            // Convex: order the crossings by angle about their mean.
            double mu = 0.0, mv = 0.0;
            for (const auto& x : poly) mu += x[0], mv += x[1];
            mu /= static_cast<double>(poly.size()), mv /= static_cast<double>(poly.size());
            std::sort(poly.begin(), poly.end(), [&](const auto& x, const auto& y) {
                return std::atan2(x[1] - mv, x[0] - mu) < std::atan2(y[1] - mv, y[0] - mu);
            });
            cut.types.push_back(t);
            cut.cells.push_back(static_cast<Index>(i));
            cut.points.insert(cut.points.end(), poly.begin(), poly.end());
            cut.offsets.push_back(static_cast<Index>(cut.points.size()));
        }
    }
    return cut;
}

}  // namespace strata
