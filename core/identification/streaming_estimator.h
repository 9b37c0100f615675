#pragma once
/// @file streaming_estimator.h
/// On-line identification on the full model, one sample at a time (a robot at 50–100 Hz):
///
/// - **Initialisation**: the first `init_samples` samples (and those after a confirmed change) go
///   through the global identification (identify.h); its estimate and the information JᵀJ of its
///   samples become the prior.
/// - **Update**: a moving-horizon estimate over the last `window` samples with an arrival cost
///   (the posterior before the window, as a Gaussian prior), `iterations` Gauss–Newton steps per
///   sample; a sample leaving the window is folded into the arrival cost, linearised at the current
///   estimate. Old information fades with a memory of `memory_samples` (the information is scaled
///   by 1 − 1/memory per sample), so the estimate can follow a slow drift. The posterior
///   covariance is the inverse of the window's information plus the arrival cost.
/// - **Change of soil**: the normalised innovation squared of each new sample, ε = eᵀ S⁻¹ e with
///   S = H P Hᵀ + I (e the residual of the prediction in units of the noise, H its Jacobian, P
///   the covariance before the sample), is χ² with m degrees of freedom (m channels) while the
///   soil stays. A change of load or slip is not a change of soil: H P Hᵀ carries how uncertain a
///   prediction at the new operating point is. A CUSUM of the log-likelihood ratio against an
///   innovation covariance inflated by λ, ℓ = ½ [ε (1 − 1/λ) − m ln λ], each step capped, confirms
///   a change when it exceeds h; the change began after the CUSUM was last zero. Its mean run
///   length between false alarms is at least e^h samples (Wald); h = ln 10⁶ by default.
///   Samples whose ε exceeds the χ²_m quantile 1 − gate_probability are not used in the update.
///   An alarm is then confirmed by a generalised likelihood-ratio test: the history and the suspect
///   samples are fitted together (identify.h) and the increase of χ² over the history's own fit
///   is compared with a χ² quantile; a linearised prediction can underrate how far a new load
///   lies from what one load determined, the refit cannot.
/// Derivation and measured figures: docs/identification.md, "Streaming".

#include <cstddef>
#include <deque>
#include <memory>
#include <optional>

#include "core/identification/data_set.h"
#include "core/identification/identify.h"
#include "core/wheel/wheel_parameters.h"

namespace terra::identification {

/// Options of the streaming estimator.
struct StreamingEstimatorOptions {
    /// The model (source, load, j_max, noise, fixed parameters, priors, bounds) and the search of
    /// each (re)initialisation. Noise levels left at 0 are estimated by the initialisation.
    IdentifyOptions fit = [] {
        IdentifyOptions o;
        o.design_points = 32;
        o.descents = 3;
        return o;
    }();
    /// Which channels the samples carry.
    DataColumns columns;
    std::size_t init_samples = 30;      ///< samples of each (re)initialisation
    std::size_t window = 5;             ///< samples of the moving horizon
    int iterations = 2;                 ///< Gauss–Newton steps per update
    double memory_samples = 2000;       ///< the information fades by 1 − 1/memory per sample
    double change_inflation = 4.0;      ///< λ of the CUSUM's alternative
    double change_threshold = 13.8155;  ///< h = ln 10⁶
    double max_step_evidence = 4.6;  ///< cap of one sample's ℓ (h/3: a lone outlier is no change)
    double gate_probability = 1e-3;  ///< samples beyond the χ²_m 1 − p quantile are not used
    /// Accepted samples kept for the confirmation of a change and the refits of the arrival cost.
    std::size_t history = 300;
    /// A CUSUM alarm is confirmed when one soil cannot explain the history and the suspect
    /// samples together: their joint fit's χ² exceeds the history's own by more than the χ²
    /// quantile 1 − p with as many degrees of freedom as the suspect samples have residuals (a
    /// generalised likelihood-ratio test). Otherwise the joint fit becomes the estimate.
    double confirm_probability = 1e-6;
};

/// The state after one sample.
struct StreamEstimate {
    std::size_t index = 0;     ///< 0-based sample number
    bool estimated = false;    ///< an estimate exists (after the first initialisation and until a
                               ///< change is confirmed)
    bool initialised = false;  ///< this sample completed an initialisation
    bool refitted = false;     ///< the arrival cost was rebuilt from a batch refit at this sample
    ParameterVector parameters{};  ///< SI
    ParameterVector std{};         ///< SI
    double nis = 0.0;              ///< ε of this sample (before it was used)
    int channels = 0;              ///< m
    bool used = false;             ///< the sample updated the estimate (not gated out)
    double cusum = 0.0;            ///< the CUSUM after this sample
    bool change_detected = false;  ///< a change of soil was confirmed at this sample
    /// The CUSUM alarmed at this sample but one soil explains the history and the suspect samples
    /// (a new load or slip range, not a new soil): the joint fit became the estimate.
    bool change_rejected = false;
    double change_statistic = 0.0;         ///< the likelihood-ratio statistic of the confirmation
    std::optional<std::size_t> change_at;  ///< the sample where that change began
    double update_ms = 0.0;                ///< wall time of this push (report only)
};

/// The estimator. Not thread-safe; one instance per wheel.
class StreamingEstimator {
public:
    /// Throws std::invalid_argument for an invalid wheel or options.
    StreamingEstimator(const wheel::WheelParameters& wheel, StreamingEstimatorOptions options = {});
    ~StreamingEstimator();
    StreamingEstimator(StreamingEstimator&&) noexcept;
    StreamingEstimator& operator=(StreamingEstimator&&) noexcept;

    /// Adds one sample, updates the estimate and the change test.
    StreamEstimate push(const Sample& sample);

    /// The posterior covariance of the current estimate (SI; zero rows for held parameters, and
    /// all zero before the first initialisation).
    std::array<std::array<double, kFullParameterCount>, kFullParameterCount> covariance() const;

    /// The noise levels in use (given, or from the last initialisation).
    const ChannelValues& noise() const;

private:
    struct State;
    std::unique_ptr<State> state_;
};

}  // namespace terra::identification
