#pragma once
/// \file
/// Text for error messages and summaries: the one way Strata prints a number, a point and a
/// list of node ids.

#include <strata/core/types.h>

#include <cstdio>
#include <string>

namespace strata {

/// \p v with \p digits significant digits, printf's %g: "0.02", "1.5e-07", "nan".
/// 17 digits read back to the same double (TetGen's switches are built with it).
inline std::string format_number(double v, int digits = 6) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*g", digits, v);
    return buf;
}

/// "(x, y, z)" with \p digits significant digits (6: where in the model; 9: to tell close
/// nodes apart).
inline std::string format_point(const Vec3& p, int digits = 6) {
    char buf[128];
    std::snprintf(buf, sizeof buf, "(%.*g, %.*g, %.*g)", digits, p.x(), digits, p.y(), digits, p.z());
    return buf;
}

/// "(a b c)": the node ids of a face or cell as a message names them.
inline std::string format_nodes(const Index* v, int n) {
    std::string s = "(";
    for (int i = 0; i < n; ++i) {
        if (i) s += ' ';
        s += std::to_string(v[i]);
    }
    return s + ')';
}

}  // namespace strata
