#pragma once
/// \file
/// Mesh sizes asked at points, each spreading into the space around it at a given growth: the
/// size field by which CAD walls are meshed finer where the layers step (CadParams::size_points).

#include <strata/core/surface_mesh.h>
#include <strata/core/types.h>

#include <memory>
#include <vector>

namespace strata {

/// An element size asked at a point.
struct SizePoint {
    Vec3 at = Vec3::Zero();
    double size = 0.0;
};

/// h(x) = min over the points i of size_i + growth · |x − at_i|: each point's size, rising by
/// \p growth per unit of distance from it (infinity without points). Exact (not the nearest
/// point's: a farther point with a smaller size wins), so h is a function of the points alone,
/// whatever their order; queries are const and may run on several threads at once.
class PointSizes {
public:
    /// InputError for a point whose size is not positive and finite, or a growth that is not.
    PointSizes(std::vector<SizePoint> points, double growth);
    ~PointSizes();
    PointSizes(const PointSizes&) = delete;
    PointSizes& operator=(const PointSizes&) = delete;

    bool empty() const { return points_.empty(); }
    double operator()(const Vec3& x) const;

private:
    struct Tree;
    std::vector<SizePoint> points_;
    double growth_ = 0.0;
    double smallest_ = 0.0;
    std::unique_ptr<Tree> tree_;
};

/// About the faces \p mesh would have if meshed again with \p sizes where they are below its
/// own: each face whose centroid asks less than its own size (the edge of an equilateral
/// triangle of its area) counts as its area in equilateral triangles of that size, every other
/// face as one.
double faces_with_sizes(const SurfaceMesh& mesh, const PointSizes& sizes);

}  // namespace strata
