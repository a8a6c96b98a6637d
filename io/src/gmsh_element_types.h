#pragma once
// Gmsh's element type numbers for the linear elements Strata reads and writes (Gmsh's
// GmshDefines.h: MSH_TRI_3 = 2, MSH_QUA_4 = 3, MSH_TET_4 = 4, MSH_HEX_8 = 5, MSH_PRI_6 = 6,
// MSH_PYR_5 = 7). Private to io/: Gmsh's numbers never leave the adapter.

namespace strata::gmsh_types {

inline constexpr int kTriangle3 = 2;
inline constexpr int kQuad4 = 3;
inline constexpr int kTet4 = 4;
inline constexpr int kHex8 = 5;
inline constexpr int kPrism6 = 6;
inline constexpr int kPyramid5 = 7;

}  // namespace strata::gmsh_types
