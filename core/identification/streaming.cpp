#include "core/identification/streaming.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>

#include "core/identification/decoupled_model.h"

namespace terra::identification {
namespace {

// Residuals of the three decoupled equations for one sample.
std::array<double, 3> residuals(const DecoupledParameters& p, const wheel::WheelParameters& w,
                                const Sample& s) {
    const HatCoefficients<double> h = hatCoefficients(p.a0, p.a1, s.slip, s.entry_angle_rad);
    return {decoupledDrawbarPull(h, w.radius_m, s.fz_n, s.my_nm) - s.fx_n,
            decoupledVerticalForce(h, w.radius_m, w.width_m, p.pressure_modulus, p.n0, p.n1, s.slip,
                                   s.entry_angle_rad, s.my_nm) -
                s.fz_n,
            decoupledTorque(h, w.radius_m, w.width_m, p.cohesion_pa, p.friction_angle_rad,
                            p.shear_modulus_m, s.slip, s.entry_angle_rad, s.fz_n) -
                s.my_nm};
}

}  // namespace

StreamingIdentifier::StreamingIdentifier(wheel::WheelParameters wheel, StreamingOptions options)
    : wheel_(std::move(wheel)), options_(options), estimate_(options.initial) {
    wheel::requireValid(wheel_);
}

double StreamingIdentifier::score(const Sample& sample) const {
    // Noise scale: the window's RMS fit residual, with floors of 1 % of the sample's own
    // magnitudes so that noise-free data do not make every rounding error a "change".
    const std::array<double, 3> r = residuals(estimate_, wheel_, sample);
    const double floors[3] = {0.01 * std::abs(sample.fz_n) * 0.1, 0.01 * std::abs(sample.fz_n),
                              0.01 * std::abs(sample.my_nm) + 1e-6};
    double worst = 0.0;
    for (int c = 0; c < 3; ++c)
        worst = std::max(worst, std::abs(r[c]) / std::max(noise_[c], floors[c]));
    return worst;
}

void StreamingIdentifier::refit(StreamUpdate& update) {
    DataSet data;
    data.samples.assign(window_.begin(), window_.end());
    const auto begin = std::chrono::steady_clock::now();
    // Warm started: the first fit may need the full 200 iterations per step, later ones start
    // next to the optimum and only follow it (StreamingOptions::max_iterations).
    const DecoupledFit fit =
        fitDecoupled(data, wheel_, estimate_, {}, estimated_ ? options_.max_iterations : 200);
    update.fit_time_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - begin).count();
    if (!fit.usable()) return;
    estimate_ = fit.parameters;
    estimated_ = true;
    double sum[3] = {0.0, 0.0, 0.0};
    for (const Sample& s : window_) {
        const std::array<double, 3> r = residuals(estimate_, wheel_, s);
        for (int c = 0; c < 3; ++c) sum[c] += r[c] * r[c];
    }
    for (int c = 0; c < 3; ++c) noise_[c] = std::sqrt(sum[c] / static_cast<double>(window_.size()));
}

StreamUpdate StreamingIdentifier::push(const Sample& sample) {
    StreamUpdate update;
    update.index = count_++;
    if (estimated_) {
        update.residual_score = score(sample);
        if (update.residual_score > options_.threshold) {
            suspects_.push_back(sample);
            if (suspects_.size() < options_.persistence) {
                // Not confirmed yet: keep the estimate, do not let the outlier into the window.
                update.estimated = true;
                update.parameters = estimate_;
                update.window_size = window_.size();
                return update;
            }
            // Confirmed: the new soil started at the first suspect; restart the window there.
            update.change_detected = true;
            update.change_at = update.index + 1 - suspects_.size();
            window_.assign(suspects_.begin(), suspects_.end());
            suspects_.clear();
            estimated_ = false;
            estimate_ = options_.initial;
            update.window_size = window_.size();
            return update;
        }
        // A lone outlier followed by a normal sample: the outlier was noise; drop it.
        suspects_.clear();
    }
    window_.push_back(sample);
    while (window_.size() > options_.window) window_.pop_front();
    update.window_size = window_.size();
    if (window_.size() >= options_.min_samples) refit(update);
    update.estimated = estimated_;
    update.parameters = estimate_;
    return update;
}

}  // namespace terra::identification
