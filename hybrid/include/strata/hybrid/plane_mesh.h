#pragma once
/// \file
/// Triangles filling a planar region bounded by polygons (a symmetry or outflow plane around
/// the layers, a half model's symmetry plane), through Gmsh's 2D mesher.

#include <strata/core/types.h>

#include <array>
#include <string>
#include <vector>

namespace strata {

struct PlaneMesh {
    std::vector<Vec3> new_points;  ///< interior points Gmsh added
    /// Counter-clockwise about the plane's normal; ids below points.size() are the caller's
    /// points, id points.size() + k is new_points[k].
    std::vector<std::array<Index, 3>> triangles;
};

/// Triangulate the region of the plane (\p origin, unit \p normal) bounded by \p loops (each a
/// cycle of ids into \p points, all in the plane): loops running counter-clockwise about the
/// normal bound a part of the region, clockwise ones are holes in the smallest such part that
/// contains them. Every loop point is kept and no point is added on a loop (each loop segment
/// is one edge of the result); the size inside grows from the loops' local spacing. With
/// \p growth > 0 it is the spacing of the nearest loop point marked in \p grow_from (every loop
/// point if empty) plus \p growth times the distance to it, at most the loops' largest spacing:
/// the tetrahedra's own rule (TetFillParams::growth), so that next to the layers the plane's
/// triangles match the tetrahedra standing on them. Runs in a scratch Gmsh model with Strata's
/// own mesh options; the caller's model and options are left as they were. TopologyError
/// (prefixed by \p context) if the loops do not bound a region, BackendError if Gmsh's result
/// does not cover it exactly.
PlaneMesh mesh_plane_region(const std::vector<Vec3>& points, const std::vector<std::vector<Index>>& loops,
                            const Vec3& origin, const Vec3& normal, const std::string& context, double growth = 0.0,
                            const std::vector<char>& grow_from = {});

}  // namespace strata
