#include "core/identification/decoupled_fit.h"

#include <ceres/ceres.h>

#include <chrono>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "core/identification/decoupled_model.h"

namespace terra::identification {
namespace {

// Parameters are scaled to order one for the solver: K_s in MPa/m^N, c in kPa.
constexpr double kKsScale = 1e6;
constexpr double kCohesionScale = 1e3;

struct StepIResidual {
    double r, slip, theta_f, fx, fz, my;
    template <typename T>
    bool operator()(const T* const a, T* residual) const {
        const HatCoefficients<T> h = hatCoefficients(a[0], a[1], slip, theta_f);
        residual[0] = decoupledDrawbarPull(h, r, fz, my) - fx;
        return true;
    }
};

struct StepIIResidual {
    double r, b, a0, a1, slip, theta_f, fz, my;
    template <typename T>
    bool operator()(const T* const x, T* residual) const {
        const HatCoefficients<T> h = hatCoefficients(T(a0), T(a1), slip, theta_f);
        residual[0] =
            decoupledVerticalForce(h, r, b, T(x[0] * kKsScale), x[1], x[2], slip, theta_f, my) - fz;
        return true;
    }
};

struct StepIIIResidual {
    double r, b, a0, a1, slip, theta_f, fz, my;
    template <typename T>
    bool operator()(const T* const x, T* residual) const {
        const HatCoefficients<T> h = hatCoefficients(T(a0), T(a1), slip, theta_f);
        residual[0] =
            decoupledTorque(h, r, b, T(x[0] * kCohesionScale), x[1], x[2], slip, theta_f, fz) - my;
        return true;
    }
};

// All samples of a step in one cost function (one residual per sample): Ceres' per-block overhead
// dominated when each sample was its own block (about 3× slower).
template <typename Residual>
struct Batch {
    std::vector<Residual> rows;
    template <typename T>
    bool operator()(const T* const x, T* residual) const {
        for (std::size_t i = 0; i < rows.size(); ++i) rows[i](x, residual + i);
        return true;
    }
};

template <int kParameters, typename Residual>
ceres::CostFunction* batchCost(std::vector<Residual> rows) {
    const int n = static_cast<int>(rows.size());
    return new ceres::AutoDiffCostFunction<Batch<Residual>, ceres::DYNAMIC, kParameters>(
        new Batch<Residual>{std::move(rows)}, n);
}

StepReport solve(ceres::Problem& problem, const std::string& name, int max_iterations) {
    ceres::Solver::Options options;
    options.linear_solver_type = ceres::DENSE_QR;
    options.max_num_iterations = max_iterations;
    // Relative cost change 1e-10 is far below any data's noise; tighter only crawls along the flat
    // valleys of full-model data (K_s at its bound, c–φ) for 100+ iterations without changing
    // the fit (docs/identification.md).
    options.function_tolerance = 1e-10;
    options.parameter_tolerance = 1e-10;
    options.gradient_tolerance = 1e-12;
    options.logging_type = ceres::SILENT;
    options.num_threads = 1;
    ceres::Solver::Summary summary;
    const auto start = std::chrono::steady_clock::now();
    ceres::Solve(options, &problem, &summary);
    const auto stop = std::chrono::steady_clock::now();
    StepReport report;
    report.name = name;
    report.usable = summary.IsSolutionUsable();
    report.termination = ceres::TerminationTypeToString(summary.termination_type) +
                         std::string(": ") + summary.message;
    report.iterations = static_cast<int>(summary.iterations.size());
    report.squared_residual_norm = 2.0 * summary.final_cost;  // Ceres' cost is ½ Σ rᵢ²
    report.wall_time_ms = std::chrono::duration<double, std::milli>(stop - start).count();
    return report;
}

}  // namespace

bool DecoupledFit::usable() const {
    if (steps.empty()) return false;
    for (const StepReport& s : steps) {
        if (!s.usable) return false;
    }
    return true;
}

DecoupledFit fitDecoupled(const DataSet& data, const wheel::WheelParameters& wheel,
                          const DecoupledParameters& guess, const DecoupledBounds& bounds,
                          int max_iterations_per_step) {
    wheel::requireValid(wheel);
    if (data.samples.empty()) throw std::invalid_argument("data set: no samples to fit");
    const double r = wheel.radius_m, b = wheel.width_m;
    DecoupledFit fit;
    DecoupledParameters& p = fit.parameters;
    p = guess;

    {  // Step I: a0, a1 from F_x (Eq. 4.12).
        double a[2] = {p.a0, p.a1};
        ceres::Problem problem;
        std::vector<StepIResidual> rows;
        for (const Sample& s : data.samples)
            rows.push_back({r, s.slip, s.entry_angle_rad, s.fx_n, s.fz_n, s.my_nm});
        problem.AddResidualBlock(batchCost<2>(std::move(rows)), nullptr, a);
        problem.SetParameterLowerBound(a, 0, 0.0);
        problem.SetParameterUpperBound(a, 0, 1.0);
        problem.SetParameterLowerBound(a, 1, -1.0);
        problem.SetParameterUpperBound(a, 1, 1.0);
        fit.steps.push_back(solve(problem, "I: a0, a1 (Fx, Eq. 4.12)", max_iterations_per_step));
        p.a0 = a[0];
        p.a1 = a[1];
    }
    {  // Step II: K_s, n0, n1 from F_z (Eq. 4.17), P_I fixed.
        double x[3] = {p.pressure_modulus / kKsScale, p.n0, p.n1};
        ceres::Problem problem;
        std::vector<StepIIResidual> rows;
        for (const Sample& s : data.samples) {
            rows.push_back({r, b, p.a0, p.a1, s.slip, s.entry_angle_rad, s.fz_n, s.my_nm});
        }
        problem.AddResidualBlock(batchCost<3>(std::move(rows)), nullptr, x);
        problem.SetParameterLowerBound(x, 0, bounds.ks_min / kKsScale);
        problem.SetParameterUpperBound(x, 0, bounds.ks_max / kKsScale);
        problem.SetParameterLowerBound(x, 1, bounds.n0_min);
        problem.SetParameterUpperBound(x, 1, bounds.n0_max);
        problem.SetParameterLowerBound(x, 2, bounds.n1_min);
        problem.SetParameterUpperBound(x, 2, bounds.n1_max);
        fit.steps.push_back(
            solve(problem, "II: Ks, n0, n1 (Fz, Eq. 4.17)", max_iterations_per_step));
        p.pressure_modulus = x[0] * kKsScale;
        p.n0 = x[1];
        p.n1 = x[2];
    }
    {  // Step III: c, φ, K from M_y (Eq. 4.18), P_I fixed.
        double x[3] = {p.cohesion_pa / kCohesionScale, p.friction_angle_rad, p.shear_modulus_m};
        ceres::Problem problem;
        std::vector<StepIIIResidual> rows;
        for (const Sample& s : data.samples) {
            rows.push_back({r, b, p.a0, p.a1, s.slip, s.entry_angle_rad, s.fz_n, s.my_nm});
        }
        problem.AddResidualBlock(batchCost<3>(std::move(rows)), nullptr, x);
        problem.SetParameterLowerBound(x, 0, bounds.c_min / kCohesionScale);
        problem.SetParameterUpperBound(x, 0, bounds.c_max / kCohesionScale);
        problem.SetParameterLowerBound(x, 1, bounds.phi_min);
        problem.SetParameterUpperBound(x, 1, bounds.phi_max);
        problem.SetParameterLowerBound(x, 2, bounds.k_min);
        problem.SetParameterUpperBound(x, 2, bounds.k_max);
        fit.steps.push_back(
            solve(problem, "III: c, phi, K (My, Eq. 4.18)", max_iterations_per_step));
        p.cohesion_pa = x[0] * kCohesionScale;
        p.friction_angle_rad = x[1];
        p.shear_modulus_m = x[2];
    }
    return fit;
}

DecoupledForces decoupledForward(const DecoupledParameters& p, const wheel::WheelParameters& wheel,
                                 double slip, double theta_f) {
    const double r = wheel.radius_m, b = wheel.width_m;
    const HatCoefficients<double> h = hatCoefficients(p.a0, p.a1, slip, theta_f);
    const double n = p.n0 + p.n1 * slip;
    const double sigma_m =
        p.pressure_modulus * std::pow(r * (std::cos(h.theta_m) - std::cos(theta_f)), n);  // Eq. 4.1
    const double tau_m = (p.cohesion_pa + sigma_m * std::tan(p.friction_angle_rad)) *
                         (1.0 - std::exp(-shearAtMaxStress(h.theta_m, r, slip, theta_f) /
                                         p.shear_modulus_m));     // Eq. 4.2
    const double x = r * b * sigma_m, y = r * b * tau_m;          // Eqs. 4.8, 4.9
    return {-h.b * x + h.a * y, h.a * x + h.b * y, r * h.c * y};  // Eq. 4.4
}

}  // namespace terra::identification
