// `terrastudio run SCRIPT.json --out DIR`: runs a list of the studio's analyses headlessly (the
// panels' own computations and drawings), writes their plots, data, a Markdown report and a
// manifest, and checks the script's expectations: a failed one makes the exit code 1
// (docs/user-guide.md, "Scripted runs").
#include <qcustomplot.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "app/cli/cli_support.h"
#include "app/cli/commands.h"
#include "app/cli/signals.h"
#include "app/headless_application.h"
#include "core/common/build_info.h"
#include "core/io/atomic_file.h"
#include "core/io/json.h"
#include "core/scenario/runner.h"
#include "core/scenario/scenario_json.h"
#include "widgets/analyses/analyses.h"
#include "widgets/analyses/soil_curves.h"
#include "widgets/plots/figures.h"
#include "widgets/plots/plot_export.h"
#include "widgets/plots/rover_figures.h"
#include "widgets/plots/sweep_plot.h"

namespace terra::app {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

struct RunOptions {
    std::string script;
    std::string out = "out";
    std::vector<std::string> formats;  // overrides the script's export.formats
};

/// One expectation: the value of `column` in the row nearest to `at` lies in [min, max].
struct Expectation {
    std::string table;  // "" = the analysis's main table
    std::string column;
    std::vector<std::pair<std::string, double>> at;
    double min = -INFINITY, max = INFINITY;
};

struct Outcome {
    std::string text;  // "Fx_N at slip = 0.3, slip_angle_deg = 5: 36.2 in [30, 40]"
    bool passed = false;
};

struct AnalysisRun {
    std::string name, type;
    std::vector<std::string> images;
    std::vector<std::string> data;
    std::vector<Outcome> outcomes;
    std::string error;
    std::vector<std::string> notes;
    double seconds = 0.0;
};

std::string describeAt(const std::vector<std::pair<std::string, double>>& at, const Table& table,
                       const std::vector<double>& row) {
    std::string text;
    for (const auto& [key, value] : at) {
        (void)value;
        text += (text.empty() ? " at " : ", ") + key + " = " + formatNumber(row[table.column(key)]);
    }
    return text;
}

Outcome check(const Expectation& e, const Table& table) {
    Outcome out;
    const std::string range = "[" + formatNumber(e.min) + ", " + formatNumber(e.max) + "]";
    if (std::find(table.columns.begin(), table.columns.end(), e.column) == table.columns.end()) {
        out.text = e.column + ": no such column in the results";
        return out;
    }
    std::vector<const std::vector<double>*> rows;
    for (const auto& row : table.rows) rows.push_back(&row);
    for (const auto& [key, value] : e.at) {
        if (std::find(table.columns.begin(), table.columns.end(), key) == table.columns.end()) {
            out.text = e.column + ": no column \"" + key + "\" to select the row by";
            return out;
        }
        const std::size_t k = table.column(key);
        double best = INFINITY;
        for (const auto* row : rows) best = std::min(best, std::abs((*row)[k] - value));
        std::erase_if(rows, [&, target = value](const auto* row) {
            return std::abs((*row)[k] - target) > best;
        });
    }
    if (rows.empty()) {
        out.text = e.column + ": the results have no rows (no equilibrium?)";
        return out;
    }
    const std::vector<double>& row = *rows.front();
    const double value = row[table.column(e.column)];
    out.passed = std::isfinite(value) && value >= e.min && value <= e.max;
    out.text = e.column + describeAt(e.at, table, row) + ": " + formatNumber(value) +
               (out.passed ? " in " : " NOT in ") + range;
    return out;
}

std::vector<Expectation> parseExpectations(const json& analysis, const std::string& where,
                                           std::vector<Issue>& issues) {
    std::vector<Expectation> out;
    if (!analysis.contains("expect")) return out;
    const json& list = analysis["expect"];
    if (!list.is_array()) {
        issues.push_back({where + ".expect", "must be a list"});
        return out;
    }
    for (std::size_t i = 0; i < list.size(); ++i) {
        const json& item = list[i];
        const std::string at = where + ".expect[" + std::to_string(i) + "]";
        Expectation e;
        if (!item.is_object() || !item.contains("column") || !item["column"].is_string()) {
            issues.push_back(
                {at, "needs \"column\" (a result column such as \"Fx_N\" or \"phi_deg\")"});
            continue;
        }
        e.column = item["column"];
        e.table = item.value("table", "");
        if (item.contains("min")) e.min = item["min"].get<double>();
        if (item.contains("max")) e.max = item["max"].get<double>();
        if (item.contains("value") && item.contains("tolerance")) {
            e.min = item["value"].get<double>() - item["tolerance"].get<double>();
            e.max = item["value"].get<double>() + item["tolerance"].get<double>();
        }
        if (!(e.min <= e.max) || (std::isinf(e.min) && std::isinf(e.max))) {
            issues.push_back({at, "needs \"min\" ≤ \"max\" (or \"value\" and \"tolerance\")"});
            continue;
        }
        if (item.contains("at")) {
            for (const auto& [key, value] : item["at"].items())
                e.at.emplace_back(key, value.get<double>());
        }
        out.push_back(e);
    }
    return out;
}

/// A rover run's summary as a one-row table for expectations: every number of the summary JSON
/// (nested objects flattened: mean_slip_FL …), plus yaw_deg, and the largest |y| and |yaw| over
/// the run (max_abs_y_m, max_abs_yaw_deg: a straight line stays on its line all along).
Table roverSummaryTable(const json& summary, const Table& series) {
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
    add("yaw_deg", summary.value("yaw_rad", 0.0) * 180.0 / M_PI);
    double max_y = 0.0, max_yaw = 0.0;
    if (!series.rows.empty()) {
        for (double y : series.values("y_m")) max_y = std::max(max_y, std::abs(y));
        for (double yaw : series.values("yaw_deg")) max_yaw = std::max(max_yaw, std::abs(yaw));
    }
    add("max_abs_y_m", max_y);
    add("max_abs_yaw_deg", max_yaw);
    return t;
}

/// The scenario of a `rover` analysis: "scenario" (a name of resources/scenarios or a file,
/// relative to the script), with the optional overrides duration_s, time_step_s and model.
scenario::Scenario roverScenario(const json& analysis, const io::PresetLocations& locations,
                                 const fs::path& base, const std::string& where) {
    if (!analysis.contains("scenario") || !analysis["scenario"].is_string()) {
        throw InputError(where + ".scenario: needs a scenario name (e.g. \"straight\") or file");
    }
    std::string name = analysis["scenario"];
    if (name.ends_with(".json") && fs::path(name).is_relative()) name = (base / name).string();
    auto loaded = scenario::resolveScenario(locations, name);
    if (!loaded) throw InputError(where + ".scenario: " + loaded.message());
    scenario::Scenario s = *loaded;
    std::vector<Issue> issues;
    auto number = [&](const char* key, double& value) {
        if (!analysis.contains(key)) return false;
        if (!analysis[key].is_number()) {
            issues.push_back({where + "." + key, "must be a number"});
            return false;
        }
        value = analysis[key].get<double>();
        return true;
    };
    double value = 0.0;
    if (number("duration_s", value) &&
        checkRange(issues, where + ".duration_s", value, {0.0, 86400.0, true, false}, "s")) {
        s.duration_s = value;
    }
    if (number("time_step_s", value) &&
        checkRange(issues, where + ".time_step_s", value, {1e-6, 0.05}, "s")) {
        s.time_step_s = value;
        s.output_interval_s = std::max(s.output_interval_s, s.time_step_s);
    }
    if (analysis.contains("model")) {
        const json& m = analysis["model"];
        if (m != "full" && m != "quadratic") {
            issues.push_back(
                {where + ".model", "= " + m.dump() + " is not one of full, quadratic"});
        } else {
            s.options.contact.model =
                m == "quadratic" ? contact::ContactModel::kQuadratic : contact::ContactModel::kFull;
        }
    }
    if (!issues.empty()) throw InputError(formatIssues(issues));
    return s;
}

/// The inputs of one analysis: the script's, with the analysis's own soil/wheel/conditions.
ui::AnalysisInputs inputsFor(const json& script, const json& analysis,
                             const io::PresetLocations& locations, const fs::path& base,
                             const std::string& where) {
    auto pick = [&](const char* key) {
        return analysis.contains(key) ? analysis[key] : script.value(key, json());
    };
    auto resolveName = [&](const json& spec, const char* fallback) {
        std::string name = spec.is_string() ? spec.get<std::string>() : fallback;
        if (name.ends_with(".json") && fs::path(name).is_relative()) name = (base / name).string();
        return name;
    };
    ui::AnalysisInputs in;
    const json soil_spec = pick("soil");
    auto soil = io::resolveSoil(locations, resolveName(soil_spec, "sandy-loam"));
    if (!soil) throw InputError(where + ".soil: " + soil.message());
    in.soil = *soil;
    const json set = pick("set");
    std::vector<Issue> issues;
    if (set.is_object()) {
        for (const auto& [key, value] : set.items()) {
            const soil::SoilField* field = soil::findSoilField(key);
            if (!field) {
                issues.push_back({where + ".set." + key, "unknown soil field"});
            } else if (!value.is_number()) {
                issues.push_back({where + ".set." + key, "must be a number"});
            } else if (checkRange(issues, where + ".set." + key, value.get<double>(), field->range,
                                  field->unit)) {
                soil::setUserValue(in.soil, *field, value.get<double>());
            }
        }
    }
    auto wheel = io::resolveWheel(locations, resolveName(pick("wheel"), "A"));
    if (!wheel) throw InputError(where + ".wheel: " + wheel.message());
    in.wheel = *wheel;
    json conditions = script.value("conditions", json::object());
    if (analysis.contains("conditions")) conditions.update(analysis["conditions"]);
    io::ObjectReader reader(conditions, issues, where, "conditions");
    analysis::readConditions(reader, in.conditions);
    reader.finish();
    if (!issues.empty()) throw InputError(formatIssues(issues));
    return in;
}

class Runner {
public:
    Runner(const json& script, const fs::path& base, const fs::path& out,
           const io::PresetLocations& locations, std::vector<std::string> formats,
           const std::atomic<bool>* cancel)
        : script_(script),
          base_(base),
          out_(out),
          locations_(locations),
          formats_(std::move(formats)),
          cancel_(cancel) {
        const json e = script.value("export", json::object());
        options_.width = e.value("width", 1200);
        options_.height = e.value("height", 800);
        options_.dpi = e.value("dpi", 96);
        if (formats_.empty()) formats_ = e.value("formats", std::vector<std::string>{"png"});
        plot_.resize(options_.width, options_.height);
        // A hidden widget gets no resize event: lay out at the export size now, so that figures
        // with equal axis scales (rover path, top view) compute their ratio for the exported image.
        plot_.setViewport(QRect(0, 0, options_.width, options_.height));
    }

    AnalysisRun run(const json& analysis, const std::string& where) {
        AnalysisRun r;
        r.type = analysis.value("type", "");
        r.name = analysis.value("name", r.type);
        std::vector<Issue> issues;
        const auto expectations = parseExpectations(analysis, where, issues);
        if (!issues.empty()) throw InputError(formatIssues(issues));
        if (r.type == "rover") {
            const auto start = std::chrono::steady_clock::now();
            runRover(r, analysis, expectations, where);
            r.seconds =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            return r;
        }
        const ui::AnalysisInputs in = inputsFor(script_, analysis, locations_, base_, where);
        const QString title =
            QString::fromStdString(analysis.value("title", in.soil.name + ", " + in.wheel.name)) +
            QString(", W = %1 N").arg(in.conditions.load_n);
        std::map<std::string, const Table*> tables;
        const auto start = std::chrono::steady_clock::now();
        if (r.type == "forces") {
            const auto result = ui::computeForceSweep(in, cancel_);
            std::vector<std::string> columns = analysis.value("plots", std::vector<std::string>{});
            for (const ui::SweepQuantity& q : ui::sweepQuantities()) {
                if (!columns.empty() &&
                    std::find(columns.begin(), columns.end(), q.column) == columns.end())
                    continue;
                ui::plotSweep(plot_, result.table, q, title);
                write(r, r.name + "-" + q.column);
            }
            writeData(r, r.name, result.table);
            r.notes = result.warnings;
            if (result.cancelled) r.notes.push_back("cancelled: the rows computed so far");
            tables[""] = &result.table;
            evaluate(r, expectations, tables);
        } else if (r.type == "soil-curves") {
            // The forces panel's curves of the soil alone: bulldozing vs sinkage (Fig. 2.15),
            // static sinkage vs load (Fig. 2.6).
            ui::SoilCurvesSettings s;
            s.points = analysis.value("points", s.points);
            s.max_load_factor = analysis.value("max_load_factor", s.max_load_factor);
            s.max_sinkage_fraction_of_radius =
                analysis.value("max_sinkage_fraction_of_radius", s.max_sinkage_fraction_of_radius);
            if (s.points < 2 || s.points > 10000)
                throw InputError(where + ".points: must be in [2, 10000]");
            if (!(s.max_load_factor > 0.0 && s.max_load_factor <= 100.0)) {
                throw InputError(where + ".max_load_factor: must be in (0, 100]");
            }
            if (!(s.max_sinkage_fraction_of_radius > 0.0 &&
                  s.max_sinkage_fraction_of_radius <= 1.0)) {
                throw InputError(where + ".max_sinkage_fraction_of_radius: must be in (0, 1]");
            }
            const ui::SoilCurves curves = ui::computeSoilCurves(in, s);
            ui::plotBulldozing(plot_, curves, title);
            write(r, r.name + "-bulldozing");
            ui::plotStaticSinkage(plot_, curves, title);
            write(r, r.name + "-static-sinkage");
            writeData(r, r.name + "-bulldozing", curves.bulldozing);
            writeData(r, r.name + "-static-sinkage", curves.static_sinkage);
            tables[""] = &curves.static_sinkage;
            tables["static_sinkage"] = &curves.static_sinkage;
            tables["bulldozing"] = &curves.bulldozing;
            evaluate(r, expectations, tables);
        } else if (r.type == "stresses") {
            ui::StressSettings s;
            s.slip = analysis.value("slip", s.slip);
            s.slip_angle_deg = analysis.value("slip_angle_deg", s.slip_angle_deg);
            const auto result = ui::computeStresses(in, s);
            if (!result.message.empty()) r.notes.push_back(result.message);
            ui::plotStresses(
                plot_, result, analysis.value("stress", "all"),
                title + QString(", s = %1, β = %2°").arg(s.slip).arg(s.slip_angle_deg));
            write(r, r.name);
            writeData(r, r.name, result.table);
            Table errors{{"stress_index", "rmse_kPa", "mae_kPa"}, {}};
            for (int i = 0; i < 4; ++i) {
                errors.rows.push_back(
                    {double(i), result.errors[i].rmse / 1e3, result.errors[i].mae / 1e3});
            }
            writeData(r, r.name + "-errors", errors);
            tables[""] = &result.table;
            tables["errors"] = &errors;
            evaluate(r, expectations, tables);
        } else if (r.type == "sensitivity") {
            ui::SensitivitySettings s;
            s.parameter = analysis.value("parameter", s.parameter);
            s.slip_angle_deg = analysis.value("slip_angle_deg", s.slip_angle_deg);
            s.tornado_slip = analysis.value("tornado_slip", s.tornado_slip);
            s.slip_count = analysis.value("slip_count", s.slip_count);
            const auto result = ui::computeSensitivity(in, s, cancel_);
            if (result.family.cancelled) r.notes.push_back("cancelled: the rows computed so far");
            const QString t = title + QString(", β = %1°").arg(s.slip_angle_deg);
            ui::plotSensitivityFamily(plot_, result, s.parameter, "Fx_N", t);
            write(r, r.name + "-Fx");
            ui::plotSensitivityFamily(plot_, result, s.parameter, "Fs_N", t);
            write(r, r.name + "-Fs");
            ui::plotTornado(plot_, result, s.tornado_slip, t);
            write(r, r.name + "-tornado");
            writeData(r, r.name, result.family.table);
            writeData(r, r.name + "-tornado", result.tornado);
            tables[""] = &result.family.table;
            tables["tornado"] = &result.tornado;
            evaluate(r, expectations, tables);
        } else if (r.type == "identification") {
            ui::IdentificationSettings s;
            s.csv = analysis.value("csv", "");
            if (!s.csv.empty() && fs::path(s.csv).is_relative()) s.csv = (base_ / s.csv).string();
            s.noise_relative = analysis.value("noise_percent", 2.0) / 100.0;
            s.seed = analysis.value("seed", 1);
            s.refine = analysis.value("refine", true);
            s.slip_count = analysis.value("slip_count", s.slip_count);
            s.loads_n = analysis.value("loads_N", std::vector<double>{});
            const auto result = ui::computeIdentification(in, s);
            if (!result.message.empty()) throw InputError(where + ": " + result.message);
            const char* channels[][2] = {{"Fx_N", "-Fx"}, {"Fz_N", "-Fz"}, {"My_Nm", "-My"}};
            for (const auto& c : channels) {
                ui::plotIdentification(plot_, result, c[0], title);
                write(r, r.name + c[1]);
            }
            writeData(r, r.name, result.curves);
            writeData(r, r.name + "-parameters", result.parameters);
            for (const auto& step : result.fit.steps) {
                r.notes.push_back(step.name + ": " + step.termination +
                                  ", Σr² = " + formatNumber(step.squared_residual_norm));
            }
            tables[""] = &result.parameters;
            tables["curves"] = &result.curves;
            evaluate(r, expectations, tables);
        } else {
            throw InputError(where + ".type: \"" + r.type +
                             "\" is not one of forces, soil-curves, stresses, sensitivity, "
                             "identification, rover");
        }
        r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        return r;
    }

private:
    /// A rover scenario (docs/dynamics.md): its figures (rover_figures.h), the time series, the
    /// summary; expectations on the summary (default table) or the time series ("timeseries").
    void runRover(AnalysisRun& r, const json& analysis,
                  const std::vector<Expectation>& expectations, const std::string& where) {
        const scenario::Scenario s = roverScenario(analysis, locations_, base_, where);
        std::vector<std::string> keys = analysis.value("plots", std::vector<std::string>{});
        for (const std::string& key : keys) {
            const bool known = key == "top-view" ||
                               std::any_of(ui::roverFigures().begin(), ui::roverFigures().end(),
                                           [&](const ui::RoverFigure& f) { return f.key == key; });
            if (!known) {
                std::string names = "top-view";
                for (const auto& f : ui::roverFigures()) names += ", " + f.key;
                throw InputError(where + ".plots: \"" + key + "\" is not one of " + names);
            }
        }
        if (keys.empty()) {
            for (const auto& f : ui::roverFigures()) keys.push_back(f.key);
            keys.push_back("top-view");
        }
        scenario::RunOptions options;
        options.cancel = cancel_;
        const scenario::RunResult result = scenario::runScenario(s, options);
        const QString title = analysis.contains("title")
                                  ? QString::fromStdString(analysis["title"].get<std::string>())
                                  : ui::roverTitle(s.name, result.status);
        for (const std::string& key : keys) {
            if (key == "top-view") {
                const std::size_t last =
                    result.series.rows.empty() ? 0 : result.series.rows.size() - 1;
                ui::plotRoverTopView(plot_, s, result.series, last, title);
            } else {
                ui::plotRoverFigure(plot_, result.series, key, title);
            }
            write(r, r.name + "-" + key);
        }
        writeData(r, r.name + "-timeseries", result.series);
        if (!result.streaming.columns.empty())
            writeData(r, r.name + "-streaming", result.streaming);
        const json summary = scenario::toJson(result, s);
        const fs::path summary_path = out_ / (r.name + "-summary.json");
        if (const auto error = io::writeFileAtomically(summary_path, summary.dump(2) + "\n"))
            throw std::runtime_error(*error);
        std::cout << "wrote " << summary_path.string() << '\n';
        r.data.push_back(summary_path.filename().string());
        if (result.status != scenario::RunResult::Status::kCompleted) {
            r.notes.push_back("run " + summary.value("status", std::string()) + ": " +
                              result.message);
        }
        if (summary.contains("warning")) r.notes.push_back(summary["warning"].get<std::string>());
        r.notes.push_back("final pose x = " + formatNumber(result.summary.x_m) +
                          " m, y = " + formatNumber(result.summary.y_m) +
                          " m, yaw = " + formatNumber(result.summary.yaw_rad * 180.0 / M_PI) +
                          " deg; motor energy " + formatNumber(result.summary.energy_j) + " J");
        const Table summary_table = roverSummaryTable(summary, result.series);
        std::map<std::string, const Table*> tables{{"", &summary_table},
                                                   {"timeseries", &result.series}};
        evaluate(r, expectations, tables);
        if (result.status == scenario::RunResult::Status::kDiverged) {
            r.outcomes.push_back({"the run diverged: " + result.message, false});
        }
    }

    void write(AnalysisRun& r, const std::string& stem) {
        for (const std::string& format : formats_) {
            const fs::path path = out_ / (stem + "." + format);
            QString error;
            if (!ui::exportPlot(plot_, QString::fromStdString(path.string()), options_, &error)) {
                throw std::runtime_error(error.toStdString());
            }
            std::cout << "wrote " << path.string() << '\n';
            r.images.push_back(path.filename().string());
        }
    }
    void writeData(AnalysisRun& r, const std::string& stem, const Table& table) {
        const fs::path path = out_ / (stem + ".csv");
        QString error;
        if (!ui::exportTable(table, QString::fromStdString(path.string()), &error))
            throw std::runtime_error(error.toStdString());
        std::cout << "wrote " << path.string() << '\n';
        r.data.push_back(path.filename().string());
    }
    static void evaluate(AnalysisRun& r, const std::vector<Expectation>& expectations,
                         const std::map<std::string, const Table*>& tables) {
        for (const Expectation& e : expectations) {
            const auto it = tables.find(e.table);
            if (it == tables.end()) {
                r.outcomes.push_back(
                    {"table \"" + e.table + "\" does not exist for " + r.type, false});
            } else {
                r.outcomes.push_back(check(e, *it->second));
            }
        }
    }

    const json& script_;
    fs::path base_, out_;
    const io::PresetLocations& locations_;
    std::vector<std::string> formats_;
    ui::ExportOptions options_;
    const std::atomic<bool>* cancel_;  // a sweep or rover run stops early and keeps its rows
    QCustomPlot plot_;
};

std::string report(const json& script, const std::string& script_path,
                   const std::vector<AnalysisRun>& runs, int failed, const std::string& cancelled) {
    std::ostringstream md;
    md << "# " << script.value("title", "TerraStudio run") << "\n\n";
    md << "Script: `" << script_path << "`  \n";
    if (!cancelled.empty()) md << "**" << cancelled << ".**  \n";
    md << (failed == 0 ? "**All expectations met.**"
                       : "**" + std::to_string(failed) + " expectation(s) or analyses FAILED.**")
       << "\n\n";
    if (failed > 0) {
        md << "## Failures\n\n";
        for (const auto& r : runs) {
            if (!r.error.empty()) md << "- `" << r.name << "`: " << r.error << "\n";
            for (const auto& o : r.outcomes) {
                if (!o.passed) md << "- `" << r.name << "`: " << o.text << "\n";
            }
        }
        md << "\n";
    }
    for (const auto& r : runs) {
        md << "## " << r.name << " (" << r.type << ")\n\n";
        if (!r.error.empty()) md << "**Error:** " << r.error << "\n\n";
        if (!r.outcomes.empty()) {
            md << "| Expectation | Result |\n|---|---|\n";
            for (const auto& o : r.outcomes)
                md << "| " << o.text << " | " << (o.passed ? "pass" : "**FAIL**") << " |\n";
            md << "\n";
        }
        for (const auto& image : r.images) {
            if (image.ends_with(".png") || image.ends_with(".svg"))
                md << "![" << image << "](" << image << ")\n\n";
        }
        if (!r.data.empty()) {
            md << "Data:";
            for (const auto& d : r.data) md << " [" << d << "](" << d << ")";
            md << "\n\n";
        }
        for (const auto& note : r.notes) md << "- " << note << "\n";
        if (!r.notes.empty()) md << "\n";
        md << "_" << formatNumber(std::round(r.seconds * 1000.0) / 1000.0) << " s_\n\n";
    }
    return md.str();
}

int run(const RunOptions& o, const io::PresetLocations& locations) {
    const Result<json> parsed = io::readJsonFile(o.script);
    if (!parsed) throw InputError(parsed.message());
    const json& script = parsed.value();
    if (!script.is_object() || !script.contains("analyses") || !script["analyses"].is_array()) {
        throw InputError(o.script + ": needs an \"analyses\" list");
    }
    for (const std::string& f : o.formats) {
        if (f != "png" && f != "svg" && f != "pdf")
            throw InputError("--format " + f + ": not one of png, svg, pdf");
    }
    std::error_code ec;
    fs::create_directories(o.out, ec);
    if (ec) throw std::runtime_error("cannot create " + o.out + ": " + ec.message());

    const HeadlessApplication application;  // QCustomPlot paints with a QPainter: it needs one

    const SignalCancellation cancellation;
    Runner runner(script, fs::path(o.script).parent_path(), o.out, locations, o.formats,
                  cancellation.flag());
    std::vector<AnalysisRun> runs;
    int failed = 0;
    const json& analyses = script["analyses"];
    for (std::size_t i = 0; i < analyses.size() && !cancellation.requested(); ++i) {
        const std::string where = o.script + ": analyses[" + std::to_string(i) + "]";
        AnalysisRun r;
        try {
            r = runner.run(analyses[i], where);
        } catch (const InputError&) {
            throw;  // a broken script is exit 2, not a failed check
        } catch (const std::exception& e) {
            r.name = analyses[i].value("name", "analysis " + std::to_string(i));
            r.type = analyses[i].value("type", "");
            r.error = e.what();
            ++failed;
        }
        for (const auto& outcome : r.outcomes) {
            std::cout << (outcome.passed ? "pass: " : "FAIL: ") << r.name << ": " << outcome.text
                      << '\n';
            if (!outcome.passed) ++failed;
        }
        runs.push_back(std::move(r));
    }
    // Cancelled: what was computed is written and reported; the analysis running at the signal
    // keeps its rows so far (its notes say so), the ones after it are not run.
    std::string cancelled;
    if (cancellation.requested()) {
        cancelled = "Cancelled by " + cancellation.signalName() + ": " +
                    std::to_string(runs.size()) + " of " + std::to_string(analyses.size()) +
                    " analyses started, the last one possibly incomplete";
    }
    const fs::path out(o.out);
    if (const auto error = io::writeFileAtomically(
            out / "report.md", report(script, o.script, runs, failed, cancelled))) {
        throw std::runtime_error(*error);
    }
    std::cout << "wrote " << (out / "report.md").string() << '\n';
    json manifest{{"tool", std::string("terrastudio ") + build_info::kVersion},
                  {"script", o.script},
                  {"inputs", script},
                  {"failed", failed}};
    if (!cancelled.empty()) manifest.update({{"cancelled", true}, {"note", cancelled}});
    for (const auto& r : runs) {
        json outcomes = json::array();
        for (const auto& oc : r.outcomes)
            outcomes.push_back({{"text", oc.text}, {"passed", oc.passed}});
        manifest["analyses"].push_back({{"name", r.name},
                                        {"type", r.type},
                                        {"images", r.images},
                                        {"data", r.data},
                                        {"error", r.error},
                                        {"expectations", outcomes},
                                        {"notes", r.notes}});
    }
    if (const auto error =
            io::writeFileAtomically(out / "manifest.json", manifest.dump(2) + "\n")) {
        throw std::runtime_error(*error);
    }
    std::cout << "wrote " << (out / "manifest.json").string() << '\n';
    if (!cancelled.empty()) exitCancelled(cancellation, cancelled);
    if (failed > 0) {
        std::cerr << failed << " expectation(s) or analyses failed (see "
                  << (out / "report.md").string() << ")\n";
        return kFailure;
    }
    return kSuccess;
}

}  // namespace

void addRunCommand(CLI::App& app, const io::PresetLocations& locations) {
    auto options = std::make_shared<RunOptions>();
    CLI::App* cmd = app.add_subcommand("run",
                                       "Run a script of analyses headlessly: plots, data, "
                                       "report.md; exit 1 when an expectation fails");
    cmd->add_option("script", options->script, "Script (JSON), see docs/user-guide.md")->required();
    cmd->add_option("--out", options->out, "Output directory")->capture_default_str();
    cmd->add_option("--format", options->formats,
                    "Image formats (png, svg, pdf), overriding the script")
        ->delimiter(',');
    cmd->callback([options, &locations] {
        const int code = run(*options, locations);
        if (code != kSuccess) throw CLI::RuntimeError(code);
    });
}

}  // namespace terra::app
