// `terrastudio stresses`: σ, τ, τ_t, τ_l and j over the contact (Eqs. 2.13–2.22), exact and from
// the quadratic approximation (Eqs. 2.36–2.38), with RMSE and MAE (Eqs. 2.39–2.40, Tables 2.4–2.5).
#include <cmath>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>

#include "app/cli/cli_support.h"
#include "app/cli/commands.h"
#include "core/common/range.h"
#include "core/common/table.h"
#include "core/common/units.h"
#include "core/contact/quadratic_model.h"
#include "core/io/csv.h"
#include "core/io/table_json.h"

namespace terra::app {
namespace {

struct StressOptions {
    ModelOptions model;
    double slip = 0.3;  // Table 2.3
    double slip_angle_deg = 12.0;
    double entry_angle_deg = 30.0;
    double step_deg = 0.01;  // MODEL-NOTES: the grid of Tables 2.4–2.5
    bool json = false;
    std::string out;
};

}  // namespace

void addStressesCommand(CLI::App& app, const io::PresetLocations& locations) {
    auto options = std::make_shared<StressOptions>();
    CLI::App* cmd = app.add_subcommand(
        "stresses",
        "Stress distributions over the contact, exact and quadratic, with RMSE/MAE "
        "(Figs. 2.11, 2.16; Tables 2.4-2.5)");
    options->model.addTo(*cmd);
    cmd->add_option("--slip", options->slip, "Slip ratio s in [-1, 1]")->capture_default_str();
    cmd->add_option("--slip-angle", options->slip_angle_deg, "Slip angle [deg]")
        ->capture_default_str();
    cmd->add_option("--entry-angle", options->entry_angle_deg, "Entry angle theta_f [deg]")
        ->capture_default_str();
    cmd->add_option("--step", options->step_deg, "Grid step [deg]")
        ->check(CLI::Range(1e-4, 10.0))
        ->capture_default_str();
    cmd->add_flag("--json", options->json, "JSON: the error summary and the grid");
    cmd->add_option("--out", options->out,
                    "Write the grid as CSV (or JSON with --json) to this file; '-': the CSV alone "
                    "to stdout");
    cmd->callback([options, &locations] {
        const StressOptions& o = *options;
        const auto soil = o.model.soilParameters(locations);
        const auto wheel = o.model.wheelParameters(locations);
        const auto p = contact::makeContactParameters(soil, wheel);
        const double theta_f = units::degToRad(o.entry_angle_deg);
        const contact::OperatingPoint<double> op{o.slip, units::degToRad(o.slip_angle_deg), theta_f,
                                                 o.model.exitCondition().exitAngle(theta_f),
                                                 o.model.maxStressAngleRad()};
        contact::requireValid(op);
        const double step = units::degToRad(o.step_deg);
        const contact::StressField<double> field(p, op);
        const contact::QuadraticStress<double> quadratic = contact::fitQuadraticStress(field);
        const auto errors = contact::quadraticApproximationErrors(p, op, step);

        Table grid;
        grid.columns = {"theta_deg",      "sigma_kPa",     "tau_kPa",        "tau_t_kPa",
                        "tau_l_kPa",      "j_m",           "sigma_quad_kPa", "tau_quad_kPa",
                        "tau_t_quad_kPa", "tau_l_quad_kPa"};
        // The grid of quadraticApproximationErrors: from the θ_r the model uses (≥ −θ_f).
        const double theta_r = field.exitAngle();
        const auto steps = static_cast<long>(std::floor((theta_f - theta_r) / step + 1e-9));
        for (long i = 0; i <= steps; ++i) {
            const double theta = theta_r + static_cast<double>(i) * step;
            const auto e = field.at(theta);
            const auto q = quadratic.at(theta);
            grid.rows.push_back({plainZero(roundSignificant(units::radToDeg(theta))), e.sigma / 1e3,
                                 e.tau / 1e3, e.tau_t / 1e3, e.tau_l / 1e3, e.shear, q.sigma / 1e3,
                                 q.tau / 1e3, q.tau_t / 1e3, q.tau_l / 1e3});
        }
        const char* names[] = {"sigma", "tau", "tau_t", "tau_l"};
        const bool to_file = !o.out.empty() && o.out != "-";
        // θ_m as the user typed it (15, not 15.000000000000002), or Eq. 2.18's value.
        const double theta_m_deg =
            plainZero(roundSignificant(units::radToDeg(field.maxStressAngle())));
        if (o.json) {
            nlohmann::json summary;
            for (int k = 0; k < 4; ++k) {
                summary[std::string(names[k]) + "_rmse_kPa"] = errors[k].rmse / 1e3;
                summary[std::string(names[k]) + "_mae_kPa"] = errors[k].mae / 1e3;
            }
            summary["max_stress_angle_deg"] = theta_m_deg;
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
        std::cout << soil.name << ", " << wheel.name << ": s = " << formatNumber(o.slip)
                  << ", beta = " << formatNumber(o.slip_angle_deg)
                  << " deg, theta_f = " << formatNumber(o.entry_angle_deg)
                  << " deg, theta_m = " << fixed(theta_m_deg, 4)
                  << " deg\nquadratic approximation vs exact over " << grid.rows.size()
                  << " angles (step " << formatNumber(o.step_deg) << " deg):\n"
                  << "            sigma      tau    tau_t    tau_l\n";
        std::cout << "  RMSE kPa";
        for (int k = 0; k < 4; ++k)
            std::cout << ' ' << std::setw(8) << fixed(errors[k].rmse / 1e3, 4);
        std::cout << "\n  MAE  kPa";
        for (int k = 0; k < 4; ++k)
            std::cout << ' ' << std::setw(8) << fixed(errors[k].mae / 1e3, 4);
        std::cout << '\n';
    });
}

}  // namespace terra::app
