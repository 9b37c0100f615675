#include "core/identification/box_solver.h"

#include <algorithm>
#include <cmath>

namespace terra::identification::detail {
namespace {

// A parameter within this fraction of its range from a bound is on it: Ceres' projection puts it
// there exactly, the margin only absorbs the rounding of the clamp.
constexpr double kOnBound = 1e-12;

bool onLower(const BoxProblem& p, const std::vector<double>& x, std::size_t k) {
    return x[k] <= p.lower[k] + kOnBound * (p.upper[k] - p.lower[k]);
}
bool onUpper(const BoxProblem& p, const std::vector<double>& x, std::size_t k) {
    return x[k] >= p.upper[k] - kOnBound * (p.upper[k] - p.lower[k]);
}

// Ends a pass once a free parameter has stayed on a bound for two successful steps: from there the
// projected steps only crawl, and the next pass holds it.
class BoundWatch : public ceres::IterationCallback {
public:
    BoundWatch(const BoxProblem& problem, const std::vector<double>& x,
               const std::vector<bool>& held)
        : problem_(problem), x_(x), held_(held), count_(x.size(), 0) {}

    ceres::CallbackReturnType operator()(const ceres::IterationSummary& iteration) override {
        if (!iteration.step_is_successful) return ceres::SOLVER_CONTINUE;
        for (std::size_t k = 0; k < x_.size(); ++k) {
            if (held_[k]) continue;
            count_[k] = onLower(problem_, x_, k) || onUpper(problem_, x_, k) ? count_[k] + 1 : 0;
            if (count_[k] >= 2) return ceres::SOLVER_TERMINATE_SUCCESSFULLY;
        }
        return ceres::SOLVER_CONTINUE;
    }

private:
    const BoxProblem& problem_;
    const std::vector<double>& x_;
    const std::vector<bool>& held_;
    std::vector<int> count_;
};

}  // namespace

bool evaluateCost(const BoxProblem& problem, const std::vector<double>& x, double& cost,
                  std::vector<double>* gradient) {
    const std::size_t n = x.size();
    cost = 0.0;
    if (gradient) gradient->assign(n, 0.0);
    const double* parameters[1] = {x.data()};
    std::vector<double> residuals, jacobian;
    for (std::size_t b = 0; b < problem.costs.size(); ++b) {
        ceres::CostFunction* f = problem.costs[b];
        const std::size_t m = static_cast<std::size_t>(f->num_residuals());
        residuals.resize(m);
        jacobian.resize(m * n);
        double* jacobians[1] = {jacobian.data()};
        if (!f->Evaluate(parameters, residuals.data(), gradient ? jacobians : nullptr)) {
            return false;
        }
        double s = 0.0;
        for (double r : residuals) s += r * r;
        double rho[3] = {s, 1.0, 0.0};
        if (problem.losses[b]) problem.losses[b]->Evaluate(s, rho);
        cost += 0.5 * rho[0];
        if (!gradient) continue;
        for (std::size_t i = 0; i < m; ++i) {
            for (std::size_t k = 0; k < n; ++k)
                (*gradient)[k] += rho[1] * jacobian[i * n + k] * residuals[i];
        }
    }
    return std::isfinite(cost);
}

double projectedGradientNorm(const BoxProblem& problem, const std::vector<double>& x,
                             const std::vector<double>& gradient) {
    double norm = 0.0;
    for (std::size_t k = 0; k < x.size(); ++k) {
        if (problem.fixed[k]) continue;
        // Moving against the gradient would leave the box: no first-order descent there.
        if ((onLower(problem, x, k) && gradient[k] > 0.0) ||
            (onUpper(problem, x, k) && gradient[k] < 0.0)) {
            continue;
        }
        norm = std::max(norm, std::abs(gradient[k]));
    }
    return norm;
}

BoxSummary solveInBox(const BoxProblem& problem, std::vector<double>& x,
                      const BoxOptions& options) {
    const std::size_t n = x.size();
    for (std::size_t k = 0; k < n; ++k) {
        if (!problem.fixed[k]) x[k] = std::clamp(x[k], problem.lower[k], problem.upper[k]);
    }
    BoxSummary summary;
    std::vector<bool> held_on_bound(n, false);
    for (;;) {
        std::vector<int> held;
        for (std::size_t k = 0; k < n; ++k) {
            if (problem.fixed[k] || held_on_bound[k]) held.push_back(static_cast<int>(k));
        }
        ++summary.passes;
        bool converged = true;
        if (held.size() < n) {
            ceres::Problem::Options problem_options;
            problem_options.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
            problem_options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
            ceres::Problem ceres_problem(problem_options);
            for (std::size_t b = 0; b < problem.costs.size(); ++b)
                ceres_problem.AddResidualBlock(problem.costs[b], problem.losses[b], x.data());
            if (!held.empty()) {
                ceres_problem.SetManifold(x.data(),
                                          new ceres::SubsetManifold(static_cast<int>(n), held));
            }
            for (std::size_t k = 0; k < n; ++k) {
                if (problem.fixed[k] || held_on_bound[k]) continue;
                ceres_problem.SetParameterLowerBound(x.data(), static_cast<int>(k),
                                                     problem.lower[k]);
                ceres_problem.SetParameterUpperBound(x.data(), static_cast<int>(k),
                                                     problem.upper[k]);
            }
            ceres::Solver::Options solver;
            solver.linear_solver_type = ceres::DENSE_QR;
            solver.max_num_iterations =
                std::min(options.iterations_per_pass, options.max_iterations - summary.iterations);
            solver.function_tolerance = options.function_tolerance;
            solver.parameter_tolerance = options.parameter_tolerance;
            solver.gradient_tolerance = options.gradient_tolerance;
            solver.use_nonmonotonic_steps = options.nonmonotonic_steps;
            solver.logging_type = ceres::SILENT;
            solver.num_threads = 1;
            std::vector<bool> held_now(n, false);
            for (int k : held) held_now[static_cast<std::size_t>(k)] = true;
            BoundWatch watch(problem, x, held_now);
            solver.callbacks.push_back(&watch);
            solver.update_state_every_iteration = true;
            ceres::Solver::Summary ceres_summary;
            ceres::Solve(solver, &ceres_problem, &ceres_summary);
            summary.iterations += static_cast<int>(ceres_summary.iterations.size()) - 1;
            summary.usable = ceres_summary.IsSolutionUsable();
            summary.termination = ceres::TerminationTypeToString(ceres_summary.termination_type) +
                                  std::string(": ") + ceres_summary.message;
            converged = ceres_summary.termination_type == ceres::CONVERGENCE ||
                        ceres_summary.termination_type == ceres::USER_SUCCESS;
            if (!summary.usable) break;
        } else {
            summary.usable = true;
            summary.termination = "CONVERGENCE: every parameter is held";
        }
        // Revise the active set: hold what the solver left on a bound, release what the gradient
        // pulls back inside.
        bool changed = false;
        for (std::size_t k = 0; k < n; ++k) {
            if (problem.fixed[k] || held_on_bound[k]) continue;
            if (onLower(problem, x, k) || onUpper(problem, x, k)) {
                held_on_bound[k] = true;
                changed = true;
            }
        }
        // The gradient decides which held parameters to release; without any held, and when the
        // caller does not want it, the cost alone will do (one Jacobian evaluation less).
        const bool any_held =
            std::find(held_on_bound.begin(), held_on_bound.end(), true) != held_on_bound.end();
        summary.gradient.clear();
        if (!evaluateCost(problem, x, summary.cost,
                          any_held || options.gradient ? &summary.gradient : nullptr)) {
            summary.usable = false;
            summary.termination = "FAILURE: the cost cannot be evaluated at the solution";
            break;
        }
        for (std::size_t k = 0; k < n; ++k) {
            if (!held_on_bound[k]) continue;
            const bool pulled_inside =
                onLower(problem, x, k) ? summary.gradient[k] < 0.0 : summary.gradient[k] > 0.0;
            if (pulled_inside) {
                held_on_bound[k] = false;
                changed = true;
            }
        }
        const bool budget_left =
            summary.iterations < options.max_iterations && summary.passes < options.max_passes;
        if ((!changed && converged) || !budget_left) {
            summary.converged = converged && !changed;
            break;
        }
    }
    summary.at_bound = held_on_bound;
    return summary;
}

}  // namespace terra::identification::detail
