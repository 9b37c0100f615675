#include "core/contact/kinks.h"

#include <algorithm>
#include <boost/math/tools/toms748_solve.hpp>
#include <cmath>
#include <cstdint>
#include <limits>

#include "core/contact/shear_deformation.h"

namespace terra::contact {
namespace {

constexpr double kHalfPi = 1.5707963267948966;

// j_t and j before the j_max limit, by the stress field's formula (shear_deformation.h).
struct Shear {
    const ShearGeometry& g;
    double sin_entry = std::sin(g.entry_angle_rad);

    ShearDeformation<double> at(double theta) const {
        return shearDeformation(g.radius_m, g.entry_angle_rad, sin_entry, g.velocity_ratio,
                                g.lateral_velocity, theta, std::sin(theta));
    }
    double tangential(double theta) const { return at(theta).tangential; }
    double magnitude(double theta) const {
        const ShearDeformation<double> j = at(theta);
        return std::hypot(j.tangential, j.lateral);
    }
};

// A root of f on [a, b] where f(a), f(b) have opposite signs, to full double precision.
template <typename F>
double bracketedRoot(F f, double a, double b, double fa, double fb) {
    std::uintmax_t iterations = 100;
    const auto [lo, hi] = boost::math::tools::toms748_solve(
        f, a, b, fa, fb, boost::math::tools::eps_tolerance<double>(52), iterations);
    return 0.5 * (lo + hi);
}

void add(Kinks& kinks, double theta, const ShearGeometry& g) {
    if (theta > g.exit_angle_rad && theta < g.entry_angle_rad && kinks.count < kMaxKinks) {
        kinks.angles[kinks.count++] = theta;
    }
}

// Adds every crossing of j = j_max on [a, b]. `monotone`: one end-to-end check suffices.
void addShearLimitCrossings(Kinks& kinks, const Shear& shear, double a, double b, bool monotone) {
    const double limit = shear.g.max_shear_m;
    auto excess = [&](double theta) { return shear.magnitude(theta) - limit; };
    const int pieces = monotone ? 1 : 8;
    double x0 = a;
    double f0 = excess(x0);
    for (int i = 1; i <= pieces; ++i) {
        const double x1 = a + (b - a) * i / pieces;
        const double f1 = excess(x1);
        if ((f0 < 0.0) != (f1 < 0.0)) add(kinks, bracketedRoot(excess, x0, x1, f0, f1), shear.g);
        x0 = x1;
        f0 = f1;
    }
}

}  // namespace

Kinks findKinks(const ShearGeometry& geometry) {
    Kinks kinks;
    const Shear shear{geometry};
    const double lo = geometry.exit_angle_rad;
    const double hi = geometry.entry_angle_rad;
    if (!(hi > lo) || std::isinf(geometry.velocity_ratio)) return kinks;
    const bool limited = std::isfinite(geometry.max_shear_m);

    if (geometry.velocity_ratio <= 1.0) {
        // Driving: dj_t/dθ = r(κ cos θ − 1) ≤ 0 and |j_l| grows away from θ_f, so j decreases
        // monotonically from θ_r to θ_f: at most one crossing of j_max.
        if (limited) addShearLimitCrossings(kinks, shear, lo, hi, true);
        return kinks;
    }

    // Braking (κ > 1): the tangential shear velocity 1 − κ cos θ vanishes at ±θ* = ±acos(1/κ),
    // where j_t has its extrema; between them j_t is monotone and may change sign once.
    const double star = std::acos(1.0 / geometry.velocity_ratio);
    std::array<double, 3> pieces_end{};
    int piece_count = 0;
    double start = lo;
    for (double edge : {-star, star}) {
        if (edge > start && edge < hi) {
            add(kinks, edge, geometry);
            pieces_end[piece_count++] = edge;
            start = edge;
        }
    }
    pieces_end[piece_count++] = hi;
    start = lo;
    for (int i = 0; i < piece_count; ++i) {
        const double end = pieces_end[i];
        auto tangential = [&](double theta) { return shear.tangential(theta); };
        const double f0 = tangential(start);
        const double f1 = tangential(end);
        double split = start;
        if (f0 != 0.0 && f1 != 0.0 && (f0 < 0.0) != (f1 < 0.0)) {
            split = bracketedRoot(tangential, start, end, f0, f1);
            add(kinks, split, geometry);
        }
        if (limited) {
            if (split > start) addShearLimitCrossings(kinks, shear, start, split, false);
            addShearLimitCrossings(kinks, shear, split, end, false);
        }
        start = end;
    }
    std::sort(kinks.angles.begin(), kinks.angles.begin() + kinks.count);
    return kinks;
}

namespace {

// c, and c − 8^k w (below) and/or c + 8^k w (above) for k = 0…5, when w is small against the
// contact. Factor 8: each piece then holds a tail that varies by a bounded ratio, which the
// 15-point rule integrates to ~1e-6 before any bisection.
void addGraded(Kinks& kinks, const ShearGeometry& g, double centre, double width, bool below,
               bool above, bool with_centre, double narrow_below) {
    const double span = g.entry_angle_rad - g.exit_angle_rad;
    if (!(width > 0.0) || !(width < narrow_below * span)) return;
    if (with_centre) add(kinks, centre, g);
    double offset = width;
    for (int k = 0; k <= 5 && offset < span; ++k, offset *= 8.0) {
        if (below) add(kinks, centre - offset, g);
        if (above) add(kinks, centre + offset, g);
    }
}

}  // namespace

double peakShearDeformation(const ShearGeometry& g) {
    if (!(g.velocity_ratio <= 1.0)) return std::numeric_limits<double>::infinity();
    if (!(g.entry_angle_rad > g.exit_angle_rad)) return 0.0;
    return Shear{g}.magnitude(g.exit_angle_rad);
}

Kinks findScaleSplits(const ShearGeometry& g) {
    Kinks splits;
    if (!(g.entry_angle_rad > g.exit_angle_rad)) return splits;
    const double kappa = g.velocity_ratio;
    const double lateral = std::abs(g.lateral_velocity);
    if (lateral > 0.0) {
        if (kappa <= 1.0) {
            addGraded(splits, g, 0.0, std::sqrt(2.0 * std::hypot(1.0 - kappa, lateral)), true, true,
                      true, 0.25);
        } else if (std::isinf(kappa)) {
            // The locked wheel: the limit of the braking width below, at ±θ* = ±90°.
            const double t = std::abs(g.slip_angle_tan);
            const double width = t / (1.0 + std::sqrt(2.0 * t));
            addGraded(splits, g, kHalfPi, width, true, true, false, 0.25);
            addGraded(splits, g, -kHalfPi, width, true, true, false, 0.25);
        } else {
            const double star = std::acos(1.0 / kappa);
            const double width =
                lateral / (kappa * std::sin(star) + std::sqrt(2.0 * kappa * lateral));
            // ±θ* are kinks already (findKinks); only the graded points are added here.
            addGraded(splits, g, star, width, true, true, false, 0.25);
            addGraded(splits, g, -star, width, true, true, false, 0.25);
        }
    }
    double depth = std::min(g.shear_modulus_m, g.max_shear_m);
    const double rate = g.radius_m * std::hypot(1.0 - kappa * std::cos(g.entry_angle_rad), lateral);
    // A limit the shear never reaches does not set the width, so that no piece then depends on
    // j_max (shearLimitUnreached). (A driven wheel's j(θ_r) is at least about rate · span / 4,
    // so such a rise is not thin and adds no split either way; checked only where it would.)
    const double span = g.entry_angle_rad - g.exit_angle_rad;
    if (depth < g.shear_modulus_m && depth < rate * span / 16.0 &&
        peakShearDeformation(g) < g.max_shear_m)
        depth = g.shear_modulus_m;
    // Only a thin layer: a wider one is resolved by the end mapping of the front region.
    if (depth > 0.0 && rate > 0.0) {
        addGraded(splits, g, g.entry_angle_rad, depth / rate, true, false, false, 1.0 / 16.0);
    }
    std::sort(splits.angles.begin(), splits.angles.begin() + splits.count);
    return splits;
}

}  // namespace terra::contact
