#include "core/analysis/sweep.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <stdexcept>
#include <thread>

#include "core/common/quoted.h"
#include "core/common/range.h"
#include "core/common/units.h"
#include "core/contact/contact_angles.h"
#include "core/contact/operating_fields.h"
#include "core/contact/quadratic_model.h"

namespace terra::analysis {
namespace {

using contact::ContactParameters;
using contact::OperatingPoint;
using contact::WheelForces;

struct Row {
    std::vector<double> values;
    std::string warning;
};

// One slip angle over all slips, warm-starting each solve from the previous one.
// `done` is called after each slip.
std::vector<Row> sweepOneAngle(const ContactParameters<double>& p, const SweepSpec& spec,
                               double beta, const std::function<void()>& done) {
    std::vector<Row> rows;
    std::optional<double> previous;
    for (double s : spec.slips) {
        if (spec.cancel && spec.cancel->load(std::memory_order_relaxed)) break;
        double theta_f = spec.entry_angle_rad;
        if (spec.load_n) {
            contact::EntryAngleProblem problem{
                *spec.load_n,     s,       beta, spec.exit, spec.max_stress_angle_rad, spec.model,
                spec.integration, previous};
            const contact::SinkageSolution solution = contact::solveEntryAngle(p, problem);
            if (!solution.ok()) {
                rows.push_back({{},
                                "β = " + formatNumber(roundedDegrees(beta)) +
                                    "°, s = " + formatNumber(s) + ": " + solution.message});
                previous.reset();
                done();
                continue;
            }
            theta_f = solution.entry_angle_rad;
            previous = theta_f;
        }
        const double theta_r = contact::clampedExitAngle(spec.exit.exitAngle(theta_f), theta_f);
        const OperatingPoint<double> op{s, beta, theta_f, theta_r, spec.max_stress_angle_rad};
        const WheelForces<double> f =
            spec.model == contact::ContactModel::kFull
                ? contact::computeForces(p, op, spec.bulldozing, spec.integration)
                : contact::computeQuadraticForces(p, op, spec.bulldozing);
        // Given angles as typed (25, not 25.000000000000004); a solved θ_f keeps every digit, so
        // that the row reproduces its forces exactly. No negative zeros anywhere in the row.
        const double theta_f_deg = spec.load_n ? units::radToDeg(theta_f) : roundedDegrees(theta_f);
        const double h = contact::slipSinkage(p.radius_m, theta_f, s, p.slip_sinkage_coefficient);
        std::vector<double> values{roundedDegrees(beta),
                                   s,
                                   theta_f_deg,
                                   roundedDegrees(theta_r),
                                   h,
                                   f.fx,
                                   f.fy,
                                   f.fz,
                                   f.mx,
                                   f.my,
                                   f.mz,
                                   f.fb,
                                   f.fs};
        for (double& v : values) v = v == 0.0 ? 0.0 : v;
        rows.push_back({std::move(values), {}});
        done();
    }
    return rows;
}

void validateSpec(const SweepSpec& spec) {
    std::vector<Issue> issues;
    auto check = [&](const FieldInfo& field, double value) {
        checkRange(issues, field.key, value, field.range, field.displayUnit());
    };
    if (spec.slips.empty()) issues.push_back({"slips", "no slip values to sweep"});
    if (spec.slip_angles_rad.empty()) issues.push_back({"slip_angles", "no slip angles to sweep"});
    for (double s : spec.slips) check(contact::slipField(), s);
    for (double b : spec.slip_angles_rad) check(contact::slipAngleField(), roundedDegrees(b));
    if (spec.load_n) {
        check(contact::loadField(), *spec.load_n);
    } else {
        check(contact::entryAngleField(), roundedDegrees(spec.entry_angle_rad));
    }
    if (spec.exit.kind == contact::ExitCondition::Kind::kRutRatio) {
        check(contact::rutRatioField(), spec.exit.value);
    } else {
        check(contact::exitAngleField(), roundedDegrees(spec.exit.value));
    }
    if (spec.max_stress_angle_rad)
        check(contact::maxStressAngleField(), roundedDegrees(*spec.max_stress_angle_rad));
    if (!issues.empty()) throw std::invalid_argument(formatIssues(issues));
}

}  // namespace

std::vector<double> linspace(double first, double last, int count) {
    if (count < 1) throw std::invalid_argument("linspace needs at least one point");
    if (count == 1) return {first};
    std::vector<double> out(static_cast<std::size_t>(count));
    for (int i = 0; i < count; ++i) {
        const double value = first + (last - first) * i / (count - 1);
        // Round to 12 significant digits so that decimal grids print as typed (0.27, not
        // 0.26999999999999996); far below any physical resolution of slip or angle.
        char text[32];
        std::snprintf(text, sizeof text, "%.12g", value);
        out[i] = std::strtod(text, nullptr);
    }
    return out;
}

std::vector<double> thesisSlips(int count) {
    std::vector<double> out;
    for (int i = 0; i < count; ++i) out.push_back(static_cast<double>(i) / count);
    return out;
}

const std::vector<std::string>& sweepColumns() {
    static const std::vector<std::string> columns{
        "slip_angle_deg", "slip",  "entry_angle_deg", "exit_angle_deg", "sinkage_m", "Fx_N", "Fy_N",
        "Fz_N",           "Mx_Nm", "My_Nm",           "Mz_Nm",          "Fb_N",      "Fs_N"};
    return columns;
}

SweepResult sweepSlip(const ContactParameters<double>& p, const SweepSpec& spec) {
    validateSpec(spec);
    const std::size_t angles = spec.slip_angles_rad.size();
    std::vector<std::vector<Row>> per_angle(angles);
    const unsigned hardware = std::max(1u, std::thread::hardware_concurrency());
    const std::size_t workers =
        std::min<std::size_t>(angles, spec.threads > 0 ? spec.threads : hardware);
    // An exception escaping a std::jthread calls std::terminate: each worker catches what it
    // throws, the others stop at their next slip angle, and the failure is rethrown here.
    std::vector<std::exception_ptr> failures(workers);
    std::atomic<bool> failed{false};
    std::atomic<std::size_t> points_done{0};
    const double points = static_cast<double>(angles * spec.slips.size());
    const std::function<void()> done = [&] {
        const std::size_t now = points_done.fetch_add(1, std::memory_order_relaxed) + 1;
        if (spec.progress) spec.progress(static_cast<double>(now) / points);
    };
    {
        std::vector<std::jthread> pool;
        for (std::size_t w = 0; w < workers; ++w) {
            pool.emplace_back([&, w] {
                try {
                    for (std::size_t i = w; i < angles && !failed.load(); i += workers) {
                        per_angle[i] = sweepOneAngle(p, spec, spec.slip_angles_rad[i], done);
                    }
                } catch (...) {
                    failures[w] = std::current_exception();
                    failed.store(true);
                }
            });
        }
    }
    for (const std::exception_ptr& failure : failures) {
        if (failure) std::rethrow_exception(failure);
    }
    SweepResult result;
    result.table.columns = sweepColumns();
    for (auto& rows : per_angle) {
        for (Row& row : rows) {
            if (row.warning.empty()) {
                result.table.rows.push_back(std::move(row.values));
            } else {
                result.warnings.push_back(std::move(row.warning));
            }
        }
    }
    result.cancelled = spec.cancel && spec.cancel->load();
    return result;
}

std::vector<SensitivityParameter> thesisSensitivityParameters() {
    return {{"n", {0.6, 0.8, 1.0, 1.2}},
            {"c_kPa", {0.0, 1.5, 3.0, 4.5}},
            {"phi_deg", {25.0, 30.0, 35.0, 40.0}},
            {"kc", {0.0, 5.0, 10.0, 20.0}},
            {"kphi", {900.0, 1200.0, 1600.0, 2000.0}},
            {"K_m", {0.01, 0.02, 0.03, 0.04}}};
}

SweepResult sensitivity(const soil::SoilParameters& soil, const wheel::WheelParameters& wheel,
                        const SensitivityParameter& parameter, const SweepSpec& spec) {
    const soil::SoilField* field = soil::findSoilField(parameter.key);
    if (!field) throw std::invalid_argument("unknown soil parameter " + quoteText(parameter.key));
    SweepResult result;
    result.table.columns = {parameter.key};
    for (const std::string& c : sweepColumns()) result.table.columns.push_back(c);
    const double count = static_cast<double>(parameter.values.size());
    for (std::size_t v = 0; v < parameter.values.size(); ++v) {
        const double value = parameter.values[v];
        soil::SoilParameters varied = soil;
        soil::setUserValue(varied, *field, value);
        SweepSpec one_spec = spec;
        if (spec.progress) {
            one_spec.progress = [&spec, v, count](double f) {
                spec.progress((static_cast<double>(v) + f) / count);
            };
        }
        const SweepResult one = sweepSlip(contact::makeContactParameters(varied, wheel), one_spec);
        for (const auto& row : one.table.rows) {
            std::vector<double> values{value};
            values.insert(values.end(), row.begin(), row.end());
            result.table.rows.push_back(std::move(values));
        }
        for (const std::string& w : one.warnings) {
            result.warnings.push_back(std::string(parameter.key) + " = " + formatNumber(value) +
                                      ": " + w);
        }
        if (one.cancelled) {
            result.cancelled = true;
            break;
        }
    }
    return result;
}

}  // namespace terra::analysis
