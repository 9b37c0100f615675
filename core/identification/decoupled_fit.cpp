#include "core/identification/decoupled_fit.h"

#include <ceres/ceres.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <optional>
#include <stdexcept>
#include <vector>

#include "core/identification/box_solver.h"
#include "core/identification/decoupled_model.h"
#include "core/identification/parameters.h"

namespace terra::identification {
namespace {

struct StepIResidual {
    double r, slip, theta_f, fx, fz, my;
    template <typename T>
    bool operator()(const T* const a, T* residual) const {
        const HatCoefficients<T> h = hatCoefficients(a[0], a[1], slip, theta_f);
        residual[0] = decoupledDrawbarPull(h, r, fz, my) - fx;
        return true;
    }
};

// Steps II and III each have one parameter that enters linearly: F_z − B M_y/(r C) = K_s g(n₀, n₁)
// (Eq. 4.17) and M_y = h(φ, K) c + q(φ, K) (Eq. 4.18). It is projected out (variable projection):
// for given values of the other two it takes its least-squares value in closed form, and the solver
// walks only those two. When that value leaves its bounds, the step is solved again with it held
// at the bound (an active set of one); clamping inside the residual instead would put a kink in
// the residual's Jacobian, along which Levenberg–Marquardt crawls for hundreds of iterations.
// Σ rᵢ² is the same function of the parameters as the thesis's; docs/identification.md, "Speed".
template <typename T>
T linearFit(const std::vector<T>& basis, const std::vector<T>& target,
            const std::optional<double>& held) {
    if (held) return T(*held);
    T gg(0.0), gy(0.0);
    for (std::size_t i = 0; i < basis.size(); ++i) {
        gg += basis[i] * basis[i];
        gy += basis[i] * target[i];
    }
    return gg > 0.0 ? T(gy / gg) : T(0.0);
}

// A sample of steps II and III with its hat coefficients (P_I is fixed in both).
struct ProjectedRow {
    double slip, theta_f, fz, my;
    HatCoefficients<double> h;
};

// Step II: x = (n₀, n₁); residual K_s g − (F_z − B M_y/(r C)) with K_s projected (or held).
struct StepIIProjected {
    double r, b;
    std::vector<ProjectedRow> rows;
    std::optional<double> held;  // K_s [Pa/m^N] held at a bound

    template <typename T>
    T linear(const T* const x, std::vector<T>& g, std::vector<T>& z) const {
        g.resize(rows.size());
        z.resize(rows.size());
        for (std::size_t i = 0; i < rows.size(); ++i) {
            const ProjectedRow& s = rows[i];
            g[i] = decoupledPressureTerm(s.h, r, b, x[0], x[1], s.slip, s.theta_f);
            z[i] = T(s.fz - s.h.b * s.my / (r * s.h.c));
        }
        return linearFit(g, z, held);
    }
    template <typename T>
    bool operator()(const T* const x, T* residual) const {
        std::vector<T> g, z;
        const T ks = linear(x, g, z);
        for (std::size_t i = 0; i < rows.size(); ++i) residual[i] = ks * g[i] - z[i];
        return true;
    }
};

// Step III: x = (φ, ln K); residual h c + q − M_y with c projected (or held). K enters through
// exp(−j/K): in ln K the valley toward small K is straight.
struct StepIIIProjected {
    double r, b;
    std::vector<ProjectedRow> rows;
    std::optional<double> held;  // c [Pa] held at a bound

    template <typename T>
    T linear(const T* const x, std::vector<T>& g, std::vector<T>& z) const {
        using std::exp;
        g.resize(rows.size());
        z.resize(rows.size());
        const T shear_modulus = exp(x[1]);
        for (std::size_t i = 0; i < rows.size(); ++i) {
            const ProjectedRow& s = rows[i];
            const TorqueTerms<T> t =
                decoupledTorqueTerms(s.h, r, b, x[0], shear_modulus, s.slip, s.theta_f, s.fz);
            g[i] = t.per_cohesion;
            z[i] = s.my - t.offset;
        }
        return linearFit(g, z, held);
    }
    template <typename T>
    bool operator()(const T* const x, T* residual) const {
        std::vector<T> g, z;
        const T c = linear(x, g, z);
        for (std::size_t i = 0; i < rows.size(); ++i) residual[i] = c * g[i] - z[i];
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

// Relative cost change 1e-10 is far below any data's noise; tighter only walks the flat valleys
// of full-model data without changing the fit (docs/identification.md).
detail::BoxOptions stepOptions(int max_iterations) {
    detail::BoxOptions options;
    options.max_iterations = max_iterations;
    options.function_tolerance = 1e-10;
    options.parameter_tolerance = 1e-10;
    options.gradient_tolerance = 1e-12;
    options.gradient = false;
    return options;
}

// Solves one step on x within [lower, upper] and accumulates its report.
void solveStep(ceres::CostFunction* cost, std::vector<double>& x, std::vector<double> lower,
               std::vector<double> upper, int max_iterations, StepReport& report) {
    const std::unique_ptr<ceres::CostFunction> owned(cost);
    detail::BoxProblem problem{
        {cost}, {nullptr}, std::move(lower), std::move(upper), std::vector<bool>(x.size(), false)};
    const auto start = std::chrono::steady_clock::now();
    const detail::BoxSummary summary =
        detail::solveInBox(problem, x, stepOptions(max_iterations - report.iterations));
    const auto stop = std::chrono::steady_clock::now();
    report.usable = summary.usable;
    report.termination = summary.termination;
    report.iterations += summary.iterations;
    report.squared_residual_norm = 2.0 * summary.cost;  // Ceres' cost is ½ Σ rᵢ²
    report.wall_time_ms += std::chrono::duration<double, std::milli>(stop - start).count();
}

// A projected step (two nonlinear parameters x, one linear parameter within [lo, hi]): free
// first; when the linear parameter's value leaves its bounds, again with it held at the nearer
// bound. Returns the linear parameter.
template <typename Step>
double solveProjected(Step& step, std::vector<double>& x, const std::vector<double>& lower,
                      const std::vector<double>& upper, double lo, double hi, int max_iterations,
                      StepReport& report) {
    const int n = static_cast<int>(step.rows.size());
    std::vector<double> g, z;
    for (;;) {
        solveStep(new ceres::AutoDiffCostFunction<Step, ceres::DYNAMIC, 2>(new Step(step), n), x,
                  lower, upper, max_iterations, report);
        const double value = step.linear(x.data(), g, z);
        if (step.held || (value >= lo && value <= hi) || !report.usable) return value;
        step.held = value < lo ? lo : hi;
    }
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
        std::vector<double> a{p.a0, p.a1};
        std::vector<StepIResidual> rows;
        for (const Sample& s : data.samples)
            rows.push_back({r, s.slip, s.entry_angle_rad, s.fx_n, s.fz_n, s.my_nm});
        const int n = static_cast<int>(rows.size());
        StepReport report;
        report.name = "I: " + reference(&DecoupledParameters::a0) + ", " +
                      reference(&DecoupledParameters::a1) + " (Fx, Eq. 4.12)";
        solveStep(new ceres::AutoDiffCostFunction<Batch<StepIResidual>, ceres::DYNAMIC, 2>(
                      new Batch<StepIResidual>{std::move(rows)}, n),
                  a, {0.0, -1.0}, {1.0, 1.0}, max_iterations_per_step, report);
        fit.steps.push_back(report);
        p.a0 = a[0];
        p.a1 = a[1];
    }
    std::vector<ProjectedRow> rows;
    for (const Sample& s : data.samples) {
        rows.push_back({s.slip, s.entry_angle_rad, s.fz_n, s.my_nm,
                        hatCoefficients(p.a0, p.a1, s.slip, s.entry_angle_rad)});
    }
    {  // Step II: n0, n1 from F_z (Eq. 4.17) with K_s projected, P_I fixed.
        std::vector<double> x{p.n0, p.n1};
        StepIIProjected step{r, b, rows, std::nullopt};
        StepReport report;
        report.name = "II: " + reference(&DecoupledParameters::pressure_modulus) + ", " +
                      reference(&DecoupledParameters::n0) + ", " +
                      reference(&DecoupledParameters::n1) + " (Fz, Eq. 4.17)";
        p.pressure_modulus =
            solveProjected(step, x, {bounds.n0_min, bounds.n1_min}, {bounds.n0_max, bounds.n1_max},
                           bounds.ks_min, bounds.ks_max, max_iterations_per_step, report);
        fit.steps.push_back(report);
        p.n0 = x[0];
        p.n1 = x[1];
    }
    {  // Step III: phi, K from M_y (Eq. 4.18) with c projected, P_I fixed.
        std::vector<double> x{p.friction_angle_rad,
                              std::log(std::clamp(p.shear_modulus_m, bounds.k_min, bounds.k_max))};
        StepIIIProjected step{r, b, rows, std::nullopt};
        StepReport report;
        report.name = "III: " + reference(&DecoupledParameters::cohesion_pa) + ", " +
                      reference(&DecoupledParameters::friction_angle_rad) + ", " +
                      reference(&DecoupledParameters::shear_modulus_m) + " (My, Eq. 4.18)";
        p.cohesion_pa = solveProjected(step, x, {bounds.phi_min, std::log(bounds.k_min)},
                                       {bounds.phi_max, std::log(bounds.k_max)}, bounds.c_min,
                                       bounds.c_max, max_iterations_per_step, report);
        fit.steps.push_back(report);
        p.friction_angle_rad = x[0];
        p.shear_modulus_m = std::exp(x[1]);
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
