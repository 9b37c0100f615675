#pragma once
/// @file sinkage_study.h
/// Sinkage against load: static sinkage by Bekker's formula (Eq. 2.8, corrected E2) and by the
/// static contact integral (Eq. 2.7, whole and front half), and the dynamic entry angle with
/// its sinkage at one slip (section 2.6.1). `terrastudio sinkage` and a script's "sinkage".

#include <vector>

#include "core/analysis/analysis.h"
#include "core/contact/operating_fields.h"

namespace terra::analysis {

struct AnalysisType;

struct SinkageSettings {
    std::vector<double> loads_n;  ///< W [N]; empty: the conditions' load
    double slip = 0.0;            ///< s of the dynamic entry angle [-]
    double slip_angle_deg = 0.0;  ///< β of the dynamic entry angle [deg]
    ModelChoices model;           ///< θ_r, θ_m of the dynamic entry angle

    /// Its file keys, one line each (core/common/declared_fields.h): the reader, the command
    /// line's flags and compute's checks.
    template <typename Visitor>
    void visitFields(Visitor& v);
};

template <typename Visitor>
void SinkageSettings::visitFields(Visitor& v) {
    v(fields::numbers("loads_N", loads_n, contact::loadField().range, "N",
                      "the loads W; absent: the conditions' load", 1));
    v(fields::number("slip", slip, contact::slipField().range, "",
                     "slip s of the dynamic entry angle"));
    v(fields::number("slip_angle_deg", slip_angle_deg, contact::slipAngleField().range, "deg",
                     "slip angle β of the dynamic entry angle"));
    v(fields::members(model));
}

/// The keys of SinkageSettings::visitFields, read strictly (io::readFields): "loads_N", "slip",
/// "slip_angle_deg" and the model choices.
void readSinkageSettings(io::ObjectReader& r, SinkageSettings& out);
/// The settings' file keys (io::fieldsToJson).
nlohmann::json toJson(const SinkageSettings& settings);

struct SinkageStudy {
    /// load_N, bekker_sinkage_m, static_sinkage_m, static_angle_deg,
    /// static_front_half_sinkage_m, entry_angle_deg, sinkage_m; NaN where a solve has no solution.
    Table table;
    /// The solves without a solution and loads beyond Bekker's validity (h > r/3).
    std::vector<std::string> notes;
    bool cancelled = false;  ///< stopped by the cancel flag: the loads after the last row missing
};

/// Throws std::invalid_argument for invalid inputs or settings (a struct built in code is
/// checked as its reader would read it: io::fieldIssues).
SinkageStudy computeSinkage(const Inputs& inputs, const SinkageSettings& settings = {},
                            const Control& control = {});
/// Table "sinkage".
Outcome sinkageOutcome(SinkageStudy study);

AnalysisType sinkageType();

}  // namespace terra::analysis
