// `terrastudio synth` (synthetic identification data, thesis chapter 5) and `terrastudio identify`:
// the global identification on the full model with its uncertainty (`--refine`, the default), the
// decoupled three-step fit of §4.3 alone (`--no-refine`), or the streaming estimator (`--stream`).
#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>

#include "app/cli/cli_support.h"
#include "app/cli/commands.h"
#include "app/cli/progress.h"
#include "app/cli/signals.h"
#include "core/analysis/identification.h"
#include "core/analysis/identified_parameters.h"
#include "core/analysis/registry.h"
#include "core/analysis/streaming_identification.h"
#include "core/common/range.h"
#include "core/common/units.h"
#include "core/contact/operating_fields.h"
#include "core/identification/synthetic.h"
#include "core/io/csv.h"
#include "core/io/parameters_json.h"

namespace terra::app {
namespace {

struct SynthOptions {
    ModelOptions model;
    std::string loads = formatNumber(contact::kDefaultLoadN);
    std::string slips = "0:0.9:60";
    double slip_angle_deg = 0.0;
    std::vector<std::string> noise;  // channel=sigma or channel=P%
    std::uint64_t seed = 1;
    std::string out;
};

// "fx=0.1" (absolute, N or N·m or deg) or "fx=1%" (of the channel's largest value).
void parseNoise(const std::vector<std::string>& items, identification::NoiseSpec& noise) {
    std::map<std::string, identification::ChannelNoise*> channels{
        {"fx", &noise.fx}, {"fz", &noise.fz}, {"my", &noise.my}, {"theta", &noise.entry_angle}};
    refuseRepeatedKeys("--noise", items);
    for (const std::string& item : items) {
        const auto equals = item.find('=');
        const std::string key = item.substr(0, equals);
        const auto it = channels.find(key);
        if (it == channels.end() || equals == std::string::npos) {
            throw InputError("--noise '" + item + "': expected fx|fz|my|theta=SIGMA or =PERCENT%");
        }
        std::string value = item.substr(equals + 1);
        const bool percent = !value.empty() && value.back() == '%';
        if (percent) value.pop_back();
        double sigma = 0.0;
        std::vector<Issue> issues;
        if (const std::string problem = numberProblem(value); !problem.empty())
            throw InputError("--noise '" + item + "': " + problem);
        io::parseNumber(value, sigma);
        // θ_f lies in (0°, 90°]: a spread beyond 90° is no measurement noise of it.
        if (percent) {
            checkRange(issues, "--noise " + key, sigma, {0.0, 1000.0}, "%");
        } else if (key == "theta") {
            checkRange(issues, "--noise " + key, sigma, {0.0, 90.0}, "deg");
        } else {
            checkRange(issues, "--noise " + key, sigma, {0.0, 1e6}, key == "my" ? "N·m" : "N");
        }
        if (!issues.empty()) throw InputError(formatIssues(issues));
        if (percent) {
            it->second->relative = sigma / 100.0;
        } else {
            it->second->absolute = key == "theta" ? units::degToRad(sigma) : sigma;
        }
    }
}

struct IdentifyOptions {
    std::string data;
    std::string wheel = "A";
    std::string guess;
    bool json = false;
    bool skip_bad_rows = false;
    bool refine = analysis::IdentificationSettings{}.refine;
    std::vector<std::string> fix;     // key=value, identified_parameters.h keys
    std::vector<std::string> noise;   // fx=, fz=, my= noise levels for the refinement weights
    std::optional<std::string> jmax;  // --jmax VALUE (held) or "fit" (identified)
    std::string stream;               // --stream FILE: one estimate per sample
    std::optional<int> window;        // --stream: samples of the moving horizon
    // The full model's global identification (core/identification/identify.h).
    std::vector<std::string> prior;  // name=mean±std items, or one soil preset/file
    std::optional<double> holdout;   // fraction in (0, 1)
    std::optional<int> folds;        // k ≥ 2
    std::optional<int> starts;       // design points
    std::string loss = "l2";
    std::optional<double> load_n;  // W of rows without a W_N cell
    bool profile = false;          // profile-likelihood intervals of the flagged parameters
    std::string save_soil;         // --save-soil OUT.json: the soil with its posterior
    std::optional<int> threads;    // the global search's threads; default: one per core
};

// --jmax VALUE as the settings' "jmax_m", for a batch fit and --stream alike: a number here, its
// range checked by the settings' reader.
void setJmax(const std::string& text, nlohmann::json& object, const char* expected) {
    double value = 0.0;
    if (!parseStrictNumber(text, value))
        throw InputError("--jmax " + text + ": expected " + expected);
    object["jmax_m"] = value;
}

// The flags as the identification's settings object (the keys of IdentificationSettings::
// visitFields), read by its own reader: the ranges, kinds and their messages are the reader's,
// named here by the flags (flagNames). What is left to the flags: the forms of their values
// (NAME=VALUE items, "fit"), a key given twice, and a second soil given to --prior. --data is
// not a key of the object: the fit reads the file (its FILE:LINE issues, the rows skipped).
nlohmann::json settingsObject(const IdentifyOptions& o,
                              std::vector<std::pair<std::string, std::string>>& flag_names) {
    nlohmann::json s = nlohmann::json::object();
    if (o.skip_bad_rows) s["skip_bad_rows"] = true;
    s["refine"] = o.refine;
    refuseRepeatedKeys("--prior", o.prior);
    std::vector<std::string> items;
    for (const std::string& item : o.prior) {
        if (item.find('=') != std::string::npos) {
            items.push_back(item);
        } else if (s.contains("prior_soil")) {
            throw InputError("--prior " + item + ": a second soil prior (after " +
                             s["prior_soil"].get<std::string>() +
                             "); give one soil and NAME=MEAN±STD items");
        } else {
            s["prior_soil"] = item;
            flag_names.emplace_back("prior_soil", "--prior " + item);
        }
    }
    if (!items.empty()) s["priors"] = items;
    if (o.holdout) s["holdout"] = *o.holdout;
    if (o.folds) s["folds"] = *o.folds;
    if (o.starts) s["starts"] = *o.starts;
    s["loss"] = o.loss;
    if (o.load_n) s["load_N"] = *o.load_n;
    if (o.profile) s["profile"] = true;
    // --fix a0=0.2: a key of the identified parameters and a value in its unit.
    refuseRepeatedKeys("--fix", o.fix);
    for (const std::string& item : o.fix) {
        const auto equals = item.find('=');
        double value = 0.0;
        if (equals == std::string::npos || !parseStrictNumber(item.substr(equals + 1), value))
            throw InputError("--fix " + item + ": expected NAME=VALUE (keys of the output)");
        s["fix"][item.substr(0, equals)] = value;
    }
    // --noise fx=0.1: σ of a channel [N, N·m].
    refuseRepeatedKeys("--noise", o.noise);
    const std::map<std::string, std::string> channels{
        {"fx", "Fx_N"}, {"fz", "Fz_N"}, {"my", "My_Nm"}};
    for (const std::string& item : o.noise) {
        const auto equals = item.find('=');
        const auto channel =
            equals == std::string::npos ? channels.end() : channels.find(item.substr(0, equals));
        double value = 0.0;
        if (channel == channels.end() || !parseStrictNumber(item.substr(equals + 1), value))
            throw InputError("--noise " + item + ": expected fx|fz|my=SIGMA (N, N·m)");
        s["noise"][channel->second] = value;
    }
    // --jmax VALUE (held) or "fit" (identified).
    if (o.jmax && *o.jmax == "fit") {
        s["fit_jmax"] = true;
    } else if (o.jmax) {
        setJmax(*o.jmax, s, "a length in m, or 'fit' to identify it");
    }
    return s;
}

// The settings keys the flags set, and the flags' names for the reader's messages.
std::vector<std::pair<std::string, std::string>> identifyFlagNames() {
    return {{"skip_bad_rows", "--skip-bad-rows"},
            {"refine", "--refine"},
            {"priors", "--prior"},  // "prior_soil": "--prior SOIL", by settingsObject
            {"holdout", "--holdout"},
            {"folds", "--folds"},
            {"starts", "--starts"},
            {"loss", "--loss"},
            {"load_N", "--load"},
            {"profile", "--profile"},
            {"fix.", "--fix "},
            {"fix", "--fix"},
            {"noise.Fx_N", "--noise fx"},
            {"noise.Fz_N", "--noise fz"},
            {"noise.My_Nm", "--noise my"},
            {"noise", "--noise"},
            {"jmax_m", "--jmax"},
            {"fit_jmax", "--jmax fit"}};
}

// The identification's settings of the flags, read by its reader (exit 2 names the flag, the
// value and what is allowed, in the reader's words).
analysis::IdentificationSettings identifySettings(const IdentifyOptions& o,
                                                  const io::PresetLocations& locations) {
    std::vector<std::pair<std::string, std::string>> names = identifyFlagNames();
    const nlohmann::json object = settingsObject(o, names);
    std::vector<Issue> issues;
    io::ObjectReader reader(object, issues);
    analysis::IdentificationSettings settings;
    analysis::readIdentificationSettings(reader, {&locations, {}}, settings);
    reader.finish();
    if (!issues.empty()) {
        nameFlags(issues, names);
        throw InputError(formatIssues(issues));
    }
    // An old parameter key ("--prior Ks=…", issue 26) is read as its new one: said once, here,
    // with the flag that gave it.
    nameFlags(settings.key_warnings, names);
    std::vector<std::string> notes;
    for (const Issue& note : settings.key_warnings)
        notes.push_back(note.where + ": " + note.message);
    printLines(notes, "warning: ");
    settings.key_warnings.clear();
    settings.csv = o.data;
    return settings;
}

// --save-soil OUT.json: the identified soil as a soil file (`base`'s γ; k_c = 0, k_φ = K_s; the
// fit's j_max) with "posterior" in the soil file's keys and units, written atomically.
void saveSoil(const IdentifyOptions& o, const analysis::IdentificationResult& result,
              const soil::SoilParameters& base, const wheel::WheelParameters& wheel,
              const analysis::IdentificationSettings& settings) {
    const double jmax =
        settings.max_shear_deformation_m.value_or(std::numeric_limits<double>::infinity());
    Result<soil::SoilParameters> soil = analysis::identifiedSoilFile(result, base, wheel, jmax);
    if (!soil) throw std::runtime_error("--save-soil " + o.save_soil + ": " + soil.message());
    soil::SoilParameters s = soil.value();
    s.name = "identified from " + std::filesystem::path(o.data).filename().string();
    s.source = "terrastudio identify --data " + o.data + " --wheel " + o.wheel + " (" +
               (result.report ? "global identification" : "decoupled fit") + ", " +
               std::to_string(result.data.samples.size()) + " samples" +
               (o.guess.empty() ? "" : "; gamma from " + o.guess) + ")";
    nlohmann::json file = io::toJson(s);
    const nlohmann::json posterior = analysis::soilPosteriorJson(result, s, wheel);
    if (!posterior.is_null()) file["posterior"] = posterior;
    writeOutput(o.save_soil, file.dump(2) + "\n");
    std::string what;
    if (posterior.is_null()) {
        what = std::string(" without a posterior (") +
               (result.report ? "the covariance is rank deficient" : "the decoupled fit has none") +
               ")";
    } else {
        for (const nlohmann::json& key : posterior["parameters"])
            what += (what.empty() ? " with its posterior (keys " : ", ") + key.get<std::string>();
        what += ")";
    }
    std::cerr << "wrote " << o.save_soil << ": the identified soil" << what << '\n';
}

// The flags of --stream as the streaming identification's settings object (the keys of
// StreamingSettings::visitFields), read by its own reader: the ranges and their messages are the
// reader's, named here by the flags. --stream itself is not a key of the object: the command
// reads the file once, when it plays it (its FILE:LINE issues, the --skip-bad-rows hint).
analysis::StreamingSettings streamSettings(const IdentifyOptions& o) {
    nlohmann::json object{{"skip_bad_rows", o.skip_bad_rows}};
    if (o.window) object["window"] = *o.window;
    if (o.load_n) object["load_N"] = *o.load_n;
    // --jmax VALUE: the model's j_max held, a key of the settings as for a batch fit; the
    // streaming estimator cannot identify it.
    if (o.jmax && *o.jmax == "fit")
        throw InputError("--jmax fit does not apply to --stream: give a value");
    if (o.jmax) setJmax(*o.jmax, object, "a length in m (--stream)");
    std::vector<Issue> issues;
    io::ObjectReader reader(object, issues);
    analysis::StreamingSettings settings;
    analysis::readStreamingSettings(reader, {}, settings);
    reader.finish();
    if (!issues.empty()) {
        nameFlags(issues, {{"skip_bad_rows", "--skip-bad-rows"},
                           {"window", "--window"},
                           {"load_N", "--load"},
                           {"jmax_m", "--jmax"}});
        throw InputError(formatIssues(issues));
    }
    return settings;
}

// `identify --stream FILE`: the samples fed one at a time to the streaming estimator on the full
// model (core/analysis/streaming_identification.h), one line per sample (JSON Lines with --json):
// the estimate with its std, the normalised innovation, the CUSUM, and a confirmed change of
// soil as `change_at` (the sample where it began) on the line of the sample that confirmed it.
void runStream(const IdentifyOptions& o, const analysis::Inputs& inputs,
               const std::optional<soil::SoilParameters>& guess) {
    analysis::StreamingSettings settings = streamSettings(o);
    settings.csv = o.stream;
    if (guess) {
        settings.options.fit.starts.push_back(
            {"guess " + o.guess, identification::fromSoil(*guess, inputs.wheel)});
    }
    analysis::StreamSource source;
    try {
        source = analysis::streamSource(inputs, settings);
    } catch (const std::invalid_argument& e) {
        throw InputError(std::string(e.what()) + "\n(use --skip-bad-rows to skip bad rows)");
    }
    // The data are read: a signal from now on stops the estimator after the sample in hand.
    const SignalCancellation cancellation;
    TerminalProgress progress("identify --stream");
    analysis::StreamingResult result;
    try {
        result = analysis::playStreaming(std::move(source), inputs.wheel, settings.options,
                                         {cancellation.flag(), progress.callback()});
    } catch (const std::invalid_argument& e) {
        throw InputError(o.stream + ": " + e.what());
    }
    progress.finish();
    printLines(result.source.warnings, "");
    if (inputs.wheel.lugShearOffset() > 0.0) {
        // The streaming estimator is the decoupled model (Eqs. 4.1–4.18) on the rim radius.
        std::cerr << "warning: the streaming estimator treats the lugged wheel as smooth "
                     "(docs/model.md, \"Lugs\")\n";
    }
    const auto fields = analysis::identifiedFields();
    if (!o.json) {
        std::cout << "sample  time_s";
        // j_max is held by the streaming estimator: no column of it.
        for (const analysis::IdentifiedField& field : fields) {
            const auto k = analysis::fullParameterOf(field);
            if (k && *k != identification::kJmax)
                std::cout << ' ' << std::setw(8) << field.key << ' ' << std::setw(8) << "±std";
        }
        std::cout << "     nis   cusum\n";
    }
    for (const analysis::StreamFrame& frame : result.frames) {
        const identification::StreamEstimate& u = frame.estimate;
        if (o.json) {
            nlohmann::json j{{"sample", u.index},
                             {"estimated", u.estimated},
                             {"used", u.used},
                             {"nis", roundSignificant(u.nis, 6)},
                             {"cusum", roundSignificant(u.cusum, 6)}};
            j["time_s"] = frame.time_s;
            if (u.estimated) {
                j.update(analysis::identifiedJson(frame.parameters));
                j["std"] = analysis::fullParametersJson(u.std);
            }
            if (u.change_rejected) j["change_rejected"] = true;
            if (u.change_detected && u.change_at) j["change_at"] = *u.change_at;
            std::cout << j.dump() << '\n';
            continue;
        }
        std::cout << std::setw(6) << u.index << ' ' << std::setw(7) << fixed(frame.time_s, 2);
        if (u.estimated) {
            for (const analysis::IdentifiedField& field : fields) {
                const auto k = analysis::fullParameterOf(field);
                if (!k || *k == identification::kJmax) continue;
                std::cout << ' ' << std::setw(8)
                          << fixed(field.userValue(frame.parameters),
                                   analysis::displayDecimals(field))
                          << ' ' << std::setw(8)
                          << roundSignificant(u.std[static_cast<std::size_t>(*k)] / field.to_si, 2);
            }
        } else {
            std::cout << "   (collecting samples for the first fit)";
        }
        std::cout << ' ' << std::setw(7) << fixed(u.nis, 2) << ' ' << std::setw(7)
                  << fixed(u.cusum, 2);
        if (u.change_detected && u.change_at)
            std::cout << "  soil change confirmed, began at sample " << *u.change_at;
        std::cout << '\n';
    }
    const std::string note = "cancelled by " + cancellation.signalName() + " after " +
                             std::to_string(result.frames.size()) + " of " +
                             std::to_string(result.sample_count) + " samples";
    if (o.json) {
        if (result.cancelled)
            std::cout << nlohmann::json{{"cancelled", true}, {"note", note}}.dump() << '\n';
    } else {
        std::cout << (result.changes.empty() ? std::string("no soil change confirmed")
                                             : "soil changes confirmed, beginning at samples:");
        for (std::size_t c : result.changes) std::cout << ' ' << c;
        std::cout << '\n';
        if (result.cancelled) std::cout << note << '\n';
    }
    std::cout.flush();
    if (result.cancelled) exitCancelled(cancellation, note);
}

}  // namespace

void addIdentifyCommands(CLI::App& app, const io::PresetLocations& locations) {
    auto synth = std::make_shared<SynthOptions>();
    CLI::App* s = app.add_subcommand(
        "synth",
        "Synthetic identification data: slip sweeps at one or more loads, noise (Eq. 5.1)");
    synth->model.addTo(*s, false);
    s->add_option("--load", synth->loads, "W [N]: value, list a,b or range first:last:count")
        ->capture_default_str();
    s->add_option("--slips,--slip", synth->slips, "Slips: range first:last:count or list")
        ->capture_default_str();
    s->add_option("--slip-angle", synth->slip_angle_deg, "Slip angle [deg] (Table 5.2: 0)")
        ->capture_default_str();
    s->add_option("--noise", synth->noise,
                  "Noise per channel: fx|fz|my|theta=SIGMA (N, N·m, deg) or =P%")
        ->delimiter(',');
    s->add_option("--seed", synth->seed, "Random seed")->capture_default_str();
    s->add_option("--out", synth->out, "Output CSV (default: stdout)");
    s->callback([synth, &locations] {
        refuseInputAsOutput("--out", synth->out, synth->model.inputFiles());
        const auto soil = synth->model.soilParameters(locations);
        const auto wheel = synth->model.wheelParameters(locations);
        identification::SyntheticSpec spec;
        spec.loads_n = parseValues(synth->loads, "--load");
        spec.slips = parseValues(synth->slips, "--slips");
        spec.slip_angle_rad = units::degToRad(synth->slip_angle_deg);
        spec.seed = synth->seed;
        parseNoise(synth->noise, spec.noise);
        const SignalCancellation cancellation;
        spec.cancel = cancellation.flag();
        TerminalProgress progress("synth");
        spec.progress = progress.callback();
        const auto out =
            identification::synthesize(contact::makeContactParameters(soil, wheel), spec);
        progress.finish();
        printLines(out.warnings, "warning: ");
        // A cancelled run is written too, marked by a last comment line (the data set reader
        // skips it, so `identify` reads the partial file).
        const std::string note = "cancelled by " + cancellation.signalName() + " after " +
                                 std::to_string(out.data.samples.size()) + " samples";
        writeOutput(synth->out, identification::toCsv(out.data) +
                                    (out.cancelled ? "# " + note + "\n" : std::string()));
        if (!synth->out.empty() && synth->out != "-") {
            std::cerr << "wrote " << synth->out << ": " << out.data.samples.size() << " samples\n";
        }
        // The data carry the soil's shear limit; identify's model has none unless --jmax gives it
        // (a fit of a CSV never reads a soil). Without it the fit meets a model error at large slip
        // (docs/identification.md §11): say so where the data are made.
        if (std::isfinite(soil.max_shear_deformation_m)) {
            const std::string jmax = formatNumber(soil.max_shear_deformation_m);
            std::cerr << "note: made with the soil's j_max = " << jmax
                      << " m (Eq. 2.16): identify these data with --jmax " << jmax
                      << ", or identify j_max with --jmax fit (identify's model has no j_max "
                         "unless given)\n";
        }
        if (out.cancelled) exitCancelled(cancellation, "synth " + note);
    });

    auto identify = std::make_shared<IdentifyOptions>();
    CLI::App* i = app.add_subcommand(
        "identify",
        "Identify soil parameters from wheel data: the global identification on the full model "
        "(no start needed), or the decoupled three-step fit (Eqs. 4.12, 4.17, 4.18)");
    CLI::Option* data_option = i->add_option(
        "--data", identify->data,
        "Data set CSV: slip, entry_angle_deg, Fx_N, Fz_N, My_Nm; or from the load: slip, W_N (or "
        "--load), any of Fx_N, My_Nm, sinkage_m, Fz_N");
    CLI::Option* stream_option =
        i->add_option("--stream", identify->stream,
                      "Streaming identification: feed the samples of this CSV one at a time, one "
                      "line of estimates per sample");
    data_option->excludes(stream_option);
    i->add_option("--window", identify->window,
                  "With --stream: samples in the moving horizon (older ones live on in the "
                  "arrival cost; default " +
                      std::to_string(identification::StreamingEstimatorOptions{}.window) + ")");
    i->add_option("--wheel", identify->wheel, "Wheel preset or JSON file")->capture_default_str();
    i->add_option("--guess", identify->guess,
                  "Optional extra start: soil preset or JSON file (the global search needs none; "
                  "with --no-refine the decoupled fit's start, default thesis chapter 5)");
    i->add_flag("--json", identify->json, "JSON output");
    i->add_flag("--skip-bad-rows", identify->skip_bad_rows,
                "Skip invalid rows instead of stopping");
    i->add_flag("--refine,!--no-refine", identify->refine,
                "Identify a0, a1, Ks_kPa, n0, c_kPa, phi_deg, K_m on the full model by a global "
                "search (removes "
                "the linearisation bias; the default); --no-refine: the decoupled fit alone")
        ->capture_default_str();
    i->add_option("--prior", identify->prior,
                  "Gaussian priors: NAME=MEAN±STD (or +-) with NAME a key of the output (a0, a1, "
                  "Ks_kPa, n0, c_kPa, phi_deg, K_m, jmax_m; the old Ks, n still read), and/or one "
                  "soil preset or file (±0.1 a0/a1, ±50 % Ks, c, K, ±0.2 n, ±5 deg phi); "
                  "repeatable")
        ->delimiter(',');
    i->add_option("--holdout", identify->holdout,
                  "Held-out error: predict this fraction (0, 1) of the samples from a fit "
                  "without them");
    i->add_option("--folds", identify->folds, "Held-out error by K-fold cross-validation (K ≥ 2)");
    i->add_option("--starts", identify->starts,
                  "Points of the space-filling design of starts (default 64; presets and --guess "
                  "come on top)");
    i->add_option("--loss", identify->loss, "Loss: l2, huber or cauchy (outliers)")
        ->capture_default_str();
    i->add_option("--load", identify->load_n,
                  "W [N] of every row without a W_N cell (data without an entry angle)");
    i->add_flag(
        "--profile", identify->profile,
        "Profile-likelihood intervals (delta chi2 = 9) of the parameters in a flagged "
        "trade-off or at a bound (JSON key profile_interval; up to 10 refinements per side)");
    i->add_option("--fix", identify->fix,
                  "Refinement: keep parameters fixed, e.g. a0=0.2,a1=0.3 (keys of the output, as "
                  "--prior)")
        ->delimiter(',');
    i->add_option(
         "--noise", identify->noise,
         "Refinement: noise levels fx=N,fz=N,my=Nm weighting the residuals (default: estimated)")
        ->delimiter(',');
    i->add_option("--save-soil", identify->save_soil,
                  "Write the identified soil to this soil file (k_c = 0, k_phi = Ks), with its "
                  "posterior (mean and covariance in the soil file's keys) for traction, bands "
                  "and gsa --posterior");
    i->add_option("--jmax", identify->jmax,
                  "Full model: the model's j_max [m] held at this value, or 'fit' to identify it "
                  "as an eighth parameter (with a prior of 20 ± 20 mm when the data do not "
                  "determine it; --prior jmax_m=MEAN±STD gives another); default: none, not "
                  "taken from --guess");
    i->add_option("--threads", identify->threads,
                  "Full model: threads of the global search (0: one per core, the default; the "
                  "same numbers whatever the count)");
    i->callback([identify, refine = i->get_option("--refine"), &locations] {
        const IdentifyOptions& o = *identify;
        if (o.data.empty() == o.stream.empty())
            throw InputError("give --data FILE or --stream FILE");
        const bool streaming = !o.stream.empty();
        if (streaming && refine->count() > 0 && o.refine)
            throw InputError("--refine does not apply to --stream");
        if (streaming && (!o.prior.empty() || o.holdout || o.folds || o.starts || o.loss != "l2" ||
                          o.profile || o.threads))
            throw InputError(
                "--prior, --holdout, --folds, --starts, --loss, --profile and --threads do not "
                "apply to --stream");
        constexpr int kMaxThreads = identification::IdentifyOptions::kMaxThreads;
        if (o.threads && (*o.threads < 0 || *o.threads > kMaxThreads))
            throw InputError("--threads " + std::to_string(*o.threads) +
                             ": outside the allowed range [0, " + std::to_string(kMaxThreads) +
                             "] (0: one per core)");
        if (streaming && !o.save_soil.empty())
            throw InputError("--save-soil does not apply to --stream");
        ModelOptions names;
        names.wheel = o.wheel;
        analysis::Inputs inputs;
        inputs.wheel = names.wheelParameters(locations);
        identification::DecoupledParameters guess;
        // The fit never uses the inputs' soil for a CSV (j_max is --jmax, else none).
        inputs.soil.max_shear_deformation_m = std::numeric_limits<double>::infinity();
        std::optional<soil::SoilParameters> guess_soil;
        if (!o.guess.empty()) {
            names.soil = o.guess;
            guess_soil = names.soilParameters(locations);
            guess = identification::decoupledOf(*guess_soil, inputs.wheel);
        }
        if (streaming) {
            runStream(o, inputs, guess_soil);
            return;
        }
        if (!o.save_soil.empty()) {
            std::vector<NamedInput> files = names.inputFiles();
            files.push_back({"--data", o.data});
            refuseInputAsOutput("--save-soil", o.save_soil, files);
        }
        const bool global_flags = !o.prior.empty() || o.holdout || o.folds || o.starts ||
                                  o.load_n || o.loss != "l2" || o.profile || o.threads;
        if (!o.refine && (!o.fix.empty() || !o.noise.empty() || o.jmax || global_flags)) {
            throw InputError(
                "--fix, --noise, --jmax, --prior, --holdout, --folds, --starts, --loss, --load, "
                "--profile and --threads belong to the full model (drop --no-refine)");
        }
        analysis::IdentificationSettings settings = identifySettings(o, locations);
        settings.guess = guess;
        if (o.refine && guess_soil) {
            settings.starts.push_back(
                {"guess " + o.guess, identification::fromSoil(*guess_soil, inputs.wheel)});
        }
        const SignalCancellation cancellation;
        TerminalProgress progress("identify");
        analysis::IdentificationResult result;
        try {
            analysis::Control control{cancellation.flag(), progress.callback()};
            control.threads = o.threads.value_or(0);
            result = analysis::computeIdentification(inputs, settings, control);
        } catch (const std::invalid_argument& e) {
            throw InputError(e.what());
        }
        progress.finish();
        if (result.status == analysis::Outcome::Status::kCancelled) {
            exitCancelled(cancellation, "identify cancelled by " + cancellation.signalName() +
                                            ": nothing written (a fit stopped halfway has no "
                                            "result; docs/cli.md, \"Stopping a long command\")");
        }
        if (!result.data_issues.empty()) {
            // The hint only where rows are bad (FILE:LINE), not for a file that cannot be read.
            const bool rows = std::any_of(
                result.data_issues.begin(), result.data_issues.end(), [](const Issue& issue) {
                    const auto colon = issue.where.rfind(':');
                    return colon != std::string::npos && colon + 1 < issue.where.size() &&
                           std::isdigit(static_cast<unsigned char>(issue.where[colon + 1]));
                });
            throw InputError(result.message +
                             (rows ? "\n(use --skip-bad-rows to skip bad rows)" : ""));
        }
        if (!result.message.empty()) throw InputError(o.data + ": " + result.message);
        std::vector<std::string> skipped;
        for (const Issue& issue : result.skipped)
            skipped.push_back("skipped " + issue.where + ": " + issue.message);
        printLines(skipped, "");
        printLines(result.warnings, "warning: ");
        if (o.json) {
            std::cout << analysis::toJson(result).dump(2) << '\n';
        } else {
            printSummary(std::cout, analysis::identificationSummary(result));
        }
        if (!result.usable())
            throw std::runtime_error("the fit did not converge to a usable solution");
        if (!o.save_soil.empty())
            saveSoil(o, result, guess_soil.value_or(soil::SoilParameters{}), inputs.wheel,
                     settings);
    });
}

}  // namespace terra::app
