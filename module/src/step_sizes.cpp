#include <strata/core/error.h>
#include <strata/core/format.h>
#include <strata/core/solver_checks.h>
#include <strata/module/step_sizes.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace strata {
namespace {

/// A point at each node of \p wall with a finite, positive size, in node order.
std::vector<SizePoint> points_at(const SurfaceMesh& wall, const std::vector<double>& size) {
    std::vector<SizePoint> points;
    for (std::size_t i = 0; i < size.size(); ++i)
        if (std::isfinite(size[i]) && size[i] > 0.0) points.push_back({wall.points[i], size[i]});
    return points;
}

}  // namespace

std::vector<SizePoint> step_sizes(const SurfaceMesh& wall, const ProximityPlan& plan,
                                  const std::vector<double>& heights, double quality) {
    if (!(quality > 0.0 && quality <= 1.0))
        throw InputError("step_sizes: quality = " + format_number(quality) +
                         ": need a scaled Jacobian in (0, 1] for the cells closing a step");
    const auto n = static_cast<std::size_t>(wall.num_points());
    if (plan.levels.size() != n || plan.proximity.size() != n)
        throw InputError("step_sizes: a plan of " + std::to_string(plan.levels.size()) + " nodes for a surface of " +
                         std::to_string(n));
    std::vector<double> size(n, std::numeric_limits<double>::infinity());
    for (Index f = 0; f < wall.num_faces(); ++f) {
        if (wall.patches[static_cast<std::size_t>(wall.face_patch[f])].kind != PatchKind::Wall) continue;
        for (const Index* a = wall.face_begin(f); a != wall.face_end(f); ++a) {
            const auto i = static_cast<std::size_t>(*a);
            const int ki = plan.levels[i];
            if (!plan.proximity[i] || ki < 0 || static_cast<std::size_t>(ki) >= heights.size()) continue;
            for (const Index* b = wall.face_begin(f); b != wall.face_end(f); ++b) {
                const auto j = static_cast<std::size_t>(*b);
                if (plan.levels[j] <= ki) continue;
                const double distance = (wall.points[j] - wall.points[i]).norm();
                const double segment = heights[static_cast<std::size_t>(ki)];
                if (!(segment < quality * distance)) continue;
                size[i] = std::min(size[i], kStepSizeShare * segment / quality);
            }
        }
    }
    return points_at(wall, size);
}

FanWedgeSizes fan_wedge_sizes(const SurfaceMesh& wall, const ProximityPlan& plan, double first_height,
                              double max_aspect_ratio) {
    if (!(first_height > 0.0) || !(max_aspect_ratio > 0.0)) return {};
    const auto n = static_cast<std::size_t>(wall.num_points());
    std::vector<double> size(n, std::numeric_limits<double>::infinity());
    std::vector<SizePoint> along;
    for (const ProximityPlan::FanWedge& e : plan.fan_wedges) {
        if (e.a < 0 || e.b < 0 || static_cast<std::size_t>(e.a) >= n || static_cast<std::size_t>(e.b) >= n)
            throw InputError("fan_wedge_sizes: a wedge on nodes " + std::to_string(e.a) + " and " +
                             std::to_string(e.b) + " of a surface of " + std::to_string(n));
        // A wedge narrower than kFanWedgeMinDeg is flat whatever its edge (its figure grows as
        // 1 / sin of its angle): no wall spacing mends it, and asking one did harm.
        if (e.d1.dot(e.d2) > std::cos(kFanWedgeMinDeg * std::numbers::pi / 180.0)) continue;
        const Vec3 &pa = wall.points[static_cast<std::size_t>(e.a)], &pb = wall.points[static_cast<std::size_t>(e.b)];
        const double ar = fan_wedge_aspect_ratio(pa, pb, e.d1, e.d2, first_height);
        if (!(ar > max_aspect_ratio) || !std::isfinite(ar)) continue;
        const double length = (pb - pa).norm(), want = length * kStepSizeShare * max_aspect_ratio / ar;
        for (const Index v : {e.a, e.b})
            size[static_cast<std::size_t>(v)] = std::min(size[static_cast<std::size_t>(v)], want);
        // Between its ends too: a size asked at the ends alone rises into the edge's middle
        // (CadParams::size_point_growth), and Gmsh's new edges there came out up to twice as
        // long (the delta wing's base at 25 layers from 5e-5: wedges at 1147). Points half the
        // length asked apart keep every point of the edge within a quarter of it of one.
        const int pieces = static_cast<int>(std::ceil(2.0 * length / want));
        for (int k = 1; k < pieces; ++k) {
            const double t = static_cast<double>(k) / static_cast<double>(pieces);
            along.push_back({pa + t * (pb - pa), want});
        }
    }
    FanWedgeSizes out;
    out.points = points_at(wall, size);
    out.nodes = static_cast<Index>(out.points.size());
    out.points.insert(out.points.end(), along.begin(), along.end());
    return out;
}

}  // namespace strata
