#include <strata/core/error.h>
#include <strata/core/face_geometry.h>
#include <strata/core/format.h>
#include <strata/geometry/kd_cloud.h>
#include <strata/geometry/point_sizes.h>

#include <nanoflann.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace strata {
namespace {

/// nanoflann result set for min_i size_i + growth·d_i: a branch and bound, the search radius
/// shrinking to the distance beyond which even the smallest size could no longer win.
class LowestSize {
public:
    LowestSize(const std::vector<SizePoint>& points, double growth, double smallest)
        : points_(points), growth_(growth), smallest_(smallest) {}
    bool full() const { return true; }
    bool addPoint(double d2, std::size_t i) {
        best_ = std::min(best_, points_[i].size + growth_ * std::sqrt(d2));
        const double reach = (best_ - smallest_) / growth_;
        radius2_ = std::nextafter(reach * reach, std::numeric_limits<double>::infinity());
        return true;
    }
    double worstDist() const { return radius2_; }
    double best() const { return best_; }

private:
    const std::vector<SizePoint>& points_;
    double growth_, smallest_;
    double best_ = std::numeric_limits<double>::infinity();
    double radius2_ = std::numeric_limits<double>::infinity();
};

}  // namespace

struct PointSizes::Tree {
    using KdTree =
        nanoflann::KDTreeSingleIndexAdaptor<KdSquaredDistance<SizePoint>, KdCloud<SizePoint>, 3, std::size_t>;
    KdCloud<SizePoint> cloud;
    KdTree index;
    explicit Tree(const std::vector<SizePoint>& points)
        : cloud{points}, index(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(10)) {
        index.buildIndex();
    }
};

PointSizes::PointSizes(std::vector<SizePoint> points, double growth) : points_(std::move(points)), growth_(growth) {
    if (!(growth > 0.0) || !std::isfinite(growth))
        throw InputError("PointSizes: growth = " + format_number(growth) +
                         ": need a positive, finite rise of the size per unit of distance");
    smallest_ = std::numeric_limits<double>::infinity();
    for (const SizePoint& p : points_) {
        if (!(p.size > 0.0) || !std::isfinite(p.size) || !p.at.allFinite())
            throw InputError("PointSizes: the size " + format_number(p.size) + " at (" + format_number(p.at.x()) +
                             ", " + format_number(p.at.y()) + ", " + format_number(p.at.z()) +
                             "): need a positive, finite size at a finite point");
        smallest_ = std::min(smallest_, p.size);
    }
    if (!points_.empty()) tree_ = std::make_unique<Tree>(points_);
}

PointSizes::~PointSizes() = default;

double PointSizes::operator()(const Vec3& x) const {
    if (!tree_) return std::numeric_limits<double>::infinity();
    LowestSize result(points_, growth_, smallest_);
    const double q[3] = {x[0], x[1], x[2]};
    tree_->index.findNeighbors(result, q, nanoflann::SearchParams());
    return result.best();
}

double faces_with_sizes(const SurfaceMesh& mesh, const PointSizes& sizes) {
    constexpr double kEquilateral = 0.4330127;  // area of the equilateral triangle of unit edge
    double faces = 0.0;
    for (Index f = 0; f < mesh.num_faces(); ++f) {
        const double area = face_area_vector(mesh, f).norm();
        Vec3 c = Vec3::Zero();
        for (const Index* v = mesh.face_begin(f); v != mesh.face_end(f); ++v)
            c += mesh.points[static_cast<std::size_t>(*v)];
        c /= static_cast<double>(mesh.face_size(f));
        const double own = std::sqrt(area / kEquilateral), asked = sizes(c);
        faces += asked < own ? area / (kEquilateral * asked * asked) : 1.0;
    }
    return faces;
}

}  // namespace strata
