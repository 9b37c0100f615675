#include "core/analysis/rover.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <memory>
#include <stdexcept>

#include "core/analysis/registry.h"
#include "core/analysis/traction.h"
#include "core/common/units.h"
#include "core/io/declared_json.h"
#include "core/io/json_reader.h"
#include "core/io/parameters_json.h"
#include "core/scenario/scenario_json.h"

namespace terra::analysis {

namespace {

/// A soil or wheel given as a preset name, a file (relative to the context's directory) or an
/// object, as the other analyses' settings take them.
template <typename T, typename FromJson, typename Resolve>
std::optional<T> readPresetOrObject(io::ObjectReader& r, const ReadContext& context,
                                    const nlohmann::json& value, const std::string& key,
                                    FromJson from_json, Resolve resolve) {
    if (value.is_object()) {
        Result<T> read = from_json(value, r.pathOf(key));
        if (read) return read.value();
        for (const Issue& issue : read.issues()) r.report(key, issue.message);
        return std::nullopt;
    }
    if (!value.is_string()) {
        r.report(key,
                 "expected a preset name, a file or an object, not " + io::describeJson(value));
        return std::nullopt;
    }
    if (context.locations == nullptr) return std::nullopt;
    Result<T> read = resolve(*context.locations, context.presetOrFile(value.get<std::string>()));
    if (read) return read.value();
    r.report(key, read.message());
    return std::nullopt;
}

/// The soil a "soils" key names in `s`: "base", a field's class code, a patch terrain's patch
/// number (from 1); nullptr with the reason in `why`.
soil::SoilParameters* soilOf(scenario::Scenario& s, const std::shared_ptr<field::FieldMap>& field,
                             const std::string& key, std::string& why) {
    if (key == "base") return field ? &field->base : &s.terrain.base;
    int number = 0;
    const char* end = key.data() + key.size();
    const auto [last, error] = std::from_chars(key.data(), end, number);
    const bool whole = error == std::errc() && last == end;
    if (field) {
        if (whole) {
            if (const auto it = field->legend.find(number); it != field->legend.end())
                return &it->second;
        }
        std::string codes;
        for (const auto& entry : field->legend)
            codes += (codes.empty() ? "" : ", ") + std::to_string(entry.first);
        why = "the field has no soil class '" + key + "': \"base\" or one of its classes " +
              (codes.empty() ? "(none)" : codes);
        return nullptr;
    }
    const int patches = static_cast<int>(s.terrain.patches.size());
    if (whole && number >= 1 && number <= patches)
        return &s.terrain.patches[static_cast<std::size_t>(number - 1)].soil;
    why = "the scenario has no soil '" + key + "': \"base\"" +
          (patches > 0 ? " or a patch number from 1 to " + std::to_string(patches) : "");
    return nullptr;
}

/// The study's overrides of the robot and the soils (RoverSettings) applied to `s`.
void applyOverrides(const RoverSettings& settings, scenario::Scenario& s,
                    std::vector<Issue>& issues) {
    if (settings.chassis_mass_kg) s.robot.chassis_mass_kg = *settings.chassis_mass_kg;
    if (settings.wheel) s.robot.wheel = *settings.wheel;
    if (settings.soils.empty()) return;
    // A field is shared between runs: the run with other soils gets a copy of it.
    std::shared_ptr<field::FieldMap> copy =
        s.field ? std::make_shared<field::FieldMap>(*s.field) : nullptr;
    for (const auto& [key, soil] : settings.soils) {
        std::string why;
        soil::SoilParameters* target = soilOf(s, copy, key, why);
        if (target == nullptr) {
            issues.push_back({"soils." + key, why});
            continue;
        }
        std::optional<soil::SoilProfile> profile = target->profile;
        *target = soil;
        if (!target->profile) target->profile = std::move(profile);
    }
    if (copy) s.field = std::move(copy);
}

}  // namespace

void readWheelOverride(io::ObjectReader& r, const char* key,
                       std::optional<wheel::WheelParameters>& out) {
    // A name needs the context's presets: readRoverSettings resolves it.
    if (const nlohmann::json* value = r.value(key); value != nullptr && !value->is_string()) {
        out = readPresetOrObject<wheel::WheelParameters>(r, {}, *value, key, io::wheelFromJson,
                                                         io::resolveWheel);
    }
}

void readSoilOverrides(io::ObjectReader& r, const char* key,
                       std::map<std::string, soil::SoilParameters>& out) {
    const nlohmann::json* soils = r.value(key);
    if (soils == nullptr) return;
    if (!soils->is_object()) {
        r.report(key, "expected an object of soils by \"base\", class code or patch number, not " +
                          io::describeJson(*soils));
        return;
    }
    for (const auto& [name, value] : soils->items()) {
        if (value.is_string()) continue;  // a preset or file: readRoverSettings
        if (auto soil = readPresetOrObject<soil::SoilParameters>(
                r, {}, value, std::string(key) + "." + name, io::soilFromJson, io::resolveSoil))
            out[name] = *soil;
    }
}

nlohmann::json wheelOverrideJson(const std::optional<wheel::WheelParameters>& wheel) {
    return wheel ? io::toJson(*wheel) : nlohmann::json();
}

nlohmann::json soilOverridesJson(const std::map<std::string, soil::SoilParameters>& soils) {
    if (soils.empty()) return nullptr;
    nlohmann::json out = nlohmann::json::object();
    for (const auto& [key, soil] : soils) out[key] = io::toJson(soil);
    return out;
}

void readRoverSettings(io::ObjectReader& r, const ReadContext& context, RoverSettings& out) {
    // Required: a key the field list cannot mark (its reader's "missing" wording).
    r.value("scenario", io::Presence::kRequired, "a string");
    io::readFields(r, out);
    if (r.has("scenario") && r.value("scenario")->is_string() && context.locations != nullptr) {
        Result<scenario::Scenario> loaded =
            scenario::resolveScenario(*context.locations, context.presetOrFile(out.scenario));
        if (loaded) {
            out.loaded = loaded.value();
        } else {
            for (const Issue& issue : loaded.issues())
                r.report(
                    "scenario",
                    (issue.where.empty() || issue.where == "scenario" ? "" : issue.where + ": ") +
                        issue.message);
        }
    }
    // The overrides against the scenario's own step and duration (a duration below one step),
    // while the file's position is at hand.
    if (out.loaded && (out.duration_s || out.time_step_s)) {
        scenario::Scenario s = *out.loaded;
        if (out.duration_s) s.duration_s = *out.duration_s;
        if (out.time_step_s) {
            s.time_step_s = *out.time_step_s;
            s.output_interval_s = std::max(s.output_interval_s, s.time_step_s);
        }
        for (const Issue& issue : scenario::validate(s)) {
            if (issue.where == "duration_s" || issue.where == "time_step_s")
                r.report(issue.where, issue.message);
        }
    }
    // A wheel or soils named by preset or file, found through the context.
    if (const nlohmann::json* wheel = r.value("wheel"); wheel != nullptr && wheel->is_string()) {
        out.wheel = readPresetOrObject<wheel::WheelParameters>(r, context, *wheel, "wheel",
                                                               io::wheelFromJson, io::resolveWheel);
    }
    if (const nlohmann::json* soils = r.value("soils"); soils != nullptr && soils->is_object()) {
        for (const auto& [key, value] : soils->items()) {
            if (!value.is_string()) continue;  // an object: readSoilOverrides
            if (auto soil = readPresetOrObject<soil::SoilParameters>(
                    r, context, value, "soils." + key, io::soilFromJson, io::resolveSoil))
                out.soils[key] = *soil;
        }
    }
    // The overrides against the scenario they change (a class the field does not have, a wheel
    // too wide for the track), while the file's position is at hand.
    if (out.loaded && (out.chassis_mass_kg || out.wheel || !out.soils.empty())) {
        scenario::Scenario s = *out.loaded;
        std::vector<Issue> issues;
        applyOverrides(out, s, issues);
        if (issues.empty()) issues = scenario::validate(s);
        for (const Issue& issue : issues) r.report(issue.where, issue.message);
    }
}

nlohmann::json toJson(const RoverSettings& settings) { return io::fieldsToJson(settings); }

std::vector<std::pair<std::string, soil::SoilParameters>> overridableSoils(
    const scenario::Scenario& s) {
    std::vector<std::pair<std::string, soil::SoilParameters>> out;
    if (s.field) {
        out.emplace_back("base", s.field->base);
        for (const auto& [code, soil] : s.field->legend)
            out.emplace_back(std::to_string(code), soil);
        return out;
    }
    out.emplace_back("base", s.terrain.base);
    for (std::size_t i = 0; i < s.terrain.patches.size(); ++i)
        out.emplace_back(std::to_string(i + 1), s.terrain.patches[i].soil);
    return out;
}

scenario::Scenario roverScenario(const RoverSettings& settings) {
    if (!settings.loaded) {
        throw std::invalid_argument("scenario '" + settings.scenario + "' is not resolved");
    }
    scenario::Scenario s = *settings.loaded;
    // The reader's checks, in its words, for settings built in code (a panel's, a test's).
    std::vector<Issue> issues = io::fieldIssues(settings);
    if (!issues.empty()) throw std::invalid_argument(formatIssues(issues));
    if (settings.duration_s) s.duration_s = *settings.duration_s;
    if (settings.time_step_s) {
        s.time_step_s = *settings.time_step_s;
        s.output_interval_s = std::max(s.output_interval_s, s.time_step_s);
    }
    if (settings.model) s.options.contact.model = *settings.model;
    if (settings.controller) s.controller.type = *settings.controller;
    if (settings.slip) s.controller.slip = *settings.slip;
    if (settings.traction_limited) s.controller.traction_limited = *settings.traction_limited;
    if (settings.robust) s.controller.robust = *settings.robust;
    if (settings.quantile) s.controller.quantile = *settings.quantile;
    if (settings.posterior_samples) s.controller.posterior_samples = *settings.posterior_samples;
    if (settings.posterior_method) s.controller.posterior_method = *settings.posterior_method;
    if (settings.identifier) s.controller.identifier = *settings.identifier;
    applyOverrides(settings, s, issues);
    // The overrides together with the scenario's own values (a --duration below the step, a
    // wheel too wide for the track).
    if (issues.empty() && (settings.duration_s || settings.time_step_s ||
                           settings.chassis_mass_kg || settings.wheel || !settings.soils.empty()))
        issues = scenario::validate(s);
    if (!issues.empty()) throw std::invalid_argument(formatIssues(issues));
    return s;
}

const std::vector<std::string>& roverFigureKeys() {
    static const std::vector<std::string> keys{
        "path",         "yaw",  "velocities", "slip",         "steering",   "wheel-vx", "wheel-vy",
        "drawbar-pull", "load", "sinkage",    "slip-control", "efficiency", "energy",   "top-view"};
    return keys;
}

nlohmann::json controllerComparison(const std::vector<ControllerRun>& runs) {
    auto meanPull = [](const scenario::RunResult& r) {
        const double distance = r.summary.distance_m;
        return distance > 0.0 ? r.traction.drawbar_work_j / distance : 0.0;
    };
    double oracle_pull = 0.0;
    for (const ControllerRun& row : runs)
        if (row.controller == "oracle") oracle_pull = meanPull(row.run);
    auto optional = [](const std::optional<double>& v) {
        return v ? nlohmann::json(*v) : nlohmann::json(nullptr);
    };
    nlohmann::json out = nlohmann::json::array();
    for (const ControllerRun& row : runs) {
        const scenario::Summary& m = row.run.summary;
        const scenario::TractionMetrics& t = row.run.traction;
        const double pull = meanPull(row.run);
        nlohmann::json mean_slip;
        for (std::size_t i = 0; i < dynamics::kWheelCount; ++i)
            mean_slip[dynamics::kCornerNames[i]] = m.mean_slip[i];
        out.push_back(
            {{"controller", row.controller},
             {"status", row.run.status == scenario::RunResult::Status::kCompleted
                            ? "completed"
                            : "not completed"},
             {"distance_m", m.distance_m},
             {"energy_per_m_J", optional(m.energy_per_m_j)},
             {"mean_efficiency", optional(m.mean_efficiency)},
             {"energy_per_drawbar_work", t.drawbar_work_j > 0.0
                                             ? nlohmann::json(t.drive_energy_j / t.drawbar_work_j)
                                             : nlohmann::json(nullptr)},
             {"mean_drawbar_N", pull},
             {"drawbar_vs_oracle",
              oracle_pull > 0.0 ? nlohmann::json(pull / oracle_pull) : nlohmann::json(nullptr)},
             {"mean_slip", mean_slip},
             {"slip_tracking_rms", optional(m.slip_tracking_rms)},
             {"border_time_s", optional(t.border_time_s)},
             {"settling_time_s", optional(t.settling_time_s)},
             {"settling_band_time_s", optional(t.settling_band_time_s)},
             {"settling_band", optional(t.settle_band)},
             {"rut_depth_m",
              t.rear_sinkage_count > 0
                  ? nlohmann::json(t.rear_sinkage_sum_m / static_cast<double>(t.rear_sinkage_count))
                  : nlohmann::json(nullptr)}});
    }
    return out;
}

std::vector<ControllerRun> compareControllers(
    const RoverSettings& settings, const Control& control,
    const std::function<void(const std::string&, RoverResult&)>& on_run) {
    const std::vector<std::string>& names = scenario::controllerNames();
    const double share = 1.0 / static_cast<double>(names.size());
    std::vector<ControllerRun> runs;
    for (std::size_t k = 0; k < names.size(); ++k) {
        RoverSettings one = settings;
        one.controller = scenario::controllerFromName(names[k]);
        Control run_control{control.cancel};
        if (control.progress) {
            run_control.progress = [&control, k, share](double fraction) {
                control.report((static_cast<double>(k) + fraction) * share);
            };
        }
        RoverResult result = runRover(one, run_control);
        const bool cancelled = result.run.status == scenario::RunResult::Status::kCancelled;
        runs.push_back({names[k], result.run});
        if (on_run) on_run(names[k], result);
        if (cancelled) break;
    }
    return runs;
}

scenario::SlipPlanner tractionPlanner() {
    return [](const scenario::SlipPlanRequest& request) -> std::optional<scenario::SlipPlan> {
        Inputs inputs;
        inputs.soil = request.soil;
        inputs.wheel = request.wheel;
        inputs.conditions.load_n = request.load_n;
        inputs.conditions.quadratic = request.model == contact::ContactModel::kQuadratic;
        TractionSettings settings;
        settings.objective = request.objective == scenario::SlipObjective::kDrawbar
                                 ? TractionObjective::kDrawbar
                                 : TractionObjective::kEfficiency;
        settings.slip_min = request.slip_min;
        settings.slip_max = request.slip_max;
        settings.curve_points = 30;
        const bool robust = request.posterior && request.robust != scenario::RobustSlip::kNone;
        if (robust) {
            settings.posterior = request.posterior;
            settings.quantile = request.quantile;
            settings.posterior_samples = request.posterior_samples;
            settings.posterior_method = request.posterior_method;
        }
        try {
            const TractionResult r = computeTraction(inputs, settings);
            if (!r.optimal_slip) return std::nullopt;
            scenario::SlipPlan plan{*r.optimal_slip, r.optimal_slip_std};
            // A robust s*, where the posterior gives one (else the estimate's own s*).
            if (robust && request.robust == scenario::RobustSlip::kQuantile && r.robust_slip)
                plan.slip = *r.robust_slip;
            if (robust && request.robust == scenario::RobustSlip::kExpected && r.expected_slip)
                plan.slip = *r.expected_slip;
            return plan;
        } catch (const std::invalid_argument&) {
            return std::nullopt;  // an estimate outside the soil's ranges: keep the set-point
        }
    };
}

RoverResult runRover(const RoverSettings& settings, const Control& control) {
    RoverResult out;
    out.scenario = roverScenario(settings);
    scenario::RunOptions options;
    options.cancel = control.cancel;
    options.progress = control.progress;
    options.slip_planner = tractionPlanner();
    out.run = scenario::runScenario(out.scenario, options);
    return out;
}

Summary roverSummary(const scenario::RunResult& run, const scenario::Scenario& scenario) {
    using Emphasis = SummaryRow::Emphasis;
    const scenario::Summary& m = run.summary;
    Summary out;
    out.push_back(
        {scenario.name, formatFixed(m.duration_s, 3) + " s simulated", "",
         std::to_string(m.steps) + " steps of " + formatNumber(scenario.time_step_s) + " s",
         Emphasis::kHeading, ""});
    if (run.status != scenario::RunResult::Status::kCompleted) {
        const bool cancelled = run.status == scenario::RunResult::Status::kCancelled;
        out.push_back({"status", cancelled ? "cancelled" : "diverged", "", run.message,
                       Emphasis::kWarning, "/status"});
    }
    const auto number = [&out](std::string label, double value, int decimals, std::string unit,
                               std::string json, std::string detail = {}, double scale = 1.0) {
        out.push_back({std::move(label), formatFixed(scale * value, decimals), std::move(unit),
                       std::move(detail), Emphasis::kNormal, std::move(json), value});
    };
    number("final x", m.x_m, 4, "m", "/x_m");
    number("final y", m.y_m, 4, "m", "/y_m");
    number("final yaw", m.yaw_rad, 3, "deg", "/yaw_rad", {}, units::radToDeg(1.0));
    number("distance", m.distance_m, 4, "m", "/distance_m");
    for (int i = 0; i < dynamics::kWheelCount; ++i) {
        const std::string corner = dynamics::kCornerNames[i];
        number("mean slip " + corner, m.mean_slip[i], 4, "", "/mean_slip/" + corner);
    }
    number("motor energy", m.energy_j, 3, "J", "/energy_J",
           "into the soil " + formatFixed(m.dissipated_j, 3) + " J");
    if (run.maps && m.cells_touched) {
        out.push_back({"cells touched", std::to_string(*m.cells_touched), "",
                       "of " + formatNumber(run.maps->passes.cell_m) + " m", Emphasis::kNormal,
                       "/cells_touched", static_cast<double>(*m.cells_touched)});
        number("deepest rut", run.maps->rut_depth_m.valueRange().second, 2, "mm",
               "/max_rut_depth_m", {}, 1000.0);
        const double risk = run.maps->compaction_risk.valueRange().second;
        const std::string at = "at " + formatNumber(run.maps->risk_depth_m) + " m";
        if (std::isnan(risk)) {
            out.push_back({"largest compaction risk", "none", "", at + ": no soil profile",
                           Emphasis::kNormal, ""});
        } else {
            number("largest compaction risk", risk, 3, "", "/max_compaction_risk", at);
        }
    }
    if (m.mission) {
        const scenario::MissionOutcome& mission = *m.mission;
        if (mission.completed && mission.time_s) {
            number("mission completed at", *mission.time_s, 2, "s", "/mission_time_s");
        } else {
            out.push_back({"mission", "not completed", "", "", Emphasis::kWarning, ""});
        }
        number("path progress", mission.progress_m, 2, "m", "/path_progress_m",
               "of " + formatFixed(mission.path_length_m, 2) + " m of path");
        number("path error RMS", mission.error_rms_m, 1, "cm", "/path_error_rms_m",
               "at most " + formatFixed(100.0 * mission.error_max_m, 1) + " cm", 100.0);
    }
    const nlohmann::json j = scenario::toJson(run, scenario);
    if (j.contains("warning"))
        out.push_back(
            {"warning", j["warning"].get<std::string>(), "", "", Emphasis::kWarning, "/warning"});
    return out;
}

Table roverSummaryTable(const RoverResult& result) {
    const nlohmann::json summary = scenario::toJson(result.run, result.scenario);
    const Table& series = result.run.series;
    Table t;
    t.rows.emplace_back();
    auto add = [&](const std::string& key, double value) {
        t.columns.push_back(key);
        t.rows[0].push_back(value);
    };
    for (const auto& [key, value] : summary.items()) {
        if (value.is_number()) add(key, value.get<double>());
        if (value.is_object()) {
            for (const auto& [sub, v] : value.items()) {
                if (v.is_number()) add(key + "_" + sub, v.get<double>());
            }
        }
    }
    add("yaw_deg", units::radToDeg(summary.value("yaw_rad", 0.0)));
    double max_y = 0.0, max_yaw = 0.0;
    if (!series.rows.empty()) {
        for (double y : series.values("y_m")) max_y = std::max(max_y, std::abs(y));
        for (double yaw : series.values("yaw_deg")) max_yaw = std::max(max_yaw, std::abs(yaw));
    }
    add("max_abs_y_m", max_y);
    add("max_abs_yaw_deg", max_yaw);
    return t;
}

Outcome roverOutcome(RoverResult result) {
    Outcome out;
    const scenario::RunResult& run = result.run;
    const nlohmann::json summary = scenario::toJson(run, result.scenario);
    if (run.status == scenario::RunResult::Status::kDiverged) {
        out.status = Outcome::Status::kFailed;
        out.message = "the run diverged: " + run.message;
    } else if (run.status == scenario::RunResult::Status::kCancelled) {
        out.status = Outcome::Status::kCancelled;
        out.message = run.message;
    }
    out.tables.push_back({"summary", std::nullopt, roverSummaryTable(result)});
    out.tables.push_back({"timeseries", "-timeseries", run.series});
    if (!run.streaming.columns.empty())
        out.tables.push_back({"streaming", "-streaming", run.streaming});
    out.documents.emplace_back("-summary.json", summary);
    if (run.status != scenario::RunResult::Status::kCompleted) {
        out.notes.push_back("run " + summary.value("status", std::string()) + ": " + run.message);
    }
    if (summary.contains("warning")) out.notes.push_back(summary["warning"].get<std::string>());
    out.notes.push_back("final pose x = " + formatNumber(run.summary.x_m) +
                        " m, y = " + formatNumber(run.summary.y_m) +
                        " m, yaw = " + formatNumber(units::radToDeg(run.summary.yaw_rad)) +
                        " deg; motor energy " + formatNumber(run.summary.energy_j) + " J");
    out.result = std::move(result);
    return out;
}

AnalysisType roverType() {
    std::vector<FigureSpec> figures;
    for (const std::string& key : roverFigureKeys()) figures.push_back({key, "-" + key});
    return makeAnalysisType<RoverSettings>(
        "rover", "the 4WD/4WS robot driven through a scenario on deformable soil (Figs. 3.7-3.15)",
        {"summary", "timeseries", "streaming"}, std::move(figures), readRoverSettings,
        [](const Inputs&, const RoverSettings& s, const Control& c) { return runRover(s, c); },
        roverOutcome, false);
}

}  // namespace terra::analysis
