#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>

#include "app/cli/cli_support.h"
#include "app/cli/commands.h"
#include "core/common/range.h"
#include "core/common/table.h"
#include "core/common/units.h"
#include "core/contact/sinkage.h"
#include "core/io/csv.h"
#include "core/io/table_json.h"

namespace terra::app {
namespace {

struct SinkageOptions {
    ModelOptions model;
    std::string loads = "58.86";
    double slip = 0.0;
    double slip_angle_deg = 0.0;
    bool json = false;
    std::string out;
};

}  // namespace

void addSinkageCommand(CLI::App& app, const io::PresetLocations& locations) {
    auto options = std::make_shared<SinkageOptions>();
    CLI::App* cmd = app.add_subcommand(
        "sinkage", "Static sinkage (Bekker Eq. 2.8, exact Eq. 2.7) and the dynamic entry angle");
    options->model.addTo(*cmd);
    cmd->add_option("--load", options->loads,
                    "W [N]: a value, a list a,b or a range first:last:count")
        ->capture_default_str();
    cmd->add_option("--slip", options->slip, "Slip s for the dynamic entry angle")
        ->capture_default_str();
    cmd->add_option("--slip-angle", options->slip_angle_deg, "Slip angle [deg]")
        ->capture_default_str();
    cmd->add_flag("--json", options->json, "JSON output");
    cmd->add_option("--out", options->out, "Write CSV (or JSON with --json) to this file");
    cmd->callback([options, &locations] {
        const SinkageOptions& o = *options;
        const auto soil = o.model.soilParameters(locations);
        const auto wheel = o.model.wheelParameters(locations);
        const auto p = contact::makeContactParameters(soil, wheel);
        const std::vector<double> loads = parseValues(o.loads, "--load");
        std::vector<Issue> issues;
        for (double w : loads) checkRange(issues, "--load", w, {0.0, 1e7, true, false}, "N");
        if (!issues.empty()) throw InputError(formatIssues(issues));
        Table table;
        table.columns = {"load_N",
                         "bekker_sinkage_m",
                         "static_sinkage_m",
                         "static_angle_deg",
                         "static_front_half_sinkage_m",
                         "entry_angle_deg",
                         "sinkage_m"};
        std::vector<std::string> notes;
        for (double w : loads) {
            const double bekker = contact::bekkerStaticSinkage(p, w);
            const auto exact =
                contact::solveStaticSinkage(p, w, contact::StaticContact::kSymmetric);
            const auto front =
                contact::solveStaticSinkage(p, w, contact::StaticContact::kFrontHalf);
            contact::EntryAngleProblem problem;
            problem.load_n = w;
            problem.slip = o.slip;
            problem.slip_angle_rad = units::degToRad(o.slip_angle_deg);
            problem.exit = o.model.exitCondition();
            problem.max_stress_angle_rad = o.model.maxStressAngleRad();
            problem.model = o.model.contactModel();
            const auto dynamic = contact::solveEntryAngle(p, problem);
            const double nan = std::nan("");
            table.rows.push_back({w, bekker, exact.ok() ? exact.sinkage_m : nan,
                                  exact.ok() ? units::radToDeg(exact.entry_angle_rad) : nan,
                                  front.ok() ? front.sinkage_m : nan,
                                  dynamic.ok() ? units::radToDeg(dynamic.entry_angle_rad) : nan,
                                  dynamic.ok() ? dynamic.sinkage_m : nan});
            const std::pair<const char*, const contact::SinkageSolution*> solves[] = {
                {"static (Eq. 2.7)", &exact},
                {"static front half", &front},
                {"dynamic entry angle", &dynamic}};
            for (const auto& [what, s] : solves) {
                if (!s->ok())
                    notes.push_back("W = " + formatNumber(w) + " N, " + what + ": " + s->message);
            }
            if (bekker > p.radius_m / 3.0) {
                notes.push_back("W = " + formatNumber(w) +
                                " N: Bekker's formula is outside its validity (h > r/3)");
            }
        }
        for (const std::string& note : notes) std::cerr << "note: " << note << '\n';
        std::string text;
        if (o.json) {
            text = io::toJson(table).dump(2) + "\n";
        } else if (!o.out.empty()) {
            text = io::toCsv(table);
        } else {
            std::cout << soil.name << ", " << wheel.name
                      << "; dynamic entry angle at s = " << formatNumber(o.slip)
                      << ", beta = " << formatNumber(o.slip_angle_deg) << " deg (" << o.model.model
                      << " model)\n";
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
