#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>

#include "app/cli/cli_support.h"
#include "app/cli/commands.h"
#include "app/cli/settings_flags.h"
#include "core/analysis/sinkage_study.h"
#include "core/common/range.h"
#include "core/common/table.h"
#include "core/contact/operating_fields.h"
#include "core/io/csv.h"
#include "core/io/table_json.h"

namespace terra::app {
namespace {

struct SinkageOptions {
    ModelOptions model;
    std::string loads = formatNumber(analysis::OperatingConditions{}.load_n);
    analysis::SinkageSettings settings;
    bool json = false;
    std::string out;
};

// The flags as the analysis's settings object (the keys of SinkageSettings::visitFields), read by
// its reader: the loads' range and its words are the reader's, named by the flags.
analysis::SinkageSettings sinkageSettings(const SinkageOptions& o) {
    nlohmann::json object{{"loads_N", parseValues(o.loads, "--load")},
                          {"slip", o.settings.slip},
                          {"slip_angle_deg", o.settings.slip_angle_deg}};
    addModelChoices(o.model, object);
    return readFlagSettings<analysis::SinkageSettings>(
        object, analysis::readSinkageSettings,
        {{"loads_N", "--load"}, {"slip", "--slip"}, {"slip_angle_deg", "--slip-angle"}});
}

}  // namespace

void addSinkageCommand(CLI::App& app, const io::PresetLocations& locations) {
    auto options = std::make_shared<SinkageOptions>();
    CLI::App* cmd = app.add_subcommand(
        "sinkage", "Static sinkage (Bekker Eq. 2.8, exact Eq. 2.7) and the dynamic entry angle");
    options->model.addTo(*cmd);
    cmd->add_option("--load", options->loads,
                    "W [N]: a value, a list a,b or a range first:last:count")
        ->capture_default_str();
    cmd->add_option("--slip", options->settings.slip, "Slip s for the dynamic entry angle")
        ->capture_default_str();
    cmd->add_option("--slip-angle", options->settings.slip_angle_deg, "Slip angle [deg]")
        ->capture_default_str();
    cmd->add_flag("--json", options->json, "JSON output");
    cmd->add_option("--out", options->out, "Write CSV (or JSON with --json) to this file");
    cmd->callback([options, &locations] {
        const SinkageOptions& o = *options;
        refuseInputAsOutput("--out", o.out, o.model.inputFiles());
        const analysis::Inputs inputs = o.model.inputs(locations);
        const analysis::SinkageSettings settings = sinkageSettings(o);
        const analysis::SinkageStudy study = analysis::computeSinkage(inputs, settings);
        printLines(study.notes, "note: ");
        const Table& table = study.table;
        const soil::SoilParameters& soil = inputs.soil;
        const wheel::WheelParameters& wheel = inputs.wheel;
        std::string text;
        if (o.json) {
            text = io::toJson(table).dump(2) + "\n";
        } else if (!o.out.empty()) {
            text = io::toCsv(table);
        } else {
            std::cout << soil.name << ", " << wheel.name
                      << "; dynamic entry angle at s = " << formatNumber(settings.slip)
                      << ", beta = " << formatNumber(settings.slip_angle_deg) << " deg ("
                      << o.model.model << " model)\n";
            std::cout
                << "  load [N]  Bekker h [mm]  Eq.2.7 h [mm]  theta_s [deg]  front-half h [mm]"
                   "  theta_f [deg]  h_f [mm]\n";
            for (const auto& row : table.rows) {
                char line[256];
                std::snprintf(line, sizeof line, "  %8s  %13s  %13s  %13s  %17s  %13s  %8s\n",
                              fixed(row[0], 2).c_str(), fixed(row[1] * 1e3, 3).c_str(),
                              fixed(row[2] * 1e3, 3).c_str(), fixed(row[3], 3).c_str(),
                              fixed(row[4] * 1e3, 3).c_str(), fixed(row[5], 3).c_str(),
                              fixed(row[6] * 1e3, 3).c_str());
                std::cout << line;
            }
            return;
        }
        writeOutput(o.out, text);
    });
}

}  // namespace terra::app
