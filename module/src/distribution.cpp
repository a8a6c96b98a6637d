#include <strata/core/enum_names.h>
#include <strata/core/error.h>
#include <strata/core/format.h>
#include <strata/module/distribution.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <utility>

namespace strata {
namespace {

/// Bisection for a monotone function on [lo, hi] (f(lo), f(hi) of opposite signs).
template <class F>
double bisect(F f, double lo, double hi) {
    const bool rising = f(hi) > f(lo);
    for (int it = 0; it < 200; ++it) {
        const double mid = 0.5 * (lo + hi);
        if ((f(mid) > 0.0) == rising)
            hi = mid;
        else
            lo = mid;
    }
    return 0.5 * (lo + hi);
}

/// The largest total thickness the layers may have: a prism's volume and Jacobians multiply
/// three of its lengths, and the layer stage must be able to compute them in double precision.
const double kMaxThickness = std::cbrt(std::numeric_limits<double>::max());  // ≈ 5.6e102

/// log10 of the geometric layers' total thickness h1 (q^n − 1)/(q − 1) and of their last
/// marching distance h1 q^n, computed so that neither overflows.
std::pair<double, double> log10_geometric_extent(double h1, double q, int n) {
    if (q == 1.0) return {std::log10(h1) + std::log10(static_cast<double>(n)), std::log10(h1)};
    const double x = n * std::log1p(q - 1.0);  // ln q^n > 0
    const double ln_total = std::log(h1) + x + std::log1p(-std::exp(-x)) - std::log(q - 1.0);
    return {ln_total / std::log(10.0), (std::log(h1) + x) / std::log(10.0)};
}

/// InputError if a geometric distribution's layers are thicker in all, or its last marching
/// distance larger, than kMaxThickness: 10000 layers at growth 1.2 are 1e787 thick, which
/// is no number a double holds.
void check_geometric_extent(const DistributionParams& p) {
    const auto [total, last] = log10_geometric_extent(p.first_height, p.growth, p.layers);
    if (std::max(total, last) <= std::log10(kMaxThickness)) return;
    const double ratio = (p.layers - 1) * std::log10(p.growth);
    auto power = [](double log10_value) {
        return "1e" + std::to_string(static_cast<long long>(std::floor(log10_value)));
    };
    throw InputError("DistributionParams::layers = " + std::to_string(p.layers) +
                     " with DistributionParams::growth = " + format_number(p.growth) + ": the last layer would be " +
                     format_number(p.growth) + "^" + std::to_string(p.layers - 1) + " ≈ " + power(ratio) +
                     " times the first layer (" + format_number(p.first_height) + ") and the layers " + power(total) +
                     " thick in all, beyond the " + format_number(kMaxThickness, 2) +
                     " a prism's volume can be computed with in double precision; use fewer layers or a smaller "
                     "growth");
}

}  // namespace

constexpr EnumNames<Distribution, 4> kDistributionNames{{"auto", "geometric", "thickness", "tanh"}};
std::string_view to_string(Distribution d) {
    return kDistributionNames.name(d);
}

Distribution parse_distribution(std::string_view text) {
    return kDistributionNames.parse(text, "DistributionParams::kind");
}

DistributionParams resolve(const DistributionParams& in) {
    DistributionParams p = in;
    if (p.layers < 1)
        throw InputError("DistributionParams::layers = " + std::to_string(p.layers) + ": need at least one layer");
    if (p.first_height > 0.0 && p.yplus > 0.0)
        throw InputError(
            "DistributionParams::first_height and DistributionParams::yplus both set the first layer height: give "
            "one of them");
    // Only first_height = 0 means "from y+": a negative or NaN height is a mistake, not a request.
    if (p.first_height == 0.0 && p.yplus > 0.0)
        p.first_height = first_height_from_yplus(p.yplus, p.reynolds, p.reference_length);
    else if (!(p.first_height > 0.0) || !std::isfinite(p.first_height))
        throw InputError("DistributionParams::first_height = " + format_number(p.first_height) +
                         ": give a positive first layer height, or DistributionParams::yplus with "
                         "DistributionParams::reynolds");
    const bool has_growth = p.growth != 0.0, has_thickness = p.thickness != 0.0;
    if (p.kind == Distribution::Auto) {
        if (has_growth && has_thickness)
            throw InputError(
                "DistributionParams::thickness with DistributionParams::growth over-determines the layers: give two "
                "of first height, growth and thickness");
        p.kind = has_thickness ? Distribution::Thickness : Distribution::Geometric;
    }
    if (p.kind == Distribution::Geometric) {
        if (has_thickness)
            throw InputError("DistributionParams::thickness = " + format_number(p.thickness) +
                             " with a geometric distribution over-determines the layers: give two of first height, "
                             "growth and thickness");
        if (!has_growth) p.growth = kDefaultGrowth;
        if (!(p.growth >= 1.0) || !std::isfinite(p.growth))
            throw InputError("DistributionParams::growth = " + format_number(p.growth) +
                             ": the growth ratio must be ≥ 1");
        check_geometric_extent(p);
    } else {
        if (has_growth)
            throw InputError("DistributionParams::growth = " + format_number(p.growth) + " with the " +
                             std::string(to_string(p.kind)) +
                             " distribution: its heights follow from the first height and the thickness; give "
                             "no growth ratio");
        if (!(p.thickness > 0.0) || !(p.thickness <= kMaxThickness))
            throw InputError(
                "DistributionParams::thickness = " + format_number(p.thickness) + ": the " +
                std::string(to_string(p.kind)) + " distribution needs a positive total thickness, at most " +
                format_number(kMaxThickness, 2) + " (a prism's volume must be computable in double precision)");
    }
    return p;
}

bool automatic_first_height(const DistributionParams& p) {
    return p.first_height == 0.0 && p.yplus == 0.0;
}

double automatic_first_height(const DistributionParams& p, double walls_length) {
    if (!(walls_length > 0.0) || !std::isfinite(walls_length))
        throw InputError("the walls are " + format_number(walls_length) +
                         " long: no first layer height can be chosen from them; give DistributionParams::first_height");
    const double thickness = p.thickness > 0.0 ? p.thickness : kAutomaticThicknessShare * walls_length;
    const double q = p.growth > 0.0 ? p.growth : kDefaultGrowth;
    const int n = std::max(p.layers, 1);
    if (!(q > 1.0)) return thickness / n;  // a growth below 1 is resolve()'s to refuse
    // T (q - 1) / (q^n - 1), with q^n taken through its logarithm so that many layers do not overflow.
    const double x = n * std::log1p(q - 1.0);
    return thickness * (q - 1.0) / std::expm1(x);
}

double first_height_from_yplus(double yplus, double re, double length) {
    if (!(yplus > 0.0) || !(re > 0.0) || !(length > 0.0))
        throw InputError("DistributionParams::yplus (y+) = " + format_number(yplus) +
                         ", DistributionParams::reynolds (Reynolds number) = " + format_number(re) +
                         ", DistributionParams::reference_length = " + format_number(length) +
                         ": all three must be positive to derive the first layer height");
    // White's flat-plate turbulent skin friction; u_tau = U sqrt(Cf/2); y = y+ nu / u_tau.
    const double cf = 0.026 / std::pow(re, 1.0 / 7.0);
    return yplus * length / (re * std::sqrt(0.5 * cf));
}

std::vector<double> layer_heights(const DistributionParams& given) {
    const DistributionParams p = resolve(given);
    const int n = p.layers;
    const double h1 = p.first_height;
    std::vector<double> d(static_cast<std::size_t>(n) + 1);
    auto at = [&d](int k) -> double& { return d[static_cast<std::size_t>(k)]; };
    switch (p.kind) {
        case Distribution::Auto:  // resolved above
        case Distribution::Geometric: {
            for (int k = 0; k <= n; ++k) at(k) = h1 * std::pow(p.growth, k);
            return d;
        }
        case Distribution::Thickness: {
            const double t = p.thickness;
            if (!(t >= n * h1 * (1.0 - 1e-12)))
                throw InputError("DistributionParams::thickness = " + format_number(t) + " is less than " +
                                 std::to_string(n) + " layers × first height " + format_number(h1) +
                                 ": increase the thickness or reduce the layers or the first height");
            // One layer has no ratio to solve for: its height is the thickness.
            if (n == 1 && !(t <= h1 * (1.0 + 1e-12)))
                throw InputError("DistributionParams::layers = 1 with DistributionParams::thickness = " +
                                 format_number(t) + " and first height " + format_number(h1) +
                                 ": one layer is the whole thickness; give more layers or thickness = first height");
            // Σ_{k<n} h1 q^k = t, monotone in q. Solved for the excess x = q − 1 with expm1/log1p:
            // h1 (q^n − 1)/(q − 1) cancels catastrophically when t is close to n h1 (q near 1).
            auto total = [&](double x) { return x == 0.0 ? n * h1 : h1 * std::expm1(n * std::log1p(x)) / x; };
            double hi = 1.0;
            while (total(hi) < t) hi *= 2.0;
            const double x = t <= n * h1 ? 0.0 : bisect([&](double e) { return total(e) - t; }, 0.0, hi);
            const double lq = std::log1p(x);
            for (int k = 0; k <= n; ++k) at(k) = h1 * std::exp(k * lq);
            return d;
        }
        case Distribution::Tanh: {
            const double t = p.thickness;
            if (n < 2)
                throw InputError("DistributionParams::layers = 1: one tanh layer is the whole thickness " +
                                 format_number(t) + ", so a first height cannot be honoured; use at least 2 layers");
            if (!(h1 < t / n))
                throw InputError("DistributionParams::first_height = " + format_number(h1) + " ≥ thickness/layers " +
                                 format_number(t / n) +
                                 ": the tanh distribution clusters towards the wall; lower the first height");
            // One-sided tanh stretching x(s) = t (1 + tanh(β (s − 1)) / tanh β), s = k / n; the first
            // spacing falls from t/n (β → 0) as β grows. Evaluated as the equal
            // t sinh(β s) / (sinh β cosh(β (s − 1))): the literal form loses digits to cancellation
            // near the wall (h1/t = 1e-7 came out 5e-10 relative off), this one loses none.
            auto x = [&](double beta, double s) {
                return t * std::sinh(beta * s) / (std::sinh(beta) * std::cosh(beta * (s - 1.0)));
            };
            const double s1 = 1.0 / n;
            const double beta = bisect([&](double b) { return x(b, s1) - h1; }, 1e-6, 100.0);
            if (!(std::abs(x(beta, s1) - h1) <= 1e-9 * h1))
                throw InputError("DistributionParams::first_height = " + format_number(h1) +
                                 " is too small for the tanh distribution over " + format_number(t) + " with " +
                                 std::to_string(n) + " layers; raise it or use more layers");
            for (int k = 0; k < n; ++k) at(k) = x(beta, (k + 1.0) / n) - x(beta, static_cast<double>(k) / n);
            // Level 2 of the last layer continues the last ratio.
            at(n) = at(n - 1) * at(n - 1) / at(n - 2);
            return d;
        }
    }
    return d;
}

}  // namespace strata
