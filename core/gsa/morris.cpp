#include "core/gsa/morris.h"

#include <boost/math/distributions/normal.hpp>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/common/range.h"
#include "core/gsa/resample.h"

namespace terra::gsa {

MorrisDesign::MorrisDesign(ParameterSpace space, std::size_t trajectories, int levels,
                           std::uint64_t seed)
    : space_(std::move(space)), trajectories_(trajectories), levels_(levels), seed_(seed) {
    if (space_.dimension() == 0) throw std::invalid_argument("parameters: no parameter to vary");
    for (std::size_t i = 0; i < space_.dimension(); ++i) {
        const Marginal* m = space_.marginal(i);
        if (!m || !std::holds_alternative<Uniform>(*m)) {
            throw std::invalid_argument("parameters." + space_.names()[i] +
                                        ": Morris screening needs a uniform range (its grid ends "
                                        "at the range's ends), not a normal distribution");
        }
    }
    if (trajectories < 2) {
        throw std::invalid_argument("trajectories = " + std::to_string(trajectories) +
                                    " is outside the allowed range [2, inf)");
    }
    if (levels < 2 || levels % 2 != 0) {
        throw std::invalid_argument("levels = " + std::to_string(levels) +
                                    " must be even and at least 2");
    }
}

MorrisTrajectory MorrisDesign::trajectory(std::size_t t) const {
    if (t >= trajectories_) {
        throw std::out_of_range("trajectory " + std::to_string(t) + " of " +
                                std::to_string(trajectories_));
    }
    const std::size_t d = parameters();
    // Each trajectory's own stream: its index mixed into the seed.
    Resampler draw(splitMix(seed_ ^ splitMix(t + 1)));
    MorrisTrajectory out{std::vector<double>(d), std::vector<std::size_t>(d), std::vector<int>(d)};
    const double step = 1.0 / (levels_ - 1);
    for (std::size_t i = 0; i < d; ++i) {
        const std::size_t level = draw.index(static_cast<std::size_t>(levels_ / 2));
        out.direction[i] = draw.index(2) == 0 ? 1 : -1;
        // Going down starts Δ above the grid level, so every point stays on the grid in [0, 1].
        out.start[i] = out.direction[i] > 0 ? level * step : (level + levels_ / 2) * step;
        out.order[i] = i;
    }
    for (std::size_t i = d; i > 1; --i) std::swap(out.order[i - 1], out.order[draw.index(i)]);
    return out;
}

Eigen::MatrixXd MorrisDesign::rows(std::size_t begin, std::size_t end) const {
    if (begin > end || end > rows()) {
        throw std::out_of_range("design rows [" + std::to_string(begin) + ", " +
                                std::to_string(end) + ") outside [0, " + std::to_string(rows()) +
                                ")");
    }
    const std::size_t d = parameters(), per = rowsPerTrajectory();
    const double step = 1.0 / (levels_ - 1);
    const int half = levels_ / 2;
    Eigen::MatrixXd out(static_cast<Eigen::Index>(end - begin), static_cast<Eigen::Index>(d));
    std::vector<double> u(d), x(d);
    for (std::size_t r = begin; r < end;) {
        const std::size_t t = r / per;
        const MorrisTrajectory traj = trajectory(t);
        // Grid levels as integers: every point is exactly level × step, whatever the path.
        std::vector<int> level(d);
        for (std::size_t i = 0; i < d; ++i)
            level[i] = static_cast<int>(std::lround(traj.start[i] / step));
        for (std::size_t k = 0; k < per; ++k) {
            if (k > 0) level[traj.order[k - 1]] += traj.direction[traj.order[k - 1]] * half;
            const std::size_t index = t * per + k;
            if (index < r || index >= end) continue;
            for (std::size_t i = 0; i < d; ++i) u[i] = level[i] * step;
            space_.transform(u, x);
            for (std::size_t i = 0; i < d; ++i) {
                out(static_cast<Eigen::Index>(index - begin), static_cast<Eigen::Index>(i)) = x[i];
            }
        }
        r = (t + 1) * per;
    }
    return out;
}

MorrisIndices estimateMorris(const MorrisDesign& design, const Eigen::MatrixXd& values,
                             const Mask& ok, const BootstrapOptions& options) {
    requireValid(options);
    const auto rows = static_cast<Eigen::Index>(design.rows());
    if (values.rows() != rows ||
        (ok.size() != 0 && (ok.rows() != values.rows() || ok.cols() != values.cols()))) {
        throw std::invalid_argument("Morris estimator: outputs " + std::to_string(values.rows()) +
                                    "×" + std::to_string(values.cols()) + ", mask " +
                                    std::to_string(ok.rows()) + "×" + std::to_string(ok.cols()) +
                                    ", the design has " + std::to_string(rows) + " rows");
    }
    const std::size_t d = design.parameters(), r = design.trajectories();
    const std::size_t per = design.rowsPerTrajectory();
    const auto columns = values.cols();
    const auto pd = static_cast<Eigen::Index>(d);
    MorrisIndices out;
    out.mu = out.mu_star = out.sigma = out.mu_star_conf = Eigen::MatrixXd::Zero(pd, columns);
    out.trajectories_used.assign(static_cast<std::size_t>(columns), 0);
    std::vector<MorrisTrajectory> paths;
    paths.reserve(r);
    for (std::size_t t = 0; t < r; ++t) paths.push_back(design.trajectory(t));
    const double z = options.resamples > 0 ? quantile(boost::math::normal(0.0, 1.0),
                                                      0.5 + 0.5 * options.confidence_level)
                                           : 0.0;
    std::vector<double> effects, boot;
    for (Eigen::Index c = 0; c < columns; ++c) {
        effects.clear();  // used trajectory-major, d effects each, by parameter index
        for (std::size_t t = 0; t < r; ++t) {
            bool usable = true;
            for (std::size_t k = 0; k < per && usable; ++k) {
                usable = ok.size() == 0 || ok(static_cast<Eigen::Index>(t * per + k), c);
            }
            if (!usable) continue;
            const std::size_t base = effects.size();
            effects.resize(base + d);
            for (std::size_t k = 1; k < per; ++k) {
                const double y0 = values(static_cast<Eigen::Index>(t * per + k - 1), c);
                const double y1 = values(static_cast<Eigen::Index>(t * per + k), c);
                if (!std::isfinite(y0) || !std::isfinite(y1)) {
                    throw std::invalid_argument("Morris estimator: output column " +
                                                std::to_string(c) + ", trajectory " +
                                                std::to_string(t) + " has the non-finite value " +
                                                formatNumber(std::isfinite(y0) ? y1 : y0) +
                                                " (mark failed evaluations in the mask)");
                }
                const std::size_t i = paths[t].order[k - 1];
                effects[base + i] = (y1 - y0) / (paths[t].direction[i] * design.delta());
            }
        }
        const std::size_t m = effects.size() / d;
        out.trajectories_used[c] = m;
        if (m < 2) continue;
        for (std::size_t i = 0; i < d; ++i) {
            double sum = 0.0, sum_abs = 0.0;
            for (std::size_t t = 0; t < m; ++t) {
                sum += effects[t * d + i], sum_abs += std::abs(effects[t * d + i]);
            }
            const auto pi = static_cast<Eigen::Index>(i);
            out.mu(pi, c) = sum / m;
            out.mu_star(pi, c) = sum_abs / m;
            out.sigma(pi, c) = standardDeviation(effects, i, d);
        }
        if (options.resamples == 0) continue;
        Resampler resampler(options.seed);
        const auto b_count = static_cast<std::size_t>(options.resamples);
        boot.assign(b_count * d, 0.0);
        for (std::size_t b = 0; b < b_count; ++b) {
            for (std::size_t k = 0; k < m; ++k) {
                const std::size_t t = resampler.index(m);
                for (std::size_t i = 0; i < d; ++i) boot[b * d + i] += std::abs(effects[t * d + i]);
            }
            for (std::size_t i = 0; i < d; ++i) boot[b * d + i] /= m;
        }
        for (std::size_t i = 0; i < d; ++i) {
            out.mu_star_conf(static_cast<Eigen::Index>(i), c) = z * standardDeviation(boot, i, d);
        }
    }
    return out;
}

}  // namespace terra::gsa
