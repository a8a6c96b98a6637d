#pragma once
// The wall sizing of CadParams::max_aspect_ratio: a Gmsh size callback on chosen entities
// (inside a GmshSession).

#include <strata/core/surface_mesh.h>
#include <strata/geometry/point_sizes.h>
#include <strata/surface/cad.h>

#include <functional>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace strata {

/// Faces a surface of area \p area gets at element size \p size: equilateral triangles of that
/// edge (Gmsh's frontal meshers give edges close to the size).
inline double faces_at_size(double area, double size) {
    return area / (0.4330127 * size * size);
}

/// Mesh sizes per Gmsh entity (dim, tag); entities not in it are left alone.
class EntitySizes {
public:
    /// \p size on (dim, tag) unless it already has a smaller one.
    void cap(int dim, int tag, double size);
    /// \p size on surface \p tag, its boundary curves and their points.
    void cap_surface(int tag, double size);
    /// \p size on curve \p tag and its end points.
    void cap_curve(int tag, double size);
    bool empty() const { return size_.empty(); }
    const std::map<std::pair<int, int>, double>& sizes() const { return size_; }

private:
    void cap_boundary(int dim, int tag, double size);
    std::map<std::pair<int, int>, double> size_;
};

/// While alive, Gmsh's size callback gives each entity of \p sizes its size and every point the
/// smallest size any of \p points asks there (Gmsh takes the smaller of the callback and its
/// other sizes), every size divided by \p factor (Gmsh multiplies the callback's by
/// Mesh.MeshSizeFactor). Removed on destruction. \p points (empty ones are skipped) must
/// outlive it.
class SizeCallback {
public:
    SizeCallback(const EntitySizes& sizes, double factor, const std::vector<const PointSizes*>& points = {});
    ~SizeCallback();
    SizeCallback(const SizeCallback&) = delete;
    SizeCallback& operator=(const SizeCallback&) = delete;

private:
    std::map<std::pair<int, int>, double> size_;
    std::vector<const PointSizes*> points_;
    double factor_ = 1.0;
};

/// What the first layer may be: its height, the largest OpenFOAM aspect ratio of its cells, the
/// layers' fan angle (0: no fans), the most faces the walls may get for it.
struct WallLimits {
    double first_height = 0.0;
    double max_aspect_ratio = 0.0;
    double fan_angle_deg = 0.0;
    double faces_budget = 0.0;
};

/// The first layer's aspect ratio over the walls of a mesh just made, and where it is over.
struct WallAspect {
    double worst = 0.0;                        ///< the largest predicted, faces and fans
    std::vector<int> surfaces;                 ///< wall surfaces with a face over the limit
    std::map<int, double> curve_need;          ///< fan curves over the limit → the edge length they need
    std::map<int, double> area;                ///< wall surface → its area
    std::map<int, Index> faces;                ///< wall surface → its faces
    std::map<int, std::vector<int>> curve_up;  ///< curve between two wall surfaces → those surfaces
    /// A boundary curve of a wall surface: its length in the mesh, the surfaces on its other
    /// side. Filled only where a surface or curve is over the limit (refine_walls' estimate).
    struct Side {
        double length = 0.0;
        std::vector<int> others;
    };
    std::map<int, std::vector<Side>> boundary;  ///< wall surface → its boundary curves
};

/// Measure \p mesh, the current Gmsh model's mesh (each face's Gmsh surface in \p face_surface,
/// \p walls the wall surfaces; the coordinates the model's): each wall face's first cell, its
/// columns starting along the angle-weighted mean normal of their node's wall faces (oriented
/// round the node, whatever each Gmsh surface's own orientation), so leaning over convex and
/// concave edges (leaning_prism_aspect_ratio); along the face's normal at a node of a fan chain,
/// or of another patch; a column leaning more than 55 degrees stops at the wall (an edge the
/// layers stop at), and the face's cell is then the step cell down to it (no cell where all
/// do). And on each curve between two wall surfaces whose faces turn by the fan angle or more,
/// the fan's first wedge (fan_wedge_aspect_ratio).
/// Inside a GmshSession (Gmsh's exceptions pass through).
WallAspect wall_aspect(const SurfaceMesh& mesh, const std::vector<int>& face_surface, const std::set<int>& walls,
                       const WallLimits& limits);

/// The sizes asked of the walls, by Gmsh tag: surfaces (with their curves and points) and fan
/// curves (with their points).
struct WallCaps {
    std::map<int, double> surface, curve;
};

/// \p caps as sizes per entity (their boundaries from the current model: inside a GmshSession).
EntitySizes entity_sizes(const WallCaps& caps);

/// The rounds of CadParams::max_aspect_ratio from the measure \p now of the first mesh: each
/// round caps what is over (a surface at 0.7 × limit × first height, again 0.7 of that if still
/// over; a fan curve at the length its worst edge needs), stops if the faces that would take
/// exceed \p limits.faces_budget, and calls \p remesh to mesh the model with the caps and
/// measure it (false: that failed, the mesh before stands). Up to three rounds. \p r says what
/// was done.
void refine_walls(const WallLimits& limits, WallAspect now, WallSizeReport& r,
                  const std::function<bool(const WallCaps&, WallAspect&)>& remesh);

}  // namespace strata
