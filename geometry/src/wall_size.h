#pragma once
// The wall sizing of CadParams::max_aspect_ratio: a Gmsh size callback on chosen entities
// (inside a GmshSession).

#include <map>
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

}  // namespace strata
