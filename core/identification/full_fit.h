#pragma once
/// @file full_fit.h
/// Refinement beyond the thesis: fit c, φ, K, n, K_s, a₀, a₁ together through the full nonlinear
/// wheel model (core/contact/wheel_forces.h, differentiated by Ceres with ceres::Jet), started from
/// one point (typically the decoupled estimate); residuals on F_x, F_z, M_y at the measured θ_f
/// weighted by their noise levels. Removes the linearisation bias of the decoupled model. Also the
/// parameters' uncertainty (Gauss–Newton covariance), with flags for what the data do not
/// determine. This is one local refinement; identify.h is the global, start-independent
/// identification built on the same model.

#include <array>
#include <limits>
#include <string>
#include <vector>

#include "core/identification/data_set.h"
#include "core/identification/decoupled_fit.h"
#include "core/identification/parameters.h"
#include "core/identification/soil_conversion.h"
#include "core/wheel/wheel_parameters.h"

namespace terra::identification {

/// Options of the refinement.
struct RefineOptions {
    std::array<bool, kFullParameterCount> fixed{};  ///< true: keep the starting value
    /// Noise standard deviations of the residuals [N, N, N·m]: residuals are divided by them. Zero
    /// or negative: estimated from the decoupled fit's residuals of that channel.
    double sigma_fx = 0.0, sigma_fz = 0.0, sigma_my = 0.0;
    /// j_max of the model [m] (a setting of the forward model, not identified); +inf for none.
    double max_shear_deformation_m = std::numeric_limits<double>::infinity();
    /// |correlation| above which a pair is flagged as not separable by the data.
    double correlation_flag = 0.98;
    /// |correlation| with a parameter that ended at its bound above which a parameter is flagged
    /// (its standard deviation is conditional on that bound and understates its error).
    double bound_correlation_flag = 0.5;
};

/// Standard deviations and correlations of the identified parameters (the Gauss–Newton covariance
/// (JᵀJ)⁻¹ at the solution, scaled by the reduced χ² when the noise levels were estimated).
struct Uncertainty {
    bool computed = false;  ///< false: the covariance is rank deficient (see flags)
    std::array<double, kFullParameterCount> std{};  ///< SI; 0 for fixed parameters
    std::array<std::array<double, kFullParameterCount>, kFullParameterCount> correlation{};
    /// What the data do not determine, and what would fix it; the parameters named through the
    /// table (parameter_text.h: worded by key in JSON, by symbol in a summary).
    std::vector<ParameterText> flags;
};

/// The refinement's result.
struct RefineResult {
    DecoupledParameters parameters;  ///< n in n0; n1 = 0 (the forward model's constant n)
    StepReport report;
    Uncertainty uncertainty;
};

/// Refines `start` (typically the decoupled estimate) on the data set. Throws
/// std::invalid_argument for an empty data set or invalid wheel.
RefineResult refineFullModel(const DataSet& data, const wheel::WheelParameters& wheel,
                             const DecoupledParameters& start, const RefineOptions& options);

}  // namespace terra::identification
