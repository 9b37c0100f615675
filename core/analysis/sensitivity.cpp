#include "core/analysis/sensitivity.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/analysis/registry.h"
#include "core/common/quoted.h"
#include "core/common/units.h"
#include "core/contact/operating_fields.h"
#include "core/io/declared_json.h"

namespace terra::analysis {
namespace {

// The parameters and values the settings name, or the problems with them.
std::vector<SensitivityParameter> parametersOf(const SensitivitySettings& s,
                                               std::vector<Issue>& issues) {
    std::vector<SensitivityParameter> out;
    if (s.parameter == "all") {
        if (!s.values.empty()) issues.push_back({"values", "values need a single parameter"});
        return thesisSensitivityParameters();
    }
    const soil::SoilField* field = soil::findSoilField(s.parameter);
    if (!field) {
        std::vector<std::string> keys{"all"};
        for (const soil::SoilField& f : soil::soilFields()) keys.emplace_back(f.key);
        const std::string near = nearestName(s.parameter, keys);
        issues.push_back(
            {"parameter", quoteText(s.parameter, '"') + " is not a soil field" +
                              (near.empty() ? "" : " (did you mean \"" + near + "\"?)")});
        return out;
    }
    SensitivityParameter parameter{s.parameter, s.values};
    if (parameter.values.empty()) {
        for (const SensitivityParameter& p : thesisSensitivityParameters()) {
            if (p.key == s.parameter) parameter.values = p.values;
        }
        if (parameter.values.empty()) {
            issues.push_back(
                {"values", "Table 4.1 has no variations of " + s.parameter + "; give its values"});
        }
    }
    for (std::size_t i = 0; i < parameter.values.size(); ++i) {
        std::vector<Issue> range;
        if (!checkRange(range, s.parameter, parameter.values[i], field->range,
                        field->displayUnit())) {
            issues.push_back(
                {"values[" + std::to_string(i) + "]", s.parameter + " = " + range.front().message});
        }
    }
    out.push_back(parameter);
    return out;
}

}  // namespace

void readSensitivityParameter(io::ObjectReader& r, const char* key, std::string& out) {
    std::vector<std::string> names{"all"};
    for (const soil::SoilField& f : soil::soilFields()) names.emplace_back(f.key);
    r.choiceName(key, out, names);
}

nlohmann::json sensitivityParameterJson(const std::string& parameter) { return parameter; }

void readSensitivitySlipAngles(io::ObjectReader& r, const char* key, std::vector<double>& out) {
    const FieldInfo& beta = contact::slipAngleField();
    if (const nlohmann::json* v = r.value(key); v && v->is_array()) {
        r.numbers(key, out, beta.range, beta.displayUnit(), 1);
    } else {
        double value = 0.0;
        if (r.number(key, value, beta.range, beta.displayUnit())) out = {value};
    }
}

nlohmann::json sensitivitySlipAnglesJson(const std::vector<double>& slip_angles_deg) {
    if (slip_angles_deg.empty()) return nullptr;
    if (slip_angles_deg.size() == 1) return slip_angles_deg.front();
    return slip_angles_deg;
}

std::vector<Issue> sensitivityRuleIssues(const SensitivitySettings& settings) {
    std::vector<Issue> issues;
    parametersOf(settings, issues);
    return issues;
}

void reportSensitivityRules(io::ObjectReader& r, const SensitivitySettings& settings) {
    const auto bad = [&r](const char* key) {
        const std::string at = r.where(key);
        return std::any_of(r.issues().begin(), r.issues().end(), [&at](const Issue& issue) {
            return issue.where == at || issue.where.starts_with(at + "[");
        });
    };
    if (bad("parameter") || bad("values")) return;
    for (Issue& issue : sensitivityRuleIssues(settings))
        r.report(issue.where, std::move(issue.message));
}

void readSensitivitySettings(io::ObjectReader& r, SensitivitySettings& out) {
    io::readFields(r, out);
    reportSensitivityRules(r, out);
}

nlohmann::json toJson(const SensitivitySettings& s) { return io::fieldsToJson(s); }

SensitivityResult computeSensitivity(const Inputs& in, const SensitivitySettings& settings,
                                     const Control& control) {
    // The reader's checks, in its words, for settings built in code (the panel's, a test's);
    // the parameter's values when the list found nothing wrong with them.
    std::vector<Issue> issues = io::fieldIssues(settings);
    const bool listed_ok = std::none_of(issues.begin(), issues.end(), [](const Issue& issue) {
        return issue.where.starts_with("parameter") || issue.where.starts_with("values");
    });
    if (listed_ok) {
        for (Issue& issue : sensitivityRuleIssues(settings)) issues.push_back(std::move(issue));
    }
    if (settings.slip_angles_deg.empty()) issues.push_back({"slip_angle_deg", "no slip angle"});
    if (!issues.empty()) throw std::invalid_argument(formatIssues(issues));
    std::vector<Issue> checked;  // empty: checked above
    const std::vector<SensitivityParameter> parameters = parametersOf(settings, checked);
    Inputs family_inputs = in;
    family_inputs.conditions.slip_angles_deg = settings.slip_angles_deg;
    ForcesSettings sweep = settings.sweep;
    if (sweep.slips.empty())
        sweep.slips = linspace(0.0, in.conditions.slip_max, settings.slip_count);
    const SweepSpec spec = forcesSpec(family_inputs, sweep, control);

    SensitivityResult out;
    const bool all = parameters.size() > 1 || settings.parameter == "all";
    out.family.table.columns = all ? std::vector<std::string>{"parameter", "value"}
                                   : std::vector<std::string>{parameters.front().key};
    for (const std::string& c : sweepColumns()) out.family.table.columns.push_back(c);
    const double count = static_cast<double>(parameters.size());
    for (std::size_t k = 0; k < parameters.size(); ++k) {
        SweepSpec family_spec = spec;
        if (control.progress) {
            // The family is the work; the tornado's dozen points after it are not counted.
            family_spec.progress = [&control, k, count](double f) {
                control.report((static_cast<double>(k) + f) / count);
            };
        }
        const SweepResult one = sensitivity(in.soil, in.wheel, parameters[k], family_spec);
        for (const auto& row : one.table.rows) {
            std::vector<double> values;
            if (all) values.push_back(static_cast<double>(k));
            values.insert(values.end(), row.begin(), row.end());
            out.family.table.rows.push_back(std::move(values));
        }
        out.family.warnings.insert(out.family.warnings.end(), one.warnings.begin(),
                                   one.warnings.end());
        out.parameter_keys.push_back(parameters[k].key);
        if (one.cancelled) {
            out.family.cancelled = true;
            return out;
        }
    }

    // Tornado: F_x at one slip (and the first slip angle) for the extreme variations of each
    // Table 4.1 parameter.
    SweepSpec point = spec;
    point.progress = nullptr;
    point.slips = {settings.tornado_slip};
    point.slip_angles_rad = {spec.slip_angles_rad.front()};
    const SweepResult base = sweepSlip(in.contact(), point);
    const double base_fx =
        base.table.rows.empty() ? std::nan("") : base.table.values("Fx_N").front();
    out.tornado.columns = {"parameter_index", "Fx_low_N", "Fx_high_N", "Fx_base_N"};
    out.tornado.label_column = "parameter";
    const std::vector<SensitivityParameter> table41 = thesisSensitivityParameters();
    for (std::size_t i = 0; i < table41.size(); ++i) {
        if (control.cancelled()) {
            out.family.cancelled = true;
            break;
        }
        const SensitivityParameter extremes{table41[i].key,
                                            {table41[i].values.front(), table41[i].values.back()}};
        const SweepResult r = sensitivity(in.soil, in.wheel, extremes, point);
        double low = std::nan(""), high = std::nan("");
        const std::size_t key = r.table.column(extremes.key), fx = r.table.column("Fx_N");
        for (const auto& row : r.table.rows) {
            if (row[key] == extremes.values[0]) low = row[fx];
            if (row[key] == extremes.values[1]) high = row[fx];
        }
        out.tornado.rows.push_back({static_cast<double>(i), low, high, base_fx});
        out.tornado_keys.push_back(extremes.key);
        out.tornado.labels.push_back(extremes.key);
    }
    return out;
}

Outcome sensitivityOutcome(SensitivityResult result) {
    Outcome out;
    out.status =
        result.family.cancelled ? Outcome::Status::kCancelled : Outcome::Status::kCompleted;
    out.tables.push_back({"family", "", result.family.table});
    out.tables.push_back({"tornado", "-tornado", result.tornado});
    out.notes = result.family.warnings;
    out.result = std::move(result);
    return out;
}

AnalysisType sensitivityType() {
    return makeAnalysisType<SensitivitySettings>(
        "sensitivity",
        "forces against slip for each value of one soil parameter, and a tornado of all of "
        "Table 4.1 (Figs. 4.1-4.6)",
        {"family", "tornado"}, {{"Fx", "-Fx"}, {"Fs", "-Fs"}, {"tornado", "-tornado"}},
        [](io::ObjectReader& r, const ReadContext&, SensitivitySettings& s) {
            readSensitivitySettings(r, s);
            if (s.parameter == "all") {
                r.report("parameter",
                         "\"all\" is the command line's (sensitivity --parameter all); a script's "
                         "family figures need one soil field key");
            }
        },
        [](const Inputs& in, const SensitivitySettings& s, const Control& c) {
            return computeSensitivity(in, s, c);
        },
        sensitivityOutcome);
}

}  // namespace terra::analysis
