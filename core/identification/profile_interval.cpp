#include "core/identification/profile_interval.h"

#include <algorithm>
#include <cmath>
#include <optional>

namespace terra::identification {

std::array<bool, kFullParameterCount> tradeOffParameters(const IdentificationReport& fit,
                                                         double threshold) {
    std::array<bool, kFullParameterCount> out{};
    for (int k = 0; k < kFullParameterCount; ++k) {
        out[k] = fit.at_bound[k];
        if (!fit.uncertainty.computed) continue;
        for (int j = 0; j < kFullParameterCount; ++j) {
            if (j != k && std::abs(fit.uncertainty.correlation[k][j]) > threshold) out[k] = true;
        }
    }
    return out;
}

std::array<ProfileInterval, kFullParameterCount> profileIntervals(
    const DataSet& data, const wheel::WheelParameters& wheel, const IdentifyOptions& options,
    const IdentificationReport& fit, const std::array<bool, kFullParameterCount>& which,
    double delta_chi2) {
    std::array<ProfileInterval, kFullParameterCount> out{};
    if (!fit.usable() || !(delta_chi2 > 0.0)) return out;
    const ParameterVector u0 = toSolver(fit.parameters);
    const ParameterVector lo = toSolver(options.bounds.lower), hi = toSolver(options.bounds.upper);
    const ParameterVector slope = physicalPerSolver(fit.parameters);
    // Each point of a profile: a local refinement of the other parameters (no design, one
    // descent from the warm start) with the fit's noise levels, so that χ² values compare.
    IdentifyOptions o = options;
    o.noise = fit.noise;
    o.design_points = 0;
    o.descents = 1;
    o.holdout_fraction = 0.0;
    o.folds = 0;
    o.progress = nullptr;
    const double target = std::sqrt(delta_chi2);
    constexpr double kTolerance = 0.05;  // on √Δ: Δ = 9 ± 0.3
    constexpr int kMaxFits = 10;         // per side

    for (int k = 0; k < kFullParameterCount; ++k) {
        if (!which[k] || options.fixed[k]) continue;
        ProfileInterval& interval = out[k];
        interval.delta_chi2 = delta_chi2;
        interval.computed = true;
        // The linearised std in solver coordinates: the first trial is its 3σ point.
        const double h = fit.uncertainty.computed && fit.uncertainty.std[k] > 0.0
                             ? fit.uncertainty.std[k] / slope[k]
                             : 0.05 * (hi[k] - lo[k]);
        for (int dir : {-1, +1}) {
            const double s_max = std::max(0.0, dir < 0 ? u0[k] - lo[k] : hi[k] - u0[k]);
            ParameterVector warm = fit.parameters;
            // √(χ²_p − χ²_min) at offset s (solver units) from the estimate; nullopt: no fit.
            auto profile = [&](double s) -> std::optional<double> {
                ParameterVector u = toSolver(warm);
                u[k] = std::clamp(u0[k] + dir * s, lo[k], hi[k]);
                const std::array<double, kFullParameterCount> p = toPhysical(u.data());
                ParameterVector start;
                std::copy(p.begin(), p.end(), start.begin());
                o.fixed[k] = start[k];
                o.starts = {Start{"profile", start}};
                const IdentificationReport r = identify(data, wheel, o);
                ++interval.fits;
                if (!r.usable()) return std::nullopt;
                warm = r.parameters;
                return std::sqrt(std::max(0.0, r.chi2 - fit.chi2));
            };
            // Bracketed secant (regula falsi) on f(s) = √Δ(s) − √Δ, nearly linear in s where χ²
            // is nearly quadratic; below the bracket's upper end, extrapolate (at most ×4).
            double a = 0.0, fa = -target;  // f(a) < 0
            std::optional<double> b;       // f(b) > 0
            double fb = 0.0;
            double s = std::min(target * h, s_max), end = s_max;
            bool at_bound = s_max <= 0.0, failed = false;
            for (int fits = 0; !at_bound && fits < kMaxFits; ++fits) {
                const std::optional<double> root = profile(s);
                if (!root) {
                    failed = true;
                    break;
                }
                const double f = *root - target;
                end = s;
                if (std::abs(f) < kTolerance) break;
                if (f < 0.0) {
                    if (s >= s_max) {
                        at_bound = true;
                        break;
                    }
                    const double grown =
                        f > fa ? s + (s - a) * (-f) / (f - fa) : 4.0 * s;  // secant from a
                    a = s, fa = f;
                    s = b ? a + (*b - a) * (-fa) / (fb - fa) : std::min({grown, 4.0 * s, s_max});
                } else {
                    b = s, fb = f;
                    s = a + (*b - a) * (-fa) / (fb - fa);
                }
            }
            if (failed) interval.computed = false;
            const ParameterVector u = [&] {
                ParameterVector v = u0;
                v[k] = std::clamp(u0[k] + dir * (at_bound ? s_max : end), lo[k], hi[k]);
                return v;
            }();
            // The interval holds the estimate (which may lie a rounding error outside its box).
            const double value = dir < 0 ? std::min(toPhysical(u.data())[k], fit.parameters[k])
                                         : std::max(toPhysical(u.data())[k], fit.parameters[k]);
            if (dir < 0) {
                interval.lower = value;
                interval.lower_at_bound = at_bound;
            } else {
                interval.upper = value;
                interval.upper_at_bound = at_bound;
            }
        }
        o.fixed[k] = options.fixed[k];
    }
    return out;
}

}  // namespace terra::identification
