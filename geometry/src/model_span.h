#pragma once
// How far apart a model's nodes may be. The geometry stage multiplies lengths: areas are
// squares, the volumes that orient closed surfaces cubes, and these overflow a double (1.8e308)
// once the model spans about 1e102. No real model comes near (the observable universe is 1e27
// millimetres); a file that does is corrupt, or its coordinates are in a unit far too small.

#include <strata/core/error.h>
#include <strata/core/face_geometry.h>
#include <strata/core/format.h>

#include <string>

namespace strata {

/// The largest bounding-box diagonal of a model, in model units.
inline constexpr double kMaxModelSpan = 1e100;

/// TopologyError "<where>the nodes span from (..) to (..), ..." unless \p box's diagonal is
/// below kMaxModelSpan (also when it overflows to infinity).
inline void require_model_span(const BoundingBox& box, const std::string& where) {
    const double diag = box.diagonal();
    if (diag < kMaxModelSpan) return;
    throw TopologyError(where + "the nodes span from " + format_point(box.min) + " to " + format_point(box.max) +
                        " (a bounding-box diagonal of " + format_number(diag, 3) + "), beyond the " +
                        format_number(kMaxModelSpan, 3) +
                        " where the areas and volumes computed from them overflow; the file is corrupt "
                        "or its coordinates are in the wrong unit (PrepareParams::scale, --scale)");
}

}  // namespace strata
