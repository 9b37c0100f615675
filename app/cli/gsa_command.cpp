// `terrastudio gsa` (Sobol' indices or Morris screening) and `terrastudio bands` (Monte Carlo
// percentile bands against slip): the flags build the settings of the registry's
// "sensitivity-global" and "uncertainty-bands" analyses (core/analysis/global_sensitivity.h), so
// the command and a script's analysis compute the same table (docs/cli.md, "gsa", "bands").
#include <cmath>
#include <iostream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <tuple>

#include "app/cli/cli_support.h"
#include "app/cli/commands.h"
#include "app/cli/progress.h"
#include "app/cli/signals.h"
#include "core/analysis/global_sensitivity.h"
#include "core/analysis/soil_posterior.h"
#include "core/common/range.h"
#include "core/contact/operating_fields.h"
#include "core/io/csv.h"
#include "core/io/table_json.h"
#include "core/soil/soil_parameters.h"

namespace terra::app {
namespace {

constexpr int kMaxSamples = 1 << 24;

struct StudyOptions {
    ModelOptions model;
    std::vector<std::string> uniform;      // --param KEY=LOW:HIGH
    std::vector<std::string> normal;       // --normal KEY=MEAN,SD[,LOW:HIGH]
    std::optional<std::string> posterior;  // --posterior FILE: a correlated group
    std::string slips;
    std::string slip_angles = "0";
    std::optional<double> load_n;
    std::optional<double> entry_angle_deg;
    std::string outputs;
    std::optional<int> samples;  // absent: the method's default (0 is a range error, not "default")
    std::uint64_t seed = 1;
    double max_failed_fraction = analysis::StudyDefinition{}.max_failed_fraction;
    int threads = 0;
    bool json = false;
    bool progress = false;
    std::string csv, out;
    CLI::App* command = nullptr;
    // compaction outputs (docs/compaction.md)
    std::optional<double> depth_m, concentration;
    std::optional<int> passes;
    std::optional<std::string> profile;
    // gsa only
    std::string method = "sobol";
    int levels = 4;
    int resamples = 1000;
    double confidence = 0.95;
    // bands only
    int slip_count = analysis::UncertaintyBandSettings{}.slip_count;
    std::string percentiles = "5,50,95";
};

[[noreturn]] void bad(const std::string& flag, const std::string& value, const std::string& why) {
    throw InputError(flag + " " + io::quoteCell(value) + ": " + why);
}

double number(const std::string& flag, const std::string& whole, const std::string& text) {
    double value = 0.0;
    if (const std::string problem = numberProblem(text); !problem.empty())
        bad(flag, whole, problem);
    io::parseNumber(text, value);
    return value;
}

// KEY=REST: the soil field and the text after '='.
std::pair<const soil::SoilField*, std::string> assignment(const std::string& flag,
                                                          const std::string& text,
                                                          const std::string& form) {
    const auto equals = text.find('=');
    if (equals == std::string::npos) bad(flag, text, "expected " + form);
    const std::string key = text.substr(0, equals);
    const soil::SoilField* field = soil::findSoilField(key);
    if (!field) {
        std::vector<std::string> keys;
        std::string all;
        for (const soil::SoilField& f : soil::soilFields()) {
            keys.emplace_back(f.key);
            all += (all.empty() ? "" : ", ") + std::string(f.key);
        }
        const std::string near = nearestName(key, keys);
        bad(flag, text,
            "\"" + key + "\" is not a soil field" +
                (near.empty() ? "" : " (did you mean \"" + near + "\"?)") + "; fields: " + all);
    }
    return {field, text.substr(equals + 1)};
}

void inField(const std::string& flag, const std::string& text, const soil::SoilField& field,
             double value) {
    std::vector<Issue> issues;
    if (!checkRange(issues, field.key, value, field.range, field.displayUnit()))
        bad(flag, text, field.key + std::string(" = ") + issues.front().message);
}

std::pair<double, double> range(const std::string& flag, const std::string& text,
                                const std::string& part, const soil::SoilField& field) {
    const auto colon = part.find(':');
    if (colon == std::string::npos || part.find(':', colon + 1) != std::string::npos)
        bad(flag, text, "expected a range LOW:HIGH, got " + io::quoteCell(part));
    const double low = number(flag, text, part.substr(0, colon));
    const double high = number(flag, text, part.substr(colon + 1));
    inField(flag, text, field, low);
    inField(flag, text, field, high);
    if (!(low < high))
        bad(flag, text, "low " + formatNumber(low) + " must be below high " + formatNumber(high));
    return {low, high};
}

analysis::UncertainParameter uniformOf(const std::string& text) {
    const auto [field, rest] = assignment("--param", text, "KEY=LOW:HIGH (e.g. phi_deg=20:35)");
    const auto [low, high] = range("--param", text, rest, *field);
    return {field->key, gsa::Uniform{low, high}};
}

analysis::UncertainParameter normalOf(const std::string& text) {
    const auto [field, rest] =
        assignment("--normal", text, "KEY=MEAN,SD or KEY=MEAN,SD,LOW:HIGH (e.g. phi_deg=29,2)");
    std::vector<std::string> parts;
    std::stringstream stream(rest);
    for (std::string part; std::getline(stream, part, ',');) parts.push_back(part);
    if (parts.size() != 2 && parts.size() != 3)
        bad("--normal", text, "expected KEY=MEAN,SD or KEY=MEAN,SD,LOW:HIGH");
    gsa::Normal n;
    n.mean = number("--normal", text, parts[0]);
    n.sd = number("--normal", text, parts[1]);
    if (!(n.sd > 0.0)) bad("--normal", text, "sd " + parts[1] + " must be above 0");
    if (parts.size() == 3) {
        std::tie(n.low, n.high) = range("--normal", text, parts[2], *field);
    }
    return {field->key, n};
}

std::vector<std::string> names(const std::string& text) {
    std::vector<std::string> out;
    std::stringstream stream(text);
    for (std::string part; std::getline(stream, part, ',');) out.push_back(part);
    return out;
}

void checkCount(const std::string& flag, long long value, long long low, long long high) {
    if (value < low || value > high) {
        bad(flag, std::to_string(value),
            "outside the allowed range [" + std::to_string(low) + ", " + std::to_string(high) +
                "]");
    }
}

void checkValues(const std::string& flag, const std::string& text,
                 const std::vector<double>& values, const FieldInfo& field) {
    for (double v : values) {
        std::vector<Issue> issues;
        if (!checkRange(issues, flag, v, field.range, field.displayUnit()))
            bad(flag, text, issues.front().message);
    }
}

// The soil and wheel of the flags: a --posterior file that is a soil file (`identify
// --save-soil`) is also the soil when --soil is not given, so that the posterior's mean and the
// fields it does not vary (k_c = 0, γ, j_max) are the identified soil's.
analysis::Inputs inputsOf(const StudyOptions& o, const io::PresetLocations& locations) {
    ModelOptions model = o.model;
    if (o.posterior && o.command->get_option("--soil")->count() == 0 &&
        analysis::isSoilFile(*o.posterior))
        model.soil = *o.posterior;
    return model.inputs(locations);
}

// --posterior FILE as the study's correlated group (soil file keys and units, correlations
// kept); a key also given by --param or --normal is an error naming it. The group's keys, shape
// and definiteness are checked with the rest of the study.
analysis::CorrelatedParameters posteriorOf(
    const std::string& path, const std::vector<analysis::UncertainParameter>& independent) {
    const Result<analysis::SoilPosterior> read = analysis::readPosteriorFile(path);
    if (!read) throw InputError("--posterior: " + formatIssues(read.issues()));
    const analysis::SoilPosterior& p = read.value();
    for (const std::string& note : p.notes) std::cerr << "warning: --posterior " << note << '\n';
    for (const std::string& key : p.parameters) {
        for (const analysis::UncertainParameter& q : independent) {
            if (q.key == key)
                throw InputError(key + " is varied twice: by --posterior " + path +
                                 " and by --param/--normal");
        }
    }
    return {p.parameters, p.mean, p.covariance};
}

// The study of the flags, every flag checked (exit 2 naming it, its value and the range).
analysis::StudyDefinition definitionOf(const StudyOptions& o,
                                       const io::PresetLocations& locations) {
    std::vector<NamedInput> inputs = o.model.inputFiles();
    if (o.posterior) inputs.push_back({"--posterior", *o.posterior});
    refuseInputAsOutput("--out", o.out, inputs);
    refuseInputAsOutput("--csv", o.csv, inputs);
    analysis::StudyDefinition d;
    // The parameters in the order they were given, --param and --normal interleaved.
    std::size_t u = 0, n = 0;
    std::vector<analysis::UncertainParameter> parameters;
    for (const CLI::Option* option : o.command->parse_order()) {
        if (option->get_name() == "--param" && u < o.uniform.size())
            parameters.push_back(uniformOf(o.uniform[u++]));
        if (option->get_name() == "--normal" && n < o.normal.size())
            parameters.push_back(normalOf(o.normal[n++]));
    }
    for (; u < o.uniform.size(); ++u) parameters.push_back(uniformOf(o.uniform[u]));
    for (; n < o.normal.size(); ++n) parameters.push_back(normalOf(o.normal[n]));
    for (std::size_t i = 0; i < parameters.size(); ++i) {
        for (std::size_t j = 0; j < i; ++j) {
            if (parameters[i].key == parameters[j].key)
                throw InputError(parameters[i].key + " is varied twice (--param/--normal)");
        }
    }
    if (o.posterior) {
        // The posterior alone, or with the independent parameters given beside it (never the
        // default ranges, which would vary its keys a second time).
        d.correlated = posteriorOf(*o.posterior, parameters);
        d.parameters = std::move(parameters);
    } else if (!parameters.empty()) {
        d.parameters = std::move(parameters);
    }
    if (!o.outputs.empty()) {
        d.outputs = names(o.outputs);
        for (const std::string& name : d.outputs) {
            if (gsa::findOutput(name)) continue;
            std::string all;
            for (const std::string& known : gsa::outputNames())
                all += (all.empty() ? "" : ",") + known;
            const std::string near = nearestName(name, gsa::outputNames());
            bad("--outputs", o.outputs,
                "\"" + name + "\" is not an output" +
                    (near.empty() ? "" : " (did you mean \"" + near + "\"?)") +
                    "; outputs: " + all);
        }
    }
    if (!o.slips.empty()) {
        d.slips = parseValues(o.slips, "--slip");
        checkValues("--slip", o.slips, d.slips, contact::slipField());
    }
    d.slip_angles_deg = parseValues(o.slip_angles, "--slip-angle");
    checkValues("--slip-angle", o.slip_angles, d.slip_angles_deg, contact::slipAngleField());
    if (o.load_n) {
        checkValues("--load", formatNumber(*o.load_n), {*o.load_n}, contact::loadField());
        d.load_n = o.load_n;
    }
    if (o.entry_angle_deg) {
        checkValues("--entry-angle", formatNumber(*o.entry_angle_deg), {*o.entry_angle_deg},
                    contact::entryAngleField());
        d.entry_angle_deg = o.entry_angle_deg;
    }
    d.seed = o.seed;
    if (!(o.max_failed_fraction >= 0.0 && o.max_failed_fraction <= 1.0)) {
        bad("--max-failed-fraction", formatNumber(o.max_failed_fraction),
            "outside the allowed range [0, 1]");
    }
    d.max_failed_fraction = o.max_failed_fraction;
    checkCount("--threads", o.threads, 0, 1024);
    d.threads = o.threads;
    d.model = o.model.choices();
    if (o.depth_m) {
        if (!(*o.depth_m > 0.0 && *o.depth_m <= 10.0))
            bad("--depth", formatNumber(*o.depth_m), "outside the allowed range (0, 10] m");
        d.compaction.depth_m = *o.depth_m;
    }
    if (o.passes) {
        checkCount("--passes", *o.passes, 1, 100);
        d.compaction.passes = *o.passes;
    }
    if (o.concentration) {
        if (!(*o.concentration >= 2.5 && *o.concentration <= 12.0))
            bad("--concentration", formatNumber(*o.concentration),
                "outside the allowed range [2.5, 12]");
        d.compaction.concentration = o.concentration;
    }
    if (o.profile) {
        Result<soil::SoilProfile> profile = io::resolveProfile(locations, *o.profile);
        if (!profile) throw InputError("--profile: " + profile.message());
        d.compaction.profile = profile.value();
    }
    return d;
}

void addStudyOptions(CLI::App& cmd, StudyOptions& o, const std::string& slips_default,
                     const std::string& samples_help) {
    o.command = &cmd;
    o.model.addTo(cmd);
    cmd.add_option("--param", o.uniform,
                   "Uniform parameter KEY=LOW:HIGH in the soil file's unit (repeatable), e.g. "
                   "--param phi_deg=20:35; default: phi_deg=20:35 c_kPa=0:5 K_m=0.005:0.04 "
                   "n=0.5:1.1");
    cmd.add_option("--normal", o.normal,
                   "Normal parameter KEY=MEAN,SD or KEY=MEAN,SD,LOW:HIGH (truncated; repeatable)");
    cmd.add_option("--posterior", o.posterior,
                   "Correlated parameters: a soil file with a \"posterior\" (identify "
                   "--save-soil), sampled with its correlations; it is also the soil when "
                   "--soil is not given");
    cmd.add_option("--slip,--slips", o.slips,
                   "Slips: list a,b,c or range first:last:count (default " + slips_default + ")");
    cmd.add_option("--slip-angle,--slip-angles", o.slip_angles, "Slip angle(s) beta [deg]")
        ->capture_default_str();
    auto* load = cmd.add_option("--load", o.load_n,
                                "Wheel load W [N], entry angle solved per sample (default " +
                                    formatNumber(analysis::OperatingConditions{}.load_n) + ")");
    cmd.add_option("--entry-angle", o.entry_angle_deg, "Fixed entry angle [deg] instead of a load")
        ->excludes(load);
    std::string all;
    for (const std::string& name : gsa::outputNames()) all += (all.empty() ? "" : ",") + name;
    cmd.add_option("--outputs", o.outputs, "Outputs, comma separated, among " + all);
    cmd.add_option("--samples", o.samples, samples_help);
    cmd.add_option("--seed", o.seed, "Seed: the same seed gives the same numbers")
        ->capture_default_str();
    cmd.add_option("--max-failed-fraction", o.max_failed_fraction,
                   "Largest share of samples without equilibrium at a point, in [0, 1]")
        ->capture_default_str();
    cmd.add_option("--threads", o.threads, "Worker threads (0: one per core; same numbers)")
        ->capture_default_str();
    cmd.add_flag("--json", o.json, "JSON output instead of CSV");
    auto* csv = cmd.add_option("--csv", o.csv, "Write the CSV table to this file");
    cmd.add_option("--out", o.out, "Output file (default: stdout)")->excludes(csv);
    cmd.add_flag("--progress", o.progress, "Report progress on stderr");
    cmd.add_option("--depth", o.depth_m,
                   "Depth [m] of the output max_sigma_z_kPa (default 0.3; docs/compaction.md)");
    cmd.add_option("--passes", o.passes,
                   "Wheels on one track for the compaction outputs (default 1)");
    cmd.add_option("--profile", o.profile,
                   "Soil profile of red_to_depth_m: preset or file (default: the soil's own)");
    cmd.add_option(
        "--concentration", o.concentration,
        "Concentration factor nu of the compaction outputs (default: per layer, else 5)");
}

// --progress: lines every 10 % wherever stderr goes; otherwise the bar on a terminal.
TerminalProgress::Mode progressMode(const StudyOptions& o) {
    return o.progress ? TerminalProgress::Mode::kLines : TerminalProgress::Mode::kBar;
}

// Writes the outcome (its table as CSV, or `json`, an object); a refused study is an error
// (exit 1), a cancelled one is written marked (JSON: "cancelled": true and a "note", as `sweep`;
// CSV: a last comment line) and exits with the signal's code.
void emit(const StudyOptions& o, const analysis::Outcome& outcome, const nlohmann::json& json,
          const SignalCancellation& cancellation) {
    printLines(outcome.notes, "note: ");
    if (outcome.status == analysis::Outcome::Status::kFailed)
        throw std::runtime_error(outcome.message);
    const bool cancelled = outcome.status == analysis::Outcome::Status::kCancelled;
    const std::string path = o.csv.empty() ? o.out : o.csv;
    // The core says "cancelled: indices from the 512 of 4096 base samples …"; the note adds
    // the signal.
    std::string detail = outcome.message;
    if (detail.rfind("cancelled: ", 0) == 0) detail.erase(0, 11);
    const std::string note =
        "cancelled by " + cancellation.signalName() + (detail.empty() ? "" : ": " + detail);
    std::string text;
    if (o.json && o.csv.empty()) {
        nlohmann::json j = json;
        if (cancelled) j.update({{"cancelled", true}, {"note", note}});
        text = j.dump(2) + "\n";
    } else {
        text = io::toCsv(outcome.tables.front().table);
        if (cancelled) text += "# " + note + "\n";
    }
    writeOutput(path, text);
    if (!path.empty() && path != "-") std::cerr << "wrote " << path << '\n';
    if (cancelled) exitCancelled(cancellation, outcome.message);
}

}  // namespace

void addGsaCommands(CLI::App& app, const io::PresetLocations& locations) {
    auto study = std::make_shared<StudyOptions>();
    CLI::App* cmd = app.add_subcommand(
        "gsa",
        "Global sensitivity: Sobol' S1/ST with confidence intervals, or Morris mu*/sigma, "
        "of outputs at chosen slips over soil parameter ranges or distributions");
    addStudyOptions(*cmd, *study, "0.1,0.3,0.6",
                    "Sobol': base samples N (N (d + 2) model runs per point; default 4096); "
                    "Morris: trajectories (default 64)");
    cmd->add_option("--method", study->method, "sobol or morris")
        ->check(CLI::IsMember({"sobol", "morris"}))
        ->capture_default_str();
    cmd->add_option("--levels", study->levels, "Morris grid levels p (even)")
        ->capture_default_str();
    cmd->add_option("--resamples", study->resamples,
                    "Bootstrap resamples of the intervals (0: none)")
        ->capture_default_str();
    cmd->add_option("--confidence", study->confidence,
                    "Confidence level of the intervals, in (0, 1)")
        ->capture_default_str();
    cmd->callback([study, &locations] {
        const StudyOptions& o = *study;
        const analysis::Inputs inputs = inputsOf(o, locations);
        analysis::GlobalSensitivitySettings s;
        s.study = definitionOf(o, locations);
        s.method =
            o.method == "morris" ? analysis::GsaMethod::kMorris : analysis::GsaMethod::kSobol;
        if (o.samples) {
            checkCount("--samples", *o.samples, 2, kMaxSamples);
            s.samples = static_cast<std::size_t>(*o.samples);
        } else if (s.method == analysis::GsaMethod::kMorris) {
            s.samples = gsa::MorrisOptions{}.trajectories;
        }
        checkCount("--levels", o.levels, 2, 1000);
        if (o.levels % 2 != 0) bad("--levels", std::to_string(o.levels), "must be even");
        checkCount("--resamples", o.resamples, 0, 1000000);
        if (!(o.confidence > 0.0 && o.confidence < 1.0))
            bad("--confidence", formatNumber(o.confidence), "outside the allowed range (0, 1)");
        s.levels = o.levels;
        s.resamples = o.resamples;
        s.confidence_level = o.confidence;
        if (s.method == analysis::GsaMethod::kMorris) {
            for (const analysis::UncertainParameter& p : s.study.parameters) {
                if (!std::holds_alternative<gsa::Uniform>(p.distribution))
                    bad("--normal", p.key, "Morris screening needs ranges (--param KEY=LOW:HIGH)");
            }
            if (o.posterior)
                bad("--posterior", *o.posterior,
                    "Morris screening needs ranges (--param KEY=LOW:HIGH)");
        }
        const SignalCancellation cancellation;
        TerminalProgress progress("gsa", progressMode(o));
        analysis::Outcome outcome =
            analysis::globalSensitivityOutcome(analysis::computeGlobalSensitivity(
                inputs, s, {cancellation.flag(), progress.callback()}));
        progress.finish();
        const auto& result =
            std::any_cast<const analysis::GlobalSensitivityResult&>(outcome.result);
        emit(o, outcome, result.toJson(), cancellation);
    });

    auto bands = std::make_shared<StudyOptions>();
    CLI::App* b = app.add_subcommand(
        "bands",
        "Uncertainty bands: Monte Carlo percentiles of outputs against slip when soil "
        "parameters follow ranges or distributions, with the nominal soil's curve");
    addStudyOptions(*b, *bands, "0:slip_max:20",
                    "Monte Carlo samples M (default " +
                        std::to_string(analysis::UncertaintyBandSettings{}.samples) + ")");
    b->add_option("--percentiles", bands->percentiles, "Percentiles in [0, 100]")
        ->capture_default_str();
    b->callback([bands, &locations] {
        const StudyOptions& o = *bands;
        const analysis::Inputs inputs = inputsOf(o, locations);
        analysis::UncertaintyBandSettings s;
        const std::vector<std::string> outputs = s.study.outputs;
        s.study = definitionOf(o, locations);
        if (o.outputs.empty()) s.study.outputs = outputs;
        if (o.slips.empty()) s.study.slips.clear();  // 0 … slip_max in slip_count points
        if (o.samples) {
            checkCount("--samples", *o.samples, 2, kMaxSamples);
            s.samples = static_cast<std::size_t>(*o.samples);
        }
        s.percentiles = parseValues(o.percentiles, "--percentiles");
        for (double q : s.percentiles) {
            if (!(q >= 0.0 && q <= 100.0))
                bad("--percentiles", o.percentiles,
                    formatNumber(q) + " is outside the allowed range [0, 100]");
        }
        const SignalCancellation cancellation;
        TerminalProgress progress("bands", progressMode(o));
        analysis::Outcome outcome =
            analysis::uncertaintyBandOutcome(analysis::computeUncertaintyBands(
                inputs, s, {cancellation.flag(), progress.callback()}));
        progress.finish();
        // An object, not the bare array of rows: a cancelled study must carry its mark.
        emit(o, outcome, nlohmann::json{{"rows", io::toJson(outcome.tables.front().table)}},
             cancellation);
    });
}

}  // namespace terra::app
