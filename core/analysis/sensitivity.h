#pragma once
/// @file sensitivity.h
/// Sensitivity of the forces to one soil parameter at a time (thesis section 4.2, Table 4.1,
/// Figs. 4.1–4.6): the sweep against slip for each value of the parameter, and a tornado of
/// F_x at one slip for the lowest and highest value of every Table 4.1 parameter. The studio's
/// sensitivity panel, `terrastudio sensitivity` and a script's "sensitivity" analysis. (The
/// global, variance-based study is core/gsa.)

#include <string>
#include <vector>

#include "core/analysis/analysis.h"
#include "core/analysis/forces.h"
#include "core/analysis/sweep.h"

namespace terra::analysis {

struct AnalysisType;

struct SensitivitySettings {
    /// A soil field key (soil_parameters.h), or "all": every parameter of Table 4.1 in turn.
    std::string parameter = "phi_deg";
    /// Its values in the field's unit; empty: Table 4.1's variations.
    std::vector<double> values;
    std::vector<double> slip_angles_deg{
        10.0};                  ///< β of the family [deg]; the tornado's is the first
    int slip_count = 50;        ///< slips 0 … the conditions' slip_max
    double tornado_slip = 0.3;  ///< s at which the tornado compares F_x
    ForcesSettings
        sweep;  ///< model choices, fixed entry angle, explicit slips (overrides slip_count)
};

/// "parameter", "values", "slip_angle_deg" (a number or a list), "slip_count", "tornado_slip" and
/// the sweep's settings (readForcesSettings).
void readSensitivitySettings(io::ObjectReader& r, SensitivitySettings& out);
nlohmann::json toJson(const SensitivitySettings& settings);

struct SensitivityResult {
    /// The family: the parameter's column (named by its key), then sweepColumns(); for "all", the
    /// columns "parameter" (index into parameter_keys) and "value" instead.
    SweepResult family;
    std::vector<std::string> parameter_keys;  ///< the parameters of the family, in order
    /// One row per Table 4.1 parameter, labelled by its soil-file key in the text column
    /// "parameter" (written first in CSV and JSON): parameter_index, Fx_low_N, Fx_high_N,
    /// Fx_base_N (F_x at the lowest and highest variation and with the soil unchanged).
    Table tornado;
    std::vector<std::string> tornado_keys;
};

/// Throws std::invalid_argument for an unknown parameter, a value outside the field's range, or
/// invalid inputs.
SensitivityResult computeSensitivity(const Inputs& inputs, const SensitivitySettings& settings = {},
                                     const Control& control = {});
/// Tables "family" and "tornado"; notes: the points without equilibrium.
Outcome sensitivityOutcome(SensitivityResult result);

AnalysisType sensitivityType();

}  // namespace terra::analysis
