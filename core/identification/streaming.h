#pragma once
/// @file streaming.h
/// Streaming identification, beyond the thesis: samples arrive one at a time (as from a robot at
/// 50–100 Hz); after each one the decoupled three-step fit is re-run on a sliding window,
/// warm-started from the previous estimate. A change of soil shows as prediction residuals of the
/// current estimate far above the noise: after `persistence` such samples in a row the change is
/// reported at the first of them, and the window restarts there. Each estimate carries a
/// covariance (Gauss–Newton on the window, step by step, the bounds as a weak prior:
/// docs/traction.md §8).

#include <array>
#include <cstddef>
#include <deque>
#include <optional>

#include "core/identification/data_set.h"
#include "core/identification/decoupled_fit.h"
#include "core/wheel/wheel_parameters.h"

namespace terra::identification {

struct StreamingOptions {
    std::size_t window = 60;       ///< samples in the sliding window
    std::size_t min_samples = 12;  ///< no estimate before this many samples
    double threshold = 8.0;        ///< residual / noise scale that counts as "far off"
    std::size_t persistence = 3;   ///< far-off samples in a row that make a change
    int max_iterations = 10;       ///< per step of each warm-started refit
    DecoupledParameters initial;   ///< start of the first fit (thesis guesses by default)
    /// Compute each estimate's covariance (StreamUpdate::covariance; ≈ 1,500 residual evaluations
    /// a refit, docs/performance.md): off, it stays zero.
    bool covariance = false;
};

/// The decoupled parameters in the covariance's order: a₀, a₁, K_s, n₀, n₁, c, φ, K (SI).
inline constexpr int kDecoupledParameterCount = 8;
using DecoupledCovariance =
    std::array<std::array<double, kDecoupledParameterCount>, kDecoupledParameterCount>;
/// The parameters of `p` in that order.
std::array<double, kDecoupledParameterCount> decoupledVector(const DecoupledParameters& p);

/// The state after one sample.
struct StreamUpdate {
    std::size_t index = 0;           ///< 0-based sample number
    bool estimated = false;          ///< an estimate exists (≥ min_samples in the window)
    DecoupledParameters parameters;  ///< current estimate
    /// Its covariance (SI, kDecoupledParameterCount order): per step (JᵀJ/σ² + P₀⁻¹)⁻¹ with J
    /// the window's residual Jacobian in the step's parameters, σ² the step's residual variance
    /// Σr²/(N − p) and P₀ the variance (hi − lo)²/12 of a uniform prior over each parameter's
    /// bounds, plus what step I's error hands on to steps II and III (docs/traction.md §8). All
    /// zero before an estimate and without StreamingOptions::covariance.
    DecoupledCovariance covariance{};
    double residual_score = 0.0;   ///< largest |prediction residual| / noise scale of this sample
    bool change_detected = false;  ///< a change of soil was confirmed at this sample
    std::optional<std::size_t> change_at;  ///< the sample where that change began
    std::size_t window_size = 0;
    double fit_time_ms = 0.0;  ///< wall time of this update's fit (report only)
};

class StreamingIdentifier {
public:
    StreamingIdentifier(wheel::WheelParameters wheel, StreamingOptions options = {});

    /// Adds one sample and re-estimates.
    StreamUpdate push(const Sample& sample);

private:
    double score(const Sample& sample) const;
    void refit(StreamUpdate& update);
    void updateCovariance();

    wheel::WheelParameters wheel_;
    StreamingOptions options_;
    std::deque<Sample> window_;
    std::deque<Sample> suspects_;  // far-off samples not yet confirmed as a change
    std::size_t count_ = 0;
    bool estimated_ = false;
    DecoupledParameters estimate_;
    DecoupledCovariance covariance_{};
    double noise_[3] = {0.0, 0.0, 0.0};  // RMS fit residual per channel in the window
};

}  // namespace terra::identification
