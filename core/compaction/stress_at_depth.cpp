#include "core/compaction/stress_at_depth.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <boost/math/tools/minima.hpp>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include "core/common/range.h"

namespace terra::compaction {
namespace {

constexpr double kMinConcentration = 2.0;  // exclusive: ν(ν − 2) = 0 carries no horizontal force
constexpr double kMaxConcentration = 12.0;

// c^e for a whole e ≥ 0 by products (ν = 3…6 are the usual factors), else pow.
double power(double c, double e, int whole) {
    if (whole >= 0) {
        double out = 1.0;
        for (int i = 0; i < whole; ++i) out *= c;
        return out;
    }
    return std::pow(c, e);
}

}  // namespace

StressMeasures measuresOf(const Eigen::Matrix3d& stress) {
    StressMeasures m;
    m.sigma_x = stress(0, 0);
    m.sigma_y = stress(1, 1);
    m.sigma_z = stress(2, 2);
    m.mean = (m.sigma_x + m.sigma_y + m.sigma_z) / 3.0;
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen;
    eigen.computeDirect(stress, Eigen::EigenvaluesOnly);
    m.major = eigen.eigenvalues().maxCoeff();
    return m;
}

StressPropagation::StressPropagation(std::vector<PointLoad> loads, double concentration)
    : loads_(std::move(loads)), nu_(concentration), integer_nu_(0) {
    if (!(concentration > kMinConcentration && concentration <= kMaxConcentration)) {
        throw std::invalid_argument("concentration factor nu = " + formatNumber(concentration) +
                                    " is outside (2, 12] (3: Boussinesq; 4-6 for agricultural "
                                    "soils, docs/compaction.md)");
    }
    if (std::floor(concentration) == concentration) integer_nu_ = static_cast<int>(concentration);
    for (std::size_t i = 0; i < loads_.size(); ++i) {
        const PointLoad& load = loads_[i];
        if (!load.position.allFinite() || !load.force.allFinite() || load.position.z() < 0.0) {
            throw std::invalid_argument("load " + std::to_string(i) +
                                        ": position and force must be finite, at depth >= 0");
        }
        deepest_ = std::max(deepest_, load.position.z());
    }
}

template <typename Accumulate>
void StressPropagation::forEachRadialStress(const Eigen::Vector3d& point,
                                            Accumulate accumulate) const {
    const double vertical_factor = nu_ / (2.0 * std::numbers::pi);
    const double horizontal_factor = nu_ * (nu_ - 2.0) / (2.0 * std::numbers::pi);
    const int whole_h = integer_nu_ > 0 ? integer_nu_ - 3 : -1;
    for (const PointLoad& load : loads_) {
        const Eigen::Vector3d r = point - load.position;
        if (!(r.z() > 0.0)) continue;
        const double r2 = r.squaredNorm();
        const Eigen::Vector3d unit = r * (1.0 / std::sqrt(r2));  // one division, not three
        const double c = unit.z();                               // cos ϑ
        // C1 and C2 of docs/compaction.md: σ_R = [ν F_z c^(ν−2) + ν(ν−2) c^(ν−3) F_h·R̂]/(2π R²).
        const double c_h = power(c, nu_ - 3.0, whole_h);
        const double tangential = load.force.x() * unit.x() + load.force.y() * unit.y();
        accumulate(
            (vertical_factor * load.force.z() * c_h * c + horizontal_factor * c_h * tangential) /
                r2,
            unit);
    }
}

Eigen::Matrix3d StressPropagation::stressAt(const Eigen::Vector3d& point) const {
    Eigen::Matrix3d out = Eigen::Matrix3d::Zero();
    forEachRadialStress(point, [&](double sigma_r, const Eigen::Vector3d& unit) {
        out.noalias() += sigma_r * (unit * unit.transpose());
    });
    return out;
}

double StressPropagation::verticalStressAt(const Eigen::Vector3d& point) const {
    double out = 0.0;
    forEachRadialStress(point, [&](double sigma_r, const Eigen::Vector3d& unit) {
        out += sigma_r * unit.z() * unit.z();
    });
    return out;
}

namespace {

// The footprint's extent along x ± 3z: where a point at depth z feels the load.
std::pair<double, double> scanRange(const StressPropagation& propagation, double z_m) {
    double lo = 0.0, hi = 0.0;
    bool first = true;
    for (const PointLoad& load : propagation.loads()) {
        lo = first ? load.position.x() : std::min(lo, load.position.x());
        hi = first ? load.position.x() : std::max(hi, load.position.x());
        first = false;
    }
    return {lo - 3.0 * z_m, hi + 3.0 * z_m};
}

void requireBelow(const StressPropagation& propagation, double z_m) {
    if (!(z_m > propagation.deepestLoad())) {
        throw std::invalid_argument("depth " + formatNumber(z_m) +
                                    " m is not below the deepest load (" +
                                    formatNumber(propagation.deepestLoad()) + " m)");
    }
}

// The largest f over [a, b] around a scan's best point: Brent's method (Boost.Math) on −f, to
// 2^-20 relative in x; never below the scan's own best value.
template <typename F>
std::pair<double, double> refineMaximum(F f, double a, double b, double x_best, double f_best) {
    std::uintmax_t iterations = 40;
    const auto [x, minus] = boost::math::tools::brent_find_minima([&](double x) { return -f(x); },
                                                                  a, b, 20, iterations);
    return -minus >= f_best ? std::pair{x, -minus} : std::pair{x_best, f_best};
}

}  // namespace

PassMaxima passMaxima(const StressPropagation& propagation, double y_m, double z_m,
                      int scan_points) {
    requireBelow(propagation, z_m);
    const auto [lo, hi] = scanRange(propagation, z_m);
    scan_points = std::max(scan_points, 5);
    const double step = (hi - lo) / (scan_points - 1);
    constexpr int kMeasures = 5;
    auto pick = [](const StressMeasures& m, int k) {
        switch (k) {
            case 0:
                return m.sigma_z;
            case 1:
                return m.sigma_x;
            case 2:
                return m.sigma_y;
            case 3:
                return m.mean;
            default:
                return m.major;
        }
    };
    std::vector<StressMeasures> scan(static_cast<std::size_t>(scan_points));
    for (int i = 0; i < scan_points; ++i)
        scan[static_cast<std::size_t>(i)] = propagation.measuresAt({lo + i * step, y_m, z_m});
    PassMaxima out;
    double* targets[kMeasures] = {&out.maxima.sigma_z, &out.maxima.sigma_x, &out.maxima.sigma_y,
                                  &out.maxima.mean, &out.maxima.major};
    for (int k = 0; k < kMeasures; ++k) {
        int best = 0;
        for (int i = 1; i < scan_points; ++i)
            if (pick(scan[static_cast<std::size_t>(i)], k) >
                pick(scan[static_cast<std::size_t>(best)], k))
                best = i;
        const double a = lo + std::max(best - 1, 0) * step;
        const double b = lo + std::min(best + 1, scan_points - 1) * step;
        const auto [x, value] = refineMaximum(
            [&](double x) {
                return pick(propagation.measuresAt({x, y_m, z_m}), k);
            },
            a, b, lo + best * step, pick(scan[static_cast<std::size_t>(best)], k));
        *targets[k] = value;
        if (k == 0) out.x_sigma_z = x;
    }
    return out;
}

VerticalStressPeak verticalStressPeak(const StressPropagation& propagation, double y_m, double z_m,
                                      int scan_points) {
    requireBelow(propagation, z_m);
    const auto [lo, hi] = scanRange(propagation, z_m);
    scan_points = std::max(scan_points, 5);
    const double step = (hi - lo) / (scan_points - 1);
    int best = 0;
    double f_best = -std::numeric_limits<double>::infinity();
    for (int i = 0; i < scan_points; ++i) {
        const double f = propagation.verticalStressAt({lo + i * step, y_m, z_m});
        if (f > f_best) best = i, f_best = f;
    }
    const auto [x, value] = refineMaximum(
        [&](double x) {
            return propagation.verticalStressAt({x, y_m, z_m});
        },
        lo + std::max(best - 1, 0) * step, lo + std::min(best + 1, scan_points - 1) * step,
        lo + best * step, f_best);
    return {x, value, step};
}

double maxVerticalStress(const StressPropagation& propagation, double y_m, double z_m,
                         int scan_points) {
    return verticalStressPeak(propagation, y_m, z_m, scan_points).sigma_z_pa;
}

VerticalStressPeak verticalStressPeakNear(const StressPropagation& propagation,
                                          const VerticalStressPeak& guess, double y_m, double z_m) {
    requireBelow(propagation, z_m);
    auto f = [&](double x) { return propagation.verticalStressAt({x, y_m, z_m}); };
    // The parabola through x* and x* ± d (d a quarter of the scan step, ≤ z/3): its vertex, when
    // the three values are concave and the vertex lies within ±d, is the peak to O(d³) in x;
    // σ_z being flat there (its scale is z), the value is to O((d/z)⁴) relative.
    const double d = 0.25 * guess.step_m;
    const double x0 = guess.x_m;
    const double f0 = f(x0), f_minus = f(x0 - d), f_plus = f(x0 + d);
    // The best of the three as a start, the middle one on ties.
    VerticalStressPeak best{x0, f0, guess.step_m};
    if (f_minus > best.sigma_z_pa) best = {x0 - d, f_minus, guess.step_m};
    if (f_plus > best.sigma_z_pa) best = {x0 + d, f_plus, guess.step_m};
    const double curvature = f_plus - 2.0 * f0 + f_minus;
    if (curvature < 0.0) {
        const double shift = -0.5 * d * (f_plus - f_minus) / curvature;
        if (std::abs(shift) <= d) {
            const double at_vertex = f(x0 + shift);
            if (at_vertex >= best.sigma_z_pa) best = {x0 + shift, at_vertex, guess.step_m};
            return best;
        }
    }
    // Otherwise Brent's method within x* ± the scan step (to 2⁻²⁰ in x); a maximum at that
    // bracket's edge may lie beyond it: the whole scan then.
    const auto [x, value] =
        refineMaximum(f, x0 - guess.step_m, x0 + guess.step_m, best.x_m, best.sigma_z_pa);
    if (!(std::abs(x - x0) < 0.99 * guess.step_m)) return verticalStressPeak(propagation, y_m, z_m);
    return {x, value, guess.step_m};
}

double maxVerticalStressNear(const StressPropagation& propagation, const VerticalStressPeak& peak,
                             double y_m, double z_m) {
    return verticalStressPeakNear(propagation, peak, y_m, z_m).sigma_z_pa;
}

double verticalStressBound(const StressPropagation& propagation, double z_m) {
    double vertical = 0.0, horizontal = 0.0;
    for (const PointLoad& load : propagation.loads()) {
        vertical += std::abs(load.force.z());
        horizontal += std::hypot(load.force.x(), load.force.y());
    }
    const double nu = propagation.concentration();
    const double distance = z_m - propagation.deepestLoad();
    return (nu * vertical + nu * (nu - 2.0) * horizontal) /
           (2.0 * std::numbers::pi * distance * distance);
}

}  // namespace terra::compaction
