#pragma once
// The wall sizing of CadParams::max_aspect_ratio: a Gmsh size callback on chosen entities
// (inside a GmshSession).

#include <strata/core/surface_mesh.h>
#include <strata/geometry/cad.h>

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

/// While alive, Gmsh's size callback gives each entity of \p sizes its size (Gmsh takes the
/// smaller of the callback and its other sizes) and leaves every other entity alone, every size
/// divided by \p factor (Gmsh multiplies the callback's by Mesh.MeshSizeFactor). Removed on
/// destruction.
class SizeCallback {
public:
    SizeCallback(const EntitySizes& sizes, double factor);
    ~SizeCallback();
    SizeCallback(const SizeCallback&) = delete;
    SizeCallback& operator=(const SizeCallback&) = delete;

private:
    std::map<std::pair<int, int>, double> size_;
};

/// What the first layer may be: its height, the largest OpenFOAM aspect ratio of its cells, the
/// layers' fan angle (0: no fans), the most faces the walls may get for it.
struct WallLimits {
    double first_height = 0.0;
    double max_aspect_ratio = 0.0;
    double fan_angle_deg = 0.0;
    double faces_budget = 0.0;
};

/// Where the first layer over the walls of \p mesh (the current Gmsh model's mesh, each face's
/// Gmsh surface in \p face_surface, the wall surfaces \p walls) would be flatter than
/// \p limits allow, mesh the model again finer there (CadParams::max_aspect_ratio says how),
/// reading it back with \p extract (which refills the face surfaces). \p r says what was done.
/// Inside a GmshSession; \p context names the model in errors.
SurfaceMesh refine_walls(const std::string& context, const WallLimits& limits, const std::set<int>& walls,
                         SurfaceMesh mesh, std::vector<int>& face_surface, WallSizeReport& r,
                         const std::function<SurfaceMesh(std::vector<int>&)>& extract);

}  // namespace strata
