#pragma once
/// @file sweep.h
/// Force-versus-slip sweeps for a set of slip angles (thesis Figs. 2.18–2.26) and the soil
/// sensitivity study of section 4.2 (Table 4.1), returned as plain tables.

#include <atomic>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/common/table.h"
#include "core/contact/bulldozing.h"
#include "core/contact/sinkage.h"
#include "core/soil/soil_parameters.h"
#include "core/wheel/wheel_parameters.h"

namespace terra::analysis {

/// What to sweep. With `load_n` set, θ_f is solved at every point (section 2.6.1); otherwise the
/// fixed `entry_angle_rad` is used.
struct SweepSpec {
    std::vector<double> slips;                              ///< s values, each in [−1, 1]
    std::vector<double> slip_angles_rad;                    ///< β values
    std::optional<double> load_n = contact::kDefaultLoadN;  ///< W [N] (Table 2.6: 6 kg)
    double entry_angle_rad = 0.5236;                        ///< θ_f when no load is given
    contact::ExitCondition exit;                            ///< θ_r = 0 by default (Table 2.6)
    std::optional<double> max_stress_angle_rad;
    contact::ContactModel model = contact::ContactModel::kFull;
    contact::BulldozingModel bulldozing = contact::BulldozingModel::kBekker;
    contact::IntegrationOptions integration;
    int threads = 0;                            ///< 0: one per hardware thread
    const std::atomic<bool>* cancel = nullptr;  ///< set to stop early (rows so far are kept)
    /// Fraction of the points done, in [0, 1]; called from the worker threads (it must be
    /// thread-safe) after each point. May be empty.
    std::function<void(double)> progress;
};

/// n evenly spaced values from first to last inclusive (n ≥ 2), or {first} for n = 1.
std::vector<double> linspace(double first, double last, int count);

/// The thesis's slip grid: s = 0, 0.01, …, 0.99 — [0, 1) with 100 points, or `count` points.
std::vector<double> thesisSlips(int count = 100);

/// A sweep's result: one row per (β, s) with an equilibrium; points without one are listed.
struct SweepResult {
    Table table;  ///< slip_angle_deg, slip, entry_angle_deg, exit_angle_deg, sinkage_m, Fx_N,
                  ///< Fy_N, Fz_N, Mx_Nm, My_Nm, Mz_Nm, Fb_N, Fs_N
    std::vector<std::string> warnings;  ///< "β = 15°, s = 0.95: no equilibrium …"
    bool cancelled = false;
};

/// The column names of a sweep table.
const std::vector<std::string>& sweepColumns();

/// Runs the sweep, slip angles in parallel; each slip angle warm-starts the entry-angle solve
/// from the previous slip. Throws std::invalid_argument naming the field, value and range for an
/// invalid spec (slips, slip angles, load or entry angle, exit angle or rut ratio, θ_m), checked
/// before any thread starts; an exception thrown while computing, in any worker thread, is
/// rethrown to the caller (never std::terminate).
SweepResult sweepSlip(const contact::ContactParameters<double>& params, const SweepSpec& spec);

/// One parameter of the sensitivity study: a soil field key ("phi_deg") and its values in the
/// field's user unit.
struct SensitivityParameter {
    std::string key;
    std::vector<double> values;
};

/// Table 4.1 of the thesis: n, c, φ, k_c, k_φ, K with four variations each.
std::vector<SensitivityParameter> thesisSensitivityParameters();

/// For each value of the parameter: that soil (others unchanged) swept over slip with `spec`.
/// The table gains a leading column named after the key. Throws std::invalid_argument for an
/// unknown key or a value outside the field's range.
SweepResult sensitivity(const soil::SoilParameters& soil, const wheel::WheelParameters& wheel,
                        const SensitivityParameter& parameter, const SweepSpec& spec);

}  // namespace terra::analysis
