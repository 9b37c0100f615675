#pragma once
/// @file box_solver.h
/// Internal (included by identification .cpp files only: Ceres types must not reach the public
/// headers). Ceres' trust-region solver on one parameter block with box bounds, wrapped in an
/// active set: a parameter the solver leaves exactly on its bound is held there and the others are
/// solved again; a held parameter whose gradient points back into the box is released. (A step
/// that leaves the box is clamped onto it, without Ceres' projected line search, which made a
/// parameter crawl toward an active bound: a geometric decrease of ~0.65 per iteration, 60–200
/// iterations, measured on the decoupled steps of full-model data.) A released
/// parameter that the solver brings back to its bound stays held (released once per solve; a
/// parameter free through a pass that converged with it on its bound, the gradient pulling it
/// inside, has had its release): the
/// solve may then end there, converged, with the gradient pointing inside, which its termination
/// says. With
/// BoxOptions::bound_shortcuts, a parameter that crawls toward a bound it has not reached (three
/// shrinking steps toward it, the bound within ten of them) is tried on that bound for one pass,
/// kept there only if that pass lowers the cost (below the cost before the trial within eight
/// iterations, or the pass ends there and the trial is undone). With BoxOptions::extrapolate, a
/// geometric crawl (steps along one direction, each a steady fraction q of the one before: Gauss–
/// Newton's linear convergence where the residuals curve) ends its pass, and the next pass starts
/// from the limit of the series when the cost there is lower.

#include <ceres/ceres.h>

#include <functional>
#include <string>
#include <vector>

namespace terra::identification::detail {

/// The problem: cost functions of one parameter block x (not owned), bounds and held parameters.
struct BoxProblem {
    std::vector<ceres::CostFunction*> costs;
    std::vector<ceres::LossFunction*> losses;  ///< parallel to costs; nullptr for squares
    std::vector<double> lower, upper;          ///< bounds of x
    std::vector<bool> fixed;                   ///< never moved
};

/// Solver settings for small dense problems.
struct BoxOptions {
    int max_iterations = 200;      ///< over all passes
    int iterations_per_pass = 25;  ///< before the active set is revised
    int max_passes = 6;            ///< not counting the passes a crawl ends (extrapolate)
    double function_tolerance = 1e-10;
    double parameter_tolerance = 1e-10;
    double gradient_tolerance = 1e-12;
    bool nonmonotonic_steps = false;
    bool gradient =
        true;  ///< compute BoxSummary::gradient (else only when the active set needs it)
    /// The shortcuts of the global search (identify.h; docs/identification.md §9): a parameter
    /// crawling toward a bound is tried on it, and steps that leave a bound by a hair and return
    /// count as staying on it.
    bool bound_shortcuts = false;
    /// Extrapolate a geometric crawl: successful steps that keep their direction and shrink by
    /// a steady ratio q (Gauss–Newton's linear convergence along a flat valley) end the pass, and
    /// the next starts from x + d q/(1 − q), the limit of the series, when its cost is lower.
    bool extrapolate = false;
    /// Called with x after each successful step, its cost (the least of the pass's successful
    /// steps': with nonmonotonic steps x is the best point) and the problem (to evaluate the cost
    /// elsewhere: evaluateCost); true ends the solve there (BoxSummary::stopped). A multi-start
    /// search uses it to end a descent that has entered the basin of a minimum another start has
    /// found.
    std::function<bool(const std::vector<double>& x, double cost, const BoxProblem& problem)> stop;
};

/// The outcome.
struct BoxSummary {
    bool usable = false;
    bool converged = false;   ///< the last pass met a tolerance (not the iteration budget)
    std::string termination;  ///< Ceres' termination type and message of the last pass
    int iterations = 0;       ///< over all passes
    int passes = 0;
    int extrapolations = 0;      ///< crawls extrapolated (BoxOptions::extrapolate), accepted or not
    double cost = 0.0;           ///< ½ Σ ρ(‖rᵢ‖²) at the solution
    bool stopped = false;        ///< ended by BoxOptions::stop
    std::vector<bool> at_bound;  ///< held on a bound at the solution
    std::vector<double> gradient;  ///< ∂cost/∂x at the solution (every component)
};

/// Solves min cost(x) within the bounds, starting from x (clamped into the box).
BoxSummary solveInBox(const BoxProblem& problem, std::vector<double>& x, const BoxOptions& options);

/// cost(x) and, when `gradient` is given, ∂cost/∂x; false when a cost function fails.
bool evaluateCost(const BoxProblem& problem, const std::vector<double>& x, double& cost,
                  std::vector<double>* gradient = nullptr);

/// The hill–valley test of multi-start clustering (Ursem 1999; docs/identification.md §9,
/// "tenth pass"): whether `minimum`, at `minimum_cost`, lies downhill of x, at `cost`. The cost
/// at the points 1/4, 1/2 and 3/4 of the way along the straight segment from x to the minimum
/// (on the coordinates marked in `walked`; the others keep x's values), and at the minimum, rises
/// nowhere by more than `ridge` (in cost, not relative) over the point before it: no ridge that
/// these points see.
bool downhillTo(const BoxProblem& problem, const std::vector<double>& x, double cost,
                const std::vector<double>& minimum, double minimum_cost,
                const std::vector<bool>& walked, double ridge);

/// The largest |component| of the gradient projected on the box: components of parameters held
/// (fixed, or on a bound with the gradient pointing out of the box) count as zero.
double projectedGradientNorm(const BoxProblem& problem, const std::vector<double>& x,
                             const std::vector<double>& gradient);

}  // namespace terra::identification::detail
