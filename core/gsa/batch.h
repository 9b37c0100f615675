#pragma once
/// @file batch.h
/// The wheel model at N operating points, each with its own soil (per-sample overrides of soil
/// fields by their file keys): the one primitive behind the global sensitivity studies, the
/// uncertainty bands and (later) the Python module's vectorised calls. Samples are independent
/// (every entry-angle solve starts cold from Bekker's static sinkage), so a sample's outputs are a
/// pure function of its inputs: identical bits on any thread count and in any chunk.

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/contact/bulldozing.h"
#include "core/contact/sinkage.h"
#include "core/soil/soil_parameters.h"
#include "core/wheel/wheel_parameters.h"

namespace terra::gsa {

/// How the model is evaluated: the same for every sample of a batch.
struct ModelOptions {
    contact::ExitCondition exit;                 ///< θ_r = 0 by default (Table 2.6)
    std::optional<double> max_stress_angle_rad;  ///< fixed θ_m [rad]; empty: Eq. 2.18
    contact::ContactModel model = contact::ContactModel::kFull;
    contact::BulldozingModel bulldozing = contact::BulldozingModel::kBekker;
    contact::IntegrationOptions integration;
};

/// Throws std::invalid_argument naming the field, value and range (exit angle or rut ratio, θ_m).
void requireValid(const ModelOptions& options);

/// Threads, progress and cancellation of a long computation.
struct RunControl {
    int threads = 0;  ///< worker threads; 0: one per hardware thread. Results do not depend on it.
    /// Fraction done in (0, 1], about every 1 %; called from the worker threads, one call at a
    /// time, with increasing values.
    std::function<void(double)> progress;
    const std::atomic<bool>* cancel = nullptr;  ///< set to stop; unevaluated samples are marked
};

/// A soil field varied per sample: its file key ("phi_deg") and values in the file's unit.
struct SoilOverride {
    std::string key;
    std::span<const double> values;  ///< `count` values, or one for all samples
};

/// The samples of a batch. Every array holds `count` values, or one value used for all samples.
struct BatchInput {
    std::size_t count = 0;
    std::span<const double> slip;            ///< s [-], in [−1, 1]
    std::span<const double> slip_angle_rad;  ///< β [rad], |β| < π/2; empty: 0
    /// W [N] > 0: θ_f solved so that F_z = W (section 2.6.1). Empty: θ_f given below.
    std::span<const double> load_n;
    std::span<const double> entry_angle_rad;  ///< θ_f [rad] in (0, π/2], when load_n is empty
    std::vector<SoilOverride> soil;           ///< fields not listed keep the base soil's value
};

/// What happened to one sample.
enum class SampleStatus : std::uint8_t {
    kOk = 0,          ///< outputs computed
    kNoEquilibrium,   ///< no θ_f ≤ 90° carries W (contact::SinkageSolution::kNoEquilibrium)
    kLoadNotMatched,  ///< F_z jumps over W (contact::SinkageSolution::kLoadNotMatched)
    /// The sample's soil is outside a field's allowed range, violates N = n + n₁ s ∈ n's range,
    /// or has K_s = k_c/b + k_φ ≤ 0 (only with InvalidSoil::kFlag; kThrow refuses the batch).
    kInvalidSoil,
    kNonFinite,     ///< an output came out non-finite (never expected; kept out of every result)
    kNotEvaluated,  ///< cancelled before this sample
};

/// Short name of a status ("no equilibrium").
const char* statusName(SampleStatus status);

/// What to do with a sample whose soil overrides are invalid.
enum class InvalidSoil {
    kThrow,  ///< refuse the whole batch before computing (std::invalid_argument naming them)
    kFlag,   ///< mark the sample kInvalidSoil and go on (sampled distributions)
};

/// Where the outputs go: caller-owned arrays of `count` values (numpy buffers, study matrices).
/// Empty spans are not written. A sample that is not kOk gets 0 in every output.
struct BatchOutputView {
    std::span<double> fx_n, fy_n, fz_n;     ///< F_x, F_y, F_z [N] (Eqs. 2.23, 2.25, 2.31)
    std::span<double> mx_nm, my_nm, mz_nm;  ///< M_x, M_y, M_z [N·m] (Eqs. 2.32, 2.34, 2.35)
    std::span<double> fb_n, fs_n;           ///< F_b, F_s [N] (Eqs. 2.30, 2.24)
    std::span<double> entry_angle_rad;      ///< θ_f [rad] (solved or given)
    std::span<double> exit_angle_rad;       ///< θ_r [rad]
    std::span<double> sinkage_m;            ///< h = r (1 − cos θ_f) [m] (Eq. 2.12)
    std::span<SampleStatus> status;         ///< per sample
};

/// Counts of a finished batch.
struct BatchSummary {
    std::size_t ok = 0;
    std::size_t failed = 0;         ///< not kOk and evaluated
    std::size_t not_evaluated = 0;  ///< left by a cancel
    bool cancelled = false;
};

/// Evaluates the batch into `out`. Throws std::invalid_argument, before any computation, naming
/// the array, the index, the value and the allowed range for a bad input (an array whose length
/// is neither count nor 1, an unknown or repeated soil key, an operating point outside the model's
/// domain, both or neither of load and entry angle, an invalid base soil or wheel, or, with
/// kThrow, an invalid soil override). An exception in a worker is rethrown here.
BatchSummary evaluateBatch(const soil::SoilParameters& soil, const wheel::WheelParameters& wheel,
                           const BatchInput& input, const ModelOptions& options,
                           const BatchOutputView& out, const RunControl& control = {},
                           InvalidSoil invalid = InvalidSoil::kThrow);

/// The outputs of a batch in owned arrays (every output filled).
struct BatchResult {
    std::vector<double> fx_n, fy_n, fz_n, mx_nm, my_nm, mz_nm, fb_n, fs_n;
    std::vector<double> entry_angle_rad, exit_angle_rad, sinkage_m;
    std::vector<SampleStatus> status;
    BatchSummary summary;

    bool ok(std::size_t i) const { return status[i] == SampleStatus::kOk; }
};

/// evaluateBatch into freshly allocated arrays.
BatchResult evaluateBatch(const soil::SoilParameters& soil, const wheel::WheelParameters& wheel,
                          const BatchInput& input, const ModelOptions& options,
                          const RunControl& control = {},
                          InvalidSoil invalid = InvalidSoil::kThrow);

}  // namespace terra::gsa
