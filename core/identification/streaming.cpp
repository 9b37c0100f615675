#include "core/identification/streaming.h"

#include <Eigen/Cholesky>
#include <Eigen/Core>
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

// Parameter k of the covariance's order (kDecoupledParameterCount) in p.
double& parameterAt(DecoupledParameters& p, int k) {
    double* const members[kDecoupledParameterCount] = {
        &p.a0, &p.a1,          &p.pressure_modulus,   &p.n0,
        &p.n1, &p.cohesion_pa, &p.friction_angle_rad, &p.shear_modulus_m};
    return *members[k];
}

// The bounds of each parameter: step I's a₀ ∈ [0, 1], a₁ ∈ [−1, 1] (decoupled_fit.h), then the
// DecoupledBounds the streaming fit runs with.
std::array<std::array<double, 2>, kDecoupledParameterCount> parameterBounds() {
    const DecoupledBounds b;
    return {{{0.0, 1.0},
             {-1.0, 1.0},
             {b.ks_min, b.ks_max},
             {b.n0_min, b.n0_max},
             {b.n1_min, b.n1_max},
             {b.c_min, b.c_max},
             {b.phi_min, b.phi_max},
             {b.k_min, b.k_max}}};
}

}  // namespace

std::array<double, kDecoupledParameterCount> decoupledVector(const DecoupledParameters& p) {
    DecoupledParameters copy = p;
    std::array<double, kDecoupledParameterCount> out{};
    for (int k = 0; k < kDecoupledParameterCount; ++k) out[k] = parameterAt(copy, k);
    return out;
}

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
    if (options_.covariance) updateCovariance();
}

// The estimate's covariance, step by step as the fit runs (docs/traction.md §8): step I's a₀, a₁
// on the F_x residuals, step II's K_s, n₀, n₁ on F_z, step III's c, φ, K on M_y. Per step, with
// J the residuals' Jacobian in its parameters (central differences, steps of 1e-5 of each bound's
// span) and σ² = Σr²/(N − p) its residual variance: C = (JᵀJ/σ² + P₀⁻¹)⁻¹, P₀ = diag((hi −
// lo)²/12), the variance of a uniform prior over the bounds the fit is held to, so that a direction
// the window does not inform keeps the bounds' spread instead of an infinite (or, by
// pseudo-inverse, zero) variance. Steps II and III are fitted with step I's a₀, a₁ held at their
// estimate, so its error moves theirs: to first order θ_c = θ̂_c + G_c (θ_I − θ̂_I) with
// G_c = −C_c J_cᵀ J_c,I / σ_c² (J_c,I: channel c's residuals in a₀, a₁), and the three channels'
// noises being independent, Cov(θ_c) = C_c + G_c C_I G_cᵀ, Cov(θ_c, θ_I) = G_c C_I and
// Cov(θ_II, θ_III) = G_II C_I G_IIIᵀ.
void StreamingIdentifier::updateCovariance() {
    const auto bounds = parameterBounds();
    const auto n = static_cast<Eigen::Index>(window_.size());
    // Channel c's residuals over the window in the parameters `which`.
    auto jacobian = [&](int channel, const std::vector<int>& which) {
        Eigen::MatrixXd j(n, static_cast<Eigen::Index>(which.size()));
        for (std::size_t col = 0; col < which.size(); ++col) {
            const int k = which[col];
            const double h = 1e-5 * (bounds[k][1] - bounds[k][0]);
            DecoupledParameters up = estimate_, down = estimate_;
            parameterAt(up, k) += h;
            parameterAt(down, k) -= h;
            Eigen::Index i = 0;
            for (const Sample& s : window_) {
                j(i++, static_cast<Eigen::Index>(col)) =
                    (residuals(up, wheel_, s)[channel] - residuals(down, wheel_, s)[channel]) /
                    (2.0 * h);
            }
        }
        return j;
    };
    const std::vector<int> steps[3] = {{0, 1}, {2, 3, 4}, {5, 6, 7}};
    Eigen::MatrixXd conditional[3], gain[3];  // C_c, and G_c for c = II, III
    for (int channel = 0; channel < 3; ++channel) {
        const std::vector<int>& step = steps[channel];
        const auto p = static_cast<Eigen::Index>(step.size());
        const Eigen::MatrixXd j = jacobian(channel, step);
        double sum = 0.0;
        for (const Sample& s : window_) {
            const double r = residuals(estimate_, wheel_, s)[channel];
            sum += r * r;
        }
        const double variance =
            std::max(sum / static_cast<double>(std::max<Eigen::Index>(1, n - p)), 1e-300);
        Eigen::MatrixXd information = j.transpose() * j / variance;
        for (Eigen::Index a = 0; a < p; ++a) {
            const auto& b = bounds[step[static_cast<std::size_t>(a)]];
            information(a, a) += 12.0 / ((b[1] - b[0]) * (b[1] - b[0]));
        }
        conditional[channel] = information.llt().solve(Eigen::MatrixXd::Identity(p, p));
        if (channel > 0) {
            gain[channel] =
                -conditional[channel] * j.transpose() * jacobian(channel, steps[0]) / variance;
        }
    }
    Eigen::MatrixXd full =
        Eigen::MatrixXd::Zero(kDecoupledParameterCount, kDecoupledParameterCount);
    const Eigen::MatrixXd& c1 = conditional[0];
    full.block(0, 0, 2, 2) = c1;
    full.block(2, 2, 3, 3) = conditional[1] + gain[1] * c1 * gain[1].transpose();
    full.block(5, 5, 3, 3) = conditional[2] + gain[2] * c1 * gain[2].transpose();
    full.block(2, 0, 3, 2) = gain[1] * c1;
    full.block(5, 0, 3, 2) = gain[2] * c1;
    full.block(5, 2, 3, 3) = gain[2] * c1 * gain[1].transpose();
    for (int a = 0; a < kDecoupledParameterCount; ++a)
        for (int b = 0; b <= a; ++b) covariance_[a][b] = covariance_[b][a] = full(a, b);
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
                update.covariance = covariance_;
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
            covariance_ = {};
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
    update.covariance = covariance_;
    return update;
}

}  // namespace terra::identification
