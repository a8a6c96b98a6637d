#pragma once
/// \file
/// Marching-distance distributions: the height of every layer of the boundary layer. The
/// defaults and the inference of the distribution from what is given live here, once, so the
/// CLI, the Gmsh-API entry point and the Python package give the same layers for the same
/// values.

#include <string_view>
#include <vector>

namespace strata {

enum class Distribution {
    Auto,       ///< Thickness when a thickness is given without a growth ratio, else Geometric
    Geometric,  ///< first height h1, growth ratio q: δ_k = h1 q^k
    Thickness,  ///< first height h1 and total thickness T: geometric, q solved from T
    Tanh,       ///< the paper's: one-sided hyperbolic-tangent stretching of T with first height h1
};
/// "auto", "geometric", "thickness", "tanh".
std::string_view to_string(Distribution d);
/// Inverse of to_string (case-insensitive); InputError naming \p text and the choices otherwise.
Distribution parse_distribution(std::string_view text);

/// The growth ratio of a geometric distribution when none is given.
inline constexpr double kDefaultGrowth = 1.2;

/// Parameters of the distance distribution. Lengths in model units. Give the first height
/// either directly or through y+ (never both), and two of first height, growth and thickness.
struct DistributionParams {
    int layers = 20;                         ///< number of layers N (≥ 1)
    Distribution kind = Distribution::Auto;  ///< see Distribution::Auto
    double first_height = 0.0;               ///< h1 (> 0), or 0 to derive it from y+ (see below)
    double growth = 0.0;                     ///< q for Geometric (≥ 1); 0 = kDefaultGrowth; not for Thickness, Tanh
    double thickness = 0.0;                  ///< T for Thickness and Tanh (≥ N h1 for Thickness); not for Geometric
    /// First height from a target y+ (used when first_height = 0 and yplus > 0): flat-plate
    /// turbulent skin friction Cf = 0.026 Re^(-1/7) (White), h1 = y+ L / (Re sqrt(Cf/2)).
    double yplus = 0.0;
    double reynolds = 0.0;          ///< Reynolds number based on reference_length
    double reference_length = 1.0;  ///< L, model units
};

/// \p p with its defaults and inference applied: kind never Auto, the growth ratio of a
/// geometric distribution set, the first height derived from y+ where asked. InputError naming
/// the parameters (DistributionParams::first_height, ...) for missing, conflicting or
/// out-of-range values.
DistributionParams resolve(const DistributionParams& p);

/// First cell height for a target y+ at Reynolds number \p re over length \p length.
double first_height_from_yplus(double yplus, double re, double length);

/// The share of the walls' length (walls_length) that the layers reach in all when no first
/// height is given: a turbulent boundary layer is 0.37 Re^(-1/5) of the length it grew on
/// (2.3 % at Re 1e6, 1.5 % at Re 1e7); 20 layers at growth 1.2 then start at 1.1e-4 of the
/// length, y+ about 4.5 at Re 1e6 (White's flat plate, first_height_from_yplus).
inline constexpr double kAutomaticThicknessShare = 0.02;

/// Whether \p p leaves the first height to be chosen: neither a first height nor a y+ given.
bool automatic_first_height(const DistributionParams& p);

/// The first height chosen for \p p when automatic_first_height(p), on walls \p walls_length
/// long: the geometric layers of p's growth (kDefaultGrowth if none) that reach p's thickness,
/// or kAutomaticThicknessShare of \p walls_length if p gives none (p's layers and growth are
/// then what resolve() checks). InputError if \p walls_length is not positive.
double automatic_first_height(const DistributionParams& p, double walls_length);

/// Marching distances δ_0 .. δ_N (N+1 values: the reference mesh of layer N−1 needs δ_N for
/// its level 2) of resolve(p). Σ_{k<N} δ_k is the total thickness. Throws InputError naming the
/// bad parameter.
std::vector<double> layer_heights(const DistributionParams& p);

}  // namespace strata
