#include <strata/core/error.h>
#include <strata/core/format.h>
#include <strata/module/distribution.h>

#include <cmath>
#include <cstddef>
#include <string>

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

}  // namespace

std::string_view to_string(Distribution d) {
    switch (d) {
        case Distribution::Geometric: return "geometric";
        case Distribution::Thickness: return "thickness";
        case Distribution::Tanh: return "tanh";
    }
    return "geometric";
}

double first_height_from_yplus(double yplus, double re, double length) {
    if (!(yplus > 0.0) || !(re > 0.0) || !(length > 0.0))
        throw InputError("y+ " + format_number(yplus) + ", Reynolds number " + format_number(re) + ", reference length " + format_number(length) +
                         ": all three must be positive to derive the first layer height");
    // White's flat-plate turbulent skin friction; u_tau = U sqrt(Cf/2); y = y+ nu / u_tau.
    const double cf = 0.026 / std::pow(re, 1.0 / 7.0);
    return yplus * length / (re * std::sqrt(0.5 * cf));
}

std::vector<double> layer_heights(const DistributionParams& p) {
    const int n = p.layers;
    if (n < 1) throw InputError("--layers " + std::to_string(n) + ": need at least one layer");
    double h1 = p.first_height;
    // Only first_height = 0 means "from y+": a negative or NaN height is a mistake, not a request.
    if (h1 == 0.0 && p.yplus > 0.0)
        h1 = first_height_from_yplus(p.yplus, p.reynolds, p.reference_length);
    else if (!(h1 > 0.0) || !std::isfinite(h1))
        throw InputError("first layer height " + format_number(h1) + ": give a positive --first-height, or --yplus with --reynolds");
    std::vector<double> d(static_cast<std::size_t>(n) + 1);
    auto at = [&d](int k) -> double& { return d[static_cast<std::size_t>(k)]; };
    switch (p.kind) {
        case Distribution::Geometric: {
            if (!(p.growth >= 1.0) || !std::isfinite(p.growth))
                throw InputError("--growth " + format_number(p.growth) + ": the growth ratio must be ≥ 1");
            for (int k = 0; k <= n; ++k) at(k) = h1 * std::pow(p.growth, k);
            return d;
        }
        case Distribution::Thickness: {
            const double t = p.thickness;
            if (!(t >= n * h1 * (1.0 - 1e-12)))
                throw InputError("--thickness " + format_number(t) + " is less than " + std::to_string(n) + " layers × first height " +
                                 format_number(h1) + ": increase the thickness or reduce the layers or the first height");
            if (!std::isfinite(t)) throw InputError("--thickness " + format_number(t) + ": the total thickness must be finite");
            // One layer has no ratio to solve for: its height is the thickness.
            if (n == 1 && !(t <= h1 * (1.0 + 1e-12)))
                throw InputError("--layers 1 with --thickness " + format_number(t) + " and first height " + format_number(h1) +
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
            if (!(t > 0.0) || !std::isfinite(t))
                throw InputError("--thickness " + format_number(t) + ": the tanh distribution needs a positive total thickness");
            if (n < 2)
                throw InputError("--layers 1: one tanh layer is the whole thickness " + format_number(t) +
                                 ", so a first height cannot be honoured; use at least 2 layers");
            if (!(h1 < t / n))
                throw InputError("first height " + format_number(h1) + " ≥ thickness/layers " + format_number(t / n) +
                                 ": the tanh distribution clusters towards the wall; lower the first height");
            // One-sided tanh stretching x(s) = t (1 + tanh(β (s − 1)) / tanh β), s = k / n; the first
            // spacing falls from t/n (β → 0) as β grows. Evaluated as the equal
            // t sinh(β s) / (sinh β cosh(β (s − 1))): the literal form loses digits to cancellation
            // near the wall (h1/t = 1e-7 came out 5e-10 relative off), this one loses none.
            auto x = [&](double beta, double s) { return t * std::sinh(beta * s) / (std::sinh(beta) * std::cosh(beta * (s - 1.0))); };
            const double s1 = 1.0 / n;
            const double beta = bisect([&](double b) { return x(b, s1) - h1; }, 1e-6, 100.0);
            if (!(std::abs(x(beta, s1) - h1) <= 1e-9 * h1))
                throw InputError("first height " + format_number(h1) + " is too small for the tanh distribution over " + format_number(t) +
                                 " with " + std::to_string(n) + " layers; raise it or use more layers");
            for (int k = 0; k < n; ++k) at(k) = x(beta, (k + 1.0) / n) - x(beta, static_cast<double>(k) / n);
            // Level 2 of the last layer continues the last ratio.
            at(n) = at(n - 1) * at(n - 1) / at(n - 2);
            return d;
        }
    }
    return d;
}

}  // namespace strata
