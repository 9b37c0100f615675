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
#include "core/contact/operating_fields.h"
#include "core/soil/soil_parameters.h"

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

    /// Its file keys, one line each (core/common/declared_fields.h): the reader, toJson, the
    /// command line's flags, the sensitivity panel's saved state and compute's checks.
    template <typename Visitor>
    void visitFields(Visitor& v);
};

/// "parameter": "all" or a soil field key (an unknown one named with the nearest); written as it
/// is, so that compute's check of a struct built in code names it as the reader does.
void readSensitivityParameter(io::ObjectReader& r, const char* key, std::string& out);
nlohmann::json sensitivityParameterJson(const std::string& parameter);
/// "slip_angle_deg": one angle [deg] or a list (a script's and a project's form); written as a
/// number when there is one, as a list otherwise (an empty list is left out).
void readSensitivitySlipAngles(io::ObjectReader& r, const char* key, std::vector<double>& out);
nlohmann::json sensitivitySlipAnglesJson(const std::vector<double>& slip_angles_deg);

template <typename Visitor>
void SensitivitySettings::visitFields(Visitor& v) {
    v(fields::custom("parameter", parameter, "name", "all, or a soil field key",
                     "the soil parameter varied; all: Table 4.1's in turn",
                     readSensitivityParameter, sensitivityParameterJson));
    // Any finite numbers here; their range is the parameter's field's (sensitivityRuleIssues).
    v(fields::numbers("values", values, {-1e300, 1e300}, "",
                      "the parameter's values in its field's unit; absent: Table 4.1's", 1));
    v(fields::custom("slip_angle_deg", slip_angles_deg, "number or list of numbers",
                     "(-90, 90) deg", "slip angle(s) β of the family; the tornado's is the first",
                     readSensitivitySlipAngles, sensitivitySlipAnglesJson));
    v(fields::integer("slip_count", slip_count, static_cast<int>(slipCountField().range.low),
                      static_cast<int>(slipCountField().range.high),
                      "slips 0 … the conditions' slip_max (when slips is absent)"));
    v(fields::number("tornado_slip", tornado_slip, contact::slipField().range, "",
                     "slip at which the tornado compares F_x"));
    v(fields::members(sweep));
}

/// The keys of SensitivitySettings::visitFields, read strictly (io::readFields): "parameter",
/// "values", "slip_angle_deg" (a number or a list), "slip_count", "tornado_slip" and the
/// sweep's settings; then what the list cannot say (sensitivityRuleIssues).
void readSensitivitySettings(io::ObjectReader& r, SensitivitySettings& out);
/// The rules the list cannot say: the values against the parameter's field's range (or Table
/// 4.1's variations when none are given), values only with a single parameter.
std::vector<Issue> sensitivityRuleIssues(const SensitivitySettings& settings);
/// The reader's hook, after io::readFields: sensitivityRuleIssues reported through `r`, when the
/// parameter and the values were read without a problem (the sensitivity panel's reader calls it
/// too).
void reportSensitivityRules(io::ObjectReader& r, const SensitivitySettings& settings);
/// The settings' file keys (io::fieldsToJson).
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
