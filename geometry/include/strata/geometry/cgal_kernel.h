#pragma once
// Private to strata_geometry: the CGAL kernel its exact queries use (exact predicates,
// inexact constructions) and the conversion from Strata's points.

#include <strata/core/types.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

namespace strata::cgal {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Triangle = Kernel::Triangle_3;
using Segment = Kernel::Segment_3;

inline Point point(const Vec3& x) {
    return {x.x(), x.y(), x.z()};
}

}  // namespace strata::cgal
