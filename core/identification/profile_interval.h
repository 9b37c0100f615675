#pragma once
/// @file profile_interval.h
/// Profile-likelihood intervals of identify()'s parameters: for parameter k,
///
///   I_k = { v : χ²_p(v) − χ²_min ≤ Δ },   χ²_p(v) = min over the other free parameters of χ²(θ |
///   θ_k = v),
///
/// with the noise levels of the fit held (χ² = Σ r² + prior terms, identify.h). By Wilks' theorem
/// χ²_p(v_true) − χ²_min is χ²₁ for a regular problem, so Δ = 9 gives the coverage of a 3σ
/// interval (99.73 %) without assuming that χ² is quadratic: where the linearised covariance
/// underrates a curved valley (one load: c–φ), the profile follows the valley.
/// Derivation and measured coverage: docs/identification.md §5.

#include <array>

#include "core/identification/identify.h"

namespace terra::identification {

/// One parameter's interval (SI).
struct ProfileInterval {
    bool computed = false;
    double lower = 0.0, upper = 0.0;
    /// The profile stayed below Δ up to the parameter's bound (ParameterBounds): the interval ends
    /// there, and the data do not bound the parameter on that side.
    bool lower_at_bound = false, upper_at_bound = false;
    double delta_chi2 = 9.0;  ///< Δ used
    int fits = 0;             ///< constrained refinements spent
};

/// The parameters worth a profile: those of a pair whose |correlation| exceeds `threshold`
/// (the trade-offs identify() flags), and those at a bound.
std::array<bool, kFullParameterCount> tradeOffParameters(const IdentificationReport& fit,
                                                         double threshold = 0.98);

/// The profile intervals of the parameters selected by `which` around a usable `fit` of `data`
/// made with `options` (the same data, wheel and options: model, fixed parameters, priors, bounds,
/// loss). Each side is found by a secant search on √(χ²_p − χ²_min) = √Δ in solver coordinates
/// (parameters.h), starting at the linearised 3σ point; each χ²_p a refinement of the other
/// parameters warm-started from the previous point. Parameters not selected, held, or without a
/// usable fit are not computed.
std::array<ProfileInterval, kFullParameterCount> profileIntervals(
    const DataSet& data, const wheel::WheelParameters& wheel, const IdentifyOptions& options,
    const IdentificationReport& fit, const std::array<bool, kFullParameterCount>& which,
    double delta_chi2 = 9.0);

}  // namespace terra::identification
