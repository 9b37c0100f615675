// `terrastudio synth` (synthetic identification data, thesis chapter 5) and `terrastudio identify`
// (the decoupled three-step fit, §4.3).
#include <iomanip>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>

#include "app/cli/cli_support.h"
#include "app/cli/commands.h"
#include "app/cli/signals.h"
#include "core/common/range.h"
#include "core/common/units.h"
#include "core/identification/decoupled_fit.h"
#include "core/identification/full_fit.h"
#include "core/identification/streaming.h"
#include "core/identification/synthetic.h"
#include "core/io/csv.h"

namespace terra::app {
namespace {

struct SynthOptions {
    ModelOptions model;
    std::string loads = "58.86";
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
    bool refine = false;
    std::vector<std::string> fix;    // name=value
    std::vector<std::string> noise;  // fx=, fz=, my= noise levels for the refinement weights
    std::optional<double> jmax_m;
    std::string stream;  // --stream FILE: one estimate per sample
    std::size_t window = 60;
};

// `identify --stream FILE`: feeds the samples one at a time to the streaming identifier and
// prints one line per sample (JSON Lines with --json), then the detected soil changes.
void runStream(const IdentifyOptions& o, const identification::DataSet& data,
               const wheel::WheelParameters& wheel,
               const identification::DecoupledParameters& guess) {
    identification::StreamingOptions options;
    options.initial = guess;
    options.window = o.window;
    identification::StreamingIdentifier identifier(wheel, options);
    std::vector<std::size_t> changes;
    const SignalCancellation cancellation;
    std::size_t fed = 0;
    if (!o.json) {
        std::cout << "sample  time_s      a0      a1   Ks_kPa      n0      n1   c_kPa  phi_deg     "
                     "K_m   score  window\n";
    }
    for (const identification::Sample& sample : data.samples) {
        if (cancellation.requested()) break;
        ++fed;
        const identification::StreamUpdate u = identifier.push(sample);
        if (u.change_detected && u.change_at) changes.push_back(*u.change_at);
        const identification::DecoupledParameters& p = u.parameters;
        if (o.json) {
            nlohmann::json j{{"sample", u.index},
                             {"estimated", u.estimated},
                             {"window", u.window_size},
                             {"score", roundSignificant(u.residual_score, 4)}};
            if (sample.time_s) j["time_s"] = *sample.time_s;
            if (u.estimated) {
                j.update({{"a0", p.a0},
                          {"a1", p.a1},
                          {"Ks", p.pressure_modulus / 1e3},
                          {"n0", p.n0},
                          {"n1", p.n1},
                          {"c_kPa", p.cohesion_pa / 1e3},
                          {"phi_deg", units::radToDeg(p.friction_angle_rad)},
                          {"K_m", p.shear_modulus_m}});
            }
            if (u.change_at) j["change_at"] = *u.change_at;
            std::cout << j.dump() << '\n';
            continue;
        }
        std::cout << std::setw(6) << u.index << ' ' << std::setw(7)
                  << (sample.time_s ? fixed(*sample.time_s, 2) : "-");
        if (u.estimated) {
            std::cout << ' ' << std::setw(7) << fixed(p.a0, 4) << ' ' << std::setw(7)
                      << fixed(p.a1, 4) << ' ' << std::setw(8) << fixed(p.pressure_modulus / 1e3, 1)
                      << ' ' << std::setw(7) << fixed(p.n0, 4) << ' ' << std::setw(7)
                      << fixed(p.n1, 4) << ' ' << std::setw(7) << fixed(p.cohesion_pa / 1e3, 3)
                      << ' ' << std::setw(8) << fixed(units::radToDeg(p.friction_angle_rad), 2)
                      << ' ' << std::setw(7) << fixed(p.shear_modulus_m, 4);
        } else {
            std::cout
                << "   (collecting samples)                                                  ";
        }
        std::cout << ' ' << std::setw(7) << fixed(u.residual_score, 2) << ' ' << std::setw(7)
                  << u.window_size;
        if (u.change_at) std::cout << "  soil change since sample " << *u.change_at;
        std::cout << '\n';
    }
    const std::string note = "cancelled by " + cancellation.signalName() + " after " +
                             std::to_string(fed) + " of " + std::to_string(data.samples.size()) +
                             " samples";
    const bool cancelled = fed < data.samples.size();
    if (o.json) {
        if (cancelled)
            std::cout << nlohmann::json{{"cancelled", true}, {"note", note}}.dump() << '\n';
    } else {
        std::cout << (changes.empty() ? std::string("no soil change detected")
                                      : "soil changes detected at samples:");
        for (std::size_t c : changes) std::cout << ' ' << c;
        std::cout << '\n';
        if (cancelled) std::cout << note << '\n';
    }
    std::cout.flush();
    if (cancelled) exitCancelled(cancellation, note);
}

// --fix a0=0.2,a1=0.3 in the output units (Ks kPa/m^n, c kPa, phi deg).
void applyFixes(const std::vector<std::string>& items, identification::DecoupledParameters& p,
                identification::RefineOptions& options) {
    using namespace identification;
    for (const std::string& item : items) {
        const auto equals = item.find('=');
        const std::string key = item.substr(0, equals);
        double value = 0.0;
        if (equals == std::string::npos || !io::parseNumber(item.substr(equals + 1), value)) {
            throw InputError(
                "--fix '" + item +
                "': expected NAME=VALUE, NAME one of a0, a1, Ks, n, c_kPa, phi_deg, K_m");
        }
        if (key == "a0")
            p.a0 = value, options.fixed[kA0] = true;
        else if (key == "a1")
            p.a1 = value, options.fixed[kA1] = true;
        else if (key == "Ks")
            p.pressure_modulus = value * 1e3, options.fixed[kKs] = true;
        else if (key == "n")
            p.n0 = value, options.fixed[kN] = true;
        else if (key == "c_kPa")
            p.cohesion_pa = value * 1e3, options.fixed[kC] = true;
        else if (key == "phi_deg")
            p.friction_angle_rad = units::degToRad(value), options.fixed[kPhi] = true;
        else if (key == "K_m")
            p.shear_modulus_m = value, options.fixed[kK] = true;
        else
            throw InputError("--fix '" + key +
                             "': unknown; one of a0, a1, Ks, n, c_kPa, phi_deg, K_m");
    }
}

// Output units of the identified parameters: Ks in kPa/m^n, c in kPa, phi in deg.
double outputValue(int k, double si) {
    using namespace identification;
    if (k == kKs || k == kC) return si / 1e3;
    if (k == kPhi) return units::radToDeg(si);
    return si;
}

identification::DecoupledParameters guessFrom(const soil::SoilParameters& soil,
                                              const wheel::WheelParameters& wheel) {
    return {soil.max_stress_a0,
            soil.max_stress_a1,
            soil.cohesive_modulus / wheel.width_m + soil.frictional_modulus,
            soil.sinkage_exponent,
            soil.sinkage_exponent_slip,
            soil.cohesion_pa,
            soil.friction_angle_rad,
            soil.shear_modulus_m};
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
    i->add_flag(
        "--refine", identify->refine,
        "Refine a0, a1, Ks, n, c, phi, K with the full model (removes the linearisation bias)");
    i->add_option("--fix", identify->fix,
                  "With --refine: keep parameters fixed, e.g. a0=0.2,a1=0.3")
        ->delimiter(',');
    i->add_option(
         "--noise", identify->noise,
         "With --refine: noise levels fx=N,fz=N,my=Nm weighting the residuals (default: estimated)")
        ->delimiter(',');
    i->add_option("--jmax", identify->jmax_m,
                  "With --refine: the model's j_max [m] (default: the guess soil's, else none)");
    i->callback([identify, &locations] {
        if (identify->data.empty() == identify->stream.empty())
            throw InputError("give --data FILE or --stream FILE");
        const bool streaming = !identify->stream.empty();
        if (streaming && identify->refine) throw InputError("--refine does not apply to --stream");
        const auto read =
            identification::readDataSet(streaming ? identify->stream : identify->data,
                                        identify->skip_bad_rows ? identification::BadRows::kSkip
                                                                : identification::BadRows::kStop);
        if (!read) throw InputError(read.message() + "\n(use --skip-bad-rows to skip bad rows)");
        for (const Issue& skipped : read->skipped)
            std::cerr << "skipped " << skipped.where << ": " << skipped.message << '\n';
        if (read->data.samples.empty())
            throw InputError((streaming ? identify->stream : identify->data) +
                             ": no valid samples");
        ModelOptions names;
        names.wheel = identify->wheel;
        const auto wheel = names.wheelParameters(locations);
        identification::DecoupledParameters guess;
        if (!identify->guess.empty()) {
            names.soil = identify->guess;
            guess = guessFrom(names.soilParameters(locations), wheel);
        }
        if (streaming) {
            runStream(*identify, read->data, wheel, guess);
            return;
        }
        const auto fit = identification::fitDecoupled(read->data, wheel, guess);
        identification::DecoupledParameters p = fit.parameters;
        std::vector<identification::StepReport> reports = fit.steps;
        std::optional<identification::Uncertainty> uncertainty;
        if (!identify->refine &&
            (!identify->fix.empty() || !identify->noise.empty() || identify->jmax_m)) {
            throw InputError("--fix, --noise and --jmax belong to --refine");
        }
        if (identify->refine) {
            identification::RefineOptions options;
            applyFixes(identify->fix, p, options);
            identification::NoiseSpec noise;
            parseNoise(identify->noise, noise);
            options.sigma_fx = noise.fx.absolute;
            options.sigma_fz = noise.fz.absolute;
            options.sigma_my = noise.my.absolute;
            if (identify->jmax_m) {
                std::vector<Issue> issues;
                checkRange(issues, "--jmax", *identify->jmax_m, {0.0, 1.0, true, false}, "m");
                if (!issues.empty()) throw InputError(formatIssues(issues));
                options.max_shear_deformation_m = *identify->jmax_m;
            } else if (!identify->guess.empty()) {
                options.max_shear_deformation_m =
                    names.soilParameters(locations).max_shear_deformation_m;
            }
            const auto refined = identification::refineFullModel(read->data, wheel, p, options);
            p = refined.parameters;
            reports.push_back(refined.report);
            uncertainty = refined.uncertainty;
        }
        nlohmann::json j{{"a0", p.a0},
                         {"a1", p.a1},
                         {"Ks", p.pressure_modulus / 1e3},
                         {"n0", p.n0},
                         {"n1", p.n1},
                         {"c_kPa", p.cohesion_pa / 1e3},
                         {"phi_deg", units::radToDeg(p.friction_angle_rad)},
                         {"K_m", p.shear_modulus_m}};
        if (identify->refine) j["n"] = p.n0;
        if (uncertainty) {
            nlohmann::json std_json = nlohmann::json::object();
            for (int k = 0; k < identification::kFullParameterCount; ++k) {
                std_json[identification::fullParameterNames()[k]] =
                    uncertainty->computed ? nlohmann::json(outputValue(k, uncertainty->std[k]))
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
        j["samples"] = read->data.samples.size();
        if (identify->json) {
            std::cout << j.dump(2) << '\n';
        } else {
            auto pm = [&](int k) {
                return uncertainty && uncertainty->computed && uncertainty->std[k] > 0
                           ? " ± " + fixed(outputValue(k, uncertainty->std[k]), 4)
                           : std::string();
            };
            using namespace identification;
            std::cout << (identify->refine ? "full-model identification (decoupled start), "
                                           : "decoupled identification, ")
                      << read->data.samples.size() << " samples, " << wheel.name << "\n"
                      << "  a0 = " << fixed(p.a0, 4) << pm(kA0) << "   a1 = " << fixed(p.a1, 4)
                      << pm(kA1) << "\n"
                      << "  Ks = " << fixed(p.pressure_modulus / 1e3, 1) << pm(kKs) << " kPa/m^n   "
                      << (identify->refine ? "n = " + fixed(p.n0, 4) + pm(kN)
                                           : "n0 = " + fixed(p.n0, 4) + "   n1 = " + fixed(p.n1, 4))
                      << "\n"
                      << "  c = " << fixed(p.cohesion_pa / 1e3, 3) << pm(kC)
                      << " kPa   phi = " << fixed(units::radToDeg(p.friction_angle_rad), 2)
                      << pm(kPhi) << " deg   K = " << fixed(p.shear_modulus_m, 4) << pm(kK)
                      << " m\n";
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
        bool usable = fit.usable();
        for (const auto& step : reports) usable = usable && step.usable;
        if (!usable) throw std::runtime_error("the fit did not converge to a usable solution");
    });
}

}  // namespace terra::app
