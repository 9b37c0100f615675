// `terrastudio compaction`: stress at depth under the wheel, compaction risk against the profile's
// precompression stress and repeated passes on one track (core/analysis/compaction.h; the
// studio's compaction panel and a script's "compaction" call the same computeCompaction). The
// flags become the analysis's own settings object, read by its reader: one wording, one exit 2.
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>

#include "app/cli/cli_support.h"
#include "app/cli/commands.h"
#include "core/analysis/compaction.h"
#include "core/common/range.h"
#include "core/contact/operating_fields.h"
#include "core/io/csv.h"
#include "core/io/json_reader.h"

namespace terra::app {
namespace {

struct CompactionOptions {
    ModelOptions model;
    std::optional<double> load_n;
    std::optional<double> slip, slip_angle_deg, concentration, reload_k0, reload_au;
    std::optional<std::string> profile, depths, width, risk_stress;
    std::optional<int> passes;
    bool no_shear_memory = false;
    bool json = false;
    std::string out;
};

// The flags as the analysis's settings object (the keys of CompactionSettings::visitFields).
nlohmann::json settingsObject(const CompactionOptions& o) {
    nlohmann::json s = nlohmann::json::object();
    if (o.slip) s["slip"] = *o.slip;
    if (o.slip_angle_deg) s["slip_angle_deg"] = *o.slip_angle_deg;
    if (o.concentration) s["concentration"] = *o.concentration;
    if (o.reload_k0) s["reload_k0_kPa_m"] = *o.reload_k0;
    if (o.reload_au) s["reload_Au_kPa_m2"] = *o.reload_au;
    if (o.profile) s["profile"] = *o.profile;
    if (o.depths) s["depths_m"] = parseValues(*o.depths, "--depths");
    if (o.width) s["width"] = *o.width;
    if (o.risk_stress) s["risk_stress"] = *o.risk_stress;
    if (o.passes) s["passes"] = *o.passes;
    if (o.no_shear_memory) s["shear_memory"] = false;
    return s;
}

// The settings keys the flags set, and the flags' names for the reader's messages.
const std::vector<std::pair<std::string, std::string>>& compactionFlagNames() {
    static const std::vector<std::pair<std::string, std::string>> names{
        {"slip_angle_deg", "--slip-angle"},
        {"slip", "--slip"},
        {"concentration", "--concentration"},
        {"reload_k0_kPa_m", "--reload-k0"},
        {"reload_Au_kPa_m2", "--reload-au"},
        {"profile", "--profile"},
        {"depths_m", "--depths"},
        {"width", "--width"},
        {"risk_stress", "--risk-stress"},
        {"passes", "--passes"}};
    return names;
}

// The core summary (what the compaction panel shows), then the depth and pass tables.
void printText(const analysis::Inputs& in, const analysis::CompactionSettings& s,
               const analysis::CompactionResult& r) {
    printSummary(std::cout, analysis::compactionSummary(in, s, r));
    std::cout << "largest stress under the centre line during the passes:\n"
              << "  depth [m]  sigma_z [kPa]  p [kPa]  sigma_1 [kPa]"
              << (r.profile ? "  sigma_pc [kPa]  risk" : "") << '\n';
    for (const analysis::DepthValues& v : r.envelope) {
        char line[256];
        std::snprintf(line, sizeof line, "  %9s  %13s  %7s  %13s", fixed(v.depth_m, 3).c_str(),
                      fixed(v.max.sigma_z / 1e3, 2).c_str(), fixed(v.max.mean / 1e3, 2).c_str(),
                      fixed(v.max.major / 1e3, 2).c_str());
        std::cout << line;
        if (v.precompression_pa) {
            std::snprintf(line, sizeof line, "  %14s  %s",
                          fixed(*v.precompression_pa / 1e3, 1).c_str(),
                          analysis::riskName(*v.risk));
            std::cout << line;
        }
        std::cout << '\n';
    }
    std::cout << "  pass  sinkage [mm]  increment [mm]  rut [mm]    Fx [N]   My [Nm]";
    if (r.profile) std::cout << "  bulk density per layer [Mg/m3]";
    std::cout << '\n';
    for (const analysis::CompactionPass& p : r.passes) {
        char line[256];
        std::snprintf(line, sizeof line, "  %4d  %12s  %14s  %8s  %8s  %8s", p.pass,
                      fixed(p.sinkage_m * 1e3, 3).c_str(),
                      fixed(p.sinkage_increment_m * 1e3, 3).c_str(),
                      fixed(p.rut_depth_m * 1e3, 3).c_str(), fixed(p.forces.fx, 3).c_str(),
                      fixed(p.forces.my, 4).c_str());
        std::cout << line;
        if (r.profile) {
            std::cout << " ";
            for (double d : p.bulk_density_kg_m3) std::cout << ' ' << fixed(d / 1e3, 4);
        }
        std::cout << '\n';
    }
}

}  // namespace

void addCompactionCommand(CLI::App& app, const io::PresetLocations& locations) {
    auto options = std::make_shared<CompactionOptions>();
    CLI::App* cmd = app.add_subcommand(
        "compaction",
        "Stress at depth under the wheel, compaction risk against the precompression stress, "
        "repeated passes on one track (docs/compaction.md)");
    options->model.addTo(*cmd);
    CompactionOptions& o = *options;
    cmd->add_option("--load", o.load_n,
                    "Wheel load W [N] (default " + formatNumber(contact::kDefaultLoadN) + ")");
    cmd->add_option("--slip", o.slip, "Slip s of every pass (default 0.1)");
    cmd->add_option("--slip-angle", o.slip_angle_deg, "Slip angle [deg] (default 0)");
    cmd->add_option("--profile", o.profile,
                    "Soil profile: a preset (presets profiles) or a JSON file; default: the "
                    "soil file's own, else none (no sigma_pc, no risk)");
    cmd->add_option("--concentration", o.concentration,
                    "Concentration factor nu for every depth (3 Boussinesq; default: each "
                    "layer's, else 5)");
    cmd->add_option("--depths", o.depths, "Depths [m]: FROM:TO:COUNT or a list (default 0.1:1:19)");
    cmd->add_option("--passes", o.passes, "Wheels on the same track (default 1)");
    cmd->add_option("--width", o.width, "Stress across the width: uniform (default) or parabolic");
    cmd->add_option("--risk-stress", o.risk_stress,
                    "Stress compared with sigma_pc: sigma_z (default) or sigma_1");
    cmd->add_option("--reload-k0", o.reload_k0,
                    "k0 [kPa/m] of the reload stiffness k_u = k0 + Au z_u (default 50000: "
                    "Chrono SCM's K_e)");
    cmd->add_option("--reload-au", o.reload_au, "Au [kPa/m^2] of k_u = k0 + Au z_u (default 0)");
    cmd->add_flag("--no-shear-memory", o.no_shear_memory,
                  "Do not carry the shear deformation of earlier passes");
    cmd->add_flag("--json", o.json, "JSON: profile, red_to_depth_m, passes");
    cmd->add_option("--out", o.out,
                    "Write the JSON (with --json) or the profile as CSV to this file");
    cmd->callback([options, &locations] {
        const CompactionOptions& o = *options;
        std::vector<NamedInput> files = o.model.inputFiles();
        if (o.profile) files.push_back({"--profile", *o.profile});
        refuseInputAsOutput("--out", o.out, files);
        analysis::Inputs inputs = o.model.inputs(locations);
        if (o.load_n) {
            std::vector<Issue> issues;
            const FieldInfo& load = contact::loadField();
            checkRange(issues, "--load", *o.load_n, load.range, load.displayUnit());
            if (!issues.empty()) throw InputError(formatIssues(issues));
            inputs.conditions.load_n = *o.load_n;
        }
        const nlohmann::json object = settingsObject(o);
        std::vector<Issue> issues;
        io::ObjectReader reader(object, issues);
        analysis::CompactionSettings settings;
        const std::filesystem::path here = std::filesystem::current_path();
        analysis::readCompactionSettings(reader, settings, &locations, here);
        reader.finish();
        if (!issues.empty()) {
            nameFlags(issues, compactionFlagNames());
            throw InputError(formatIssues(issues));
        }
        settings.model = o.model.choices();
        const analysis::CompactionResult result = analysis::computeCompaction(inputs, settings);
        // The printed text's summary says the notes; otherwise (the JSON, the CSV on stdout, no
        // pass) stderr does.
        const bool text = !o.json && (o.out.empty() || o.out != "-") && !result.passes.empty();
        if (!text)
            for (const std::string& note : result.notes) std::cerr << "note: " << note << '\n';
        if (o.json) {
            writeOutput(o.out, analysis::toJson(result).dump(2) + "\n");
        } else if (!o.out.empty()) {
            writeOutput(o.out, io::toCsv(analysis::compactionOutcome(result).tables.front().table));
        }
        if (text) printText(inputs, settings, result);
        if (!result.ok()) throw std::runtime_error(result.message);
    });
}

}  // namespace terra::app
