// `terrastudio gsa` (Sobol' indices or Morris screening) and `terrastudio bands` (Monte Carlo
// percentile bands against slip): the flags build the settings of the registry's
// "sensitivity-global" and "uncertainty-bands" analyses (core/analysis/global_sensitivity.h), so
// the command and a script's analysis compute the same table (docs/cli.md, "gsa", "bands").
#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

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

// KEY=REST: the key and the text after '=' (the key is the reader's to check).
std::pair<std::string, std::string> assignment(const std::string& flag, const std::string& text,
                                               const std::string& form) {
    const auto equals = text.find('=');
    if (equals == std::string::npos) bad(flag, text, "expected " + form);
    return {text.substr(0, equals), text.substr(equals + 1)};
}

// LOW:HIGH as two numbers (their range and order are the reader's to check).
nlohmann::json range(const std::string& flag, const std::string& text, const std::string& part) {
    const auto colon = part.find(':');
    if (colon == std::string::npos || part.find(':', colon + 1) != std::string::npos)
        bad(flag, text, "expected a range LOW:HIGH, got " + io::quoteCell(part));
    return {number(flag, text, part.substr(0, colon)), number(flag, text, part.substr(colon + 1))};
}

// --param KEY=LOW:HIGH as an element of the study's "parameters".
nlohmann::json uniformOf(const std::string& text) {
    const auto [key, rest] = assignment("--param", text, "KEY=LOW:HIGH (e.g. phi_deg=20:35)");
    return {{"key", key}, {"range", range("--param", text, rest)}};
}

// --normal KEY=MEAN,SD[,LOW:HIGH] as an element of the study's "parameters".
nlohmann::json normalOf(const std::string& text) {
    const auto [key, rest] =
        assignment("--normal", text, "KEY=MEAN,SD or KEY=MEAN,SD,LOW:HIGH (e.g. phi_deg=29,2)");
    std::vector<std::string> parts;
    std::stringstream stream(rest);
    for (std::string part; std::getline(stream, part, ',');) parts.push_back(part);
    if (parts.size() != 2 && parts.size() != 3)
        bad("--normal", text, "expected KEY=MEAN,SD or KEY=MEAN,SD,LOW:HIGH");
    nlohmann::json out{
        {"key", key},
        {"normal", {number("--normal", text, parts[0]), number("--normal", text, parts[1])}}};
    if (parts.size() == 3) out["bounds"] = range("--normal", text, parts[2]);
    return out;
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

// --posterior FILE as the study's "correlated" group (soil file keys and units, correlations
// kept); its notes are printed. Its keys, shape and definiteness, and a key also given by
// --param or --normal, are the reader's to check.
nlohmann::json posteriorOf(const std::string& path) {
    const Result<analysis::SoilPosterior> read = analysis::readPosteriorFile(path);
    if (!read) throw InputError("--posterior: " + formatIssues(read.issues()));
    const analysis::SoilPosterior& p = read.value();
    for (const std::string& note : p.notes) std::cerr << "warning: --posterior " << note << '\n';
    return {{"keys", p.parameters}, {"mean", p.mean}, {"covariance", p.covariance}};
}

// The flags of a study as its settings object (the keys of StudyDefinition::visitFields), read
// by the analysis's own reader: the soil fields, ranges, outputs and their messages are the
// reader's, named by the flags (nameStudyFlags). Left to the flags: the forms KEY=LOW:HIGH and
// KEY=MEAN,SD[,LOW:HIGH], the number lists and --threads. `parameter_flags` gets each
// parameter's flag and text ("--param 'phi_deg=20:35'"), in the order of "parameters".
nlohmann::json studyObject(const StudyOptions& o, std::vector<std::string>& parameter_flags) {
    std::vector<NamedInput> inputs = o.model.inputFiles();
    if (o.posterior) inputs.push_back({"--posterior", *o.posterior});
    refuseInputAsOutput("--out", o.out, inputs);
    refuseInputAsOutput("--csv", o.csv, inputs);
    nlohmann::json s = nlohmann::json::object();
    // The parameters in the order they were given, --param and --normal interleaved.
    std::size_t u = 0, n = 0;
    nlohmann::json parameters = nlohmann::json::array();
    auto addUniform = [&](const std::string& text) {
        parameters.push_back(uniformOf(text));
        parameter_flags.push_back("--param " + io::quoteCell(text));
    };
    auto addNormal = [&](const std::string& text) {
        parameters.push_back(normalOf(text));
        parameter_flags.push_back("--normal " + io::quoteCell(text));
    };
    for (const CLI::Option* option : o.command->parse_order()) {
        if (option->get_name() == "--param" && u < o.uniform.size()) addUniform(o.uniform[u++]);
        if (option->get_name() == "--normal" && n < o.normal.size()) addNormal(o.normal[n++]);
    }
    for (; u < o.uniform.size(); ++u) addUniform(o.uniform[u]);
    for (; n < o.normal.size(); ++n) addNormal(o.normal[n]);
    if (o.posterior) {
        // The posterior alone, or with the independent parameters given beside it (never the
        // default ranges, which would vary its keys a second time).
        s["correlated"] = posteriorOf(*o.posterior);
        s["parameters"] = std::move(parameters);
    } else if (!parameters.empty()) {
        s["parameters"] = std::move(parameters);
    }
    if (!o.outputs.empty()) s["outputs"] = names(o.outputs);
    if (!o.slips.empty()) s["slips"] = parseValues(o.slips, "--slip");
    s["slip_angles_deg"] = parseValues(o.slip_angles, "--slip-angle");
    if (o.load_n) s["load_N"] = *o.load_n;
    if (o.entry_angle_deg) s["entry_angle_deg"] = *o.entry_angle_deg;
    s["seed"] = o.seed;
    s["max_failed_fraction"] = o.max_failed_fraction;
    nlohmann::json compaction = nlohmann::json::object();
    if (o.depth_m) compaction["depth_m"] = *o.depth_m;
    if (o.passes) compaction["passes"] = *o.passes;
    if (o.concentration) compaction["concentration"] = *o.concentration;
    if (!compaction.empty()) s["compaction"] = std::move(compaction);
    return s;
}

// The reader's issues named by the flags: a parameter's by its flag and text, the posterior's
// by its file, the others by the flag of their key ("slips[1]" → "--slip[1]").
void nameStudyFlags(std::vector<Issue>& issues, const StudyOptions& o,
                    const std::vector<std::string>& parameter_flags) {
    for (Issue& issue : issues) {
        for (std::size_t i = 0; i < parameter_flags.size(); ++i) {
            const std::string prefix = "parameters[" + std::to_string(i) + "]";
            if (issue.where.rfind(prefix, 0) == 0) issue.where = parameter_flags[i];
        }
        if (o.posterior && issue.where.rfind("correlated", 0) == 0)
            issue.where = "--posterior " + io::quoteCell(*o.posterior);
    }
    nameFlags(issues, {{"parameters", "--param"},
                       {"outputs", "--outputs"},
                       {"slips", "--slip"},
                       {"slip_angles_deg", "--slip-angle"},
                       {"load_N", "--load"},
                       {"entry_angle_deg", "--entry-angle"},
                       {"seed", "--seed"},
                       {"max_failed_fraction", "--max-failed-fraction"},
                       {"compaction.depth_m", "--depth"},
                       {"compaction.passes", "--passes"},
                       {"compaction.concentration", "--concentration"},
                       {"method", "--method"},
                       {"samples", "--samples"},
                       {"levels", "--levels"},
                       {"resamples", "--resamples"},
                       {"confidence", "--confidence"},
                       {"percentiles", "--percentiles"}});
}

// Settings of the flags read by `read` (the analysis's reader), every problem named by its flag
// (exit 2); then what the flags give beside the settings object: the model choices, the
// threads and a --profile found among the presets.
template <typename Settings, typename Read>
Settings readStudySettings(const StudyOptions& o, const nlohmann::json& object,
                           const std::vector<std::string>& parameter_flags,
                           const io::PresetLocations& locations, Read read) {
    std::vector<Issue> issues;
    io::ObjectReader reader(object, issues);
    Settings settings;
    read(reader, settings);
    reader.finish();
    if (!issues.empty()) {
        nameStudyFlags(issues, o, parameter_flags);
        throw InputError(formatIssues(issues));
    }
    checkCount("--threads", o.threads, 0, 1024);
    settings.study.threads = o.threads;
    settings.study.model = o.model.choices();
    if (o.profile) {
        Result<soil::SoilProfile> profile = io::resolveProfile(locations, *o.profile);
        if (!profile) throw InputError("--profile: " + profile.message());
        settings.study.compaction.profile = profile.value();
    }
    return settings;
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
    // Checked by the analysis's reader, as a script's "method" is ("did you mean").
    cmd->add_option("--method", study->method, "sobol or morris")->capture_default_str();
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
        std::vector<std::string> parameter_flags;
        nlohmann::json object = studyObject(o, parameter_flags);
        object["method"] = o.method;
        if (o.samples) {
            object["samples"] = *o.samples;
        } else if (o.method == "morris") {
            object["samples"] = gsa::MorrisOptions{}.trajectories;
        }
        object["levels"] = o.levels;
        object["resamples"] = o.resamples;
        object["confidence"] = o.confidence;
        const auto s = readStudySettings<analysis::GlobalSensitivitySettings>(
            o, object, parameter_flags, locations, analysis::readGlobalSensitivitySettings);
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
        std::vector<std::string> parameter_flags;
        nlohmann::json object = studyObject(o, parameter_flags);
        if (o.samples) object["samples"] = *o.samples;
        object["percentiles"] = parseValues(o.percentiles, "--percentiles");
        const auto s = readStudySettings<analysis::UncertaintyBandSettings>(
            o, object, parameter_flags, locations, analysis::readUncertaintyBandSettings);
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
