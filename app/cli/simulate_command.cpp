// terrastudio simulate: run a rover scenario (docs/dynamics.md), write the time series and the
// summary, with a progress bar on a terminal; Ctrl-C, SIGTERM and SIGHUP stop it and it still
// writes.
#include <cmath>
#include <iostream>

#include "app/cli/cli_support.h"
#include "app/cli/commands.h"
#include "app/cli/progress.h"
#include "app/cli/signals.h"
#include "core/analysis/registry.h"
#include "core/analysis/rover.h"
#include "core/common/range.h"
#include "core/io/atomic_file.h"
#include "core/io/json_reader.h"
#include "core/scenario/runner.h"
#include "core/scenario/scenario_json.h"
#include "core/scenario/traction_control.h"

namespace terra::app {
namespace {

struct SimulateOptions {
    std::string scenario;
    std::string out;
    bool json = false;
    std::optional<double> duration_s;
    std::optional<double> time_step_s;
    std::optional<std::string> model;
    std::optional<std::string> controller;
    std::optional<double> slip;
    std::optional<std::string> traction_limited;
    std::optional<std::string> robust;
    std::optional<double> quantile;
    std::optional<std::string> posterior_method;
    std::optional<std::string> identifier;
    bool compare = false;
};

// The flags as the rover's settings object (the keys of RoverSettings::visitFields), read by its
// own reader: the ranges, the names and their messages are the reader's, named here by the
// flags. The scenario is resolved by the command (its message as before); what the overrides do
// to it (a step the robot cannot take) is checked when it runs, named by the scenario.
nlohmann::json settingsObject(const SimulateOptions& o) {
    nlohmann::json s{{"scenario", o.scenario}};
    if (o.duration_s) s["duration_s"] = *o.duration_s;
    if (o.time_step_s) s["time_step_s"] = *o.time_step_s;
    if (o.model) s["model"] = *o.model;
    if (o.controller) s["controller"] = *o.controller;
    if (o.slip) s["slip"] = *o.slip;
    if (o.traction_limited) s["traction_limited"] = *o.traction_limited == "on";
    if (o.robust) s["robust"] = *o.robust;
    if (o.quantile) s["quantile"] = *o.quantile;
    if (o.posterior_method) s["posterior_method"] = *o.posterior_method;
    if (o.identifier) s["identifier"] = *o.identifier;
    return s;
}

// The rover's settings of the flags, read by its reader (exit 2 names the flag, the value and
// what is allowed, in the reader's words), without the presets: the scenario is not resolved.
analysis::RoverSettings simulateSettings(const SimulateOptions& o) {
    const nlohmann::json object = settingsObject(o);
    std::vector<Issue> issues;
    io::ObjectReader reader(object, issues);
    analysis::RoverSettings settings;
    analysis::readRoverSettings(reader, {}, settings);
    reader.finish();
    if (o.compare && o.controller)
        issues.push_back({"--compare", "runs every controller: drop --controller"});
    if (!issues.empty()) {
        nameFlags(issues, {{"scenario", "--scenario"},
                           {"duration_s", "--duration"},
                           {"time_step_s", "--step"},
                           {"model", "--model"},
                           {"controller", "--controller"},
                           {"slip", "--slip"},
                           {"traction_limited", "--traction-limited"},
                           {"robust", "--robust"},
                           {"quantile", "--quantile"},
                           {"posterior_method", "--posterior-method"},
                           {"identifier", "--identifier"}});
        throw InputError(formatIssues(issues));
    }
    return settings;
}

void printComparison(const nlohmann::json& table, const std::string& name) {
    std::cout << name << ": controllers compared\n"
              << "controller       distance_m  energy_J/m  energy/work  efficiency  drawbar_N  "
                 "vs_oracle  slip_rms  settling_s  band_s  rut_mm\n";
    auto cell = [](const nlohmann::json& v, int decimals, double scale = 1.0) {
        return v.is_number() ? fixed(v.get<double>() * scale, decimals) : std::string("-");
    };
    for (const nlohmann::json& row : table) {
        std::string line = row["controller"].get<std::string>();
        line.resize(15, ' ');
        auto column = [&line](const std::string& text, std::size_t width) {
            line += std::string(width > text.size() ? width - text.size() : 1, ' ') + text;
        };
        column(cell(row["distance_m"], 3), 12);
        column(cell(row["energy_per_m_J"], 2), 12);
        column(cell(row["energy_per_drawbar_work"], 2), 13);
        column(cell(row["mean_efficiency"], 4), 12);
        column(cell(row["mean_drawbar_N"], 3), 11);
        column(cell(row["drawbar_vs_oracle"], 3), 11);
        column(cell(row["slip_tracking_rms"], 4), 10);
        // After a border a controller with a set-point to reach (optimal, oracle) that did not
        // reach it "never" settled; "-" where settling is not defined (no border, no plan, no
        // robust band).
        const std::string controller = row["controller"].get<std::string>();
        const bool plans = controller == "optimal" || controller == "oracle";
        auto settling = [&](const char* key, bool defined) {
            return row[key].is_number() ? cell(row[key], 2)
                   : defined            ? std::string("never")
                                        : std::string("-");
        };
        column(settling("settling_time_s", plans && row["border_time_s"].is_number()), 12);
        column(settling("settling_band_time_s", plans && row["border_time_s"].is_number() &&
                                                    row["settling_band"].is_number()),
               8);
        column(cell(row["rut_depth_m"], 2, 1000.0), 8);
        std::cout << line << '\n';
    }
    std::cout << "energy/work: motor energy per joule of drawbar work, lower is better "
                 "(energy_J/m favours the robot that pulls least)\n"
              << "vs_oracle: drawbar pull over the oracle's; settling_s: from the first border "
                 "until the set-point stays within "
              << formatNumber(scenario::kSettleTolerance) << " of the oracle's\n"
              << "(band_s: within its posterior's band); never: not by the end; -: not "
                 "defined\n";
}

void printHuman(const scenario::RunResult& r, const scenario::Scenario& s, const std::string& out) {
    printSummary(std::cout, analysis::roverSummary(r, s));  // the core's words and digits
    std::cout << "wrote " << out << "/timeseries.csv, " << out << "/summary.json"
              << (r.streaming.columns.empty() ? "" : ", " + out + "/streaming.csv");
    if (r.maps) {
        for (const std::string& name : scenario::mapFileNames())
            std::cout << ", " << out << "/" << name;
    }
    std::cout << '\n';
}

// --compare: the scenario under each controller, one after the other.
void compare(const analysis::RoverSettings& settings, const SimulateOptions& o) {
    const SignalCancellation cancellation;
    std::string name;
    analysis::Control control;
    control.cancel = cancellation.flag();
    TerminalProgress progress("simulate --compare");
    control.progress = progress.callback();
    std::vector<analysis::ControllerRun> rows;
    try {
        rows = analysis::compareControllers(
            settings, control, [&](const std::string& type, analysis::RoverResult& rover) {
                const std::filesystem::path dir = std::filesystem::path(o.out) / type;
                if (const auto error = scenario::writeResults(rover.run, rover.scenario, dir))
                    throw std::runtime_error(*error);
                name = rover.scenario.name;
                if (rover.run.status == scenario::RunResult::Status::kCancelled) {
                    progress.finish();
                    exitCancelled(cancellation, rover.run.message + " by " +
                                                    cancellation.signalName() +
                                                    "; partial results written to " + dir.string());
                }
            });
    } catch (const std::invalid_argument& e) {
        throw InputError(std::string(o.scenario) + ": " + e.what());
    }
    progress.finish();
    const nlohmann::json table = analysis::controllerComparison(rows);
    if (const auto error = io::writeFileAtomically(std::filesystem::path(o.out) / "comparison.json",
                                                   table.dump(2) + "\n")) {
        throw std::runtime_error(*error);
    }
    if (o.json) {
        std::cout << table.dump(2) << '\n';
    } else {
        printComparison(table, name);
        std::cout << "wrote " << o.out << "/comparison.json and " << o.out
                  << "/<controller>/{timeseries.csv, summary.json}\n";
    }
    for (const analysis::ControllerRun& row : rows) {
        if (row.run.status == scenario::RunResult::Status::kDiverged) {
            std::cerr << "error: " << row.controller << ": " << row.run.message << '\n';
            throw CLI::RuntimeError(kFailure);
        }
    }
}

}  // namespace

void addSimulateCommand(CLI::App& app, const io::PresetLocations& locations) {
    auto options = std::make_shared<SimulateOptions>();
    CLI::App* cmd = app.add_subcommand(
        "simulate",
        "Drive the 4WD/4WS robot through a scenario on deformable soil (docs/dynamics.md)");
    cmd->add_option("--scenario", options->scenario,
                    "Scenario file or name in resources/scenarios (straight, pulse-steering, ...)")
        ->required();
    cmd->add_option("--out", options->out, "Output directory (timeseries.csv, summary.json)")
        ->required();
    cmd->add_flag("--json", options->json, "Print the summary as JSON");
    cmd->add_option("--duration", options->duration_s, "Override the scenario's duration [s]");
    cmd->add_option("--step", options->time_step_s, "Override the scenario's time step [s]");
    cmd->add_option("--model", options->model, "Override the contact model: full or quadratic");
    cmd->add_option("--controller", options->controller,
                    "Override the controller: constant-speed, fixed-slip, optimal or oracle "
                    "(docs/traction.md)");
    cmd->add_option("--slip", options->slip, "Override the controller's fixed slip set-point");
    cmd->add_option("--traction-limited", options->traction_limited,
                    "Override the slip controllers' traction-limited mode: on or off "
                    "(docs/traction.md)")
        ->check(CLI::IsMember({"on", "off"}));
    cmd->add_option("--robust", options->robust,
                    "Override the optimal controller's set-point: none (s* of the soil estimate), "
                    "expected or quantile (over its posterior; docs/traction.md)");
    cmd->add_option("--quantile", options->quantile,
                    "Override the robust set-point's quantile of the objective (0.01 to 0.99)");
    cmd->add_option("--posterior-method", options->posterior_method,
                    "Override how a robust set-point carries the posterior: sigma-points or "
                    "samples");
    cmd->add_option("--identifier", options->identifier,
                    "Override the optimal controller's soil estimator: decoupled or full");
    cmd->add_flag("--compare", options->compare,
                  "Run every controller on the scenario; write OUT/<controller>/ and "
                  "OUT/comparison.json, print the comparison table");
    cmd->callback([options, &locations] {
        const SimulateOptions& o = *options;
        std::vector<std::string> outputs{"timeseries.csv", "summary.json", "streaming.csv"};
        for (const std::string& name : scenario::mapFileNames()) outputs.push_back(name);
        for (const std::string& file : outputs) {
            refuseInputAsOutput("--out", std::filesystem::path(o.out) / file,
                                {{"--scenario", o.scenario}});
        }
        // The rover service (core/analysis/rover.h), as the studio's rover panel and scripts:
        // the flags are its settings object, read by its own reader.
        analysis::RoverSettings settings = simulateSettings(o);
        Result<scenario::Scenario> loaded = scenario::resolveScenario(locations, o.scenario);
        if (!loaded) throw InputError(loaded.message());
        settings.loaded = loaded.value();

        if (o.compare) {
            compare(settings, o);
            return;
        }
        const SignalCancellation cancellation;
        analysis::Control run;
        run.cancel = cancellation.flag();
        TerminalProgress progress("simulate");
        run.progress = progress.callback();
        scenario::RunResult result;
        scenario::Scenario s;
        try {
            analysis::RoverResult rover = analysis::runRover(settings, run);
            result = std::move(rover.run);
            s = std::move(rover.scenario);
        } catch (const std::invalid_argument& e) {
            throw InputError(std::string(o.scenario) + ": " + e.what());
        }
        progress.finish();

        if (const auto error = scenario::writeResults(result, s, o.out))
            throw std::runtime_error(*error);
        const nlohmann::json summary = scenario::toJson(result, s);
        // The warning once: the human summary has it as a row; with --json stdout is for
        // programs, so a person reading the terminal gets it on stderr.
        if (o.json && summary.contains("warning")) {
            std::cerr << "warning: " << summary["warning"].get<std::string>() << '\n';
        }
        if (o.json) {
            std::cout << summary.dump(2) << '\n';
        } else {
            printHuman(result, s, o.out);
        }
        if (result.status == scenario::RunResult::Status::kCancelled) {
            exitCancelled(cancellation, result.message + " by " + cancellation.signalName() +
                                            "; partial results written to " + o.out);
        }
        if (result.status == scenario::RunResult::Status::kDiverged) {
            std::cerr << "error: " << result.message << "; partial results written to " << o.out
                      << '\n';
            throw CLI::RuntimeError(kFailure);
        }
    });
}

}  // namespace terra::app
