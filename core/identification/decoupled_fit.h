#pragma once
/// @file decoupled_fit.h
/// The thesis's three-step identification (§4.3.3–4.3.4, chapter 5) with Ceres instead of MATLAB's
/// lsqcurvefit: step I fits P_I = {a₀, a₁} to F_x (Eq. 4.12), step II P_II = {K_s, n₀, n₁} to F_z
/// (Eq. 4.17) with P_I fixed, step III P_III = {c, φ, K} to M_y (Eq. 4.18) with P_I fixed.

#include <limits>
#include <string>
#include <vector>

#include "core/identification/data_set.h"
#include "core/identification/parameter_text.h"
#include "core/wheel/wheel_parameters.h"

namespace terra::identification {

/// Decoupled-model parameters, SI.
struct DecoupledParameters {
    double a0 = 0.01;                    ///< [-] (Eq. 2.18); thesis initial guess 0.01
    double a1 = 0.03;                    ///< [-]; thesis initial guess 0.03
    double pressure_modulus = 1.4e6;     ///< K_s [Pa/m^N] (thesis guess 1400 kPa/m^N, sandy loam)
    double n0 = 0.1;                     ///< [-]
    double n1 = 0.0;                     ///< [-]
    double cohesion_pa = 3.5e3;          ///< c [Pa]
    double friction_angle_rad = 0.4014;  ///< φ [rad] (23°)
    double shear_modulus_m = 0.2;        ///< K [m]
    /// j_max [m] (Eq. 2.16) of the model the parameters were fitted with, +inf for none:
    /// identified by `identify --jmax fit`, else the value it was held at (the decoupled steps
    /// never see it).
    double max_shear_deformation_m = std::numeric_limits<double>::infinity();
};

/// Bounds of steps II and III (chapter 5; step I is unbounded in the thesis, here a₀ ∈ [0, 1],
/// a₁ ∈ [−1, 1] so that θ_m stays a plausible fraction of θ_f).
struct DecoupledBounds {
    double ks_min = 300e3, ks_max = 5000e3;  ///< [Pa/m^N]
    double n0_min = 0.01, n0_max = 1.5;
    double n1_min = -0.5, n1_max = 1.0;
    double c_min = 0.0, c_max = 50e3;           ///< [Pa]
    double phi_min = 0.0873, phi_max = 1.0123;  ///< [rad] 5°..58°
    double k_min = 0.001, k_max = 0.5;          ///< [m]
};

/// The outcome of one step.
struct StepReport {
    /// "I: {a0}, {a1} (Fx, Eq. 4.12)": the parameters it fits named through the table
    /// (parameter_text.h).
    ParameterText name;
    bool usable = false;      ///< Ceres' solution is usable
    std::string termination;  ///< Ceres' termination type and message
    int iterations = 0;
    double squared_residual_norm = 0.0;  ///< Σ rᵢ² [N² or (N·m)²] (thesis Tables 5.5–5.6)
    double wall_time_ms = 0.0;           ///< measured, for the report only
};

/// The identified parameters and one report per step.
struct DecoupledFit {
    DecoupledParameters parameters;
    std::vector<StepReport> steps;
    bool usable() const;
};

/// Runs steps I–III on the data set (driving samples, θ_r = 0 as in Table 5.2) for the wheel,
/// starting from `guess`. On full-model data steps II and III crawl along flat valleys toward a
/// bound (K_s, c) for 100+ iterations; a warm-started caller (streaming) can cap them. Throws
/// std::invalid_argument for an empty data set or a bad wheel.
DecoupledFit fitDecoupled(const DataSet& data, const wheel::WheelParameters& wheel,
                          const DecoupledParameters& guess, const DecoupledBounds& bounds = {},
                          int max_iterations_per_step = 200);

/// Forces and torque of the decoupled (linearised) model itself for given parameters at (s, θ_f):
/// the forward form Eq. 4.4 with σ_m (Eq. 4.1) and τ_m (Eq. 4.2). Used to make data that the
/// decoupled fit must recover exactly.
struct DecoupledForces {
    double fx_n, fz_n, my_nm;
};
DecoupledForces decoupledForward(const DecoupledParameters& p, const wheel::WheelParameters& wheel,
                                 double slip, double theta_f);

}  // namespace terra::identification
