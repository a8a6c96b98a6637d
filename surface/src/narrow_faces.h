#pragma once
// CadParams::narrow_face_ratio: size points along the boundary of the CAD faces narrower than
// the element size (inside a GmshSession, on an OpenCASCADE model).

#include <strata/geometry/point_sizes.h>
#include <strata/surface/cad.h>

#include <vector>

namespace strata {

/// How fast the sizes asked along a narrow face rise into the faces around, per unit of distance:
/// back to the size within twice the size.
inline constexpr double kNarrowFaceGrowth = 0.5;

/// The size points that mesh the faces of \p surfaces narrower than \p size / ratio at ratio times
/// their width (CadParams::narrow_face_ratio), to spread at kNarrowFaceGrowth; faces that would
/// need sizes below \p floor are left alone (their triangles would stay slivers, only more of
/// them); what was found goes into \p r (WallSizeReport's narrow_*). A face is
/// narrow when ratio times its width is below both the size and its length (half its
/// perimeter less its width: not a disc or a square). None when the ratio is 0, or when the
/// faces they would add exceed CadParams::wall_faces_budget (\p r says so). Faces
/// OpenCASCADE cannot measure (a .geo's built-in kernel) are skipped.
std::vector<SizePoint> narrow_face_points(const std::vector<int>& surfaces, const CadParams& params, double size,
                                          double floor, WallSizeReport& r);

}  // namespace strata
