#include <iostream>
#include <nlohmann/json.hpp>

#include "app/cli/cli_support.h"
#include "app/cli/commands.h"
#include "app/cli/signals.h"
#include "core/analysis/sweep.h"
#include "core/common/units.h"
#include "core/io/csv.h"
#include "core/io/table_json.h"

namespace terra::app {
namespace {

struct SweepOptions {
    ModelOptions model;
    std::string slips = "0:0.99:100";
    std::string slip_angles = "5,10,15,20,25,30";
    std::optional<double> load_n;
    std::optional<double> entry_angle_deg;
    bool json = false;
    std::string out;
    // sensitivity only
    std::string parameter = "all";
    std::string values;
};

analysis::SweepSpec makeSpec(const SweepOptions& o) {
    analysis::SweepSpec spec;
    spec.slips = parseValues(o.slips, "--slips");
    spec.slip_angles_rad.clear();
    for (double deg : parseValues(o.slip_angles, "--slip-angles")) {
        spec.slip_angles_rad.push_back(units::degToRad(deg));
    }
    if (o.entry_angle_deg) {
        spec.load_n.reset();
        spec.entry_angle_rad = units::degToRad(*o.entry_angle_deg);
    } else {
        spec.load_n = o.load_n.value_or(units::kGravity * 6.0);  // Table 2.6: 6 kg
    }
    spec.exit = o.model.exitCondition();
    spec.max_stress_angle_rad = o.model.maxStressAngleRad();
    spec.model = o.model.contactModel();
    spec.bulldozing = o.model.bulldozingModel();
    return spec;
}

// Writes the table; a cancelled sweep is written too, marked: "cancelled": true in JSON, a last
// comment line in CSV (which the CSV readers skip), then the cancellation's exit code.
void emit(const SweepOptions& o, const analysis::SweepResult& result,
          const SignalCancellation& cancellation) {
    for (const std::string& warning : result.warnings) std::cerr << "warning: " << warning << '\n';
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

void addCommonOptions(CLI::App& cmd, SweepOptions& o) {
    o.model.addTo(cmd);
    cmd.add_option("--slips", o.slips, "Slips: range first:last:count or list")
        ->capture_default_str();
    auto* load = cmd.add_option("--load", o.load_n, "Wheel load W [N] (default 58.86 = 6 kg)");
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
    addCommonOptions(*cmd, *sweep);
    cmd->add_option("--slip-angles", sweep->slip_angles, "Slip angles [deg]")
        ->capture_default_str();
    cmd->callback([sweep, &locations] {
        const auto soil = sweep->model.soilParameters(locations);
        const auto wheel = sweep->model.wheelParameters(locations);
        analysis::SweepSpec spec = makeSpec(*sweep);
        const SignalCancellation cancellation;
        spec.cancel = cancellation.flag();
        emit(*sweep, analysis::sweepSlip(contact::makeContactParameters(soil, wheel), spec),
             cancellation);
    });

    auto sens = std::make_shared<SweepOptions>();
    sens->slip_angles = "15";
    CLI::App* s = app.add_subcommand(
        "sensitivity", "Vary one soil parameter, sweep slip (section 4.2, Table 4.1)");
    addCommonOptions(*s, *sens);
    s->add_option("--slip-angle", sens->slip_angles, "Slip angle(s) [deg]")->capture_default_str();
    s->add_option("--parameter", sens->parameter,
                  "Soil field key (n, c_kPa, phi_deg, kc, kphi, K_m, ...) or 'all' for Table 4.1")
        ->capture_default_str();
    s->add_option("--values", sens->values, "Values in file units (default: Table 4.1's)");
    s->callback([sens, &locations] {
        const auto soil = sens->model.soilParameters(locations);
        const auto wheel = sens->model.wheelParameters(locations);
        std::vector<analysis::SensitivityParameter> parameters;
        if (sens->parameter == "all") {
            if (!sens->values.empty()) throw InputError("--values needs a single --parameter");
            parameters = analysis::thesisSensitivityParameters();
        } else {
            if (!soil::findSoilField(sens->parameter)) {
                throw InputError("--parameter: unknown soil field '" + sens->parameter + "'");
            }
            analysis::SensitivityParameter parameter{sens->parameter, {}};
            if (!sens->values.empty()) {
                parameter.values = parseValues(sens->values, "--values");
            } else {
                for (const auto& p : analysis::thesisSensitivityParameters()) {
                    if (p.key == sens->parameter) parameter.values = p.values;
                }
                if (parameter.values.empty()) {
                    throw InputError("--values: Table 4.1 has no variations of '" +
                                     sens->parameter + "'; give --values");
                }
            }
            parameters.push_back(parameter);
        }
        // Validate every value before computing anything.
        std::vector<Issue> issues;
        for (const auto& parameter : parameters) {
            const soil::SoilField* field = soil::findSoilField(parameter.key);
            for (double v : parameter.values) {
                checkRange(issues, "--values " + parameter.key, v, field->range, field->unit);
            }
        }
        if (!issues.empty()) throw InputError(formatIssues(issues));
        analysis::SweepResult all;
        all.table.columns = {"parameter", "value"};
        for (const std::string& c : analysis::sweepColumns()) all.table.columns.push_back(c);
        analysis::SweepSpec spec = makeSpec(*sens);
        const SignalCancellation cancellation;
        spec.cancel = cancellation.flag();
        for (std::size_t k = 0; k < parameters.size() && !all.cancelled; ++k) {
            const auto one = analysis::sensitivity(soil, wheel, parameters[k], spec);
            all.cancelled = one.cancelled;
            for (const auto& row : one.table.rows) {
                std::vector<double> values{static_cast<double>(k)};
                values.insert(values.end(), row.begin(), row.end());
                all.table.rows.push_back(std::move(values));
            }
            all.warnings.insert(all.warnings.end(), one.warnings.begin(), one.warnings.end());
        }
        if (parameters.size() == 1) {
            // A single parameter: name the value column after it.
            all.table.columns.erase(all.table.columns.begin());
            all.table.columns[0] = parameters[0].key;
            for (auto& row : all.table.rows) row.erase(row.begin());
        } else {
            std::string legend;
            for (std::size_t k = 0; k < parameters.size(); ++k) {
                legend += (k ? ", " : "") + std::to_string(k) + " = " + parameters[k].key;
            }
            std::cerr << "parameter column: " << legend << '\n';
        }
        emit(*sens, all, cancellation);
    });
}

void addPresetsCommand(CLI::App& app, const io::PresetLocations& locations) {
    auto json = std::make_shared<bool>(false);
    CLI::App* cmd = app.add_subcommand("presets", "List the soil and wheel presets");
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
        std::cout << (*json ? all.dump(2) + "\n" : text.str());
    });
}

}  // namespace terra::app
