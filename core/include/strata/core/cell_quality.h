#pragma once
/// \file
/// Scaled Jacobians of cells in Gmsh node order: at each corner, det(e1, e2, e3) /
/// (|e1| |e2| |e3|) with e1, e2, e3 the corner's three edges in right-handed order; 1 for a
/// right-angled corner, ≤ 0 for an inverted one. The cell's value is its minimum over corners.

#include <strata/core/types.h>
#include <strata/core/volume_mesh.h>

#include <array>
#include <vector>

namespace strata {

/// Scaled Jacobian of the corner at \p o with edges to \p a, \p b, \p c (right-handed); 0 for a
/// collapsed edge, NaN where it cannot be computed (NaN coordinates, or edge lengths whose product
/// overflows). A cell's value is NaN if any corner's is.
double corner_scaled_jacobian(const Vec3& o, const Vec3& a, const Vec3& b, const Vec3& c);

double tet_min_scaled_jacobian(const std::vector<Vec3>& p, const std::array<Index, 4>& v);
double pyramid_min_scaled_jacobian(const std::vector<Vec3>& p, const std::array<Index, 5>& v);
double prism_min_scaled_jacobian(const std::vector<Vec3>& p, const std::array<Index, 6>& v);
double hex_min_scaled_jacobian(const std::vector<Vec3>& p, const std::array<Index, 8>& v);
/// The cell's value for a cell of type \p t with corners \p v (cell_corners(t) of them).
double min_scaled_jacobian(const std::vector<Vec3>& p, const Index* v, CellType t);
/// The same for a cell given by its cell_corners(t) corner positions \p corners, in order.
double min_scaled_jacobian(const Vec3* corners, CellType t);

/// The fixed bins of the scaled-Jacobian histograms (ValidationReport, OUT.report.json):
/// logarithmic, kQualityBinsPerDecade a decade from 1e-kQualityDecades up to 1, since the
/// cells worth seeing are the few between 1e-5 and 1e-1. Bin 0 holds everything below
/// 1e-kQualityDecades (≤ 0 and NaN too: an invalid mesh); bin b ≥ 1 holds
/// [quality_bin_edge(b − 1), quality_bin_edge(b)), the last one also 1 and rounding above it.
inline constexpr int kQualityDecades = 6;
inline constexpr int kQualityBinsPerDecade = 4;
inline constexpr int kQualityBins = 1 + kQualityDecades * kQualityBinsPerDecade;
/// The upper edge of bin \p b ≥ 0: 10^(−kQualityDecades + b / kQualityBinsPerDecade).
double quality_bin_edge(int b);
/// The bin of scaled Jacobian \p sj.
int quality_bin(double sj);

}  // namespace strata
