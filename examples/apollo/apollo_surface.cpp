// A notional Apollo command + service module (the paper's section 5.1): the meridian as a
// chain of exact curves, 80 stations on it by arc length with clustering at the corners,
// revolved into 20 sectors.

#include "apollo/apollo_surface.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <numbers>
#include <vector>

namespace strata {
namespace {

using Point2 = std::array<double, 2>;  // (x, r), metres

/// One piece of the meridian, (x, r) at parameter u in [0, 1].
using Curve = std::function<Point2(double)>;

constexpr double deg = std::numbers::pi / 180.0;

// Dimensions, metres (a notional shape; proportions of the real CSM).
constexpr double kNoseRadius = 0.6;  // blunt forward end of the command module
constexpr double kConeHalfAngle = 33.0 * deg;
constexpr double kBodyRadius = 1.95;     // command module base and service module
constexpr double kShoulderRadius = 0.2;  // toroidal shoulder, cone → cylinder
constexpr double kServiceLength = 4.7;   // shoulder end to the base plane
constexpr double kRimRadius = 0.15;      // rounded aft rim of the service module
constexpr double kNozzleRoot = 0.55;     // nozzle radius where it leaves the base
constexpr double kNozzleLength = 2.8;
constexpr double kNozzleExit = 1.25;
constexpr double kNozzleRootAngle = 20.0 * deg;

struct Meridian {
    std::vector<Curve> curves;
    /// Target spacing at the curves' joints (0: no clustering there), #curves + 1.
    std::vector<double> joint_spacing;
};

Meridian meridian() {
    Meridian m;
    const double tc = kConeHalfAngle;
    // Nose cap: the sphere meets the cone where its normal is perpendicular to the cone.
    const double cap_end = std::numbers::pi / 2.0 - tc;
    m.curves.push_back([=](double u) {
        const double a = u * cap_end;
        return Point2{kNoseRadius * (1.0 - std::cos(a)), kNoseRadius * std::sin(a)};
    });
    const Point2 p1{kNoseRadius * (1.0 - std::cos(cap_end)), kNoseRadius * std::sin(cap_end)};
    // Cone up to its tangent point on the shoulder torus (centre at r = body − shoulder radius).
    const double r_t1 = kBodyRadius - kShoulderRadius * (1.0 - std::cos(tc));
    const double cone = (r_t1 - p1[1]) / std::sin(tc);
    const Point2 t1{p1[0] + cone * std::cos(tc), r_t1};
    m.curves.push_back([=](double u) { return Point2{p1[0] + u * (t1[0] - p1[0]), p1[1] + u * (t1[1] - p1[1])}; });
    const Point2 cs{t1[0] + kShoulderRadius * std::sin(tc), kBodyRadius - kShoulderRadius};
    m.curves.push_back([=](double u) {
        const double a = (1.0 - u) * tc;  // tangent direction turns from the cone's to the axis
        return Point2{cs[0] - kShoulderRadius * std::sin(a), cs[1] + kShoulderRadius * std::cos(a)};
    });
    // Service module cylinder, then the rounded rim down onto the base plane x = xb.
    const double xb = cs[0] + kServiceLength;
    const Point2 cr{xb - kRimRadius, kBodyRadius - kRimRadius};
    m.curves.push_back([=](double u) { return Point2{cs[0] + u * (cr[0] - cs[0]), kBodyRadius}; });
    m.curves.push_back([=](double u) {
        const double a = u * std::numbers::pi / 2.0;
        return Point2{cr[0] + kRimRadius * std::sin(a), cr[1] + kRimRadius * std::cos(a)};
    });
    m.curves.push_back([=](double u) { return Point2{xb, cr[1] + u * (kNozzleRoot - cr[1])}; });
    // Nozzle bell r = r0 + a t + b t²: root slope tan 20°, through the exit lip.
    const double a = std::tan(kNozzleRootAngle);
    const double b = (kNozzleExit - kNozzleRoot - a * kNozzleLength) / (kNozzleLength * kNozzleLength);
    m.curves.push_back([=](double u) {
        const double t = u * kNozzleLength;
        return Point2{xb + t, kNozzleRoot + t * (a + b * t)};
    });
    // Apex, cap/cone (tangent, curvature jump only), cone/shoulder, shoulder/cylinder,
    // cylinder/rim, rim/base (convex corners, rounded), base/nozzle (concave), exit lip.
    // The concave corner is clustered less than the convex ones: its spacing, about the
    // circumferential one there (0.17 m), must stay well above the outer layers' heights
    // (ALGORITHM.md section 6). Measured with the example's layers: at 0.03 m the outer
    // corner cells degrade (min scaled Jacobian 0.42 at layer 30; with geometric growth 1.15
    // to 0.435 m they fold at layer 28); at 0.12 m every hexahedron stays above 0.56.
    m.joint_spacing = {0.08, 0.0, 0.05, 0.05, 0.05, 0.05, 0.12, 0.08};
    return m;
}

/// Arc-length stations: \p n + 1 points from the apex to the exit lip (both included), spaced
/// in proportion to h(s) = min(h_max, min over joints (h_j + g |s − s_j|)).
std::vector<Point2> stations(const Meridian& m, int n) {
    // Dense arc-length table per curve (u is not arc length on the nozzle).
    constexpr int kSamples = 4000;
    struct Sample {
        int curve;
        double u, s;
    };
    std::vector<Sample> table;
    std::vector<double> joint_s{0.0};
    double s = 0.0;
    for (int c = 0; c < static_cast<int>(m.curves.size()); ++c) {
        Point2 prev = m.curves[static_cast<std::size_t>(c)](0.0);
        if (c == 0) table.push_back({0, 0.0, 0.0});
        for (int i = 1; i <= kSamples; ++i) {
            const double u = static_cast<double>(i) / kSamples;
            const Point2 p = m.curves[static_cast<std::size_t>(c)](u);
            s += std::hypot(p[0] - prev[0], p[1] - prev[1]);
            table.push_back({c, u, s});
            prev = p;
        }
        joint_s.push_back(s);
    }
    constexpr double kGrowth = 0.25, kMaxSpacing = 0.4;
    auto spacing = [&](double x) {
        double h = kMaxSpacing;
        for (std::size_t j = 0; j < joint_s.size(); ++j)
            if (m.joint_spacing[j] > 0.0) h = std::min(h, m.joint_spacing[j] + kGrowth * std::abs(x - joint_s[j]));
        return h;
    };
    // G(s) = ∫ ds / h on the table's abscissae; stations equally spaced in G.
    std::vector<double> g(table.size(), 0.0);
    for (std::size_t i = 1; i < table.size(); ++i) {
        const double ds = table[i].s - table[i - 1].s;
        g[i] = g[i - 1] + ds * 0.5 * (1.0 / spacing(table[i - 1].s) + 1.0 / spacing(table[i].s));
    }
    // The sharp concave corner (base/nozzle) must be a station: split there and give each
    // side its share of the intervals.
    const std::size_t corner = table.size() - kSamples - 1;  // last sample of the base
    const int n1 = static_cast<int>(std::lround(n * g[corner] / g.back()));
    auto at = [&](double target) {
        const auto it = std::lower_bound(g.begin(), g.end(), target);
        const std::size_t k = std::max<std::size_t>(1, static_cast<std::size_t>(it - g.begin()));
        const Sample &a = table[k - 1], &b = table[k];
        const double w = (target - g[k - 1]) / (g[k] - g[k - 1]);
        // Interpolate the curve parameter, then evaluate the exact curve.
        const double u = b.curve == a.curve ? a.u + w * (b.u - a.u) : w * b.u;
        return m.curves[static_cast<std::size_t>(b.curve)](u);
    };
    std::vector<Point2> out;
    out.push_back(m.curves.front()(0.0));
    for (int i = 1; i < n1; ++i) out.push_back(at(g[corner] * i / n1));
    out.push_back(m.curves.back()(0.0));  // the corner, exactly
    for (int i = 1; i < n - n1; ++i) out.push_back(at(g[corner] + (g.back() - g[corner]) * i / (n - n1)));
    out.push_back(m.curves.back()(1.0));  // the exit lip, exactly at x_exit
    return out;
}

}  // namespace

SurfaceMesh apollo_surface() {
    const std::vector<Point2> st = stations(meridian(), kApolloRings);
    SurfaceMesh mesh;
    mesh.patches.push_back({"apollo", PatchKind::Wall});
    mesh.points.emplace_back(st[0][0], 0.0, 0.0);
    for (int i = 1; i <= kApolloRings; ++i)
        for (int j = 0; j < kApolloSectors; ++j) {
            const double a = 2.0 * std::numbers::pi * j / kApolloSectors;
            const double r = st[static_cast<std::size_t>(i)][1];
            mesh.points.emplace_back(st[static_cast<std::size_t>(i)][0], r * std::cos(a), r * std::sin(a));
        }
    auto node = [](int i, int j) { return static_cast<Index>(1 + (i - 1) * kApolloSectors + (j % kApolloSectors)); };
    // Going round (+θ) then aft (+s) is the outward orientation: ∂θ × ∂s points away from the body.
    for (int j = 0; j < kApolloSectors; ++j) mesh.add_face({0, node(1, j + 1), node(1, j)}, 0);
    for (int i = 1; i < kApolloRings; ++i)
        for (int j = 0; j < kApolloSectors; ++j)
            mesh.add_face({node(i, j), node(i, j + 1), node(i + 1, j + 1), node(i + 1, j)}, 0);
    return mesh;
}

LayerParams apollo_layer_params() {
    LayerParams p;
    p.distribution.layers = 30;
    p.distribution.kind = Distribution::Tanh;
    p.distribution.first_height = 1e-3;
    p.distribution.thickness = 0.3;
    p.sweeps = 10;
    p.max_sweeps = 50;
    return p;
}

}  // namespace strata
