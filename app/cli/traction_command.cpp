// `terrastudio traction`: the slip that maximises drawbar pull or tractive efficiency, with the
// posterior's band and a robust slip (core/analysis/traction.h; docs/traction.md). The flags become
// the analysis's settings object, read by its own reader: one wording, one exit 2.
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>

#include "app/cli/cli_support.h"
#include "app/cli/commands.h"
#include "core/analysis/traction.h"
#include "core/common/range.h"
#include "core/contact/operating_fields.h"
#include "core/io/csv.h"
#include "core/io/json_reader.h"

namespace terra::app {
namespace {

struct TractionOptions {
    ModelOptions model;
    std::optional<double> load_n, slip_angle_deg, max_sinkage_m, slip_min, slip_max, quantile;
    std::optional<std::string> objective, posterior;
    std::optional<int> samples, points;
    std::optional<std::uint64_t> seed;
    bool json = false;
    std::string out;
};

nlohmann::json settingsObject(const TractionOptions& o) {
    nlohmann::json s = nlohmann::json::object();
    if (o.slip_angle_deg) s["slip_angle_deg"] = *o.slip_angle_deg;
    if (o.objective) s["objective"] = *o.objective;
    if (o.max_sinkage_m) s["max_sinkage_m"] = *o.max_sinkage_m;
    if (o.slip_min) s["slip_min"] = *o.slip_min;
    if (o.slip_max) s["slip_max"] = *o.slip_max;
    if (o.quantile) s["quantile"] = *o.quantile;
    if (o.posterior) s["posterior"] = *o.posterior;
    if (o.samples) s["posterior_samples"] = *o.samples;
    if (o.points) s["curve_points"] = *o.points;
    if (o.seed) s["seed"] = *o.seed;
    return s;
}

// The settings keys the flags set, and the flags' names for the reader's messages.
const std::vector<std::pair<std::string, std::string>>& tractionFlagNames() {
    static const std::vector<std::pair<std::string, std::string>> names{
        {"slip_angle_deg", "--slip-angle"}, {"objective", "--objective"},
        {"max_sinkage_m", "--max-sinkage"}, {"slip_min", "--slip-min"},
        {"slip_max", "--slip-max"},         {"quantile", "--quantile"},
        {"posterior_samples", "--samples"}, {"posterior", "--posterior"},
        {"curve_points", "--points"},       {"seed", "--seed"}};
    return names;
}

// The core summary (what the panels would show), then the curve.
void printText(const analysis::Inputs& in, const analysis::TractionSettings& s,
               const analysis::TractionResult& r) {
    printSummary(std::cout, analysis::tractionSummary(in, s, r));
    std::cout << "     slip    Fx [N]   My [Nm]  efficiency  sinkage [mm]\n";
    const std::size_t step = std::max<std::size_t>(1, r.curve.size() / 12);
    for (std::size_t i = 0; i < r.curve.size(); i += step) {
        const analysis::TractionPoint& c = r.curve[i];
        char line[160];
        std::snprintf(line, sizeof line, "  %7s  %8s  %8s  %10s  %12s%s\n",
                      fixed(c.slip, 3).c_str(), fixed(c.fx_n, 3).c_str(), fixed(c.my_nm, 4).c_str(),
                      fixed(c.efficiency, 4).c_str(), fixed(c.sinkage_m * 1e3, 3).c_str(),
                      c.ok ? "" : "  (excluded)");
        std::cout << line;
    }
}

}  // namespace

void addTractionCommand(CLI::App& app, const io::PresetLocations& locations) {
    auto options = std::make_shared<TractionOptions>();
    TractionOptions& o = *options;
    CLI::App* cmd = app.add_subcommand(
        "traction",
        "The slip that maximises drawbar pull or tractive efficiency (optionally under a sinkage "
        "cap, robust over a soil posterior; docs/traction.md)");
    o.model.addTo(*cmd);
    cmd->add_option("--load", o.load_n,
                    "Wheel load W [N] (default " + formatNumber(contact::kDefaultLoadN) + ")");
    cmd->add_option("--slip-angle", o.slip_angle_deg, "Slip angle [deg] (default 0)");
    cmd->add_option("--objective", o.objective, "drawbar or efficiency (default efficiency)");
    cmd->add_option("--max-sinkage", o.max_sinkage_m, "Sinkage cap [m]");
    cmd->add_option(
        "--posterior", o.posterior,
        "A soil file with a \"posterior\" (identify --save-soil): the band and a robust "
        "slip; it is also the soil when --soil is not given");
    cmd->add_option("--quantile", o.quantile,
                    "Robust slip: maximise this quantile of the objective (default 0.1)");
    cmd->add_option("--samples", o.samples, "Soils drawn from the posterior (default 200)");
    cmd->add_option("--seed", o.seed, "Seed of the draws (default 1)");
    cmd->add_option("--slip-min", o.slip_min, "Smallest slip searched (default 0.01)");
    cmd->add_option("--slip-max", o.slip_max, "Largest slip searched (default 0.9)");
    cmd->add_option("--points", o.points, "Slips on the curve (default 60)");
    cmd->add_flag("--json", o.json,
                  "JSON: optimal_slip, objective, Fx_N, My_Nm, efficiency, curve");
    cmd->add_option("--out", o.out,
                    "Write the JSON (with --json) or the curve as CSV to this file");
    cmd->callback([options, cmd, &locations] {
        const TractionOptions& o = *options;
        std::vector<NamedInput> files = o.model.inputFiles();
        if (o.posterior) files.push_back({"--posterior", *o.posterior});
        refuseInputAsOutput("--out", o.out, files);
        // A --posterior soil file (`identify --save-soil`) is the soil when --soil is not given:
        // the posterior's mean and the fields it does not vary are then the identified soil's.
        ModelOptions model = o.model;
        if (o.posterior && cmd->get_option("--soil")->count() == 0 &&
            analysis::isSoilFile(*o.posterior))
            model.soil = *o.posterior;
        analysis::Inputs inputs = model.inputs(locations);
        std::vector<Issue> issues;
        if (o.load_n) {
            const FieldInfo& load = contact::loadField();
            checkRange(issues, "--load", *o.load_n, load.range, load.displayUnit());
            inputs.conditions.load_n = *o.load_n;
        }
        const nlohmann::json object = settingsObject(o);
        io::ObjectReader reader(object, issues);
        analysis::TractionSettings settings;
        analysis::readTractionSettings(reader, settings, std::filesystem::current_path());
        reader.finish();
        if (!issues.empty()) {
            nameFlags(issues, tractionFlagNames());
            throw InputError(formatIssues(issues));
        }
        settings.model = o.model.choices();
        const analysis::TractionResult result = analysis::computeTraction(inputs, settings);
        // The printed text's summary says the notes; otherwise (the JSON, the CSV on stdout, no
        // s*) stderr does.
        const bool text = !o.json && o.out != "-";
        if (!text || !result.ok())
            for (const std::string& note : result.notes) std::cerr << "note: " << note << '\n';
        // The JSON is written either way (its "status" says failed, with the message), then exit 1.
        if (o.json) writeOutput(o.out, analysis::toJson(result).dump(2) + "\n");
        if (!result.ok()) throw std::runtime_error(result.message);
        if (o.json) return;
        if (!o.out.empty())
            writeOutput(o.out, io::toCsv(analysis::tractionOutcome(result).tables.front().table));
        if (text) printText(inputs, settings, result);
    });
}

}  // namespace terra::app
