#pragma once
/// @file wheel_forces.h
/// Forces and moments on a rigid wheel from the stresses of the contact (thesis Eqs. 2.23–2.35),
/// by numerical integration that is exact to ~1e-9 relative in a few dozen stress evaluations.
/// Templated on the scalar (double for simulation, ceres::Jet for identification).
///
/// Integration (derivation and accuracy study in docs/model.md, "Integration"):
/// - the contact splits at θ_m into a front region [θ_m, θ_f] and a rear region [θ_r, θ_m];
/// - σ behaves like (θ_f − θ)^N at the front end and like (θ − θ_r)^N at the rear end, whose
///   derivatives are singular for N < 1. Each region is mapped from u ∈ [0, 1] with
///   θ_f − θ = L u^q (front) or θ − θ_r = L u^q (rear): the integrand becomes
///   u^(q(N+1)−1) × smooth, regular enough for Gauss–Legendre to converge fast;
/// - the regions are split further at the kinks of kinks.h (j_max, braking sign changes).

#include <algorithm>
#include <cmath>

#include "core/common/scalar.h"
#include "core/contact/bulldozing.h"
#include "core/contact/contact_parameters.h"
#include "core/contact/gauss_rule.h"
#include "core/contact/kinks.h"
#include "core/contact/stress_field.h"

namespace terra::contact {

/// Forces and moments that the soil applies to the wheel, in the wheel frame of section 2.2.1
/// (x along travel, z up, y to the left; frame steers with the wheel but does not spin).
template <typename T>
struct WheelForces {
    T fx{};  ///< F_x [N]: drawbar pull (Eq. 2.23)
    T fy{};  ///< F_y [N]: lateral force from the shear stress (Eq. 2.25)
    T fz{};  ///< F_z [N]: vertical force (Eq. 2.31)
    T mx{};  ///< M_x [N·m]: roll moment (Eq. 2.32)
    T my{};  ///< M_y [N·m]: resistance torque (Eq. 2.34)
    T mz{};  ///< M_z [N·m]: yaw moment (Eq. 2.35)
    T fb{};  ///< F_b [N]: bulldozing resistance of one side wall, a magnitude (Eq. 2.30, E1)
    T fs{};  ///< F_s [N]: side force F_y − sign(β) F_b (Eq. 2.24 with MODEL-NOTES signs)
};

/// How the contact integrals are evaluated.
struct IntegrationOptions {
    int points = 10;  ///< Gauss–Legendre points per piece: 7, 10, 15, 20, 25 or 30
    /// Exponent q of the end mapping θ_end − θ = L u^q; 0 picks it from the sinkage exponent N
    /// (smallest q ≥ 2 with q(N + 1) − 1 ≥ 3, so the integrand is C³ at the singular end).
    int end_exponent = 0;
};

/// The end-mapping exponent for sinkage exponent N (see IntegrationOptions::end_exponent).
inline int endExponent(double sinkage_exponent, int requested) {
    if (requested > 0) return requested;
    const double needed = 4.0 / (std::max(sinkage_exponent, 0.05) + 1.0);
    return std::clamp(static_cast<int>(std::ceil(needed - 1e-12)), 2, 8);
}

namespace detail {

template <typename T>
struct ForceSums {
    T fx{}, fy{}, fz{}, mx{}, my{}, mz{};
};

// Integrates one region [θ_lo, θ_hi] whose σ-singular end is `singular_at_hi` (front region: θ_f)
// or the low end (rear region: θ_r), splitting at the kinks inside it.
template <typename T>
void integrateRegion(const StressField<T>& field, const T& theta_lo, const T& theta_hi,
                     bool singular_at_hi, const Kinks& kinks, const GaussRule& rule, int q,
                     ForceSums<T>& sums) {
    using std::cos;
    using std::sin;
    const T length = theta_hi - theta_lo;
    if (!(length > 0.0)) return;
    const double lo = scalarValue(theta_lo);
    const double hi = scalarValue(theta_hi);
    const double len = hi - lo;

    // Break points in u, ascending, from 0 (the singular end) to 1.
    std::array<double, kMaxKinks + 2> breaks{};
    int count = 0;
    breaks[count++] = 0.0;
    for (int k = 0; k < kinks.count; ++k) {
        const double theta = kinks.angles[k];
        if (theta <= lo || theta >= hi) continue;
        const double distance = singular_at_hi ? hi - theta : theta - lo;
        breaks[count++] = std::pow(distance / len, 1.0 / q);
    }
    breaks[count++] = 1.0;
    std::sort(breaks.begin() + 1, breaks.begin() + count - 1);

    for (int piece = 0; piece + 1 < count; ++piece) {
        const double u0 = breaks[piece];
        const double du = breaks[piece + 1] - u0;
        if (!(du > 0.0)) continue;
        for (std::size_t i = 0; i < rule.nodes.size(); ++i) {
            const double u = u0 + du * rule.nodes[i];
            double uq1 = 1.0;  // u^(q−1)
            for (int e = 1; e < q; ++e) uq1 *= u;
            const T offset = length * (uq1 * u);
            const T theta = singular_at_hi ? T(theta_hi - offset) : T(theta_lo + offset);
            const T weight = length * (q * uq1 * du * rule.weights[i]);
            const T s = sin(theta);
            const T c = cos(theta);
            const StressSample<T> st = field.at(theta, s, c);
            sums.fx += weight * (st.tau_t * c - st.sigma * s);
            sums.fz += weight * (st.sigma * c + st.tau_t * s);
            sums.fy += weight * st.tau_l;
            sums.mx += weight * (st.tau_l * c);
            sums.my += weight * st.tau_t;
            sums.mz += weight * (st.tau_l * s);
        }
    }
}

template <typename T>
ShearGeometry shearGeometry(const ContactParameters<T>& p, const StressField<T>& field) {
    return {scalarValue(p.radius_m),       scalarValue(field.entryAngle()),
            scalarValue(field.exitAngle()), scalarValue(field.velocityRatio()),
            scalarValue(field.lateralVelocity()), p.max_shear_deformation_m};
}

}  // namespace detail

/// Applies the integral prefactors (r b, r² b and the signs of Eqs. 2.23–2.35) and bulldozing.
template <typename T>
WheelForces<T> assembleForces(const ContactParameters<T>& p, const OperatingPoint<T>& op,
                              const detail::ForceSums<T>& sums, BulldozingModel bulldozing) {
    const T rb = p.radius_m * p.width_m;
    const T r2b = rb * p.radius_m;
    WheelForces<T> f;
    f.fx = rb * sums.fx;
    f.fy = -rb * sums.fy;
    f.fz = rb * sums.fz;
    f.mx = -r2b * sums.mx;
    f.my = r2b * sums.my;
    f.mz = -r2b * sums.mz;
    f.fb = bulldozingForce(p, op.entry_angle_rad, bulldozing);
    if (op.slip_angle_rad > 0.0) {
        f.fs = f.fy - f.fb;
    } else if (op.slip_angle_rad < 0.0) {
        f.fs = f.fy + f.fb;
    } else {
        f.fs = f.fy;  // no lateral motion, no bulldozing (MODEL-NOTES)
    }
    return f;
}

/// F_x, F_y, F_z, M_x, M_y, M_z, F_b and F_s of the full model at one operating point.
/// Preconditions (checked by requireValid in the double API of sinkage.h / the CLI): valid
/// parameters and operating point.
template <typename T>
WheelForces<T> computeForces(const ContactParameters<T>& p, const OperatingPoint<T>& op,
                             BulldozingModel bulldozing = BulldozingModel::kBekker,
                             const IntegrationOptions& options = {}) {
    const StressField<T> field(p, op);
    const Kinks kinks = findKinks(detail::shearGeometry(p, field));
    const GaussRule& rule = gaussRule(options.points);
    const int q = endExponent(scalarValue(field.sinkageExponent()), options.end_exponent);
    detail::ForceSums<T> sums;
    detail::integrateRegion(field, field.maxStressAngle(), field.entryAngle(), true, kinks, rule, q,
                            sums);
    detail::integrateRegion(field, field.exitAngle(), field.maxStressAngle(), false, kinks, rule, q,
                            sums);
    return assembleForces(p, op, sums, bulldozing);
}

/// F_z alone (what the entry-angle solver needs); same integration as computeForces.
template <typename T>
T computeVerticalForce(const ContactParameters<T>& p, const OperatingPoint<T>& op,
                       const IntegrationOptions& options = {}) {
    return computeForces(p, op, BulldozingModel::kBekker, options).fz;
}

}  // namespace terra::contact
