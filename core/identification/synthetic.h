#pragma once
/// @file synthetic.h
/// Synthetic identification data from the wheel–soil model (the thesis's chapter-5 procedure):
/// a slip sweep at one or several loads, θ_f from the entry-angle estimator (§2.6.1), forces from
/// the full model, plus Gaussian measurement noise ỹ = y + e (Eq. 5.1) with a fixed seed.

#include <atomic>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "core/contact/contact_parameters.h"
#include "core/contact/sinkage.h"
#include "core/identification/data_set.h"

namespace terra::identification {

/// The noise of one channel: e ~ N(0, σ²) with σ absolute, or a fraction of the channel's
/// largest absolute value in the noise-free data.
struct ChannelNoise {
    double absolute = 0.0;  ///< σ in the channel's unit (N, N·m, rad)
    double relative = 0.0;  ///< σ as a fraction of max |y| of the channel

    double sigma(double channel_max_abs) const { return absolute + relative * channel_max_abs; }
};

/// Noise per channel (Eq. 5.1); the default is noise-free.
struct NoiseSpec {
    ChannelNoise fx, fz, my, entry_angle;
};

/// What to synthesise.
struct SyntheticSpec {
    std::vector<double> loads_n{contact::kDefaultLoadN};  ///< W [N], one sweep per load (Table 5.2)
    std::vector<double> slips;                            ///< s values of each sweep
    double slip_angle_rad = 0.0;                          ///< β (Table 5.2: 0)
    contact::ExitCondition exit;                          ///< θ_r = 0 (Table 5.2)
    NoiseSpec noise;
    std::uint64_t seed = 1;
    double sample_period_s = 0.01;              ///< time between samples (100 Hz)
    const std::atomic<bool>* cancel = nullptr;  ///< set to stop early (the samples so far are kept)
    std::function<void(double)> progress;  ///< fraction of the points done, in [0, 1]; may be empty
};

/// The data set and the points left out because the soil cannot carry the load there.
struct SyntheticData {
    DataSet data;
    std::vector<std::string> warnings;
    bool cancelled = false;  ///< stopped by `cancel` before every point was computed
};

/// Generates the data set. Samples carry `time_s`, and `load_n` when more than one load is given.
/// The noise is drawn from Boost.Random's mt19937_64 and normal distribution, so a seed gives the
/// same data on every platform; a cancelled run adds the noise to the samples it has (its relative
/// noise levels then come from those samples' largest values). Throws std::invalid_argument for
/// invalid loads, slips or noise.
SyntheticData synthesize(const contact::ContactParameters<double>& params,
                         const SyntheticSpec& spec);

}  // namespace terra::identification
