// `terrastudio synth` (synthetic identification data, thesis chapter 5) and `terrastudio identify`
// (the decoupled three-step fit, §4.3).
#include <iomanip>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>

#include "app/cli/cli_support.h"
#include "app/cli/commands.h"
#include "app/cli/signals.h"
#include "core/analysis/identification.h"
#include "core/analysis/identified_parameters.h"
#include "core/analysis/streaming_identification.h"
#include "core/common/range.h"
#include "core/common/units.h"
#include "core/contact/operating_fields.h"
#include "core/identification/synthetic.h"
#include "core/io/csv.h"

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
        if (!io::parseNumber(value, sigma))
            throw InputError("--noise '" + item + "': not a number");
        checkRange(issues, "--noise " + key, sigma, {0.0, percent ? 1000.0 : 1e6});
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
    std::vector<std::string> fix;    // key=value, identified_parameters.h keys
    std::vector<std::string> noise;  // fx=, fz=, my= noise levels for the refinement weights
    std::optional<double> jmax_m;
    std::string stream;  // --stream FILE: one estimate per sample
    std::size_t window = identification::StreamingOptions{}.window;
};

// Decimals of an identified parameter in the text output (K_s in kPa/m^n is in the thousands).
int decimals(const analysis::IdentifiedField& field) {
    const std::string key = field.key;
    return key == "Ks_kPa" ? 1 : key == "c_kPa" ? 3 : key == "phi_deg" ? 2 : 4;
}

// One identified parameter for a human: its symbol, value (and ± std) and unit.
std::string shown(const analysis::IdentifiedField& field, double si,
                  const std::optional<double>& std_si = std::nullopt) {
    std::string text = std::string(field.symbol) + " = " + fixed(field.toUser(si), decimals(field));
    if (std_si && *std_si > 0) text += " ± " + fixed(*std_si / field.to_si, 4);
    const std::string unit = field.displayUnit();
    return unit.empty() ? text : text + " " + unit;
}

// The identified parameters as JSON: the field table's keys in its units.
nlohmann::json parametersJson(const identification::DecoupledParameters& p) {
    nlohmann::json j = nlohmann::json::object();
    for (const analysis::IdentifiedField& field : analysis::identifiedFields())
        j[field.key] = field.userValue(p);
    return j;
}

// `identify --stream FILE`: the samples fed one at a time to the streaming identifier
// (core/analysis/streaming_identification.h), one line per sample (JSON Lines with --json), then
// the detected soil changes.
void runStream(const IdentifyOptions& o, const analysis::Inputs& inputs,
               const identification::DecoupledParameters& guess) {
    analysis::StreamingSettings settings;
    settings.csv = o.stream;
    settings.skip_bad_rows = o.skip_bad_rows;
    settings.options.initial = guess;
    settings.options.window = o.window;
    analysis::StreamSource source;
    try {
        source = analysis::streamSource(inputs, settings);
    } catch (const std::invalid_argument& e) {
        throw InputError(std::string(e.what()) + "\n(use --skip-bad-rows to skip bad rows)");
    }
    // The data are read: a signal from now on stops the identifier after the sample in hand.
    const SignalCancellation cancellation;
    const analysis::StreamingResult result = analysis::playStreaming(
        std::move(source), inputs.wheel, settings.options, cancellation.flag());
    for (const std::string& w : result.source.warnings) std::cerr << w << '\n';
    if (!o.json) {
        std::cout << "sample  time_s";
        for (const analysis::IdentifiedField& field : analysis::identifiedFields())
            std::cout << ' ' << std::setw(8) << field.key;
        std::cout << "   score  window\n";
    }
    for (const analysis::StreamFrame& frame : result.frames) {
        const identification::StreamUpdate& u = frame.update;
        if (o.json) {
            nlohmann::json j{{"sample", u.index},
                             {"estimated", u.estimated},
                             {"window", u.window_size},
                             {"score", roundSignificant(u.residual_score, 4)}};
            j["time_s"] = frame.time_s;
            if (u.estimated) j.update(parametersJson(u.parameters));
            if (u.change_at) j["change_at"] = *u.change_at;
            std::cout << j.dump() << '\n';
            continue;
        }
        std::cout << std::setw(6) << u.index << ' ' << std::setw(7) << fixed(frame.time_s, 2);
        if (u.estimated) {
            for (const analysis::IdentifiedField& field : analysis::identifiedFields()) {
                std::cout << ' ' << std::setw(8)
                          << fixed(field.userValue(u.parameters), decimals(field));
            }
        } else {
            std::cout << "   (collecting samples)                                              ";
        }
        std::cout << ' ' << std::setw(7) << fixed(u.residual_score, 2) << ' ' << std::setw(7)
                  << u.window_size;
        if (u.change_at) std::cout << "  soil change since sample " << *u.change_at;
        std::cout << '\n';
    }
    const std::string note = "cancelled by " + cancellation.signalName() + " after " +
                             std::to_string(result.frames.size()) + " of " +
                             std::to_string(result.sample_count) + " samples";
    if (o.json) {
        if (result.cancelled)
            std::cout << nlohmann::json{{"cancelled", true}, {"note", note}}.dump() << '\n';
    } else {
        std::cout << (result.changes.empty() ? std::string("no soil change detected")
                                             : "soil changes detected at samples:");
        for (std::size_t c : result.changes) std::cout << ' ' << c;
        std::cout << '\n';
        if (result.cancelled) std::cout << note << '\n';
    }
    std::cout.flush();
    if (result.cancelled) exitCancelled(cancellation, note);
}

// --fix a0=0.2,a1=0.3: identified_parameters.h keys, values in their units.
std::vector<std::pair<std::string, double>> parseFixes(const std::vector<std::string>& items) {
    std::vector<std::string> keys;
    for (const analysis::IdentifiedField& field : analysis::identifiedFields()) {
        if (analysis::fullParameterOf(field)) keys.emplace_back(field.key);
    }
    std::string list;
    for (const std::string& k : keys) list += (list.empty() ? "" : ", ") + k;
    std::vector<std::pair<std::string, double>> out;
    std::vector<Issue> issues;
    for (const std::string& item : items) {
        const auto equals = item.find('=');
        const std::string key = item.substr(0, equals);
        double value = 0.0;
        if (equals == std::string::npos || !io::parseNumber(item.substr(equals + 1), value)) {
            issues.push_back({"--fix " + item, "expected NAME=VALUE, NAME one of " + list});
        } else if (std::find(keys.begin(), keys.end(), key) == keys.end()) {
            const std::string near = nearestName(key, keys);
            issues.push_back(
                {"--fix " + key, "not a refined parameter (" + list + ")" +
                                     (near.empty() ? "" : "; did you mean " + near + "?")});
        } else {
            const analysis::IdentifiedField& field = *analysis::findIdentifiedField(key);
            if (checkRange(issues, "--fix " + key, value, field.range, field.displayUnit()))
                out.emplace_back(key, value);
        }
    }
    if (!issues.empty()) throw InputError(formatIssues(issues));
    return out;
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
    s->add_option("--slips", synth->slips, "Slips: range first:last:count or list")
        ->capture_default_str();
    s->add_option("--slip-angle", synth->slip_angle_deg, "Slip angle [deg] (Table 5.2: 0)")
        ->capture_default_str();
    s->add_option("--noise", synth->noise,
                  "Noise per channel: fx|fz|my|theta=SIGMA (N, N·m, deg) or =P%")
        ->delimiter(',');
    s->add_option("--seed", synth->seed, "Random seed")->capture_default_str();
    s->add_option("--out", synth->out, "Output CSV (default: stdout)");
    s->callback([synth, &locations] {
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
        const auto out =
            identification::synthesize(contact::makeContactParameters(soil, wheel), spec);
        for (const std::string& w : out.warnings) std::cerr << "warning: " << w << '\n';
        // A cancelled run is written too, marked by a last comment line (the data set reader
        // skips it, so `identify` reads the partial file).
        const std::string note = "cancelled by " + cancellation.signalName() + " after " +
                                 std::to_string(out.data.samples.size()) + " samples";
        writeOutput(synth->out, identification::toCsv(out.data) +
                                    (out.cancelled ? "# " + note + "\n" : std::string()));
        if (!synth->out.empty() && synth->out != "-") {
            std::cerr << "wrote " << synth->out << ": " << out.data.samples.size() << " samples\n";
        }
        if (out.cancelled) exitCancelled(cancellation, "synth " + note);
    });

    auto identify = std::make_shared<IdentifyOptions>();
    CLI::App* i = app.add_subcommand("identify",
                                     "Identify soil parameters from wheel data: the decoupled "
                                     "three-step fit (Eqs. 4.12, 4.17, 4.18)");
    CLI::Option* data_option = i->add_option(
        "--data", identify->data, "Data set CSV (slip, entry_angle_deg, Fx_N, Fz_N, My_Nm)");
    CLI::Option* stream_option =
        i->add_option("--stream", identify->stream,
                      "Streaming identification: feed the samples of this CSV one at a time, one "
                      "line of estimates per sample");
    data_option->excludes(stream_option);
    i->add_option("--window", identify->window, "With --stream: samples in the sliding window")
        ->capture_default_str()
        ->check(CLI::Range(std::size_t{12}, std::size_t{100000}));
    i->add_option("--wheel", identify->wheel, "Wheel preset or JSON file")->capture_default_str();
    i->add_option("--guess", identify->guess,
                  "Initial guess: soil preset or JSON file (default: thesis chapter 5)");
    i->add_flag("--json", identify->json, "JSON output");
    i->add_flag("--skip-bad-rows", identify->skip_bad_rows,
                "Skip invalid rows instead of stopping");
    i->add_flag("--refine,!--no-refine", identify->refine,
                "Refine a0, a1, Ks, n, c, phi, K with the full model (removes the linearisation "
                "bias; the default); --no-refine: the decoupled fit alone")
        ->capture_default_str();
    i->add_option("--fix", identify->fix,
                  "Refinement: keep parameters fixed, e.g. a0=0.2,a1=0.3 (keys of the output)")
        ->delimiter(',');
    i->add_option(
         "--noise", identify->noise,
         "Refinement: noise levels fx=N,fz=N,my=Nm weighting the residuals (default: estimated)")
        ->delimiter(',');
    i->add_option("--jmax", identify->jmax_m,
                  "Refinement: the model's j_max [m] (default: the guess soil's, else none)");
    i->callback([identify, refine = i->get_option("--refine"), &locations] {
        const IdentifyOptions& o = *identify;
        if (o.data.empty() == o.stream.empty())
            throw InputError("give --data FILE or --stream FILE");
        const bool streaming = !o.stream.empty();
        if (streaming && refine->count() > 0 && o.refine)
            throw InputError("--refine does not apply to --stream");
        ModelOptions names;
        names.wheel = o.wheel;
        analysis::Inputs inputs;
        inputs.wheel = names.wheelParameters(locations);
        identification::DecoupledParameters guess;
        // j_max of the forward model: --jmax, else the guess soil's, else none.
        inputs.soil.max_shear_deformation_m = std::numeric_limits<double>::infinity();
        if (!o.guess.empty()) {
            names.soil = o.guess;
            inputs.soil = names.soilParameters(locations);
            guess = analysis::identifiedOf(inputs.soil, inputs.wheel);
        }
        if (streaming) {
            runStream(o, inputs, guess);
            return;
        }
        if (!o.refine && (!o.fix.empty() || !o.noise.empty() || o.jmax_m)) {
            throw InputError(
                "--fix, --noise and --jmax belong to the refinement (drop --no-refine)");
        }
        analysis::IdentificationSettings settings;
        settings.csv = o.data;
        settings.skip_bad_rows = o.skip_bad_rows;
        settings.guess = guess;
        settings.refine = o.refine;
        settings.fixed = parseFixes(o.fix);
        identification::NoiseSpec noise;
        parseNoise(o.noise, noise);
        settings.sigma_fx_n = noise.fx.absolute;
        settings.sigma_fz_n = noise.fz.absolute;
        settings.sigma_my_nm = noise.my.absolute;
        if (o.jmax_m) {
            std::vector<Issue> issues;
            const soil::SoilField& jmax = *soil::findSoilField("jmax_m");
            checkRange(issues, "--jmax", *o.jmax_m, jmax.range, jmax.displayUnit());
            if (!issues.empty()) throw InputError(formatIssues(issues));
            settings.max_shear_deformation_m = *o.jmax_m;
        }
        const analysis::IdentificationResult result =
            analysis::computeIdentification(inputs, settings);
        if (!result.data_issues.empty())
            throw InputError(result.message + "\n(use --skip-bad-rows to skip bad rows)");
        if (!result.message.empty()) throw InputError(o.data + ": " + result.message);
        for (const Issue& skipped : result.skipped)
            std::cerr << "skipped " << skipped.where << ": " << skipped.message << '\n';
        const identification::DecoupledParameters& p = result.identified;
        const std::optional<identification::Uncertainty> uncertainty =
            result.refined ? std::optional(result.refined->uncertainty) : std::nullopt;
        const std::vector<identification::StepReport> reports = result.steps();
        nlohmann::json j = parametersJson(p);
        if (uncertainty) {
            nlohmann::json std_json = nlohmann::json::object();
            for (int k = 0; k < identification::kFullParameterCount; ++k) {
                const analysis::IdentifiedField& field =
                    analysis::fieldOf(static_cast<identification::FullParameter>(k));
                std_json[field.key] =
                    uncertainty->computed
                        ? nlohmann::json(uncertainty->std[static_cast<std::size_t>(k)] /
                                         field.to_si)
                        : nlohmann::json();
            }
            j["std"] = std_json;
            j["flags"] = uncertainty->flags;
        }
        nlohmann::json steps = nlohmann::json::array();
        for (const auto& step : reports) {
            steps.push_back({{"step", step.name},
                             {"usable", step.usable},
                             {"termination", step.termination},
                             {"iterations", step.iterations},
                             {"squared_residual_norm", step.squared_residual_norm},
                             {"time_ms", step.wall_time_ms}});
        }
        j["steps"] = steps;
        j["samples"] = result.data.samples.size();
        if (o.json) {
            std::cout << j.dump(2) << '\n';
        } else {
            std::cout << (o.refine ? "full-model identification (decoupled start), "
                                   : "decoupled identification, ")
                      << result.data.samples.size() << " samples, " << inputs.wheel.name << "\n";
            int column = 0;
            for (const analysis::IdentifiedField& field : analysis::identifiedFields()) {
                const auto full = analysis::fullParameterOf(field);
                if (o.refine && !full) continue;  // n1 = 0 after the refinement
                std::optional<double> sd;
                if (uncertainty && uncertainty->computed && full)
                    sd = uncertainty->std[static_cast<std::size_t>(*full)];
                std::cout << (column % 3 == 0 ? "  " : "   ") << shown(field, p.*field.member, sd)
                          << (column % 3 == 2 ? "\n" : "");
                ++column;
            }
            if (column % 3 != 0) std::cout << '\n';
            for (const auto& step : reports) {
                std::cout << "  step " << step.name << ": |r|^2 = " << step.squared_residual_norm
                          << ", " << fixed(step.wall_time_ms, 2) << " ms, " << step.termination
                          << '\n';
            }
            if (uncertainty) {
                for (const std::string& flag : uncertainty->flags)
                    std::cout << "  note: " << flag << '\n';
            }
        }
        if (!result.usable())
            throw std::runtime_error("the fit did not converge to a usable solution");
    });
}

}  // namespace terra::app
