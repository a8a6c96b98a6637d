#pragma once
/// \file
/// Text for error messages and summaries: one way to print a point.

#include <strata/core/types.h>

#include <cstdio>
#include <string>

namespace strata {

/// "(x, y, z)" with \p digits significant digits (6: where in the model; 9: to tell close
/// nodes apart).
inline std::string format_point(const Vec3& p, int digits = 6) {
    char buf[128];
    std::snprintf(buf, sizeof buf, "(%.*g, %.*g, %.*g)", digits, p.x(), digits, p.y(), digits, p.z());
    return buf;
}

}  // namespace strata
