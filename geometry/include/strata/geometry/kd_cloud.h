#pragma once
/// \file
/// Points as a nanoflann dataset, with the squared distance as Eigen computes it (the same
/// rounding wherever a point is found): the one adapter the size fields' k-d trees share
/// (point_sizes.cpp here, hybrid's tetgen_sizing.cpp). Header-only and free of nanoflann itself.

#include <strata/core/types.h>

#include <cstddef>
#include <vector>

namespace strata {

/// Where a point of a dataset is: the point itself, or its `at` (SizePoint).
inline const Vec3& kd_position(const Vec3& p) {
    return p;
}
template <class P>
const Vec3& kd_position(const P& p) {
    return p.at;
}

/// \p points as nanoflann's dataset (its bounding box computed by nanoflann).
template <class P>
struct KdCloud {
    const std::vector<P>& points;
    std::size_t kdtree_get_point_count() const { return points.size(); }
    double kdtree_get_pt(std::size_t i, std::size_t axis) const {
        return kd_position(points[i])[static_cast<Eigen::Index>(axis)];
    }
    template <class Box>
    bool kdtree_get_bbox(Box& /*box*/) const {
        return false;
    }
};

/// nanoflann's metric: the squared Euclidean distance as Eigen computes it for Vec3.
template <class P>
struct KdSquaredDistance {
    using ElementType = double;
    using DistanceType = double;
    const KdCloud<P>& cloud;
    explicit KdSquaredDistance(const KdCloud<P>& c) : cloud(c) {}
    double evalMetric(const double* a, std::size_t b, std::size_t /*dim*/) const {
        return (Vec3(a[0], a[1], a[2]) - kd_position(cloud.points[b])).squaredNorm();
    }
    double accum_dist(double a, double b, std::size_t /*axis*/) const { return (a - b) * (a - b); }
};

}  // namespace strata
