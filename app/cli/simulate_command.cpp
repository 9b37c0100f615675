// terrastudio simulate: run a rover scenario (docs/dynamics.md), write the time series and the
// summary, with a progress bar on a terminal; Ctrl-C, SIGTERM and SIGHUP stop it and it still
// writes.
#include <iostream>

#include "app/cli/cli_support.h"
#include "app/cli/commands.h"
#include "app/cli/progress.h"
#include "app/cli/signals.h"
#include "core/analysis/rover.h"
#include "core/common/range.h"
#include "core/scenario/runner.h"
#include "core/scenario/scenario_json.h"

namespace terra::app {
namespace {

struct SimulateOptions {
    std::string scenario;
    std::string out;
    bool json = false;
    std::optional<double> duration_s;
    std::optional<double> time_step_s;
    std::optional<std::string> model;
};

void printHuman(const scenario::RunResult& r, const scenario::Scenario& s, const std::string& out) {
    const scenario::Summary& m = r.summary;
    std::cout << s.name << ": " << fixed(m.duration_s, 3) << " s simulated in " << m.steps
              << " steps of " << formatNumber(s.time_step_s) << " s\n"
              << "  final pose   x = " << fixed(m.x_m, 4) << " m, y = " << fixed(m.y_m, 4)
              << " m, yaw = " << fixed(m.yaw_rad * 180.0 / M_PI, 3) << " deg\n"
              << "  distance     " << fixed(m.distance_m, 4) << " m\n"
              << "  mean slip   ";
    for (int i = 0; i < dynamics::kWheelCount; ++i) {
        std::cout << " " << dynamics::kCornerNames[i] << " " << fixed(m.mean_slip[i], 4);
    }
    std::cout << "\n  motor energy " << fixed(m.energy_j, 3) << " J (into the soil "
              << fixed(m.dissipated_j, 3) << " J)\n"
              << "wrote " << out << "/timeseries.csv, " << out << "/summary.json"
              << (r.streaming.columns.empty() ? "" : ", " + out + "/streaming.csv") << '\n';
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
    cmd->add_option("--model", options->model, "Override the contact model: full or quadratic")
        ->check(CLI::IsMember({"full", "quadratic"}));
    cmd->callback([options, &locations] {
        const SimulateOptions& o = *options;
        for (const char* file : {"timeseries.csv", "summary.json", "streaming.csv"}) {
            refuseInputAsOutput("--out", std::filesystem::path(o.out) / file,
                                {{"--scenario", o.scenario}});
        }
        // The rover service (core/analysis/rover.h), as the studio's rover panel and scripts.
        analysis::RoverSettings settings;
        settings.scenario = o.scenario;
        Result<scenario::Scenario> loaded = scenario::resolveScenario(locations, o.scenario);
        if (!loaded) throw InputError(loaded.message());
        settings.loaded = loaded.value();
        settings.duration_s = o.duration_s;
        settings.time_step_s = o.time_step_s;
        if (o.model) {
            settings.model = *o.model == "quadratic" ? contact::ContactModel::kQuadratic
                                                     : contact::ContactModel::kFull;
        }
        std::vector<Issue> issues;
        if (o.duration_s)
            checkRange(issues, "--duration", *o.duration_s, scenario::kDurationRange, "s");
        if (o.time_step_s)
            checkRange(issues, "--step", *o.time_step_s, scenario::kTimeStepRange, "s");
        if (!issues.empty()) throw InputError(formatIssues(issues));

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
        if (summary.contains("warning")) {
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
