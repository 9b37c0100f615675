#pragma once
/// @file identify.h
/// Global identification of the seven soil parameters θ = (a₀, a₁, K_s, n, c, φ, K) on the full
/// wheel model (observation_model.h), beyond the thesis's decoupled fit:
///
/// 1. **Screening**: many starts — the caller's (presets, a guess) and a space-filling design over
///    the parameter box — are scored on a subset of the samples. With a measured entry angle the
///    forces are linear in (K_s, c, K_s tan φ) for given (a₀, a₁, n, K) (Eqs. 2.17, 2.20), so those
///    three are projected out (bounded linear least squares) and only (a₀, a₁, n, K) is sampled.
/// 2. **Descent** of the best few on the subset, **refinement** of the distinct ones on all samples
///    (Ceres, Levenberg–Marquardt, box bounds with an active set); the lowest cost is the answer.
/// 3. Noise levels per channel (given, or estimated from the residuals and the fit redone with
///    them), the covariance (Gauss–Newton, priors included), flags for what the data do not
///    determine, the first-order check (projected gradient), and **ambiguity**: another local
///    minimum whose χ² is within the threshold of the best is reported beside it.
/// 4. Optional Gaussian **priors** (MAP estimate, prior vs posterior per parameter), a robust
///    **loss** (Huber, Cauchy) and **held-out** prediction errors (a fraction, or k folds).
/// Derivations, thresholds and measured figures: docs/identification.md.

#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "core/common/issue.h"
#include "core/identification/adequacy.h"
#include "core/identification/data_set.h"
#include "core/identification/full_fit.h"
#include "core/identification/observation_model.h"
#include "core/identification/parameters.h"
#include "core/wheel/wheel_parameters.h"

namespace terra::identification {

/// The loss applied to each sample's squared normalised residual s = Σ_channels rᵢ².
enum class Loss {
    kSquared,  ///< ρ(s) = s: least squares
    kHuber,    ///< ρ(s) = s for s ≤ k², 2k√s − k² above
    kCauchy,   ///< ρ(s) = k² ln(1 + s/k²)
};

/// A named starting point of the search.
struct Start {
    std::string label;  ///< "sandy loam (preset)", "guess"
    ParameterVector parameters;
};

/// The box the space-filling design covers (solver coordinates are sampled uniformly, i.e. K_s
/// and K log-uniformly). It spans the presets of resources/soils with margin.
/// j_max (when identified) is sampled in 3 mm … 0.3 m.
struct DesignBox {
    ParameterVector lower{0.0, 0.0, 1e5, 0.1, 0.0, 0.0873, 0.002, 0.003};
    ParameterVector upper{0.6, 0.6, 1e7, 1.7, 3e4, 0.785, 0.1, 0.3};
};

/// Options of identify(). Every field has a usable default: identify(data, wheel) works.
struct IdentifyOptions {
    /// Where θ_f comes from (observation_model.h).
    DataSource source = DataSource::kAuto;
    /// W [N] of every sample without a W_N cell.
    std::optional<double> load_n;
    /// j_max of the model [m] (Eq. 2.16), +inf for none: the value it is held at unless
    /// `fit_max_shear_deformation`.
    double max_shear_deformation_m = std::numeric_limits<double>::infinity();
    /// Identify j_max as an eighth parameter (bounds.lower/upper[kJmax], 1 mm … 1 m). When the
    /// data do not determine it (shearLimitSeen), the fit is redone with the prior
    /// kDefaultShearLimitPrior (unless priors[kJmax] gives one) and a flag says so.
    bool fit_max_shear_deformation = false;
    /// n₁ of Ding's slip-sinkage exponent N = n + n₁ s (docs/model.md, "Slip-sinkage"), held at
    /// this value (not estimated: a caller profiles it); 0, the default, is the thesis model.
    double sinkage_exponent_slip = 0.0;
    /// S of Lyasko's slip sinkage h = h₀ (1 + S s) (docs/model.md, Eq. S.1), held at this value
    /// (a caller profiles it, as validate --calibrate --fit-slip-sinkage does); 0: the thesis.
    double slip_sinkage_coefficient = 0.0;
    /// The wheel model fitted: the full model (the default) or the quadratic approximation
    /// (ModelSetup::model): the rover's estimator fits the model its scenario drives on.
    contact::ContactModel model = contact::ContactModel::kFull;
    /// Noise std per channel [N, N, N·m, m]; ≤ 0: estimated from the residuals of the fit.
    ChannelValues noise{};
    /// Parameters held at a value (SI) instead of estimated.
    std::array<std::optional<double>, kFullParameterCount> fixed{};
    /// Gaussian priors (SI); the estimate is then the maximum a posteriori.
    Priors priors{};
    Loss loss = Loss::kSquared;
    /// k of the loss, in units of the noise std (of √s). 0: √(χ²₀.₉₅) for the sample's number of
    /// channels (2.45 for two, 2.80 for three): 95 % of good samples are inside, untouched.
    double loss_scale = 0.0;
    ParameterBounds bounds;

    /// Starts besides the design (presets, the user's guess); none is needed.
    std::vector<Start> starts;
    /// Points of the space-filling design (a Halton sequence, shifted by `seed`).
    int design_points = 64;
    DesignBox design;
    /// Screened starts that are descended on the subset.
    int descents = 4;
    /// Samples (evenly spread over the data) on which the starts are screened, and on which the
    /// best are descended; 0: all.
    int screening_samples = 12;
    int subset_samples = 24;
    /// Δχ² below which another minimum is reported as ambiguous; 0: the χ² quantile 0.99 with as
    /// many degrees of freedom as free parameters (18.5 for seven): the other minimum lies inside
    /// the best one's 99 % joint confidence region, so the data cannot reject it.
    double ambiguity_delta_chi2 = 0.0;

    /// Held-out validation: a fraction of the samples (0 < f < 1), or k folds (k ≥ 2).
    double holdout_fraction = 0.0;
    int folds = 0;
    /// Seed of the design's shift and of the held-out selection.
    std::uint64_t seed = 1;
    /// Threads, the caller's included (1: none started; 0: one per hardware thread, at most 8).
    /// With θ_f measured the screening's starts, and the samples of the model's evaluations, are
    /// shared among them (with a robust loss the descents and refinement stay on one: they
    /// evaluate each sample apart); the result is the same whatever the count
    /// (docs/identification.md §9). From the load the search runs on one thread.
    int threads = 1;
    static constexpr int kMaxThreads = 64;  ///< the largest `threads` accepted
    /// The search's screening, descents and (where the noise allows) refinement rounds on the
    /// 7-point Gauss rule alone, finished on the default rule (docs/identification.md §9, "fourth
    /// pass"); false: the default rule throughout (the same minimum, ~1.5× the time).
    bool gauss_rule_search = true;

    /// Progress in [0, 1]; return false to cancel (the report then says so).
    std::function<bool(double)> progress;

    /// |correlation| above which a pair is flagged as not separable by the data.
    double correlation_flag = 0.98;
    /// p of the trend test (adequacy.h) below which a channel's residuals are flagged as
    /// systematic: 1e-3 per channel keeps the false alarms of a right model near 0.3 % with
    /// three channels, while a missing j_max on the README tour's data gives p of 1e-5 to 1e-10.
    double adequacy_p = 1e-3;
};

/// Everything identify() checks before it runs: issues name the option or the data (among them,
/// fewer measured values, with the priors on free parameters, than free parameters).
std::vector<Issue> validate(const DataSet& data, const wheel::WheelParameters& wheel,
                            const IdentifyOptions& options);

/// The residuals per channel of a data set read with `setup` (the setup's channels at every
/// sample, the sinkage only where the sample has one): the "measured values" the fit sees.
std::array<int, kChannelCount> measuredValueCounts(const DataSet& data, const ModelSetup& setup);

/// One start of the search and what became of it.
struct StartReport {
    std::string label;
    ParameterVector start{};
    double screening_cost = 0.0;  ///< χ² on the subset after the linear projection (screening)
    bool descended = false;       ///< among the best screened, descended on the subset
    bool refined = false;         ///< refined on all samples
    ParameterVector end{};        ///< after descent (and refinement)
    double chi2 = 0.0;            ///< after refinement (all samples), else after descent (subset)
    int iterations = 0;
    std::string termination;
};

/// A local minimum on all samples.
struct Minimum {
    ParameterVector parameters{};
    ParameterVector std{};    ///< 0 where not computed
    double chi2 = 0.0;        ///< Σ r² + prior terms, with the final noise levels
    double delta_chi2 = 0.0;  ///< χ² − best χ²
    std::string label;        ///< the start it came from
};

/// Prior against posterior for one parameter.
struct PriorComparison {
    bool active = false;
    double prior_mean = 0.0, prior_std = 0.0;          ///< SI
    double posterior_mean = 0.0, posterior_std = 0.0;  ///< SI
    /// (posterior − prior mean)/prior std: how far the data moved the estimate.
    double shift_in_prior_std = 0.0;
    /// posterior std / prior std: near 1, the data do not see the parameter; ≪ 1, they do.
    double std_ratio = 0.0;
};

/// Whether the fit's residuals are noise (adequacy.h): per channel, the lack-of-fit F test of
/// a cubic trend in slip within each sweep (the samples of one W_N and slip angle).
struct AdequacyReport {
    std::array<TrendTest, kChannelCount> trend{};  ///< not tested where p is NaN
    double p = 1.0;                                ///< the smallest p of the channels tested
    bool flag = false;  ///< p < IdentifyOptions::adequacy_p: the misfit is systematic
};

/// Held-out prediction error per channel.
struct HoldoutReport {
    bool computed = false;
    int folds = 0;            ///< 1 for a fraction
    std::size_t samples = 0;  ///< held-out samples predicted
    std::size_t failed = 0;   ///< held-out samples the fold's estimate could not predict
    std::array<bool, kChannelCount> channels{};
    ChannelValues rms{};             ///< RMS of (predicted − measured) on held-out samples
    ChannelValues rms_in_fit{};      ///< the same on the samples of the fit (all-data estimate)
    ChannelValues rms_over_noise{};  ///< held-out RMS / noise std: ≈ 1 for a model that predicts
};

enum class IdentifyStatus {
    kConverged,     ///< the best minimum converged (first-order check passed)
    kNotConverged,  ///< usable, but the solver stopped on its iteration budget
    kInvalidInput,  ///< see issues
    kCancelled,
    kFailed,  ///< no start gave a usable fit
};

/// Wall times of the phases [ms] (report only).
struct IdentifyTiming {
    double screening_ms = 0.0, descent_ms = 0.0, refinement_ms = 0.0, covariance_ms = 0.0,
           holdout_ms = 0.0, total_ms = 0.0;
};

/// The result of identify().
struct IdentificationReport {
    IdentifyStatus status = IdentifyStatus::kFailed;
    std::string message;
    std::vector<Issue> issues;  ///< kInvalidInput: every problem
    bool usable() const {
        return status == IdentifyStatus::kConverged || status == IdentifyStatus::kNotConverged;
    }

    ModelSetup setup;              ///< data source and channels used
    ParameterVector parameters{};  ///< the estimate (SI)
    Uncertainty uncertainty;       ///< std, correlations, flags (full_fit.h)
    std::array<bool, kFullParameterCount> at_bound{};
    double chi2 = 0.0;  ///< Σ r² (+ prior terms) at the estimate
    int residuals = 0;  ///< data residuals
    int free_parameters = 0;
    ChannelValues noise{};  ///< noise std used per channel (given or estimated)
    bool noise_estimated = false;
    /// Measured values per channel (measuredValueCounts).
    std::array<int, kChannelCount> channel_values{};
    /// Channels the fit interpolates: their noise level was estimated from no more measured
    /// values than free parameters, and the fit passes through every one (RMS residual below
    /// 0.1 % of the channel's largest value): the estimated noise has collapsed and the
    /// channel's weight grown without bound, so its noise level and its residuals mean nothing
    /// (a flag says so; a calibration is then not usable).
    std::array<bool, kChannelCount> interpolated{};
    ChannelValues rms{};      ///< RMS residual per channel [N, N, N·m, m]
    AdequacyReport adequacy;  ///< are the residuals noise or a pattern in slip?
    /// The first-order check: largest |∂(½χ²)/∂u| over free parameters, u the solver coordinates
    /// (parameters.h), and the Newton decrement gᵀ H⁻¹ g (the χ² one more Newton step would
    /// remove; ≪ 1 at a minimum).
    double gradient_norm = 0.0;
    double newton_decrement = 0.0;
    int iterations = 0;  ///< of the refinement of the best minimum
    std::string termination;

    std::vector<StartReport> starts;
    /// Other minima within the ambiguity threshold (and distinct: some parameter more than three
    /// std away from the best, and from each other by distinctMinima); empty when the answer is
    /// unique.
    std::vector<Minimum> ambiguity;
    double ambiguity_delta_chi2 = 0.0;  ///< the threshold used
    std::vector<Minimum> minima;        ///< every distinct minimum refined, best first

    std::array<PriorComparison, kFullParameterCount> prior{};
    /// j_max was identified but the data did not determine it: the fit was redone with the
    /// prior kDefaultShearLimitPrior (a flag says so).
    bool shear_limit_prior = false;
    HoldoutReport holdout;
    IdentifyTiming timing;
};

/// Relative distance of two parameter vectors: max over the parameters of |a − b| / scale, scale
/// the larger of |a|, |b| and the parameter's floor (the design box's width for those that may
/// be 0: a₀, a₁, c); 0 when equal (held +inf included).
double relativeDistance(const ParameterVector& a, const ParameterVector& b);

/// The minima of `minima` that are distinct, in order: one is dropped when its relative distance
/// (relativeDistance) to one kept before it is at most `tolerance` (1 %: values that print the
/// same to 3 digits are one minimum found from several starts), or when only its j_max differs
/// and its χ² is the same (to 1e-9 relative): j_max on the plateau beyond the data's reach.
std::vector<Minimum> distinctMinima(const std::vector<Minimum>& minima, double tolerance = 0.01);

/// Runs the identification. Bad options or data give kInvalidInput with the issues (no throw);
/// an invalid wheel throws std::invalid_argument (an API misuse).
IdentificationReport identify(const DataSet& data, const wheel::WheelParameters& wheel,
                              const IdentifyOptions& options = {});

/// The model's predictions for every sample at parameters p (for plots and held-out errors).
std::vector<Prediction> predictAll(const DataSet& data, const wheel::WheelParameters& wheel,
                                   const ParameterVector& p, const IdentifyOptions& options);

/// Starts from soil presets (for IdentifyOptions::starts): one per soil, labelled by its name.
std::vector<Start> startsFromSoils(const std::vector<soil::SoilParameters>& soils,
                                   const wheel::WheelParameters& wheel);

}  // namespace terra::identification
