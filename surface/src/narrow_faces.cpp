// A face much narrower than the element size (a CAD model's strip along a trailing edge, a
// fillet, a thin band) is meshed with one row of triangles as long as the size and as wide as
// the face: slivers whose centres sit off their shared edges, so the prisms standing on them
// have faces far from orthogonal to the line between their centres (checkMesh's
// non-orthogonality; ALGORITHM.md, "Narrow faces meshed at four times their width"). Sizes
// asked along such a face's boundary give it triangles about as long as it is wide (times the
// ratio).
#include "narrow_faces.h"

#include "wall_size.h"

#include <gmsh.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <map>
#include <utility>

namespace strata {
namespace {

struct Narrow {
    int tag = 0;
    double width = 0.0;   ///< twice the area over the perimeter: a strip's width, a disc's radius
    double length = 0.0;  ///< the perimeter
    double target = 0.0;  ///< the size asked along it
    std::vector<std::pair<int, double>> curves;  ///< its boundary curves and their lengths
};

/// \p s's width and boundary (seams left out: a curve the face meets on both sides, as a
/// cylinder's, is not an edge of it, so a thin tube is not narrow across its circumference), if
/// OpenCASCADE can measure them.
bool measure(int s, Narrow& n) {
    try {
        double area = 0.0;
        gmsh::model::occ::getMass(2, s, area);
        gmsh::vectorpair boundary;
        gmsh::model::getBoundary({{2, s}}, boundary, false, false, false);
        std::map<int, int> uses;
        for (const auto& [dim, c] : boundary) ++uses[std::abs(c)];
        for (const auto& [c, count] : uses) {
            if (count != 1) continue;
            double length = 0.0;
            gmsh::model::occ::getMass(1, c, length);
            n.length += length;
            n.curves.emplace_back(c, length);
        }
        if (!(area > 0.0) || !(n.length > 0.0)) return false;
        n.tag = s;
        n.width = 2.0 * area / n.length;
        return true;
    } catch (...) {  // not an OpenCASCADE face (a .geo's built-in kernel): left alone
        return false;
    }
}

/// Points along curve \p c, \p length long, at most \p spacing apart (in its parameter), each
/// asking \p size.
void sample_curve(int c, double length, double spacing, double size, std::vector<SizePoint>& out) {
    std::vector<double> lo, hi;
    try {
        gmsh::model::getParametrizationBounds(1, c, lo, hi);
    } catch (...) {
        return;
    }
    if (lo.empty() || hi.empty() || !(length > 0.0)) return;
    const int n = static_cast<int>(std::clamp(std::ceil(length / spacing), 2.0, 20000.0));
    std::vector<double> params(static_cast<std::size_t>(n) + 1), xyz;
    for (int i = 0; i <= n; ++i) params[static_cast<std::size_t>(i)] = lo[0] + (hi[0] - lo[0]) * i / n;
    gmsh::model::getValue(1, c, params, xyz);
    for (std::size_t i = 0; i + 2 < xyz.size(); i += 3) out.push_back({Vec3(xyz[i], xyz[i + 1], xyz[i + 2]), size});
}

/// Faces the sizes would add around a boundary of \p length asking \p target where the size is
/// \p size: both sides of it, the size rising at \p growth (∫ dx / (0.433 h(x)²) per unit of
/// length), an upper bound (the bands of a strip's two sides overlap).
double added_faces(double length, double target, double size, double growth) {
    return length * 2.0 * faces_at_size(1.0, 1.0) / growth * (1.0 / target - 1.0 / size);
}

}  // namespace

std::vector<SizePoint> narrow_face_points(const std::vector<int>& surfaces, const CadParams& params, double size,
                                          double floor, WallSizeReport& r) {
    r.narrow_ratio = params.narrow_face_ratio;
    if (!(params.narrow_face_ratio > 0.0) || !(size > 0.0)) return {};
    std::vector<Narrow> narrow;
    double estimate = 0.0;
    for (const int s : surfaces) {
        Narrow n;
        if (!measure(s, n) || !(n.width * params.narrow_face_ratio < std::min(size, 0.5 * n.length - n.width)))
            continue;
        // Below the floor its triangles would stay slivers, only more of them (a thin plate's edge).
        n.target = params.narrow_face_ratio * n.width;
        if (!(n.target >= floor)) continue;
        estimate += added_faces(n.length, n.target, size, kNarrowFaceGrowth);
        if (r.narrow_faces == 0 || n.width < r.narrowest) r.narrowest = n.width, r.narrowest_surface = s;
        r.narrow_size = r.narrow_faces == 0 ? n.target : std::min(r.narrow_size, n.target);
        ++r.narrow_faces;
        narrow.push_back(std::move(n));
    }
    r.narrow_faces_estimate = estimate;
    if (estimate > params.wall_faces_budget) {
        r.narrow_over_budget = true;
        return {};
    }
    std::vector<SizePoint> points;
    for (const Narrow& n : narrow)
        for (const auto& [c, length] : n.curves) sample_curve(c, length, 0.5 * n.target, n.target, points);
    return points;
}

}  // namespace strata
