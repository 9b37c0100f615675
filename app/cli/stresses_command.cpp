// `terrastudio stresses`: σ, τ, τ_t, τ_l and j over the contact (Eqs. 2.13–2.22), exact and from
// the quadratic approximation (Eqs. 2.36–2.38), with RMSE and MAE (Eqs. 2.39–2.40, Tables 2.4–2.5):
// core/analysis/stresses.h, as the studio's stress panel and a script's "stresses".
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>

#include "app/cli/cli_support.h"
#include "app/cli/commands.h"
#include "app/cli/settings_flags.h"
#include "core/analysis/stresses.h"
#include "core/common/range.h"
#include "core/contact/operating_fields.h"
#include "core/io/csv.h"
#include "core/io/table_json.h"

namespace terra::app {
namespace {

struct StressOptions {
    ModelOptions model;
    analysis::StressSettings settings;
    std::optional<double> load_n;
    bool json = false;
    std::string out;
};

// The flags as the analysis's settings object (the keys of StressSettings::visitFields), read by
// its reader: the ranges and their words are the reader's, named by the flags.
analysis::StressSettings stressSettings(const StressOptions& o) {
    const analysis::StressSettings& s = o.settings;
    nlohmann::json object{
        {"slip", s.slip}, {"slip_angle_deg", s.slip_angle_deg}, {"step_deg", s.step_deg}};
    if (s.entry_angle_deg) object["entry_angle_deg"] = *s.entry_angle_deg;
    addModelChoices(o.model, object);
    return readFlagSettings<analysis::StressSettings>(object, analysis::readStressSettings,
                                                      {{"slip", "--slip"},
                                                       {"slip_angle_deg", "--slip-angle"},
                                                       {"step_deg", "--step"},
                                                       {"entry_angle_deg", "--entry-angle"}});
}

}  // namespace

void addStressesCommand(CLI::App& app, const io::PresetLocations& locations) {
    auto options = std::make_shared<StressOptions>();
    analysis::StressSettings& s = options->settings;
    CLI::App* cmd = app.add_subcommand(
        "stresses",
        "Stress distributions over the contact, exact and quadratic, with RMSE/MAE "
        "(Figs. 2.11, 2.16; Tables 2.4-2.5)");
    options->model.addTo(*cmd);
    cmd->add_option("--slip", s.slip, "Slip ratio s in " + contact::slipField().range.describe())
        ->capture_default_str();
    cmd->add_option("--slip-angle", s.slip_angle_deg, "Slip angle [deg]")->capture_default_str();
    auto* load = cmd->add_option("--load", options->load_n,
                                 "Wheel load W [N]: theta_f solved from F_z = W (default " +
                                     formatNumber(contact::kDefaultLoadN) + ")");
    cmd->add_option("--entry-angle", s.entry_angle_deg,
                    "Fixed entry angle theta_f [deg] instead of a load (Table 2.3: 30)")
        ->excludes(load);
    cmd->add_option("--step", s.step_deg,
                    "Grid step [deg] in " + analysis::kStressStepRange.describe())
        ->capture_default_str();
    cmd->add_flag("--json", options->json, "JSON: the error summary and the grid");
    cmd->add_option("--out", options->out,
                    "Write the grid as CSV (or JSON with --json) to this file; '-': the CSV alone "
                    "to stdout");
    cmd->callback([options, &locations] {
        const StressOptions& o = *options;
        refuseInputAsOutput("--out", o.out, o.model.inputFiles());
        analysis::Inputs inputs = o.model.inputs(locations);
        if (o.load_n) inputs.conditions.load_n = *o.load_n;
        const analysis::StressSettings settings = stressSettings(o);
        const analysis::StressResult result = analysis::computeStresses(inputs, settings);
        if (!result.message.empty()) throw std::runtime_error(result.message);
        const Table& grid = result.table;
        const char* names[] = {"sigma", "tau", "tau_t", "tau_l"};
        const bool to_file = !o.out.empty() && o.out != "-";
        // θ_m as the user typed it (15, not 15.000000000000002), or Eq. 2.18's value.
        const double theta_m_deg = plainZero(roundSignificant(result.max_stress_angle_deg));
        if (o.json) {
            nlohmann::json summary;
            for (int k = 0; k < 4; ++k) {
                summary[std::string(names[k]) + "_rmse_kPa"] = result.errors[k].rmse / 1e3;
                summary[std::string(names[k]) + "_mae_kPa"] = result.errors[k].mae / 1e3;
            }
            summary["max_stress_angle_deg"] = theta_m_deg;
            summary["entry_angle_deg"] = plainZero(roundSignificant(result.entry_angle_deg));
            summary["points"] = grid.rows.size();
            writeOutput(
                o.out,
                nlohmann::json{{"errors", summary}, {"grid", io::toJson(grid)}}.dump(2) + "\n");
            if (to_file) std::cerr << "wrote " << o.out << ": " << grid.rows.size() << " angles\n";
            return;
        }
        if (!o.out.empty()) {
            writeOutput(o.out, io::toCsv(grid));
            // `--out -`: stdout carries the CSV alone, so the summary below is left out.
            if (!to_file) return;
            std::cerr << "wrote " << o.out << ": " << grid.rows.size() << " angles\n";
        }
        std::cout << inputs.soil.name << ", " << inputs.wheel.name
                  << ": s = " << formatNumber(settings.slip)
                  << ", beta = " << formatNumber(settings.slip_angle_deg) << " deg, theta_f = "
                  << (settings.entry_angle_deg ? formatNumber(*settings.entry_angle_deg) + " deg"
                                               : fixed(result.entry_angle_deg, 4) + " deg (W = " +
                                                     formatNumber(inputs.conditions.load_n) + " N)")
                  << ", theta_m = " << fixed(theta_m_deg, 4)
                  << " deg\nquadratic approximation vs exact over " << grid.rows.size()
                  << " angles (step " << formatNumber(settings.step_deg) << " deg):\n"
                  << "            sigma      tau    tau_t    tau_l\n";
        std::cout << "  RMSE kPa";
        for (int k = 0; k < 4; ++k)
            std::cout << ' ' << std::setw(8) << fixed(result.errors[k].rmse / 1e3, 4);
        std::cout << "\n  MAE  kPa";
        for (int k = 0; k < 4; ++k)
            std::cout << ' ' << std::setw(8) << fixed(result.errors[k].mae / 1e3, 4);
        std::cout << '\n';
    });
}

}  // namespace terra::app
