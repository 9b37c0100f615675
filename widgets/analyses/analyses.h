#pragma once
/// @file analyses.h
/// The studio's analyses as plain functions of plain inputs, shared by the panels (run off the GUI
/// thread) and the headless `terrastudio run`: each returns tables ready to plot and write as CSV.
/// The numbers come from the core; this layer only assembles grids and reference curves.

#include <array>
#include <atomic>
#include <optional>
#include <string>
#include <vector>

#include "core/analysis/sweep.h"
#include "core/common/table.h"
#include "core/contact/quadratic_model.h"
#include "core/identification/decoupled_fit.h"
#include "core/identification/full_fit.h"
#include "core/project/project.h"

namespace terra::ui {

/// What every analysis reads from the project.
struct AnalysisInputs {
    soil::SoilParameters soil;
    wheel::WheelParameters wheel;
    analysis::OperatingConditions conditions;
    static AnalysisInputs from(const project::Project& project) {
        return {project.soil, project.wheel, project.conditions};
    }
};

/// Forces vs slip for every slip angle of the conditions (Figs. 2.18–2.26).
analysis::SweepResult computeForceSweep(const AnalysisInputs& in,
                                        const std::atomic<bool>* cancel = nullptr);

/// Stress distribution at one operating point (Figs. 2.11, 2.16; Tables 2.4–2.5).
struct StressSettings {
    double slip = 0.2;             ///< s [-]
    double slip_angle_deg = 10.0;  ///< β [deg]
    int points = 361;              ///< θ grid size
};
struct StressResult {
    /// theta_deg, sigma_kPa, tau_kPa, tau_t_kPa, tau_l_kPa and the quadratic *_quad_kPa columns.
    Table table;
    std::array<contact::ApproximationError, 4> errors{};  ///< σ, τ, τ_t, τ_l [Pa]
    double entry_angle_deg = 0.0;
    double max_stress_angle_deg = 0.0;
    std::string message;  ///< non-empty: no equilibrium at this load
};
StressResult computeStresses(const AnalysisInputs& in, const StressSettings& settings);

/// Sensitivity to one soil parameter (section 4.2, Table 4.1) and a tornado of all of them.
struct SensitivitySettings {
    std::string parameter = "phi_deg";  ///< soil field key of Table 4.1
    double slip_angle_deg = 10.0;       ///< β of the family [deg]
    double tornado_slip = 0.3;          ///< s at which the tornado compares F_x
    int slip_count = 50;
};
struct SensitivityResult {
    analysis::SweepResult family;  ///< leading column = the parameter key
    /// One row per Table 4.1 parameter: index, Fx at the lowest and the highest variation [N]
    /// (columns parameter_index, Fx_low_N, Fx_high_N, Fx_base_N).
    Table tornado;
    std::vector<std::string> tornado_keys;
};
SensitivityResult computeSensitivity(const AnalysisInputs& in, const SensitivitySettings& settings,
                                     const std::atomic<bool>* cancel = nullptr);

/// Identification (chapter 5): synthesise data from the project's soil or read a CSV; fit.
struct IdentificationSettings {
    std::string csv;               ///< data file; empty: synthesise
    double noise_relative = 0.02;  ///< σ as fraction of each channel's max (synthetic)
    /// W [N] of the synthetic sweeps; empty: the project's load. Several loads let the fit
    /// separate c and φ (one load cannot, with noise: core/identification/full_fit.h).
    std::vector<double> loads_n;
    std::uint64_t seed = 1;
    int slip_count = 50;
    bool refine = true;  ///< also refine through the full model (std deviations)
};
struct IdentificationResult {
    identification::DataSet data;
    identification::DecoupledFit fit;
    std::optional<identification::RefineResult> refined;
    /// slip, entry_angle_deg, Fx_N, Fz_N, My_Nm (data), Fx_fit_N, Fz_fit_N, My_fit_Nm and W_N
    /// (the sample's load, NaN when the data do not say).
    Table curves;
    /// One row: the identified parameters in user units (a0, a1, Ks_kPa, n0, n1, c_kPa, phi_deg,
    /// K_m) and, when refined, *_std columns.
    Table parameters;
    double fit_time_ms = 0.0;
    std::string message;  ///< non-empty: the data could not be read
};
IdentificationResult computeIdentification(const AnalysisInputs& in,
                                           const IdentificationSettings& settings);

}  // namespace terra::ui
