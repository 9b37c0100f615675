#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "app/cli/cli_support.h"
#include "app/cli/commands.h"
#include "app/cli/progress.h"
#include "app/cli/settings_flags.h"
#include "app/cli/signals.h"
#include "core/analysis/operating_point.h"
#include "core/common/range.h"
#include "core/common/units.h"
#include "core/contact/operating_fields.h"
#include "core/contact/quadratic_model.h"
#include "core/contact/sinkage.h"
#include "core/contact/wheel_forces.h"
#include "core/io/csv.h"

namespace terra::app {
namespace {

using contact::ContactParameters;
using contact::OperatingPoint;
using contact::WheelForces;

struct WheelOptions {
    ModelOptions model;
    double slip = 0.0;
    double slip_angle_deg = 0.0;
    std::optional<double> entry_angle_deg;
    std::optional<double> load_n;
    bool json = false;
    std::string input;
    std::string output;
    bool skip_bad_rows = false;
};

using analysis::PointResult;
using analysis::PointSpec;

// One operating point of the command line: the model flags' choices and contact model.
PointResult evaluate(const ContactParameters<double>& p, const WheelOptions& options,
                     PointSpec in) {
    in.contact_model = options.model.contactModel();
    in.model.bulldozing = options.model.bulldozingModel();
    try {
        return analysis::evaluatePoint(p, in);
    } catch (const std::invalid_argument& e) {
        throw InputError(e.what());
    }
}

nlohmann::json toJson(const PointResult& r) {
    const WheelForces<double>& f = r.forces;
    const auto z = plainZero;
    return {{"Fx_N", z(f.fx)},
            {"Fy_N", z(f.fy)},
            {"Fz_N", z(f.fz)},
            {"Mx_Nm", z(f.mx)},
            {"My_Nm", z(f.my)},
            {"Mz_Nm", z(f.mz)},
            {"Fb_N", z(f.fb)},
            {"Fs_N", z(f.fs)},
            {"entry_angle_deg", z(r.entry_angle_deg)},
            {"exit_angle_deg", z(r.exit_angle_deg)},
            {"sinkage_m", z(r.sinkage_m)}};
}

void printHuman(const soil::SoilParameters& soil, const wheel::WheelParameters& wheel,
                const WheelOptions& o, const PointSpec& in, const PointResult& r) {
    std::ostringstream s;
    s << soil.name << ", " << wheel.name << " (r = " << wheel.radius_m
      << " m, b = " << wheel.width_m << " m), " << o.model.model << " model\n";
    s << "s = " << formatNumber(in.slip) << ", beta = " << formatNumber(in.slip_angle_deg)
      << " deg, ";
    if (r.solved_from_load) {
        s << "W = " << formatNumber(*in.load_n) << " N -> theta_f = " << fixed(r.entry_angle_deg, 4)
          << " deg, sinkage = " << fixed(r.sinkage_m * 1e3, 3) << " mm\n";
    } else {
        s << "theta_f = " << fixed(r.entry_angle_deg, 4)
          << " deg (given), sinkage = " << fixed(r.sinkage_m * 1e3, 3) << " mm\n";
    }
    s << "theta_r = " << fixed(r.exit_angle_deg, 4) << " deg\n\n";
    const WheelForces<double>& f = r.forces;
    auto line = [&](const char* name, double value, const char* unit, const char* what) {
        char buffer[128];
        // Pad by display width: "N·m" is three columns but four bytes.
        const char* padded = std::string(unit) == "N" ? "N  " : unit;
        std::snprintf(buffer, sizeof buffer, "  %-3s %12s %s  %s\n", name, fixed(value, 4).c_str(),
                      padded, what);
        s << buffer;
    };
    line("Fx", f.fx, "N", "drawbar pull (Eq. 2.23)");
    line("Fy", f.fy, "N", "lateral force from shear (Eq. 2.25)");
    line("Fz", f.fz, "N", "vertical force (Eq. 2.31)");
    line("Mx", f.mx, "N·m", "roll moment (Eq. 2.32)");
    line("My", f.my, "N·m", "resistance torque (Eq. 2.34)");
    line("Mz", f.mz, "N·m", "yaw moment (Eq. 2.35)");
    line("Fb", f.fb, "N",
         ("bulldozing, one side wall (Eq. 2.30, " + o.model.bulldozing + ")").c_str());
    line("Fs", f.fs, "N", "side force Fy - sign(beta) Fb (Eq. 2.24)");
    std::cout << s.str();
}

// The batch CSV's columns: the operating point's field table (contact/operating_fields.h), as
// the single-point flags (docs/cli.md).
const io::NumericColumn kSlip = io::numericColumn(contact::slipField());
const io::NumericColumn kSlipAngle = io::numericColumn(contact::slipAngleField());
const io::NumericColumn kEntryAngle = io::numericColumn(contact::entryAngleField());
const io::NumericColumn kLoad = io::numericColumn(contact::loadField());
const io::NumericColumn kExitAngle = io::numericColumn(contact::exitAngleField());
const io::NumericColumn kRutRatio = io::numericColumn(contact::rutRatioField());
const io::NumericColumn kMaxStressAngle = io::numericColumn(contact::maxStressAngleField());

// Batch mode: one operating point per CSV row.
int runBatch(const ContactParameters<double>& p, const WheelOptions& o) {
    std::vector<NamedInput> inputs = o.model.inputFiles();
    inputs.push_back({"--input", o.input});
    refuseInputAsOutput("--output", o.output, inputs);
    Result<io::CsvDocument> read = io::readCsv(o.input);
    if (!read) throw InputError(read.message());
    const io::CsvDocument& doc = read.value();
    std::vector<Issue> issues = doc.row_issues;  // rows with the wrong number of cells
    int skipped = static_cast<int>(issues.size());
    auto index = [&](const std::string& name) -> int {
        for (std::size_t i = 0; i < doc.header.size(); ++i) {
            if (doc.header[i] == name) return static_cast<int>(i);
        }
        return -1;
    };
    const int c_slip = index("slip"), c_beta = index("slip_angle_deg"),
              c_theta = index("entry_angle_deg"), c_load = index("load_N"),
              c_exit = index("exit_angle_deg"), c_rut = index("rut_ratio"),
              c_theta_m = index("max_stress_angle_deg");
    // A misspelt column ("slp", "Slip") would leave every row at the flag's default: an error
    // when the column it most likely means is missing, a warning for any other unknown column.
    const std::string header_at = o.input + ":" + std::to_string(doc.header_line);
    const io::ColumnCheck columns =
        io::checkColumns(doc.header,
                         {kSlip.name, kSlipAngle.name, kEntryAngle.name, kLoad.name,
                          kExitAngle.name, kRutRatio.name, kMaxStressAngle.name},
                         header_at, "copied to the output as it is");
    if (!columns.errors.empty()) throw InputError(formatIssues(columns.errors));
    for (const Issue& warning : columns.warnings)
        std::cerr << warning.where << ": warning: " << warning.message << '\n';
    if (c_theta < 0 && c_load < 0 && !o.entry_angle_deg && !o.load_n) {
        throw InputError(o.input + ": needs a column entry_angle_deg or load_N (or the flag " +
                         "--entry-angle / --load for every row)");
    }
    // Slip is the quantity a batch varies: say when its column is absent, so that a file
    // without slips is not read as a file of slip 0 unnoticed.
    if (c_slip < 0) {
        std::cerr << o.input << ": note: no column slip: every row at s = " << formatNumber(o.slip)
                  << " (--slip)\n";
    }
    std::string csv;
    for (std::size_t i = 0; i < doc.header.size(); ++i) csv += (i ? "," : "") + doc.header[i];
    csv +=
        ",status,entry_angle_deg_out,exit_angle_deg_out,sinkage_m,Fx_N,Fy_N,Fz_N,Mx_Nm,My_Nm,"
        "Mz_Nm,Fb_N,Fs_N\n";
    int failed = 0;
    std::size_t cancelled = 0;
    std::vector<std::string> row_warnings;  // printed after the rows, bounded
    const SignalCancellation cancellation;
    TerminalProgress progress("wheel --input");
    const double row_count = static_cast<double>(doc.rows.size());
    for (std::size_t row = 0; row < doc.rows.size(); ++row) {
        const auto& cells = doc.rows[row];
        if (cancellation.requested()) {
            // The rows not computed are written too, marked, so the output lines up with the input.
            for (std::size_t i = 0; i < cells.size(); ++i) csv += (i ? "," : "") + cells[i];
            csv += ",cancelled,,,,,,,,,,,\n";
            ++cancelled;
            continue;
        }
        progress.update(static_cast<double>(row) / row_count);
        const std::string where = o.input + ":" + std::to_string(doc.line_numbers[row]);
        const std::size_t before = issues.size();
        // A cell of a column (its range checked, docs/cli.md "Batch mode"), else the flag's value.
        auto cell = [&](int column, const io::NumericColumn& spec,
                        std::optional<double> fallback) -> std::optional<double> {
            if (column < 0 || cells[column].empty()) return fallback;
            return io::readCell(cells[column], spec, where, issues);
        };
        PointSpec in;
        in.slip = cell(c_slip, kSlip, o.slip).value_or(0.0);
        in.slip_angle_deg = cell(c_beta, kSlipAngle, o.slip_angle_deg).value_or(0.0);
        in.entry_angle_deg = cell(c_theta, kEntryAngle, o.entry_angle_deg);
        in.load_n = cell(c_load, kLoad, o.load_n);
        if (in.entry_angle_deg && in.load_n) {
            if (c_theta >= 0 && c_load >= 0 && !cells[c_theta].empty() && !cells[c_load].empty()) {
                issues.push_back({where, "give entry_angle_deg or load_N, not both"});
            } else if (c_load >= 0 && !cells[c_load].empty()) {
                in.entry_angle_deg.reset();
            } else {
                in.load_n.reset();
            }
        }
        if (!in.entry_angle_deg && !in.load_n && issues.size() == before)
            issues.push_back({where, "no entry_angle_deg or load_N"});
        in.model.exit = o.model.exitCondition();
        const auto exit = cell(c_exit, kExitAngle, std::nullopt);
        const auto rut = cell(c_rut, kRutRatio, std::nullopt);
        if (exit && rut) {
            issues.push_back({where, "give exit_angle_deg or rut_ratio, not both"});
        } else if (exit) {
            in.model.exit = {contact::ExitCondition::Kind::kAngle, units::degToRad(*exit)};
        } else if (rut) {
            in.model.exit = {contact::ExitCondition::Kind::kRutRatio, *rut};
        }
        in.model.max_stress_angle_rad = o.model.maxStressAngleRad();
        if (auto theta_m = cell(c_theta_m, kMaxStressAngle, std::nullopt)) {
            in.model.max_stress_angle_rad = units::degToRad(*theta_m);
        }
        PointResult result;
        if (issues.size() == before) {
            try {
                result = evaluate(p, o, in);
            } catch (const std::exception& e) {  // InputError and invalid_argument: a bad row
                issues.push_back({where, e.what()});
            }
        }
        if (issues.size() != before) {
            ++skipped;
            continue;
        }
        if (!result.warning.empty()) row_warnings.push_back(where + ": warning: " + result.warning);
        for (std::size_t i = 0; i < cells.size(); ++i) csv += (i ? "," : "") + cells[i];
        if (!result.failure.empty()) {
            ++failed;
            csv += "," + result.status + ",,,,,,,,,,,\n";
            continue;
        }
        const WheelForces<double>& f = result.forces;
        csv += ",ok";
        for (double v : {result.entry_angle_deg, result.exit_angle_deg, result.sinkage_m, f.fx,
                         f.fy, f.fz, f.mx, f.my, f.mz, f.fb, f.fs}) {
            csv += "," + formatNumber(v);
        }
        csv += '\n';
    }
    if (cancelled == 0) progress.update(1.0);
    progress.finish();
    printLines(row_warnings, "");
    if (!issues.empty()) {
        // In line order: rows with the wrong cell count come from the reader, the rest from here.
        const std::string prefix = o.input + ":";
        auto line = [&](const Issue& issue) {
            return issue.where.rfind(prefix, 0) == 0
                       ? std::atol(issue.where.c_str() + prefix.size())
                       : 0L;
        };
        std::stable_sort(issues.begin(), issues.end(),
                         [&](const Issue& a, const Issue& b) { return line(a) < line(b); });
        std::cerr << formatIssues(issues) << '\n';
        if (!o.skip_bad_rows) {
            std::cerr << skipped
                      << " bad row(s); nothing written (use --skip-bad-rows to skip them)\n";
            return kBadInput;
        }
        std::cerr << "skipped " << skipped << " bad row(s)\n";
    }
    writeOutput(o.output, csv);
    if (!o.output.empty() && o.output != "-") {
        std::cerr << "wrote " << o.output << ": "
                  << doc.rows.size() + doc.row_issues.size() - skipped << " rows (" << failed
                  << " without a solution)\n";
    }
    if (cancelled > 0) {
        exitCancelled(cancellation, "cancelled by " + cancellation.signalName() + ": " +
                                        std::to_string(cancelled) +
                                        " row(s) not computed, marked 'cancelled'");
    }
    return kSuccess;
}

}  // namespace

void addWheelCommand(CLI::App& app, const io::PresetLocations& locations) {
    auto options = std::make_shared<WheelOptions>();
    CLI::App* cmd = app.add_subcommand(
        "wheel", "Forces and moments of one wheel at one operating point (or a CSV of points)");
    options->model.addTo(*cmd);
    cmd->add_option("--slip", options->slip,
                    "Slip ratio s in " + contact::slipField().range.describe() +
                        " (Eq. 2.1; 1: spinning in place, -1: locked)")
        ->capture_default_str();
    cmd->add_option("--slip-angle", options->slip_angle_deg, "Slip angle beta [deg] (Eq. 2.2)")
        ->capture_default_str();
    auto* entry =
        cmd->add_option("--entry-angle", options->entry_angle_deg, "Entry angle theta_f [deg]");
    cmd->add_option("--load", options->load_n, "Wheel load W [N]: solve theta_f from F_z = W")
        ->excludes(entry);
    cmd->add_flag("--json", options->json, "Machine-readable JSON output");
    cmd->add_option("--input", options->input, "Batch mode: CSV of operating points");
    cmd->add_option("--output", options->output, "Batch mode: result CSV (default: stdout)");
    cmd->add_flag("--skip-bad-rows", options->skip_bad_rows, "Batch mode: skip invalid rows");
    cmd->callback([options, &locations] {
        const WheelOptions& o = *options;
        const soil::SoilParameters soil = o.model.soilParameters(locations);
        const wheel::WheelParameters wheel = o.model.wheelParameters(locations);
        const ContactParameters<double> p = contact::makeContactParameters(soil, wheel);
        if (!o.input.empty()) {
            if (o.json) throw InputError("--json: batch mode (--input) writes CSV; drop --json");
            const int code = runBatch(p, o);
            if (code != kSuccess) throw CLI::RuntimeError(code);
            return;
        }
        if (!o.output.empty() || o.skip_bad_rows) {
            throw InputError(
                "--output and --skip-bad-rows belong to batch mode: add --input points.csv");
        }
        if (!o.entry_angle_deg && !o.load_n) {
            throw InputError("wheel: give --entry-angle DEG or --load N (or --input points.csv)");
        }
        PointSpec in;
        in.slip = o.slip;
        in.slip_angle_deg = o.slip_angle_deg;
        in.entry_angle_deg = o.entry_angle_deg;
        in.load_n = o.load_n;
        // The model flags as the choices' settings object, read by their reader.
        nlohmann::json choices = nlohmann::json::object();
        addModelChoices(o.model, choices);
        in.model =
            readFlagSettings<analysis::ModelChoices>(choices, analysis::readModelChoices, {});
        const PointResult result = evaluate(p, o, in);
        if (!result.failure.empty()) throw std::runtime_error(result.failure);
        if (!result.warning.empty()) std::cerr << "warning: " << result.warning << '\n';
        if (o.json) {
            std::cout << toJson(result).dump(2) << '\n';
        } else {
            printHuman(soil, wheel, o, in, result);
        }
    });
}

}  // namespace terra::app
