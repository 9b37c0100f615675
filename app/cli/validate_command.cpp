// `terrastudio validate`: the model against a measured single-wheel test
// (core/analysis/validation.h, docs/validation.md), optionally calibrated to it first.
#include <iostream>
#include <map>
#include <sstream>

#include "app/cli/cli_support.h"
#include "app/cli/commands.h"
#include "app/cli/progress.h"
#include "app/cli/signals.h"
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

void parseNoise(const std::vector<std::string>& items, analysis::ValidationSettings& s) {
    std::map<std::string, std::size_t> channels{
        {"Fx_N", io::kExpFx}, {"My_Nm", io::kExpMy}, {"sinkage_m", io::kExpSinkage}};
    refuseRepeatedKeys("--noise", items);
    std::vector<Issue> issues;
    for (const std::string& item : items) {
        const auto equals = item.find('=');
        const auto it = channels.find(item.substr(0, equals));
        double sigma = 0.0;
        if (equals == std::string::npos || it == channels.end() ||
            !parseStrictNumber(item.substr(equals + 1), sigma)) {
            issues.push_back({"--noise " + io::quoteCell(item),
                              "expected Fx_N=SIGMA, My_Nm=SIGMA or sinkage_m=SIGMA (N, N·m, m)"});
            continue;
        }
        const io::ExperimentColumn& column = io::experimentChannels()[it->second];
        if (checkRange(issues, "--noise " + it->first, sigma, {0.0, 1e6, true, false}, column.unit))
            s.noise[it->second] = sigma;
    }
    if (!issues.empty()) throw InputError(formatIssues(issues));
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
            const std::optional<double> predicted =
                p.predicted ? std::optional(p.values[c]) : std::nullopt;
            std::snprintf(buffer, sizeof buffer, "  %10s %10s",
                          cellOf(p.point.measured[c], displayScale(c), 2).c_str(),
                          p.point.measured[c] ? cellOf(predicted, displayScale(c), 2).c_str() : "");
            out << buffer;
        }
        if (with_fit) out << (p.in_fit ? "  yes" : "  held out");
        if (!p.predicted) out << "  (no prediction: " << p.failure << ")";
        out << '\n';
    }
}

void printMetrics(std::ostream& out, const analysis::ValidationMetrics& metrics,
                  const std::string& title) {
    out << title << '\n';
    for (std::size_t c = 0; c < metrics.size(); ++c) {
        if (!metrics[c]) continue;
        const analysis::ChannelMetrics& m = *metrics[c];
        const double k = displayScale(c);
        const std::string unit = c == io::kExpSinkage ? "mm" : io::experimentChannels()[c].unit;
        out << "  " << displayName(c) << ": RMSE " << fixed(m.rmse * k, 3) << ' ' << unit
            << ", MAE " << fixed(m.mae * k, 3) << ' ' << unit << ", max relative error "
            << (std::isnan(m.max_rel_error) ? std::string("-")
                                            : fixed(100.0 * m.max_rel_error, 1) + " %")
            << " (" << m.count << " points)\n";
    }
}

void printHuman(const analysis::ValidationResult& r, const analysis::Inputs& in) {
    std::ostringstream out;
    out << "validation of " << in.soil.name << " on " << in.wheel.name << " against " << r.source
        << "\n";
    printRun(out, r.before, false);
    printMetrics(out, r.before.metrics, "metrics (given soil):");
    if (r.calibration) {
        const analysis::Calibration& c = *r.calibration;
        out << "\ncalibration (identification from the load, " << in.soil.name
            << " as prior; channels";
        for (const std::string& ch : c.channels) out << ' ' << ch;
        out << "): ";
        if (!c.report.usable()) {
            out << "FAILED: " << c.report.message << '\n';
        } else {
            out << c.report.termination << '\n';
            // The calibration holds j_max at the soil's (the shear limit is the soil file's).
            for (int k = 0; k < identification::kJmax; ++k) {
                const auto i = static_cast<std::size_t>(k);
                const identification::ParameterInfo& info = identification::parameterInfo()[i];
                const std::string unit = std::string(info.unit) == "-" ? "" : info.unit;
                out << "  " << info.name << " = "
                    << formatNumber(roundSignificant(c.report.parameters[i] * info.to_user, 5));
                if (c.report.uncertainty.computed)
                    out << " ± "
                        << formatNumber(
                               roundSignificant(c.report.uncertainty.std[i] * info.to_user, 3));
                out << (unit.empty() ? "" : " " + unit) << "   (prior "
                    << formatNumber(roundSignificant(c.prior[i] * info.to_user, 5)) << ")\n";
            }
            if (c.n1) {
                out << "  n1 = " << formatNumber(roundSignificant(*c.n1, 4));
                if (c.n1_std) out << " ± " << formatNumber(roundSignificant(*c.n1_std, 3));
                out << "   (thesis model: 0; from the profile of chi2 over n1)\n";
            }
            if (c.slip_sinkage) {
                out << "  slip_sinkage = " << formatNumber(roundSignificant(*c.slip_sinkage, 4));
                if (c.slip_sinkage_std)
                    out << " ± " << formatNumber(roundSignificant(*c.slip_sinkage_std, 3));
                out << "   (thesis model: 0; Lyasko's S of h = h0 (1 + S s), from the profile of "
                       "chi2 over S)\n";
            }
            for (const std::string& flag : c.report.uncertainty.flags)
                out << "  note: " << flag << '\n';
            printRun(out, *c.after, true);
            printMetrics(out, c.after->metrics, "metrics (calibrated soil):");
            if (c.held_out) {
                printMetrics(out, *c.held_out_before, "held-out points, given soil:");
                printMetrics(out, *c.held_out, "held-out points, calibrated soil:");
            }
        }
    }
    for (const std::string& note : r.notes) out << "note: " << note << '\n';
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
        analysis::ValidationSettings settings;
        settings.experiments = o->experiments;
        settings.data = experiment;
        settings.calibrate = o->calibrate;
        settings.fit_n1 = o->fit_n1;
        settings.fit_slip_sinkage = o->fit_slip_sinkage;
        if (!o->fit_slips.empty()) settings.fit_slips = parseValues(o->fit_slips, "--fit-slips");
        parseNoise(o->noise, settings);
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
            if (cancellation.requested()) {
                exitCancelled(cancellation,
                              "validate cancelled by " + cancellation.signalName() +
                                  ": nothing written (a calibration stopped halfway has no "
                                  "result; docs/cli.md, \"Stopping a long command\")");
            }
        }
        if (o->json) {
            std::cout << analysis::toJson(result).dump(2) << '\n';
        } else {
            printHuman(result, inputs);
        }
        std::cout.flush();
        // No calibrated soil, nothing predicted: exit 1 with the reason, and no soil saved.
        if (const std::string failure = analysis::validationFailure(result); !failure.empty())
            throw std::runtime_error(failure);
        if (!o->save_soil.empty()) {
            if (const auto error = io::writeFileAtomically(
                    o->save_soil, io::toJson(result.calibration->soil).dump(2) + "\n"))
                throw std::runtime_error(o->save_soil + ": " + *error);
            std::cerr << "wrote " << o->save_soil << '\n';
        }
    });
}

}  // namespace terra::app
