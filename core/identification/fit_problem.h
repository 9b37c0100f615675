#pragma once
/// @file fit_problem.h
/// Internal (identification .cpp files only; Ceres types stay out of the public headers): the
/// least-squares problem of the full-model identification — data residuals of an
/// ObservationModel, prior residuals, loss, bounds, held parameters — as Ceres cost functions for
/// box_solver.h, and what is computed at a solution (Gauss–Newton covariance, flags, gradient).

#include <ceres/ceres.h>

#include <memory>
#include <vector>

#include "core/identification/adequacy.h"
#include "core/identification/box_solver.h"
#include "core/identification/full_fit.h"
#include "core/identification/identify.h"
#include "core/identification/observation_model.h"

namespace terra {
class WorkerPool;
}

namespace terra::identification::detail {

/// Everything that defines the objective (besides the samples used).
struct Objective {
    const ObservationModel* model = nullptr;
    ChannelValues sigma{};  ///< noise std per channel
    Priors priors{};
    Loss loss = Loss::kSquared;
    double loss_scale = 0.0;  ///< 0: √(χ²₀.₉₅) of each sample's channel count
    std::array<bool, kFullParameterCount> fixed{};
    ParameterBounds bounds;
    /// Threads for the projected problem's per-sample loops (screening.h); null: one.
    WorkerPool* pool = nullptr;
};

/// The objective on a set of samples as a BoxProblem (solver coordinates u, parameters.h). With the
/// squared loss all samples share one cost function (Ceres' per-block overhead is then paid once);
/// a robust loss needs one block per sample.
class FitProblem {
public:
    FitProblem(const Objective& objective, const std::vector<std::size_t>& samples);
    const BoxProblem& box() const { return box_; }
    int dataResiduals() const { return data_residuals_; }

private:
    std::vector<std::unique_ptr<ceres::CostFunction>> costs_;
    std::vector<std::unique_ptr<ceres::LossFunction>> losses_;
    BoxProblem box_;
    int data_residuals_ = 0;
};

/// Solver settings of the phases (descent on a subset, refinement on all samples).
BoxOptions descentOptions();
BoxOptions refinementOptions();

/// χ² = Σ ρ + prior terms at u (2 × the box cost); +inf when the model fails.
double chiSquare(const FitProblem& problem, const std::vector<double>& u);

/// Unweighted residual RMS per channel at u over the given samples, and the residual counts.
struct ChannelResiduals {
    ChannelValues rms{};
    std::array<int, kChannelCount> count{};
    ChannelValues robust_std{};  ///< 1.4826 × median |r| (for robust losses)
    ChannelValues largest{};     ///< largest |measured value| of the samples predicted
    /// The residuals themselves (predicted − measured) with their sweep and slip (adequacy.h).
    std::array<std::vector<OrderedResidual>, kChannelCount> residuals;
};
ChannelResiduals channelResiduals(const ObservationModel& model, const ParameterVector& p,
                                  const std::vector<std::size_t>& samples);

/// What is computed at a solution from one Jacobian: covariance of the free parameters
/// (Gauss–Newton JᵀJ of the data with the loss's weights, plus the priors' information), std in
/// SI, correlations, flags, the gradient of ½χ² (Jᵀr with the same weights) and its Newton
/// decrement over the parameters not on a bound.
struct AtSolution {
    Uncertainty uncertainty;
    std::vector<double> gradient;
    double newton_decrement = 0.0;
};
AtSolution analyseSolution(const Objective& objective, const std::vector<std::size_t>& samples,
                           const std::vector<double>& u, const std::vector<bool>& at_bound,
                           double covariance_scale, double correlation_flag,
                           double bound_correlation_flag);

/// Gauss–Newton steps on the full seven-parameter objective (squared loss) from u, each with a
/// backtracking line search, while they remove more than `tolerance` of χ²: the Levenberg–
/// Marquardt damping crawls along a valley whose width is near the rounding of the normal
/// equations (one load, no noise: c–φ), where an undamped step on the scaled normal equations
/// (pseudo-inverse below 1e-14 of the largest eigenvalue) lands on the minimum in one or two.
/// A parameter on a bound moves only where the gradient and the step take it inside, and such a
/// step gets two trials (the full step and a thousandth of it) instead of the backtracking; if
/// both fail, every parameter on a bound is held for the rest of the call and the step solved
/// again without them (the model has a kink at a₀ = 0, where the slope inside is not the
/// gradient's). Returns the steps taken;
/// `remaining` (if given) gets the χ² that the last Gauss–Newton model still predicted it could
/// remove: 0 when it ended on `tolerance` (or nothing is left to move), else that of its last step
/// (a failed line search, `max_steps`), +inf when a row failed before any.
int polish(const Objective& objective, const std::vector<std::size_t>& samples,
           std::vector<double>& u, int max_steps, double tolerance, double* remaining = nullptr);

/// Indices 0..n−1.
std::vector<std::size_t> allSamples(std::size_t n);

}  // namespace terra::identification::detail
