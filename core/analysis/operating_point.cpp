#include "core/analysis/operating_point.h"

#include <cmath>
#include <stdexcept>

#include "core/common/range.h"
#include "core/common/units.h"
#include "core/contact/contact_angles.h"
#include "core/contact/operating_fields.h"
#include "core/contact/quadratic_model.h"
#include "core/contact/sinkage.h"

namespace terra::analysis {

PointResult evaluatePoint(const contact::ContactParameters<double>& p, const PointSpec& in) {
    std::vector<Issue> issues;
    auto check = [&](const FieldInfo& field, double value) {
        checkRange(issues, field.key, value, field.range, field.displayUnit());
    };
    check(contact::slipField(), in.slip);
    check(contact::slipAngleField(), in.slip_angle_deg);
    if (in.load_n) check(contact::loadField(), *in.load_n);
    if (in.entry_angle_deg) check(contact::entryAngleField(), *in.entry_angle_deg);
    if (!in.load_n && !in.entry_angle_deg) {
        issues.push_back({"entry_angle_deg", "give an entry angle or a load"});
    }
    if (!issues.empty()) throw std::invalid_argument(formatIssues(issues));

    PointResult out;
    double theta_f = 0.0;
    const double beta = units::degToRad(in.slip_angle_deg);
    if (in.load_n) {
        contact::EntryAngleProblem problem;
        problem.load_n = *in.load_n;
        problem.slip = in.slip;
        problem.slip_angle_rad = beta;
        problem.exit = in.model.exit;
        problem.max_stress_angle_rad = in.model.max_stress_angle_rad;
        problem.model = in.contact_model;
        const contact::SinkageSolution solution = contact::solveEntryAngle(p, problem);
        if (!solution.ok()) {
            out.failure = solution.message;
            out.status = solution.status == contact::SinkageSolution::Status::kLoadNotMatched
                             ? "load-not-matched"
                             : "no-equilibrium";
            return out;
        }
        theta_f = solution.entry_angle_rad;
        out.solved_from_load = true;
    } else {
        theta_f = units::degToRad(*in.entry_angle_deg);
    }
    // θ_r kept ≥ −θ_f, as the model does (docs/model.md); reported as used.
    const contact::OperatingPoint<double> op{
        in.slip, beta, theta_f,
        contact::clampedExitAngle(in.model.exit.exitAngle(theta_f), theta_f),
        in.model.max_stress_angle_rad};
    contact::requireValid(op);
    if (in.contact_model == contact::ContactModel::kFull) {
        contact::IntegrationReport report;
        out.forces = contact::computeForces(p, op, in.model.bulldozing, {}, &report);
        if (!report.converged) {
            out.warning = "the force integration stopped at its cap of " +
                          std::to_string(report.pieces) +
                          " pieces before reaching its tolerance (estimated relative error " +
                          formatNumber(roundSignificant(report.error_estimate, 2)) + ")";
        }
    } else {
        out.forces = contact::computeQuadraticForces(p, op, in.model.bulldozing);
    }
    out.entry_angle_deg = roundSignificant(units::radToDeg(theta_f));
    out.exit_angle_deg = roundSignificant(units::radToDeg(op.exit_angle_rad));
    out.sinkage_m = contact::slipSinkage(p.radius_m, theta_f, op.slip, p.slip_sinkage_coefficient);
    return out;
}

}  // namespace terra::analysis
