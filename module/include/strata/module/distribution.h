#pragma once
/// \file
/// Marching-distance distributions: the height of every layer of the boundary layer.

#include <string_view>
#include <vector>

namespace strata {

enum class Distribution {
    Geometric,  ///< first height h1, growth ratio q: δ_k = h1 q^k
    Thickness,  ///< first height h1 and total thickness T: geometric, q solved from T
    Tanh,       ///< the paper's: one-sided hyperbolic-tangent stretching of T with first height h1
};
std::string_view to_string(Distribution d);

/// Parameters of the distance distribution. Lengths in model units.
struct DistributionParams {
    int layers = 20;                  ///< number of layers N (≥ 1)
    Distribution kind = Distribution::Geometric;
    double first_height = 0.0;        ///< h1 (> 0), or 0 to derive it from y+ (see below)
    double growth = 1.2;              ///< q for Geometric (≥ 1)
    double thickness = 0.0;           ///< T for Thickness and Tanh (> N h1 for Thickness)
    /// First height from a target y+ (used when first_height = 0 and yplus > 0): flat-plate
    /// turbulent skin friction Cf = 0.026 Re^(-1/7) (White), h1 = y+ L / (Re sqrt(Cf/2)).
    double yplus = 0.0;
    double reynolds = 0.0;            ///< Reynolds number based on reference_length
    double reference_length = 1.0;    ///< L, model units
};

/// First cell height for a target y+ at Reynolds number \p re over length \p length.
double first_height_from_yplus(double yplus, double re, double length);

/// Marching distances δ_0 .. δ_N (N+1 values: the reference mesh of layer N−1 needs δ_N for
/// its level 2). Σ_{k<N} δ_k is the total thickness. Throws InputError naming the bad value.
std::vector<double> layer_heights(const DistributionParams& p);

}  // namespace strata
