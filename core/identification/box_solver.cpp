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

// Within kNearBound of its range from a bound (not on it).
constexpr double kNearBound = 1e-3;
bool nearBound(const BoxProblem& p, const std::vector<double>& x, std::size_t k) {
    const double margin = kNearBound * (p.upper[k] - p.lower[k]);
    return x[k] <= p.lower[k] + margin || x[k] >= p.upper[k] - margin;
}

// Ends a pass once a free parameter has stayed on a bound for two successful steps: the next pass
// holds it. Also ends it when a free parameter crawls toward a bound it has not reached: three
// successful steps in a row toward the same bound, each shorter than the one before, the bound
// within kApproachSteps of the last; the caller then tries the parameter on that bound
// (solveInBox). (Ceres' projected line search made such crawls: a₀ → 0 at one load, 0.16 → 5e-4
// in 40 iterations. Without it, a step past the bound is clamped onto it and the crawl is rare:
// the rule measured neutral, docs/identification.md §9, "fifth pass".) With extrapolation
// (BoxOptions::extrapolate), also ends it on a geometric crawl (crawling()): the caller goes on
// from the limit of its series.
class BoundWatch : public ceres::IterationCallback {
public:
    /// A crawl is tried on its bound when the bound is within this many of its last steps.
    static constexpr double kApproachSteps = 10.0;
    /// The iterations a trial's pass has to fall below the cost before the trial: on the
    /// identification matrix every kept trial did so within three, and the undone ones ran up to
    /// 40 (j_max put on its lower bound; docs/identification.md §9, "tenth pass").
    static constexpr int kTrialIterations = 8;

    /// `trial_cost`: the cost before the trial when this pass is a trial's, else +inf.
    BoundWatch(const BoxProblem& problem, const std::vector<double>& x,
               const std::vector<bool>& held, const std::vector<bool>& may_snap,
               const BoxOptions& options, double trial_cost, bool extrapolate)
        : problem_(problem),
          x_(x),
          held_(held),
          may_snap_(may_snap),
          options_(options),
          trial_cost_(trial_cost),
          extrapolate_(extrapolate),
          count_(x.size(), 0),
          previous_(x),
          last_move_(x.size(), 0.0),
          approach_(x.size(), 0) {}

    ceres::CallbackReturnType operator()(const ceres::IterationSummary& iteration) override {
        // The cost at x_: the least of the successful steps' (with nonmonotonic steps Ceres keeps
        // the best point in x_, and a rejected step reports its candidate's cost).
        if (iteration.step_is_successful) best_cost_ = std::min(best_cost_, iteration.cost);
        radius_ = iteration.trust_region_radius;
        // A trial's pass that has not fallen below the cost before the trial by now ends: the
        // trial will be undone (solveInBox).
        if (iteration.iteration >= kTrialIterations && best_cost_ > trial_cost_) {
            trial_cut_ = true;
            return ceres::SOLVER_TERMINATE_SUCCESSFULLY;
        }
        if (!iteration.step_is_successful) return ceres::SOLVER_CONTINUE;
        if (options_.stop && options_.stop(x_, best_cost_, problem_)) {
            stopped_ = true;
            return ceres::SOLVER_TERMINATE_SUCCESSFULLY;
        }
        for (std::size_t k = 0; k < x_.size(); ++k) {
            if (held_[k]) continue;
            // Steps that leave the bound by a hair and return (a₀ at 0 ↔ 1e-5 at one load, where
            // the model is not smooth in a₀) count as staying on it.
            const bool on = onLower(problem_, x_, k) || onUpper(problem_, x_, k);
            const bool near = options_.bound_shortcuts && nearBound(problem_, x_, k);
            count_[k] = on ? count_[k] + 1 : (near ? count_[k] : 0);
            if (count_[k] >= 2) return ceres::SOLVER_TERMINATE_SUCCESSFULLY;
        }
        double snap_steps = kApproachSteps;
        for (std::size_t k = 0; k < x_.size() && options_.bound_shortcuts; ++k) {
            if (held_[k] || !may_snap_[k]) continue;
            const double move = x_[k] - previous_[k];
            const int toward = move < 0.0 ? -1 : (move > 0.0 ? 1 : 0);
            const bool slower = std::abs(move) < last_move_[k];
            approach_[k] =
                toward != 0 && slower && approach_[k] * toward > 0 ? approach_[k] + toward : toward;
            const double distance =
                toward < 0 ? x_[k] - problem_.lower[k] : problem_.upper[k] - x_[k];
            last_move_[k] = std::abs(move);
            const double steps = distance / std::abs(move);
            if (std::abs(approach_[k]) >= 3 && distance > 0.0 && steps < kApproachSteps &&
                steps < snap_steps) {
                snap_ = static_cast<int>(k);
                snap_lower_ = toward < 0;
                snap_steps = steps;
            }
        }
        previous_ = x_;
        if (snap_ >= 0) return ceres::SOLVER_TERMINATE_SUCCESSFULLY;
        // The steps are followed through the whole pass; a crawl ends it, in a trial's pass
        // only once below the cost before the trial (the trial is kept then).
        if (extrapolate_ && crawling() && best_cost_ < trial_cost_ && radius_ >= kCrawlRadius) {
            crawled_ = true;
            return ceres::SOLVER_TERMINATE_SUCCESSFULLY;
        }
        return ceres::SOLVER_CONTINUE;
    }

    /// Whether a geometric crawl ended the pass; its last step and that step's ratio q to the
    /// one before (negative: an oscillation).
    bool crawled() const { return crawled_; }
    const std::vector<double>& crawlStep() const { return step_; }
    double crawlRatio() const { return crawl_ratio_; }
    /// The cost at x: the least of the pass's successful steps'.
    double cost() const { return best_cost_; }

    /// The parameter heading for a bound (-1: none) and whether it is the lower one.
    int snap() const { return snap_; }
    bool snapLower() const { return snap_lower_; }
    /// Whether BoxOptions::stop ended the pass.
    bool stopped() const { return stopped_; }
    /// Whether a trial's pass was ended for not paying (kTrialIterations).
    bool trialCut() const { return trial_cut_; }

private:
    // Whether the steps so far make a geometric crawl: three successful steps in a row, each
    // along (or against: an oscillation) the one before, within kCrawlCosine, and shorter by a
    // ratio whose size is in [kCrawlLeast, kCrawlMost], the two signed ratios within
    // kCrawlSpread of each other.
    static constexpr double kCrawlCosine = 0.98, kCrawlLeast = 0.2, kCrawlMost = 0.85,
                            kCrawlSpread = 0.15;
    // A crawl is extrapolated only while the trust region's radius is at least Ceres' initial
    // one (10⁴, which solveInBox leaves as it is): the steps are then Gauss–Newton's own, their
    // shrinking the residuals' curvature, not the damping of a trust region that rejected steps.
    static inline const double kCrawlRadius = ceres::Solver::Options().initial_trust_region_radius;
    bool crawling() {
        std::vector<double> step(x_.size());
        double dot = 0.0, norm = 0.0, last_norm = 0.0;
        for (std::size_t k = 0; k < x_.size(); ++k) {
            step[k] = x_[k] - crawl_from_[k];
            if (!step_.empty()) dot += step[k] * step_[k];
            norm += step[k] * step[k];
            if (!step_.empty()) last_norm += step_[k] * step_[k];
        }
        crawl_from_ = x_;
        const double size = last_norm > 0.0 ? std::sqrt(norm / last_norm) : 0.0;
        const double ratio = dot < 0.0 ? -size : size;
        const bool geometric = norm > 0.0 && last_norm > 0.0 &&
                               std::abs(dot) >= kCrawlCosine * std::sqrt(norm * last_norm) &&
                               size >= kCrawlLeast && size <= kCrawlMost;
        const bool steady =
            geometric && last_ratio_ != 0.0 && std::abs(ratio - last_ratio_) <= kCrawlSpread;
        last_ratio_ = geometric ? ratio : 0.0;
        step_ = std::move(step);
        crawl_ratio_ = steady ? ratio : 0.0;
        return steady;
    }

    const BoxProblem& problem_;
    const std::vector<double>& x_;
    const std::vector<bool>& held_;
    const std::vector<bool>& may_snap_;
    const BoxOptions& options_;
    const double trial_cost_;
    const bool extrapolate_;
    double best_cost_ = INFINITY;
    bool stopped_ = false;
    bool trial_cut_ = false;
    std::vector<int> count_;
    std::vector<double> previous_;
    std::vector<double> last_move_;  // |x − previous| of the last successful step
    std::vector<int> approach_;      // consecutive shrinking moves toward a bound, signed
    int snap_ = -1;
    bool snap_lower_ = false;
    std::vector<double> crawl_from_ = x_;  // x at the last successful step
    std::vector<double> step_;             // the last successful step
    double last_ratio_ = 0.0;              // its ratio to the step before, if geometric
    double crawl_ratio_ = 0.0;
    bool crawled_ = false;
    double radius_ = 0.0;  // the trust region's radius after the last iteration
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

bool downhillTo(const BoxProblem& problem, const std::vector<double>& x, double cost,
                const std::vector<double>& minimum, double minimum_cost,
                const std::vector<bool>& walked, double ridge) {
    double previous = cost;
    std::vector<double> v = x;
    for (double t : {0.25, 0.5, 0.75}) {
        for (std::size_t k = 0; k < x.size(); ++k) {
            if (walked[k]) v[k] = x[k] + t * (minimum[k] - x[k]);
        }
        double c = 0.0;
        if (!evaluateCost(problem, v, c) || !(c <= previous + ridge)) return false;
        previous = c;
    }
    return minimum_cost <= previous + ridge;
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
    // A parameter put on the bound it was heading for (BoundWatch) is a trial, held for one pass:
    // the point before it is kept, and restored when that pass ends with a higher cost (or no
    // pass is left to solve it). Each parameter is tried once per solve.
    std::vector<bool> may_snap(n, true);
    std::vector<int> releases(n, 0);
    struct Trial {
        int parameter = -1;
        std::vector<double> x;
        double cost = 0.0;
    } trial;
    // Whether a crawl may still be extrapolated: not after one whose limit cost more.
    bool extrapolate = options.extrapolate;
    // The passes' budget (BoxOptions::max_passes) does not count the extrapolations'.
    const auto budgetLeft = [&] {
        return summary.iterations < options.max_iterations &&
               summary.passes - summary.extrapolations < options.max_passes;
    };
    // The caller's stop ended the solve at x (after a step, or an extrapolation).
    const auto endStopped = [&] {
        summary.stopped = true;
        summary.termination = "STOPPED: the caller's stop condition holds";
        if (!evaluateCost(problem, x, summary.cost,
                          options.gradient ? &summary.gradient : nullptr)) {
            summary.usable = false;
            summary.termination = "FAILURE: the cost cannot be evaluated at the solution";
        }
    };
    for (;;) {
        std::vector<int> held;
        for (std::size_t k = 0; k < n; ++k) {
            if (problem.fixed[k] || held_on_bound[k]) held.push_back(static_cast<int>(k));
        }
        ++summary.passes;
        bool converged = true;
        bool ceres_converged = false;  // Ceres' own criteria ended the pass
        int snap = -1;
        bool snap_lower = false;
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
            // No line search. With bounds, Ceres otherwise runs a projected Armijo line search
            // along every step before it evaluates the step's end again: ≥ 2 evaluations per
            // step, and where the step leaves the box the search backs off along it, so that a
            // parameter crawls toward its bound instead of landing on it. Without it, a step is
            // projected onto the box (ParameterBlock::Plus clamps) and judged by its gain ratio
            // like any other: one evaluation per step. Measured on the one-load identification
            // matrix (72 cells, one thread): residual evaluations 5.0M → 1.0M values, Jacobian
            // rows 0.74M → 0.64M, the same minima (docs/identification.md §9, "fifth pass").
            solver.max_num_line_search_step_size_iterations = 0;
            solver.logging_type = ceres::SILENT;
            solver.num_threads = 1;
            std::vector<bool> held_now(n, false);
            for (int k : held) held_now[static_cast<std::size_t>(k)] = true;
            BoundWatch watch(problem, x, held_now, may_snap, options,
                             trial.parameter >= 0 ? trial.cost : INFINITY, extrapolate);
            solver.callbacks.push_back(&watch);
            solver.update_state_every_iteration = true;
            ceres::Solver::Summary ceres_summary;
            ceres::Solve(solver, &ceres_problem, &ceres_summary);
            summary.iterations += static_cast<int>(ceres_summary.iterations.size()) - 1;
            summary.usable = ceres_summary.IsSolutionUsable();
            summary.termination = ceres::TerminationTypeToString(ceres_summary.termination_type) +
                                  std::string(": ") + ceres_summary.message;
            // The only callback is the bound watch: its end of a pass says why (a step that the
            // budget leaves as the last is worded by solverOutcome).
            if (ceres_summary.termination_type == ceres::USER_SUCCESS) {
                summary.termination = watch.trialCut()
                                          ? "USER_SUCCESS: a trial on a bound did not pay"
                                          : "USER_SUCCESS: a parameter reached its bound";
            }
            ceres_converged = ceres_summary.termination_type == ceres::CONVERGENCE;
            converged = ceres_summary.termination_type == ceres::CONVERGENCE ||
                        ceres_summary.termination_type == ceres::USER_SUCCESS;
            if (!summary.usable && trial.parameter >= 0) {
                // The pass from a trial failed: back to the point before it.
                held_on_bound[static_cast<std::size_t>(trial.parameter)] = false;
                x = trial.x;
                trial.parameter = -1;
                const bool budget_left = budgetLeft();
                summary.usable = evaluateCost(problem, x, summary.cost,
                                              options.gradient ? &summary.gradient : nullptr);
                if (summary.usable && budget_left) continue;
                break;
            }
            if (!summary.usable) break;
            if (watch.stopped()) {
                endStopped();
                break;
            }
            snap = watch.snap();
            snap_lower = watch.snapLower();
            // A geometric crawl: on from the limit of its series when that costs less (Aitken's
            // Δ² extrapolation along the step; the active set is left as it is, the next pass
            // revises it). Its pass is not counted against max_passes: only the iterations can
            // run out.
            if (watch.crawled() && summary.iterations < options.max_iterations) {
                ++summary.extrapolations;
                trial.parameter = -1;  // a trial's pass extrapolates below its cost: kept
                const double q = watch.crawlRatio();
                std::vector<double> far = x;
                for (std::size_t k = 0; k < n; ++k) {
                    if (problem.fixed[k]) continue;
                    far[k] = std::clamp(x[k] + watch.crawlStep()[k] * q / (1.0 - q),
                                        problem.lower[k], problem.upper[k]);
                }
                double cost = 0.0;
                if (evaluateCost(problem, far, cost) && cost < watch.cost()) {
                    x = std::move(far);
                    // The caller's stop sees the point as it sees every step's.
                    if (options.stop && options.stop(x, cost, problem)) {
                        endStopped();
                        break;
                    }
                } else {
                    extrapolate = false;
                }
                continue;
            }
            if (watch.crawled()) {
                // The iterations ran out in the crawl: Ceres would have stopped there too.
                converged = false;
                summary.termination = "NO_CONVERGENCE: the iteration limit came within a crawl";
            }
        } else {
            summary.usable = true;
            summary.termination = "CONVERGENCE: every parameter is held";
        }
        // Revise the active set: hold what the solver left on a bound, release what the gradient
        // pulls back inside.
        bool changed = false;
        bool kept_against_gradient = false;
        // Free through the pass just solved, which Ceres ended converged with it on its bound.
        std::vector<bool> landed(n, false);
        if (trial.parameter >= 0) {
            // The pass after a trial: keep it only if it lowered the cost.
            double cost = 0.0;
            if (!evaluateCost(problem, x, cost) || cost > trial.cost) {
                x = trial.x;
                held_on_bound[static_cast<std::size_t>(trial.parameter)] = false;
                changed = true;
            }
            trial.parameter = -1;
        }
        if (snap >= 0) {
            const std::size_t k = static_cast<std::size_t>(snap);
            trial.parameter = snap;
            trial.x = x;
            may_snap[k] = false;
            double on_bound = 0.0;
            x[k] = snap_lower ? problem.lower[k] : problem.upper[k];
            // Tried only where the model can be evaluated there (from the load, a bound may be a
            // soil that cannot carry it).
            if (evaluateCost(problem, trial.x, trial.cost) && evaluateCost(problem, x, on_bound)) {
                held_on_bound[k] = true;
            } else {
                x = trial.x;
                trial.parameter = -1;
            }
            changed = true;  // the pass ended for the trial, not at a minimum
        }
        for (std::size_t k = 0; k < n; ++k) {
            if (problem.fixed[k] || held_on_bound[k]) continue;
            if (onLower(problem, x, k) || onUpper(problem, x, k)) {
                held_on_bound[k] = true;
                changed = true;
                landed[k] = ceres_converged;
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
            // A parameter just put on its bound is held for one pass whatever the gradient says
            // there: the others have not followed it yet.
            if (!held_on_bound[k] || (snap >= 0 && static_cast<int>(k) == trial.parameter))
                continue;
            const bool pulled_inside =
                onLower(problem, x, k) ? summary.gradient[k] < 0.0 : summary.gradient[k] > 0.0;
            // A parameter released once that the solver brought back to its bound stays there:
            // the steps inside failed (at a bound where the model is not smooth the gradient's
            // pull is not a descent direction), and releasing it again would repeat them. (From
            // the load too: a calibration on three slips of a lugged wheel spent its six passes
            // of one iteration each releasing one parameter and holding it again, and ended
            // "not converged" 0.54 in χ² above the minimum found with one release.)
            if (pulled_inside && landed[k]) {
                // It was free through a pass that converged with it there, the gradient pulling
                // it inside: that pass was its release (releasing it now would repeat it: a₀ at 0
                // at one load, a kink where every step inside fails, 8 rejected steps a pass).
                releases[k] = std::max(releases[k], 1);
                kept_against_gradient = true;
            } else if (pulled_inside && releases[k] < 1) {
                held_on_bound[k] = false;
                ++releases[k];
                changed = true;
            } else if (pulled_inside) {
                kept_against_gradient = true;
            }
        }
        const bool budget_left = budgetLeft();
        // A trial that no pass is left to solve is undone.
        if (trial.parameter >= 0 && !budget_left) {
            held_on_bound[static_cast<std::size_t>(trial.parameter)] = false;
            x = trial.x;
            trial.parameter = -1;
            if (!evaluateCost(problem, x, summary.cost,
                              any_held || options.gradient ? &summary.gradient : nullptr)) {
                summary.usable = false;
                summary.termination = "FAILURE: the cost cannot be evaluated at the solution";
                break;
            }
        }
        if ((!changed && converged) || !budget_left) {
            summary.converged = converged && !changed;
            if (summary.converged && kept_against_gradient) {
                summary.termination +=
                    " (a parameter stays on its bound although the gradient "
                    "points inside: the steps that took it inside failed)";
            }
            break;
        }
    }
    summary.at_bound = held_on_bound;
    return summary;
}

}  // namespace terra::identification::detail
