// `terrastudio validate`: the model against a measured single-wheel test
// (core/analysis/validation.h, docs/validation.md), optionally calibrated to it first.
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "app/cli/cli_support.h"
#include "app/cli/commands.h"
#include "app/cli/progress.h"
#include "app/cli/signals.h"
#include "core/analysis/registry.h"
#include "core/analysis/validation.h"
#include "core/common/range.h"
#include "core/io/atomic_file.h"
#include "core/io/csv.h"

namespace terra::app {
namespace {

struct ValidateOptions {
    std::string experiments;
    std::string soil, wheel;  // empty: the test's (its metadata)
    std::vector<std::string> set;
    std::string model = "full";
    bool json = false;
    bool calibrate = false;
    bool fit_n1 = false;
    bool fit_slip_sinkage = false;
    std::string fit_slips;
    std::vector<std::string> noise;  // CHANNEL=SIGMA
    std::string save_soil;
};

// The flags as the validation's settings object (the keys of ValidationSettings::visitFields),
// read by its own reader: the ranges, the slips of the test and their messages are the reader's,
// named here by the flags. Left to the flags: the form CHANNEL=SIGMA of --noise and a channel
// given twice.
nlohmann::json settingsObject(const ValidateOptions& o) {
    nlohmann::json s{{"experiments", o.experiments},
                     {"calibrate", o.calibrate},
                     {"fit_n1", o.fit_n1},
                     {"fit_slip_sinkage", o.fit_slip_sinkage}};
    if (!o.fit_slips.empty()) s["fit_slips"] = parseValues(o.fit_slips, "--fit-slips");
    refuseRepeatedKeys("--noise", o.noise);
    for (const std::string& item : o.noise) {
        const auto equals = item.find('=');
        double sigma = 0.0;
        if (equals == std::string::npos || !parseStrictNumber(item.substr(equals + 1), sigma)) {
            throw InputError("--noise " + io::quoteCell(item) +
                             ": expected Fx_N=SIGMA, My_Nm=SIGMA or sinkage_m=SIGMA (N, N·m, m)");
        }
        s["noise"][item.substr(0, equals)] = sigma;
    }
    return s;
}

// The validation's settings of the flags, read by its reader (exit 2 names the flag, the value
// and what is allowed, in the reader's words). The test is the one the command has read already.
analysis::ValidationSettings validateSettings(const ValidateOptions& o,
                                              const io::Experiment& experiment) {
    const nlohmann::json object = settingsObject(o);
    std::vector<Issue> issues;
    io::ObjectReader reader(object, issues);
    analysis::ValidationSettings settings;
    settings.data = experiment;
    analysis::readValidationSettings(reader, {}, settings);
    reader.finish();
    if (!issues.empty()) {
        nameFlags(issues, {{"experiments", "--experiments"},
                           {"calibrate", "--calibrate"},
                           {"fit_slips", "--fit-slips"},
                           {"noise.", "--noise "},
                           {"noise", "--noise"},
                           {"fit_n1", "--fit-n1"},
                           {"fit_slip_sinkage", "--fit-slip-sinkage"}});
        throw InputError(formatIssues(issues));
    }
    return settings;
}

std::string cellOf(const std::optional<double>& v, double scale, int decimals) {
    return v ? fixed(*v * scale, decimals) : std::string("-");
}

// Units for people: forces in N, torque in N·m, sinkage in mm.
double displayScale(std::size_t c) { return c == io::kExpSinkage ? 1e3 : 1.0; }
std::string displayName(std::size_t c) {
    return c == io::kExpSinkage ? "sinkage_mm" : io::experimentChannels()[c].name;
}

void printRun(std::ostream& out, const analysis::ValidationRun& run, bool with_fit) {
    std::array<bool, io::kExperimentChannelCount> measured{};
    for (const auto& p : run.points) {
        for (std::size_t c = 0; c < measured.size(); ++c)
            measured[c] = measured[c] || p.point.measured[c].has_value();
    }
    char buffer[64];
    out << "  load_N    slip  beta_deg";
    for (std::size_t c = 0; c < measured.size(); ++c) {
        if (!measured[c]) continue;
        std::snprintf(buffer, sizeof buffer, "  %21s", (displayName(c) + " meas/pred").c_str());
        out << buffer;
    }
    out << (with_fit ? "  fit\n" : "\n");
    for (const auto& p : run.points) {
        std::snprintf(buffer, sizeof buffer, "  %6s  %6s  %8s",
                      formatNumber(p.point.load_n).c_str(), formatNumber(p.point.slip).c_str(),
                      formatNumber(p.point.slip_angle_deg).c_str());
        out << buffer;
        for (std::size_t c = 0; c < measured.size(); ++c) {
            if (!measured[c]) continue;
            const std::string predicted =
                p.point.measured[c]
                    ? (p.predicted ? fixed(p.values[c] * displayScale(c), 2) : std::string("-"))
                    : std::string();
            std::snprintf(buffer, sizeof buffer, "  %10s %10s",
                          cellOf(p.point.measured[c], displayScale(c), 2).c_str(),
                          predicted.c_str());
            out << buffer;
        }
        if (with_fit) out << (p.in_fit ? "  yes" : "  held out");
        if (!p.predicted) out << "  (no prediction: " << p.failure << ")";
        out << '\n';
    }
}

// The summary (analysis::validationSummary), the points of each run printed before its metrics.
void printHuman(const analysis::ValidationResult& r) {
    std::ostringstream out;
    for (const analysis::SummaryRow& row : analysis::validationSummary(r)) {
        if (row.emphasis == analysis::SummaryRow::Emphasis::kHeading) {
            if (row.json == "/metrics") printRun(out, r.before, false);
            if (row.json == "/calibration/metrics") printRun(out, *r.calibration->after, true);
        }
        printSummaryRow(out, row);
    }
    std::cout << out.str();
}

}  // namespace

void addValidateCommand(CLI::App& app, const io::PresetLocations& locations) {
    auto o = std::make_shared<ValidateOptions>();
    CLI::App* cmd = app.add_subcommand(
        "validate",
        "The model against a measured single-wheel test: per point and channel, RMSE, MAE and "
        "largest relative error; --calibrate fits the soil to the test first");
    cmd->add_option("--experiments", o->experiments,
                    "The test: its CSV (load_N, slip, slip_angle_deg, Fx_N, My_Nm, sinkage_m, "
                    "Fy_N, Fz_N) or its sidecar JSON")
        ->required();
    cmd->add_option("--soil", o->soil, "Soil preset or JSON file (default: the test's preset)");
    cmd->add_option("--wheel", o->wheel, "Wheel preset or JSON file (default: the test's wheel)");
    cmd->add_option("--set", o->set, "Override a soil field in file units, e.g. --set phi_deg=30");
    cmd->add_option("--model", o->model, "full (numerical integration) or quadratic (closed form)")
        ->check(CLI::IsMember({"full", "quadratic"}))
        ->capture_default_str();
    cmd->add_flag("--json", o->json, "JSON output");
    cmd->add_flag("--calibrate", o->calibrate,
                  "Fit the soil to the test (identification from the load, the soil as prior)");
    cmd->add_option("--fit-slips", o->fit_slips,
                    "With --calibrate: fit on the points at these slips only (list a,b,c); the "
                    "others are held out");
    cmd->add_option("--noise", o->noise,
                    "With --calibrate: noise std per channel weighting the fit, e.g. "
                    "Fx_N=1,sinkage_m=0.001 (default: estimated)")
        ->delimiter(',');
    cmd->add_flag("--fit-n1", o->fit_n1,
                  "With --calibrate: fit n1 of the slip-sinkage exponent N = n + n1 s too "
                  "(docs/model.md, Slip-sinkage)");
    cmd->add_flag("--fit-slip-sinkage", o->fit_slip_sinkage,
                  "With --calibrate: fit S of Lyasko's slip sinkage h = h0 (1 + S s) too "
                  "(docs/model.md, Slip sinkage); not with --fit-n1");
    cmd->add_option("--save-soil", o->save_soil,
                    "With --calibrate: write the calibrated soil as a soil file");
    cmd->callback([o, &locations] {
        if (!o->calibrate && (!o->fit_slips.empty() || !o->noise.empty() || !o->save_soil.empty() ||
                              o->fit_n1 || o->fit_slip_sinkage))
            throw InputError(
                "--fit-slips, --noise, --fit-n1, --fit-slip-sinkage and --save-soil belong to "
                "--calibrate");
        Result<io::Experiment> read = io::readExperiment(o->experiments);
        if (!read) throw InputError(read.message());
        const io::Experiment& experiment = read.value();
        // The calibrated soil must not replace the test it was fitted to (or its sidecar, or
        // the soil or wheel file it started from).
        refuseInputAsOutput("--save-soil", o->save_soil,
                            {{"--experiments", o->experiments},
                             {"--experiments (its data)", experiment.source},
                             {"--experiments (its sidecar)",
                              std::filesystem::path(experiment.source).replace_extension(".json")},
                             {"--soil", o->soil},
                             {"--wheel", o->wheel}});
        ModelOptions names;
        names.set = o->set;
        names.model = o->model;
        names.soil = o->soil;
        if (names.soil.empty()) {
            if (!experiment.metadata || experiment.metadata->soil_preset.empty())
                throw InputError("--soil: the test names no soil preset; give --soil");
            names.soil = experiment.metadata->soil_preset;
        }
        analysis::Inputs inputs;
        inputs.soil = names.soilParameters(locations);
        if (!o->wheel.empty()) {
            names.wheel = o->wheel;
            inputs.wheel = names.wheelParameters(locations);
        } else if (experiment.metadata && experiment.metadata->wheel) {
            inputs.wheel = *experiment.metadata->wheel;
        } else {
            throw InputError("--wheel: the test has no wheel in its metadata; give --wheel");
        }
        inputs.conditions.quadratic = o->model == "quadratic";
        const analysis::ValidationSettings settings = validateSettings(*o, experiment);
        analysis::ValidationResult result;
        {
            const SignalCancellation cancellation;
            TerminalProgress progress("validate");
            try {
                result = analysis::computeValidation(inputs, settings,
                                                     {cancellation.flag(), progress.callback()});
            } catch (const std::invalid_argument& e) {
                throw InputError(e.what());
            }
            progress.finish();
            if (result.status == analysis::Outcome::Status::kInvalidInput)
                throw InputError(formatIssues(result.issues));
            if (result.status == analysis::Outcome::Status::kCancelled) {
                exitCancelled(cancellation,
                              "validate cancelled by " + cancellation.signalName() +
                                  ": nothing written (a calibration stopped halfway has no "
                                  "result; docs/cli.md, \"Stopping a long command\")");
            }
        }
        if (o->json) {
            std::cout << analysis::toJson(result).dump(2) << '\n';
        } else {
            printHuman(result);
        }
        std::cout.flush();
        // No calibrated soil, nothing predicted: exit 1 with the reason, and no soil saved.
        if (result.status == analysis::Outcome::Status::kFailed)
            throw std::runtime_error(result.message);
        if (!o->save_soil.empty()) {
            if (const auto error = io::writeFileAtomically(
                    o->save_soil, io::toJson(result.calibration->soil).dump(2) + "\n"))
                throw std::runtime_error(o->save_soil + ": " + *error);
            std::cerr << "wrote " << o->save_soil << '\n';
        }
    });
}

}  // namespace terra::app
