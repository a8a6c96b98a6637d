#include <gtest/gtest.h>

#include <strata/core/error.h>
#include <strata/module/distribution.h>

#include "test_support.h"

#include <cmath>
#include <limits>
#include <numeric>
#include <string>
#include <vector>

namespace strata {
namespace {

std::size_t sz(int i) {
    return static_cast<std::size_t>(i);
}

double total(const std::vector<double>& d, int n) {
    return std::accumulate(d.begin(), d.begin() + n, 0.0);
}

/// The parameter a kind does not use is left unset (0): giving it is an error (resolve).
DistributionParams params(Distribution kind, int layers, double h1, double growth, double thickness) {
    DistributionParams p;
    p.kind = kind;
    p.layers = layers;
    p.first_height = h1;
    p.growth = kind == Distribution::Geometric ? growth : 0.0;
    p.thickness = kind == Distribution::Geometric ? 0.0 : thickness;
    return p;
}

/// Throws InputError whose message contains \p needle.
template <class F>
void expect_input_error(F f, const std::string& needle) {
    test::expect_error<InputError>(f, {needle});
}

// ---------------------------------------------------------------- geometric

TEST(Distribution, GeometricIsH1TimesQToTheK) {
    for (int n : {1, 2, 20, 75})
        for (double q : {1.0, 1.05, 1.2, 2.5}) {
            const double h1 = 3.7e-4;
            const std::vector<double> d = layer_heights(params(Distribution::Geometric, n, h1, q, 0.0));
            ASSERT_EQ(d.size(), sz(n) + 1);
            for (int k = 0; k <= n; ++k) {
                const double want = h1 * std::pow(q, k);
                EXPECT_NEAR(d[sz(k)], want, 1e-15 * want) << "n " << n << " q " << q << " k " << k;
            }
        }
}

// ---------------------------------------------------------------- thickness

/// \p d: the heights of \p kind (Thickness or Tanh, which ignore \p growth) for \p n layers from
/// \p h1 to the thickness \p t: n + 1 of them, the first n summing to t, the first h1 within
/// \p h1_tolerance × h1.
void heights_of_thickness(std::vector<double>& d, Distribution kind, int n, double h1, double growth, double t,
                          double h1_tolerance) {
    d = layer_heights(params(kind, n, h1, growth, t));
    ASSERT_EQ(d.size(), sz(n) + 1);
    EXPECT_NEAR(total(d, n), t, 1e-12 * t);
    EXPECT_NEAR(d[0], h1, h1_tolerance * h1);
}

/// A distribution to a thickness (Thickness, Tanh): n layers from h1 to t.
struct ThicknessCase {
    int n;
    double h1, t;
};

class Thickness : public ::testing::TestWithParam<ThicknessCase> {};

TEST_P(Thickness, SumsToTheThicknessWithConstantRatio) {
    const auto [n, h1, t] = GetParam();
    std::vector<double> d;
    ASSERT_NO_FATAL_FAILURE(heights_of_thickness(d, Distribution::Thickness, n, h1, 99.0, t, 1e-14));
    const double q = n >= 2 ? d[1] / d[0] : d[1] / d[0];
    EXPECT_GE(q, 1.0 - 1e-15);
    for (int k = 0; k < n; ++k) EXPECT_NEAR(d[sz(k) + 1] / d[sz(k)], q, 1e-12 * q) << "k " << k;
}

INSTANTIATE_TEST_SUITE_P(Cases, Thickness,
                         ::testing::Values(ThicknessCase{20, 1e-3, 0.5}, ThicknessCase{10, 0.01, 0.1 + 1e-9},
                                           ThicknessCase{30, 1e-6, 0.2}, ThicknessCase{100, 1e-5, 3.0},
                                           ThicknessCase{2, 0.1, 0.35}, ThicknessCase{5, 1e-3, 1e3},
                                           ThicknessCase{50, 2e-3, 0.1 * (1.0 + 1e-11)}));  // q − 1 ~ 1e-14

TEST(Distribution, ThicknessEqualToLayersTimesH1IsUniform) {
    const std::vector<double> d = layer_heights(params(Distribution::Thickness, 8, 0.125, 1.2, 1.0));
    ASSERT_EQ(d.size(), 9u);
    for (double v : d) EXPECT_DOUBLE_EQ(v, 0.125);
}

TEST(Distribution, OneLayerThicknessIsH1) {
    // One layer of thickness T: q is free, so T must be h1; the extra level continues at h1 q.
    const std::vector<double> d = layer_heights(params(Distribution::Thickness, 1, 0.2, 1.2, 0.2));
    ASSERT_EQ(d.size(), 2u);
    EXPECT_DOUBLE_EQ(d[0], 0.2);
}

// ---------------------------------------------------------------- tanh

class Tanh : public ::testing::TestWithParam<ThicknessCase> {};

TEST_P(Tanh, SumsToTheThicknessFromH1Increasing) {
    const auto [n, h1, t] = GetParam();
    std::vector<double> d;
    ASSERT_NO_FATAL_FAILURE(heights_of_thickness(d, Distribution::Tanh, n, h1, 1.2, t, 1e-10));
    for (int k = 0; k < n; ++k) EXPECT_GT(d[sz(k) + 1], d[sz(k)]) << "k " << k << " of " << n;
    for (double v : d) EXPECT_TRUE(std::isfinite(v) && v > 0.0);
    // The extra level (reference mesh of the last layer) continues the last ratio.
    if (n >= 2) {
        EXPECT_NEAR(d[sz(n)] / d[sz(n) - 1], d[sz(n) - 1] / d[sz(n) - 2], 1e-12);
    }
}

INSTANTIATE_TEST_SUITE_P(Cases, Tanh,
                         ::testing::Values(ThicknessCase{30, 1e-3, 1.0}, ThicknessCase{20, 1e-4, 0.05},
                                           ThicknessCase{2, 0.1, 1.0},
                                           ThicknessCase{10, 0.0999, 1.0},  // nearly uniform
                                           ThicknessCase{40, 1e-7, 1.0},    // y+ ~ 1 scale
                                           ThicknessCase{60, 2e-9, 0.3}, ThicknessCase{200, 1e-6, 10.0}));

TEST(Distribution, TanhIsTheOneSidedTanhStretching) {
    // x_k = T (1 + tanh(β (k/N − 1)) / tanh β), β fixed by x_1 = h1; check x at every k for
    // the β the first height implies.
    const int n = 12;
    const double t = 2.0, h1 = 0.01;
    const std::vector<double> d = layer_heights(params(Distribution::Tanh, n, h1, 1.2, t));
    auto x = [&](double beta, double s) { return t * (1.0 + std::tanh(beta * (s - 1.0)) / std::tanh(beta)); };
    double lo = 1e-6, hi = 50.0;  // x(β, 1/N) falls as β grows
    for (int it = 0; it < 200; ++it) {
        const double mid = 0.5 * (lo + hi);
        (x(mid, 1.0 / n) > h1 ? lo : hi) = mid;
    }
    const double beta = 0.5 * (lo + hi);
    double xk = 0.0;
    for (int k = 0; k < n; ++k) {
        xk += d[sz(k)];
        EXPECT_NEAR(xk, x(beta, (k + 1.0) / n), 1e-12 * t) << "k " << k;
    }
}

// ---------------------------------------------------------------- y+

TEST(Distribution, FirstHeightFromYplusIsWhitesFormula) {
    const double re = 1e6, yplus = 1.0, length = 1.0;
    const double cf = 0.026 * std::pow(re, -1.0 / 7.0);
    const double want = yplus * length / (re * std::sqrt(cf / 2.0));
    EXPECT_NEAR(first_height_from_yplus(yplus, re, length), want, 1e-14 * want);
    EXPECT_NEAR(first_height_from_yplus(1.0, 1e6, 1.0), 2.353e-5, 0.002e-5);  // the number, by hand
    // Linear in y+ and in the reference length.
    EXPECT_NEAR(first_height_from_yplus(30.0, re, 2.5), 75.0 * want, 1e-13 * want);
}

TEST(Distribution, LayerHeightsDerivesFirstHeightFromYplus) {
    for (Distribution kind : {Distribution::Geometric, Distribution::Thickness, Distribution::Tanh}) {
        DistributionParams p = params(kind, 25, 0.0, 1.2, 0.8);
        p.yplus = 2.0;
        p.reynolds = 5e6;
        p.reference_length = 3.0;
        const double h1 = first_height_from_yplus(2.0, 5e6, 3.0);
        const std::vector<double> d = layer_heights(p);
        ASSERT_EQ(d.size(), 26u);
        EXPECT_NEAR(d[0], h1, 1e-10 * h1) << to_string(kind);
    }
    // A first height and a y+ both set the first height: an error, not a silent choice.
    DistributionParams p = params(Distribution::Geometric, 5, 1e-3, 1.2, 0.0);
    p.yplus = 1.0;
    p.reynolds = 1e6;
    expect_input_error([&] { (void)layer_heights(p); }, "DistributionParams::yplus");
}

// ---------------------------------------------------------------- defaults and inference

TEST(Distribution, AnAutomaticFirstHeightGivesTheLayersTheShareOfTheWallsOrTheThicknessAsked) {
    DistributionParams p;  // no first height, no y+: chosen
    EXPECT_TRUE(automatic_first_height(p));
    for (const int n : {1, 5, 20, 60}) {
        p.layers = n;
        p.first_height = automatic_first_height(p, 10.0);
        // The geometric layers at the default growth then reach the share of the walls' length.
        EXPECT_NEAR(total(layer_heights(p), n), kAutomaticThicknessShare * 10.0, 1e-12) << n;
        EXPECT_FALSE(automatic_first_height(p));
        p.first_height = 0.0;
    }
    p.layers = 20;
    EXPECT_NEAR(automatic_first_height(p, 1.0), 1.07e-4, 0.005e-4);  // the share's figure, by hand
    p.growth = 1.0;  // uniform layers: the share over their count
    EXPECT_DOUBLE_EQ(automatic_first_height(p, 10.0), 0.01);
    p.growth = 1.3;
    p.first_height = automatic_first_height(p, 10.0);
    EXPECT_NEAR(total(layer_heights(p), 20), 0.2, 1e-12);
    // A thickness given is reached instead, whatever the walls' length (the Thickness kind).
    DistributionParams t;
    t.layers = 8;
    t.thickness = 0.05;
    t.first_height = automatic_first_height(t, 1000.0);
    const DistributionParams r = resolve(t);
    EXPECT_EQ(r.kind, Distribution::Thickness);
    const std::vector<double> d = layer_heights(t);
    EXPECT_NEAR(d[1] / d[0], kDefaultGrowth, 1e-9);  // the growth the Thickness kind solves for
    EXPECT_NEAR(total(d, 8), 0.05, 1e-15);
    // A y+ or a first height given is not automatic; walls of no length choose nothing.
    DistributionParams y;
    y.yplus = 1.0;
    EXPECT_FALSE(automatic_first_height(y));
    expect_input_error([&] { (void)automatic_first_height(p, 0.0); }, "DistributionParams::first_height");
    expect_input_error([&] { (void)automatic_first_height(p, std::nan("")); }, "no first layer height");
}

TEST(Distribution, AutoInfersTheKindFromWhatIsGiven) {
    DistributionParams p;  // the defaults: Auto, no growth, no thickness
    p.layers = 3;
    p.first_height = 1e-3;
    DistributionParams r = resolve(p);
    EXPECT_EQ(r.kind, Distribution::Geometric);
    EXPECT_EQ(r.growth, kDefaultGrowth);
    p.growth = 1.5;
    r = resolve(p);
    EXPECT_EQ(r.kind, Distribution::Geometric);
    EXPECT_EQ(r.growth, 1.5);
    p.growth = 0.0;
    p.thickness = 0.01;
    r = resolve(p);
    EXPECT_EQ(r.kind, Distribution::Thickness);
    EXPECT_NEAR(total(layer_heights(p), 3), 0.01, 1e-15);
    p.growth = 1.5;  // all three: over-determined
    expect_input_error([&] { (void)resolve(p); }, "DistributionParams::growth");
}

TEST(Distribution, ParametersAKindDoesNotUseAreRefused) {
    DistributionParams p;
    p.layers = 3;
    p.first_height = 1e-3;
    p.kind = Distribution::Geometric;
    p.thickness = 0.01;
    expect_input_error([&] { (void)resolve(p); }, "DistributionParams::thickness");
    for (Distribution kind : {Distribution::Thickness, Distribution::Tanh}) {
        p.kind = kind;
        p.growth = 1.2;
        expect_input_error([&] { (void)resolve(p); }, "DistributionParams::growth");
    }
}

// ---------------------------------------------------------------- errors

TEST(Distribution, RejectsBadInput) {
    using P = DistributionParams;
    auto heights = [](P p) { return [p] { (void)layer_heights(p); }; };
    for (Distribution kind : {Distribution::Geometric, Distribution::Thickness, Distribution::Tanh}) {
        expect_input_error(heights(params(kind, 0, 1e-3, 1.2, 1.0)), "0");
        expect_input_error(heights(params(kind, -3, 1e-3, 1.2, 1.0)), "-3");
        expect_input_error(heights(params(kind, 10, 0.0, 1.2, 1.0)), "first");  // no h1, no y+
        expect_input_error(heights(params(kind, 10, -1e-3, 1.2, 1.0)), "first");
        expect_input_error(heights(params(kind, 10, std::nan(""), 1.2, 1.0)), "first");
        P p = params(kind, 10, -1e-3, 1.2, 1.0);  // a negative height is an error even with y+
        p.yplus = 1.0;
        p.reynolds = 1e6;
        expect_input_error(heights(p), "first");
        p = params(kind, 10, 0.0, 1.2, 1.0);  // y+ without a Reynolds number
        p.yplus = 1.0;
        expect_input_error(heights(p), "Reynolds");
    }
    expect_input_error(heights(params(Distribution::Geometric, 10, 1e-3, 0.95, 0.0)), "growth");
    expect_input_error(heights(params(Distribution::Geometric, 10, 1e-3, std::nan(""), 0.0)), "growth");
    expect_input_error(heights(params(Distribution::Thickness, 10, 1e-3, 1.2, 0.0099)), "thickness");
    expect_input_error(heights(params(Distribution::Thickness, 10, 1e-3, 1.2, 0.0)), "thickness");
    expect_input_error(heights(params(Distribution::Thickness, 10, 1e-3, 1.2, std::nan(""))), "thickness");
    expect_input_error(heights(params(Distribution::Thickness, 10, 1e-3, 1.2, HUGE_VAL)), "thickness");
    // One layer of thickness T > h1: there is no ratio to solve for (used to give δ_1 = inf).
    expect_input_error(heights(params(Distribution::Thickness, 1, 0.2, 1.2, 0.3)), "layer");
    expect_input_error(heights(params(Distribution::Tanh, 10, 0.1, 1.2, 1.0)), "first height");  // h1 = T/N
    expect_input_error(heights(params(Distribution::Tanh, 10, 0.2, 1.2, 1.0)), "first height");  // h1 > T/N
    expect_input_error(heights(params(Distribution::Tanh, 10, 1e-3, 1.2, 0.0)), "thickness");
    expect_input_error(heights(params(Distribution::Tanh, 10, 1e-3, 1.2, -1.0)), "thickness");
    // One tanh layer is the whole thickness: a smaller first height cannot be honoured.
    expect_input_error(heights(params(Distribution::Tanh, 1, 1e-3, 1.2, 1.0)), "layer");
    // Beyond what the stretching parameter can reach: an error, not a silently wrong first height.
    expect_input_error(heights(params(Distribution::Tanh, 2, 1e-60, 1.2, 1.0)), "too small");

    expect_input_error([] { (void)first_height_from_yplus(0.0, 1e6, 1.0); }, "y+");
    expect_input_error([] { (void)first_height_from_yplus(1.0, -1e6, 1.0); }, "Reynolds");
    expect_input_error([] { (void)first_height_from_yplus(1.0, 1e6, 0.0); }, "length");
}

TEST(Distribution, GeometricLayersBeyondDoublePrecisionAreRefused) {
    // 10000 layers at 1.2 would be 1e787 thick: "inf" everywhere downstream.
    test::expect_error<InputError>(
        [] { (void)layer_heights(params(Distribution::Geometric, 10000, 1e-5, 1.2, 0.0)); },
        {"DistributionParams::layers = 10000 with DistributionParams::growth = 1.2: the last layer would be "
         "1.2^9999 ≈ 1e791 times the first layer (1e-05) and the layers 1e787 thick in all",
         "use fewer layers or a smaller growth"});
    // The bound is that a prism's volume, three lengths multiplied, stays a double: at h1 1e-5 and
    // growth 1.2 the layers reach it between 1351 (4.7e102 thick) and 1352 layers (5.6e102).
    const std::vector<double> d = layer_heights(params(Distribution::Geometric, 1351, 1e-5, 1.2, 0.0));
    const double t = total(d, 1351);
    EXPECT_TRUE(std::isfinite(t * t * t)) << t;
    EXPECT_GT(t, 4.7e102);
    expect_input_error([] { (void)layer_heights(params(Distribution::Geometric, 1352, 1e-5, 1.2, 0.0)); }, "1352");
    // Growth 1 never grows: any number of layers is a finite thickness.
    EXPECT_NEAR(total(layer_heights(params(Distribution::Geometric, 100000, 1e-5, 1.0, 0.0)), 100000), 1.0, 1e-9);
    // A given thickness is bounded the same way.
    expect_input_error([] { (void)layer_heights(params(Distribution::Thickness, 10, 1e-3, 0.0, 1e200)); },
                       "DistributionParams::thickness = 1e+200");
    expect_input_error([] { (void)layer_heights(params(Distribution::Tanh, 10, 1e-3, 0.0, 1e200)); },
                       "at most 5.6e+102");
}

TEST(Distribution, Names) {
    for (Distribution d : {Distribution::Auto, Distribution::Geometric, Distribution::Thickness, Distribution::Tanh})
        EXPECT_EQ(parse_distribution(to_string(d)), d);
    EXPECT_EQ(parse_distribution("TANH"), Distribution::Tanh);
    expect_input_error([] { (void)parse_distribution("linear"); }, "linear");
    EXPECT_EQ(to_string(Distribution::Geometric), "geometric");
    EXPECT_EQ(to_string(Distribution::Thickness), "thickness");
    EXPECT_EQ(to_string(Distribution::Tanh), "tanh");
}

}  // namespace
}  // namespace strata
