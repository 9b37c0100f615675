#include <iostream>
#include <nlohmann/json.hpp>

#include "app/cli/cli_support.h"
#include "app/cli/commands.h"
#include "app/cli/progress.h"
#include "app/cli/settings_flags.h"
#include "app/cli/signals.h"
#include "core/analysis/forces.h"
#include "core/analysis/sensitivity.h"
#include "core/common/units.h"
#include "core/io/csv.h"
#include "core/io/table_json.h"

namespace terra::app {
namespace {

// The defaults of the sweeps are the conditions' (core/analysis/conditions.h).
std::string defaultGrid() {
    const analysis::OperatingConditions c;
    return "0:" + formatNumber(c.slip_max) + ":" + std::to_string(c.slip_count);
}

std::string joined(const std::vector<double>& values) {
    std::string text;
    for (double v : values) {
        if (!text.empty()) text += ',';
        text += formatNumber(v);
    }
    return text;
}

struct SweepOptions {
    ModelOptions model;
    std::string slips;  // empty: the conditions' grid
    std::string slip_angles = joined(analysis::OperatingConditions{}.slip_angles_deg);
    std::string slip_angles_flag = "--slip-angles";
    std::optional<double> load_n;
    std::optional<double> entry_angle_deg;
    bool json = false;
    std::string out;
    // sensitivity only
    analysis::SensitivitySettings sensitivity;
    std::string values;

    analysis::Inputs inputs(const io::PresetLocations& locations) const {
        refuseInputAsOutput("--out", out, model.inputFiles());
        analysis::Inputs in = model.inputs(locations);
        in.conditions.slip_angles_deg = parseValues(slip_angles, slip_angles_flag);
        if (load_n) in.conditions.load_n = *load_n;
        return in;
    }
    // The flags of the sweep as its settings object (the keys of ForcesSettings::visitFields).
    nlohmann::json forcesObject() const {
        nlohmann::json s = nlohmann::json::object();
        if (entry_angle_deg) s["entry_angle_deg"] = *entry_angle_deg;
        if (!slips.empty()) s["slips"] = parseValues(slips, "--slips");
        addModelChoices(model, s);
        return s;
    }
    // The forces' settings of the flags, read by their reader (exit 2 names the flag).
    analysis::ForcesSettings forces() const {
        return readFlagSettings<analysis::ForcesSettings>(
            forcesObject(), analysis::readForcesSettings, forcesFlags());
    }
    // The sensitivity's: the sweep's keys and its own.
    analysis::SensitivitySettings sensitivitySettings() const {
        nlohmann::json s = forcesObject();
        s["parameter"] = sensitivity.parameter;
        s["slip_angle_deg"] = parseValues(slip_angles, slip_angles_flag);
        if (!values.empty()) s["values"] = parseValues(values, "--values");
        FlagNames names = forcesFlags();
        names.insert(names.end(), {{"parameter", "--parameter"},
                                   {"slip_angle_deg", slip_angles_flag},
                                   {"values", "--values"}});
        return readFlagSettings<analysis::SensitivitySettings>(s, analysis::readSensitivitySettings,
                                                               names, sensitivity);
    }
    static FlagNames forcesFlags() {
        return {{"entry_angle_deg", "--entry-angle"}, {"slips", "--slips"}};
    }
};

// Writes the table; a cancelled sweep is written too, marked: "cancelled": true in JSON, a last
// comment line in CSV (which the CSV readers skip), then the cancellation's exit code.
void emit(const SweepOptions& o, const analysis::SweepResult& result,
          const SignalCancellation& cancellation) {
    printLines(result.warnings, "warning: ");
    const std::string note = "cancelled by " + cancellation.signalName() + " after " +
                             std::to_string(result.table.rows.size()) + " rows";
    std::string text;
    if (o.json) {
        nlohmann::json j{{"rows", io::toJson(result.table)}, {"warnings", result.warnings}};
        if (result.cancelled) j.update({{"cancelled", true}, {"note", note}});
        text = j.dump(2) + "\n";
    } else {
        text = io::toCsv(result.table);
        if (result.cancelled) text += "# " + note + "\n";
    }
    writeOutput(o.out, text);
    if (!o.out.empty() && o.out != "-") {
        std::cerr << "wrote " << o.out << ": " << result.table.rows.size() << " rows\n";
    }
    if (result.cancelled) {
        exitCancelled(
            cancellation,
            "sweep " + note + (o.out.empty() || o.out == "-" ? "" : "; written to " + o.out));
    }
}

void addCommonOptions(CLI::App& cmd, SweepOptions& o, const std::string& slips_default) {
    o.model.addTo(cmd);
    cmd.add_option("--slips,--slip", o.slips,
                   "Slips: range first:last:count or list (default " + slips_default + ")");
    auto* load = cmd.add_option(
        "--load", o.load_n,
        "Wheel load W [N] (default " + formatNumber(analysis::OperatingConditions{}.load_n) + ")");
    cmd.add_option("--entry-angle", o.entry_angle_deg, "Fixed entry angle [deg] instead of a load")
        ->excludes(load);
    cmd.add_flag("--json", o.json, "JSON output instead of CSV");
    cmd.add_option("--out", o.out, "Output file (default: stdout)");
}

}  // namespace

void addSweepCommands(CLI::App& app, const io::PresetLocations& locations) {
    auto sweep = std::make_shared<SweepOptions>();
    CLI::App* cmd = app.add_subcommand(
        "sweep", "Forces vs slip for a set of slip angles (Figs. 2.18-2.26), CSV or JSON");
    addCommonOptions(*cmd, *sweep, defaultGrid());
    cmd->add_option("--slip-angles,--slip-angle", sweep->slip_angles, "Slip angles [deg]")
        ->capture_default_str();
    cmd->callback([sweep, &locations] {
        const analysis::Inputs inputs = sweep->inputs(locations);
        const analysis::ForcesSettings settings = sweep->forces();
        const SignalCancellation cancellation;
        TerminalProgress progress("sweep");
        const analysis::ForcesResult result = analysis::computeForceSweep(
            inputs, settings, {cancellation.flag(), progress.callback()});
        progress.finish();
        emit(*sweep, result, cancellation);
    });

    auto sens = std::make_shared<SweepOptions>();
    analysis::SensitivitySettings& defaults = sens->sensitivity;
    sens->slip_angles = joined(defaults.slip_angles_deg);
    sens->slip_angles_flag = "--slip-angle";
    CLI::App* s = app.add_subcommand(
        "sensitivity", "Vary one soil parameter, sweep slip (section 4.2, Table 4.1)");
    addCommonOptions(*s, *sens,
                     "0:" + formatNumber(analysis::OperatingConditions{}.slip_max) + ":" +
                         std::to_string(defaults.slip_count));
    s->add_option("--slip-angle,--slip-angles", sens->slip_angles, "Slip angle(s) [deg]")
        ->capture_default_str();
    auto* parameter =
        s->add_option(
             "--parameter", defaults.parameter,
             "Soil field key (n, c_kPa, phi_deg, kc, kphi, K_m, ...) or 'all' for Table 4.1")
            ->capture_default_str();
    // Values are in one field's unit: without --parameter they would silently vary the default.
    s->add_option("--values", sens->values, "Values in file units (default: Table 4.1's)")
        ->needs(parameter);
    s->callback([sens, &locations] {
        const analysis::Inputs inputs = sens->inputs(locations);
        const analysis::SensitivitySettings settings = sens->sensitivitySettings();
        const SignalCancellation cancellation;
        TerminalProgress progress("sensitivity");
        const analysis::SensitivityResult result = analysis::computeSensitivity(
            inputs, settings, {cancellation.flag(), progress.callback()});
        progress.finish();
        if (result.parameter_keys.size() > 1) {
            std::string legend;
            for (std::size_t k = 0; k < result.parameter_keys.size(); ++k) {
                legend += (k ? ", " : "") + std::to_string(k) + " = " + result.parameter_keys[k];
            }
            std::cerr << "parameter column: " << legend << '\n';
        }
        emit(*sens, result.family, cancellation);
    });
}

void addPresetsCommand(CLI::App& app, const io::PresetLocations& locations) {
    auto json = std::make_shared<bool>(false);
    CLI::App* cmd = app.add_subcommand("presets", "List the soil, wheel and soil-profile presets");
    cmd->add_flag("--json", *json, "JSON output");
    cmd->callback([json, &locations] {
        nlohmann::json all{{"soils", nlohmann::json::array()}, {"wheels", nlohmann::json::array()}};
        std::ostringstream text;
        text << "Soils (n, c kPa, phi deg, kc kN/m^(n+1), kphi kN/m^(n+2), K m, gamma kN/m3):\n";
        for (const std::string& name : io::presetNames(locations, "soils")) {
            const auto soil = io::resolveSoil(locations, name);
            if (!soil) {
                std::string message = soil.message();
                for (std::size_t at = message.find('\n'); at != std::string::npos;
                     at = message.find('\n', at + 1)) {
                    message.insert(at + 1, "      ");
                }
                text << "  " << name << ": INVALID:\n      " << message << '\n';
                all["soils"].push_back({{"preset", name}, {"error", soil.message()}});
                continue;
            }
            nlohmann::json j = io::toJson(soil.value());
            j["preset"] = name;
            all["soils"].push_back(j);
            char line[256];
            std::snprintf(line, sizeof line,
                          "  %-24s n=%-5g c=%-6g phi=%-5g kc=%-7g kphi=%-7g K=%-6g gamma=%g\n",
                          name.c_str(), j["n"].get<double>(), j["c_kPa"].get<double>(),
                          j["phi_deg"].get<double>(), j["kc"].get<double>(),
                          j["kphi"].get<double>(), j["K_m"].get<double>(),
                          j["gamma_kN_m3"].get<double>());
            text << line;
        }
        text << "Wheels:\n";
        for (const std::string& name : io::presetNames(locations, "wheels")) {
            const auto wheel = io::resolveWheel(locations, name);
            if (!wheel) {
                std::string message = wheel.message();
                for (std::size_t at = message.find('\n'); at != std::string::npos;
                     at = message.find('\n', at + 1)) {
                    message.insert(at + 1, "      ");
                }
                text << "  " << name << ": INVALID:\n      " << message << '\n';
                all["wheels"].push_back({{"preset", name}, {"error", wheel.message()}});
                continue;
            }
            nlohmann::json j = io::toJson(wheel.value());
            j["preset"] = name;
            all["wheels"].push_back(j);
            text << "  " << name << "  " << wheel->name << ": r = " << wheel->radius_m
                 << " m, b = " << wheel->width_m << " m\n";
        }
        text << "Soil profiles (layers; docs/compaction.md):\n";
        all["profiles"] = nlohmann::json::array();
        for (const std::string& name : io::presetNames(locations, "profiles")) {
            const auto profile = io::resolveProfile(locations, name);
            if (!profile) {
                text << "  " << name << ": INVALID: " << profile.message() << '\n';
                all["profiles"].push_back({{"preset", name}, {"error", profile.message()}});
                continue;
            }
            nlohmann::json j = io::toJson(profile.value());
            j["preset"] = name;
            all["profiles"].push_back(j);
            text << "  " << name << "  " << profile->name << ": " << profile->layers.size()
                 << " layers to " << profile->layers.back().bottom_m << " m\n";
        }
        std::cout << (*json ? all.dump(2) + "\n" : text.str());
    });
}

}  // namespace terra::app
