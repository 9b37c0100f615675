#include "core/contact/sinkage.h"

#include <boost/math/tools/toms748_solve.hpp>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <stdexcept>
#include <string>

#include "core/common/range.h"
#include "core/common/units.h"
#include "core/contact/contact_angles.h"
#include "core/contact/quadratic_model.h"

namespace terra::contact {
namespace {

constexpr double kRightAngle = std::numbers::pi / 2.0;
constexpr double kSmallestAngle = 1e-6;  // [rad] F_z is ~1e-12 of its 90° value here
constexpr int kToleranceBits = 42;       // θ_f to ~2e-13 relative: F_z = W to ~1e-12

void requirePositiveLoad(double load_n) {
    if (!(load_n > 0.0) || !std::isfinite(load_n)) {
        throw std::invalid_argument("load W = " + formatNumber(load_n) +
                                    " N must be > 0 and finite");
    }
}

// F_z = W is accepted when |F_z − W| ≤ kLoadTolerance · W. The root finder normally stops at
// ~1e-12; a residual above this bound means F_z jumps across the final bracket (a very small
// sinkage exponent with θ_m fixed near θ_f makes F_z rise like (θ_f − θ_m)^N, N = 0.13: a step at
// double resolution) and no representable θ_f carries W.
constexpr double kLoadTolerance = 1e-9;
// The root finder stops early once the bracket is 42 bits narrow and F_z is this close to W.
constexpr double kEarlyStopTolerance = 1e-10;
// When F_z(90°) < W, F_z(θ_f) is scanned at this many equal steps before "no equilibrium" is
// declared: under strong braking F_z can peak inside (0°, 90°) (heavy clay, s = −0.95: a maximum
// of 5.4 kN at 62° but 4.6 kN at 90°).
constexpr int kScanSteps = 45;

std::string degrees(double rad) { return formatNumber(roundSignificant(units::radToDeg(rad), 10)); }

// Root of f(θ) − target on (0, 90°] with TOMS 748, starting from a guess. F_z usually rises with
// θ_f; when it does not reach the target at 90° the range is scanned for the first crossing.
template <typename F>
SinkageSolution bracketAndSolve(F force, double target, double guess, int& evaluations) {
    SinkageSolution out;
    // Every evaluation is remembered: the answer is the evaluated angle with the smallest
    // residual, whose F_z is then known without another evaluation.
    double best_theta = std::nan(""), best_residual = INFINITY;
    auto residual = [&](double theta) {
        ++evaluations;
        const double r = force(theta) - target;
        if (std::abs(r) < std::abs(best_residual)) best_theta = theta, best_residual = r;
        return r;
    };
    const double f_max = residual(kRightAngle);
    double lo = kSmallestAngle, hi = kRightAngle;
    double f_lo = std::nan(""), f_hi = f_max;
    if (f_max < 0.0) {
        // Scan upward for the first sign change (the wheel sinks until F_z first reaches W).
        double a = kSmallestAngle, fa = residual(a), peak = f_max, peak_theta = kRightAngle;
        for (int k = 1; k <= kScanSteps && std::isnan(f_lo); ++k) {
            const double b = k == kScanSteps ? kRightAngle : kRightAngle * k / kScanSteps;
            const double fb = k == kScanSteps ? f_max : residual(b);
            if (fb > peak) peak = fb, peak_theta = b;
            if (fa <= 0.0 && fb >= 0.0) lo = a, hi = b, f_lo = fa, f_hi = fb;
            a = b, fa = fb;
        }
        if (std::isnan(f_lo)) {
            out.status = SinkageSolution::Status::kNoEquilibrium;
            out.entry_angle_rad = kRightAngle;
            out.vertical_force_n = f_max + target;
            out.message = "no equilibrium: at 90° (sunk to the axle) the soil carries only " +
                          formatNumber(f_max + target) + " N of the load " + formatNumber(target) +
                          " N; the wheel would sink to its axle";
            if (peak_theta < kRightAngle) {
                out.message += " (the largest F_z found, scanning θ_f in 2° steps, is " +
                               formatNumber(peak + target) + " N at " + degrees(peak_theta) + "°)";
            }
            return out;
        }
    } else if (guess > kSmallestAngle && guess < kRightAngle) {
        // Bracket around the guess, widening by 1.3× per step; fall back to the whole range.
        const double f_guess = residual(guess);
        double a = guess, fa = f_guess;
        for (int step = 0; step < 12 && f_guess != 0.0; ++step) {
            const double b =
                f_guess < 0.0 ? std::min(a * 1.3, kRightAngle) : std::max(a / 1.3, kSmallestAngle);
            const double fb = b == kRightAngle ? f_max : residual(b);
            if ((fa < 0.0) != (fb < 0.0) || fb == 0.0) {
                lo = std::min(a, b), hi = std::max(a, b);
                f_lo = a < b ? fa : fb, f_hi = a < b ? fb : fa;
                break;
            }
            a = b, fa = fb;
            if (b == kRightAngle || b == kSmallestAngle) break;
        }
    }
    if (best_residual == 0.0) {
        out.entry_angle_rad = best_theta;
        out.vertical_force_n = target;
        return out;
    }
    if (std::isnan(f_lo)) {
        lo = kSmallestAngle, hi = kRightAngle;
        f_lo = residual(lo), f_hi = f_max;
    }
    if (f_lo > 0.0) {
        out.status = SinkageSolution::Status::kNoEquilibrium;
        out.message = "F_z does not rise through the load W = " + formatNumber(target) +
                      " N on (0°, 90°]: no unique equilibrium";
        return out;
    }
    boost::math::tools::eps_tolerance<double> narrow(kToleranceBits), exhausted(53);
    auto done = [&](double a, double b) -> bool {
        return exhausted(a, b) ||
               (narrow(a, b) && std::abs(best_residual) <= kEarlyStopTolerance * target);
    };
    std::uintmax_t iterations = 100;
    auto [a, b] = boost::math::tools::toms748_solve(residual, lo, hi, f_lo, f_hi, done, iterations);
    if (!(std::abs(best_residual) <= kLoadTolerance * target)) {
        // A jump (or TOMS 748 out of iterations): bisect until the bracket is a few ulps wide
        // (eps_tolerance(53): 4 eps), so that a failure below means no angle carries W.
        double fa = residual(a), fb = residual(b);
        while (!exhausted(a, b) && fa != 0.0 && fb != 0.0 && best_residual != 0.0) {
            const double m = a + 0.5 * (b - a);
            if (m <= a || m >= b) break;
            const double fm = residual(m);
            if ((fm < 0.0) == (fa < 0.0)) {
                a = m, fa = fm;
            } else {
                b = m, fb = fm;
            }
        }
        if (!(std::abs(best_residual) <= kLoadTolerance * target)) {
            out.status = SinkageSolution::Status::kLoadNotMatched;
            // Full digits: the two angles differ in the last places.
            out.message = "no entry angle carries W = " + formatNumber(target) +
                          " N: F_z jumps from " + formatNumber(fa + target) + " N to " +
                          formatNumber(fb + target) +
                          " N between θ_f = " + formatNumber(units::radToDeg(a)) + "° and " +
                          formatNumber(units::radToDeg(b)) +
                          "°, a few units in the last place apart (a small sinkage exponent N with "
                          "θ_m fixed near θ_f makes F_z rise like (θ_f − θ_m)^N: a step at double "
                          "precision)";
        }
    }
    out.entry_angle_rad = best_theta;
    out.vertical_force_n = best_residual + target;
    return out;
}

// ∫_0^θs (cos θ − cos θ_s)^n cos θ dθ with the end mapping of wheel_forces.h (singular at θ_s).
double staticIntegral(double n, double theta_s) {
    const GaussRule& rule = gaussRule(15);
    const int q = endExponent(n, 0);
    double sum = 0.0;
    for (std::size_t i = 0; i < rule.nodes.size(); ++i) {
        const double u = rule.nodes[i];
        const double uq1 = std::pow(u, q - 1);
        const double gap = theta_s * (uq1 * u);  // θ_s − θ, exact
        const double theta = theta_s - gap;
        // cos θ − cos θ_s = 2 sin((θ_s + θ)/2) sin((θ_s − θ)/2): no cancellation at small θ_s.
        const double base = 2.0 * std::sin(theta_s - 0.5 * gap) * std::sin(0.5 * gap);
        if (base > 0.0)
            sum += rule.weights[i] * q * uq1 * theta_s * std::pow(base, n) * std::cos(theta);
    }
    return sum;
}

}  // namespace

double bekkerStaticSinkage(const ContactParameters<double>& p, double load_n) {
    requirePositiveLoad(load_n);
    const double n = p.sinkage_exponent;
    const double denominator =
        std::sqrt(2.0 * p.radius_m) * p.width_m * p.pressure_modulus * (1.0 - n / 3.0);
    return std::pow(load_n / denominator, 1.0 / (n + 0.5));
}

double staticLoad(const ContactParameters<double>& p, double static_angle_rad,
                  StaticContact contact) {
    const double n = p.sinkage_exponent;
    const double halves = contact == StaticContact::kSymmetric ? 2.0 : 1.0;
    return halves * p.radius_m * p.width_m * p.pressure_modulus * std::pow(p.radius_m, n) *
           staticIntegral(n, static_angle_rad);
}

SinkageSolution solveStaticSinkage(const ContactParameters<double>& p, double load_n,
                                   StaticContact contact) {
    requirePositiveLoad(load_n);
    int evaluations = 0;
    const double h_bekker = bekkerStaticSinkage(p, load_n);
    const double guess = h_bekker < p.radius_m ? std::acos(1.0 - h_bekker / p.radius_m) : 1.0;
    SinkageSolution out = bracketAndSolve(
        [&](double theta) { return staticLoad(p, theta, contact); }, load_n, guess, evaluations);
    out.evaluations = evaluations;
    out.exit_angle_rad = contact == StaticContact::kSymmetric ? -out.entry_angle_rad : 0.0;
    out.sinkage_m = p.radius_m * (1.0 - std::cos(out.entry_angle_rad));
    return out;
}

double ExitCondition::exitAngle(double entry_angle_rad) const {
    return kind == Kind::kAngle ? value : exitAngleFromRutRatio(entry_angle_rad, value);
}

OperatingPoint<double> operatingPoint(const EntryAngleProblem& problem, double entry_angle_rad) {
    return {problem.slip, problem.slip_angle_rad, entry_angle_rad,
            clampedExitAngle(problem.exit.exitAngle(entry_angle_rad), entry_angle_rad),
            problem.max_stress_angle_rad};
}

double verticalForce(const ContactParameters<double>& p, const EntryAngleProblem& problem,
                     double entry_angle_rad) {
    const OperatingPoint<double> op = operatingPoint(problem, entry_angle_rad);
    return problem.model == ContactModel::kFull
               ? computeForces(p, op, BulldozingModel::kBekker, problem.integration).fz
               : computeQuadraticForces(p, op).fz;
}

SinkageSolution solveEntryAngle(const ContactParameters<double>& p,
                                const EntryAngleProblem& problem) {
    requirePositiveLoad(problem.load_n);
    // Validate the kinematics once, at a representative entry angle.
    OperatingPoint<double> probe = operatingPoint(problem, kRightAngle);
    probe.max_stress_angle_rad.reset();
    requireValid(probe);
    if (problem.exit.kind == ExitCondition::Kind::kRutRatio &&
        !(problem.exit.value >= 0.0 && problem.exit.value <= 1.0)) {
        throw std::invalid_argument("rut ratio λ = " + formatNumber(problem.exit.value) +
                                    " is outside the allowed range [0, 1]");
    }
    double guess = problem.initial_guess_rad.value_or(0.0);
    if (!problem.initial_guess_rad) {
        const double h = bekkerStaticSinkage(p, problem.load_n);
        guess = h < p.radius_m ? std::acos(1.0 - h / p.radius_m) : 1.2;
    }
    int evaluations = 0;
    SinkageSolution out =
        bracketAndSolve([&](double theta) { return verticalForce(p, problem, theta); },
                        problem.load_n, guess, evaluations);
    out.evaluations = evaluations;
    out.exit_angle_rad = operatingPoint(problem, out.entry_angle_rad).exit_angle_rad;
    out.sinkage_m =
        slipSinkage(p.radius_m, out.entry_angle_rad, problem.slip, p.slip_sinkage_coefficient);
    return out;
}

}  // namespace terra::contact
