#pragma once
/// @file stresses.h
/// The stress distributions over the contact at one operating point (thesis Figs. 2.11, 2.16):
/// σ, τ, τ_t, τ_l and the shear deformation j (Eqs. 2.13–2.22), exact and from the quadratic
/// approximation (Eqs. 2.36–2.38), with the approximation's RMSE and MAE over the grid
/// (Eqs. 2.39–2.40, Tables 2.4–2.5). The studio's stress panel, `terrastudio stresses` and a
/// script's "stresses" analysis.

#include <array>
#include <optional>
#include <string>

#include "core/analysis/analysis.h"
#include "core/common/range.h"
#include "core/contact/operating_fields.h"
#include "core/contact/quadratic_model.h"

namespace terra::analysis {

struct AnalysisType;

struct StressSettings {
    double slip = 0.3;             ///< s [-] (Table 2.3)
    double slip_angle_deg = 12.0;  ///< β [deg] (Table 2.3)
    /// A fixed entry angle θ_f [deg] (Table 2.3: 30°); empty: solved so that F_z = W (§2.6.1).
    std::optional<double> entry_angle_deg;
    /// Grid step [deg] of the table and of the errors: 0.01° reproduces Tables 2.4–2.5
    /// (docs/model.md).
    double step_deg = 0.01;
    std::string stress = "all";  ///< what the figure shows: all, sigma, tau, tau_t, tau_l
    ModelChoices model;          ///< θ_r and θ_m (the bulldozing choice does not apply)

    /// Its file keys, one line each (core/common/declared_fields.h): the reader, toJson, the
    /// command line's flags, the stress panel's saved state and compute's checks.
    template <typename Visitor>
    void visitFields(Visitor& v);
};

/// The names a figure can show (StressSettings::stress).
const std::vector<std::string>& stressNames();

/// The range of the grid step [deg]: a grid of at most ~1e6 points, at least one step.
inline constexpr Range kStressStepRange{1e-4, 10.0};

template <typename Visitor>
void StressSettings::visitFields(Visitor& v) {
    v(fields::number("slip", slip, contact::slipField().range, "", "slip ratio s"));
    v(fields::number("slip_angle_deg", slip_angle_deg, contact::slipAngleField().range, "deg",
                     "slip angle β"));
    v(fields::number("entry_angle_deg", entry_angle_deg, contact::entryAngleField().range, "deg",
                     "fixed entry angle θ_f; absent: solved so that F_z = W"));
    v(fields::number("step_deg", step_deg, kStressStepRange, "deg",
                     "grid step of the table and of the errors"));
    fields::Enum<std::string> shown{"stress", &stress, {}, "what the figure shows"};
    for (const std::string& name : stressNames()) shown.names.push_back({name.c_str(), name});
    v(shown);
    v(fields::members(model));
}

/// The keys of StressSettings::visitFields, read strictly (io::readFields): "slip",
/// "slip_angle_deg", "entry_angle_deg", "step_deg", "stress" and the model choices.
void readStressSettings(io::ObjectReader& r, StressSettings& out);
/// The settings' file keys (io::fieldsToJson): a default value is written, an absent entry
/// angle left out.
nlohmann::json toJson(const StressSettings& settings);

struct StressResult {
    /// theta_deg, sigma_kPa, tau_kPa, tau_t_kPa, tau_l_kPa, j_m and the quadratic
    /// sigma_quad_kPa, tau_quad_kPa, tau_t_quad_kPa, tau_l_quad_kPa: θ = θ_r, θ_r + step, …, ≤ θ_f
    /// with the θ_r the model uses (≥ −θ_f).
    Table table;
    std::array<contact::ApproximationError, 4> errors{};  ///< σ, τ, τ_t, τ_l [Pa]
    double entry_angle_deg = 0.0;                         ///< θ_f used (given or solved)
    double max_stress_angle_deg = 0.0;  ///< θ_m used (Eq. 2.18 or fixed, inside [θ_r, θ_f])
    std::string message;                ///< non-empty: no equilibrium at this load
    bool cancelled = false;             ///< stopped by the cancel flag: the grid is partial

    /// kCancelled: stopped by the cancel flag; kFailed: no equilibrium at this load (`message`);
    /// else kCompleted. Invalid inputs or settings throw (computeStresses): never kInvalidInput.
    Outcome::Status status() const {
        return cancelled         ? Outcome::Status::kCancelled
               : message.empty() ? Outcome::Status::kCompleted
                                 : Outcome::Status::kFailed;
    }
};

/// Throws std::invalid_argument for invalid inputs or settings (a struct built in code is
/// checked as its reader would read it: io::fieldIssues).
StressResult computeStresses(const Inputs& inputs, const StressSettings& settings = {},
                             const Control& control = {});
/// `terrastudio stresses --json`: "errors": {"sigma_rmse_kPa", "sigma_mae_kPa", … for sigma,
/// tau, tau_t, tau_l, "entry_angle_deg", "max_stress_angle_deg" (as typed: 15, not
/// 15.000000000000002), "points"}, "grid" (the table's columns), "status"
/// (statusName(result.status())) and "message" when there is one.
nlohmann::json toJson(const StressResult& result);
/// The result for a person, as `terrastudio stresses` prints it: a heading with the soil, the
/// wheel, s and β; θ_f (given, or solved from F_z = W) and θ_m [deg]; under a heading with the
/// grid's angles and step, each stress's RMSE of the quadratic approximation [kPa] with its MAE
/// after it (Tables 2.4–2.5). Without an equilibrium, or cancelled: the heading and why. Each
/// number's `json` points at it in toJson(result).
Summary stressSummary(const Inputs& inputs, const StressSettings& settings,
                      const StressResult& result);

/// The errors as a table: stress_index (0 σ, 1 τ, 2 τ_t, 3 τ_l), rmse_kPa, mae_kPa.
Table errorTable(const StressResult& result);
/// Tables "stresses" and "errors"; with no equilibrium (StressResult::message), no table and
/// the status failed with that message.
Outcome stressOutcome(StressResult result);

AnalysisType stressesType();

}  // namespace terra::analysis
