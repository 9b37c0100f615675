#include "core/analysis/stresses.h"

#include <cmath>
#include <stdexcept>

#include "core/analysis/registry.h"
#include "core/common/range.h"
#include "core/common/units.h"
#include "core/contact/operating_fields.h"
#include "core/io/declared_json.h"
#include "core/io/table_json.h"

namespace terra::analysis {
namespace {

double plainZero(double value) { return value == 0.0 ? 0.0 : value; }

}  // namespace

const std::vector<std::string>& stressNames() {
    static const std::vector<std::string> names{"all", "sigma", "tau", "tau_t", "tau_l"};
    return names;
}

void readStressSettings(io::ObjectReader& r, StressSettings& out) { io::readFields(r, out); }

nlohmann::json toJson(const StressSettings& s) { return io::fieldsToJson(s); }

StressResult computeStresses(const Inputs& in, const StressSettings& settings,
                             const Control& control) {
    // The reader's checks, in its words, for settings built in code (the panel's, a test's).
    if (const std::vector<Issue> issues = io::fieldIssues(settings); !issues.empty())
        throw std::invalid_argument(formatIssues(issues));
    const contact::ContactParameters<double> params = in.contact();
    const double beta = units::degToRad(settings.slip_angle_deg);
    StressResult out;
    if (control.cancelled()) {
        out.cancelled = true;
        return out;
    }
    out.table.columns = {"theta_deg",      "sigma_kPa",     "tau_kPa",        "tau_t_kPa",
                         "tau_l_kPa",      "j_m",           "sigma_quad_kPa", "tau_quad_kPa",
                         "tau_t_quad_kPa", "tau_l_quad_kPa"};
    contact::OperatingPoint<double> op;
    if (settings.entry_angle_deg) {
        const double theta_f = units::degToRad(*settings.entry_angle_deg);
        op = {settings.slip, beta, theta_f, settings.model.exit.exitAngle(theta_f),
              settings.model.max_stress_angle_rad};
    } else {
        contact::EntryAngleProblem problem;
        problem.load_n = in.conditions.load_n;
        problem.slip = settings.slip;
        problem.slip_angle_rad = beta;
        problem.exit = settings.model.exit;
        problem.max_stress_angle_rad = settings.model.max_stress_angle_rad;
        problem.model = in.conditions.model();
        const contact::SinkageSolution solution = contact::solveEntryAngle(params, problem);
        if (!solution.ok()) {
            out.message = solution.message;
            return out;
        }
        op = contact::operatingPoint(problem, solution.entry_angle_rad);
    }
    contact::requireValid(op);
    const double step = units::degToRad(settings.step_deg);
    const contact::StressField<double> field(params, op);
    const contact::QuadraticStress<double> quadratic = contact::fitQuadraticStress(field);
    out.entry_angle_deg = units::radToDeg(field.entryAngle());
    out.max_stress_angle_deg = units::radToDeg(field.maxStressAngle());
    // The grid of quadraticApproximationErrors: from the θ_r the model uses (≥ −θ_f).
    const double theta_r = field.exitAngle();
    const auto steps = static_cast<long>(std::floor((field.entryAngle() - theta_r) / step + 1e-9));
    for (long i = 0; i <= steps; ++i) {
        const double theta = theta_r + static_cast<double>(i) * step;
        const auto e = field.at(theta);
        const auto q = quadratic.at(theta);
        out.table.rows.push_back({plainZero(roundSignificant(units::radToDeg(theta))),
                                  e.sigma / 1e3, e.tau / 1e3, e.tau_t / 1e3, e.tau_l / 1e3, e.shear,
                                  q.sigma / 1e3, q.tau / 1e3, q.tau_t / 1e3, q.tau_l / 1e3});
    }
    out.errors = contact::quadraticApproximationErrors(params, op, step);
    return out;
}

namespace {

constexpr const char* kStressKeys[] = {"sigma", "tau", "tau_t", "tau_l"};

}  // namespace

nlohmann::json toJson(const StressResult& r) {
    nlohmann::json errors;
    for (std::size_t k = 0; k < 4; ++k) {
        errors[std::string(kStressKeys[k]) + "_rmse_kPa"] = r.errors[k].rmse / 1e3;
        errors[std::string(kStressKeys[k]) + "_mae_kPa"] = r.errors[k].mae / 1e3;
    }
    // θ_m and θ_f as typed (15, not 15.000000000000002), or as solved.
    errors["max_stress_angle_deg"] = plainZero(roundSignificant(r.max_stress_angle_deg));
    errors["entry_angle_deg"] = plainZero(roundSignificant(r.entry_angle_deg));
    errors["points"] = r.table.rows.size();
    nlohmann::json out{{"errors", errors}, {"grid", io::toJson(r.table)}};
    out["status"] = statusName(r.status());
    if (!r.message.empty()) out["message"] = r.message;
    return out;
}

Summary stressSummary(const Inputs& in, const StressSettings& s, const StressResult& r) {
    using Emphasis = SummaryRow::Emphasis;
    Summary out;
    out.push_back({"stresses",
                   in.soil.name + ", " + in.wheel.name + ", s = " + formatNumber(s.slip) +
                       ", beta = " + formatNumber(s.slip_angle_deg) + " deg",
                   "", "", Emphasis::kHeading, ""});
    if (r.status() != Outcome::Status::kCompleted) {
        out.push_back({statusName(r.status()), r.message, "", "", Emphasis::kWarning,
                       r.message.empty() ? "" : "/message"});
        return out;
    }
    const double theta_f = plainZero(roundSignificant(r.entry_angle_deg));
    const double theta_m = plainZero(roundSignificant(r.max_stress_angle_deg));
    out.push_back(
        {"theta_f", s.entry_angle_deg ? formatNumber(theta_f) : formatFixed(theta_f, 4), "deg",
         s.entry_angle_deg ? "given"
                           : "from F_z = W = " + formatNumber(in.conditions.load_n) + " N",
         Emphasis::kNormal, "/errors/entry_angle_deg", theta_f});
    out.push_back({"theta_m", formatFixed(theta_m, 4), "deg", "", Emphasis::kNormal,
                   "/errors/max_stress_angle_deg", theta_m});
    out.push_back({"quadratic approximation vs exact",
                   std::to_string(r.table.rows.size()) + " angles", "",
                   "step " + formatNumber(s.step_deg) + " deg", Emphasis::kHeading, "/errors"});
    for (std::size_t k = 0; k < 4; ++k) {
        const std::string key = kStressKeys[k];
        out.push_back({key + " RMSE", formatFixed(r.errors[k].rmse / 1e3, 4), "kPa",
                       "MAE " + formatFixed(r.errors[k].mae / 1e3, 4) + " kPa", Emphasis::kNormal,
                       "/errors/" + key + "_rmse_kPa", r.errors[k].rmse / 1e3});
    }
    return out;
}

Table errorTable(const StressResult& result) {
    Table errors{{"stress_index", "rmse_kPa", "mae_kPa"}, {}};
    for (int i = 0; i < 4; ++i) {
        errors.rows.push_back(
            {static_cast<double>(i), result.errors[i].rmse / 1e3, result.errors[i].mae / 1e3});
    }
    return errors;
}

Outcome stressOutcome(StressResult result) {
    Outcome out;
    if (result.cancelled) {
        out.status = Outcome::Status::kCancelled;
        out.message = "cancelled";
    } else if (!result.message.empty()) {
        // No equilibrium: there is no grid, and an error table would read as zero errors (an
        // expectation on it would pass). The analysis failed, with the reason.
        out.status = Outcome::Status::kFailed;
        out.message = result.message;
    } else {
        out.tables.push_back({"stresses", "", result.table});
        out.tables.push_back({"errors", "-errors", errorTable(result)});
    }
    out.documents.push_back({".json", toJson(result)});  // what `stresses --json` prints
    out.result = std::move(result);
    return out;
}

AnalysisType stressesType() {
    return makeAnalysisType<StressSettings>(
        "stresses",
        "stress distributions at one operating point, exact and quadratic, with RMSE/MAE "
        "(Figs. 2.11, 2.16; Tables 2.4-2.5)",
        {"stresses", "errors"}, {{"stresses", ""}},
        [](io::ObjectReader& r, const ReadContext&, StressSettings& s) {
            readStressSettings(r, s);
        },
        [](const Inputs& in, const StressSettings& s, const Control& c) {
            return computeStresses(in, s, c);
        },
        stressOutcome);
}

}  // namespace terra::analysis
