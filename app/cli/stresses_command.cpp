// `terrastudio stresses`: σ, τ, τ_t, τ_l and j over the contact (Eqs. 2.13–2.22), exact and from
// the quadratic approximation (Eqs. 2.36–2.38), with RMSE and MAE (Eqs. 2.39–2.40, Tables 2.4–2.5):
// core/analysis/stresses.h, as the studio's stress panel and a script's "stresses".
#include <iostream>
#include <nlohmann/json.hpp>

#include "app/cli/cli_support.h"
#include "app/cli/commands.h"
#include "app/cli/settings_flags.h"
#include "core/analysis/stresses.h"
#include "core/common/range.h"
#include "core/contact/operating_fields.h"
#include "core/io/csv.h"

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
        const bool to_file = !o.out.empty() && o.out != "-";
        if (o.json) {
            writeOutput(o.out, analysis::toJson(result).dump(2) + "\n");
            if (to_file) std::cerr << "wrote " << o.out << ": " << grid.rows.size() << " angles\n";
            return;
        }
        if (!o.out.empty()) {
            writeOutput(o.out, io::toCsv(grid));
            // `--out -`: stdout carries the CSV alone, so the summary below is left out.
            if (!to_file) return;
            std::cerr << "wrote " << o.out << ": " << grid.rows.size() << " angles\n";
        }
        printSummary(std::cout, analysis::stressSummary(inputs, settings, result));
    });
}

}  // namespace terra::app
