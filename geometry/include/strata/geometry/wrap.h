#pragma once
/// \file
/// A watertight surface around a surface that cannot be repaired in place (non-manifold edges,
/// holes, self-intersections, parts that overlap or touch, faces given twice): CGAL's 3D alpha
/// wrapping (CGAL/alpha_wrap_3.h, Portaneri et al. 2022), which returns a closed, 2-manifold,
/// non-self-intersecting triangle mesh enclosing every input face at a chosen offset. Each
/// face of the wrap takes the patch of the input face nearest its centre, and the result says
/// how far the wrap lies from the input, both ways, measured.

#include <strata/core/surface_mesh.h>

#include <algorithm>

namespace strata {

struct WrapParams {
    /// The wrap's α: the smallest cavity, gap or hole it follows; anything narrower is closed
    /// over. 0: a hundredth of the input's bounding-box diagonal.
    double alpha = 0.0;
    /// Distance of the wrap from the input. 0: α / 30 (CGAL's default).
    double offset = 0.0;
    /// Threads measuring the distances (0: all cores); the wrap itself is CGAL's, on one.
    int threads = 0;
};

/// How far the wrap lies from its input (distances in the mesh's units), measured at every
/// node, edge midpoint and face centre of each against the other's faces.
struct WrapReport {
    double alpha = 0.0;   ///< the α used
    double offset = 0.0;  ///< the offset used
    Index input_faces = 0;
    Index faces = 0;                ///< the wrap's triangles
    double wrap_to_input = 0.0;     ///< the farthest point of the wrap from the input ...
    Vec3 wrap_to_input_at = Vec3::Zero();  ///< ... and where it is
    double input_to_wrap = 0.0;     ///< the farthest point of the input from the wrap (inner faces of overlapping parts count) ...
    Vec3 input_to_wrap_at = Vec3::Zero();  ///< ... and where it is
    double seconds = 0.0;           ///< the wrapping alone
    /// The two-sided (Hausdorff) distance: the larger of the two.
    double hausdorff() const { return std::max(wrap_to_input, input_to_wrap); }
};

/// The alpha wrap of \p soup (any triangles and quads, in any state; quads split along their
/// first diagonal) by \p params, faces oriented outward, each with the patch of the nearest
/// input face. Deterministic. InputError for an empty soup, a non-finite coordinate, or α,
/// offset or threads negative (or not finite).
SurfaceMesh wrap_surface(const SurfaceMesh& soup, const WrapParams& params, WrapReport* report = nullptr);

}  // namespace strata
