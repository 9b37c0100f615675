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
///   u^(q(N+1)−1) × smooth, regular enough for Gauss quadrature to converge fast;
/// - the regions are split further at the kinks of kinks.h (j_max, braking sign changes);
/// - each piece gets a 15-point Gauss–Kronrod rule; pieces whose Kronrod–Gauss difference exceeds
///   the tolerance are bisected (sharp but smooth features: small s and β near θ = 0).

#include <algorithm>
#include <cmath>

#include "core/common/scalar.h"
#include "core/contact/bulldozing.h"
#include "core/contact/contact_parameters.h"
#include <array>

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
    /// Bound on each piece's |Kronrod − Gauss| difference relative to |F_z| + |F_x| + |M_y|/r
    /// (as raw integrals). That difference overestimates the Kronrod result's error by orders of
    /// magnitude: at 1e-7 the worst error over the test grid is 5e-11 (docs/model.md).
    double tolerance = 1e-7;
    int max_pieces = 24;  ///< cap on adaptive bisections (both regions together)
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

    ForceSums& operator+=(const ForceSums& o) {
        fx += o.fx, fy += o.fy, fz += o.fz, mx += o.mx, my += o.my, mz += o.mz;
        return *this;
    }
};

// One region [θ_lo, θ_hi] mapped from u ∈ [0, 1]; u = 0 is the σ-singular end (θ_f for the front
// region, θ_r for the rear one).
template <typename T>
struct Region {
    T theta_lo, theta_hi, length;
    bool singular_at_hi;
    int q;

    T theta(double u, double& jacobian) const {
        double uq1 = 1.0;  // u^(q−1)
        for (int e = 1; e < q; ++e) uq1 *= u;
        jacobian = q * uq1;
        const T offset = length * (uq1 * u);
        return singular_at_hi ? T(theta_hi - offset) : T(theta_lo + offset);
    }
};

// A piece [u0, u1] of a region with its Kronrod sums and error estimate.
template <typename T>
struct Piece {
    int region;
    double u0, u1;
    ForceSums<T> sums;
    double error;
};

// Integrates the six integrands over one piece with the 15-point Kronrod rule; the error is the
// largest difference to the embedded 7-point Gauss rule (on the plain values).
template <typename T>
void evaluatePiece(const StressField<T>& field, const Region<T>& region, const KronrodRule& rule,
                   Piece<T>& piece) {
    using std::cos;
    using std::sin;
    ForceSums<T> k;
    double g[6] = {0, 0, 0, 0, 0, 0};
    const double du = piece.u1 - piece.u0;
    for (std::size_t i = 0; i < rule.nodes.size(); ++i) {
        double jacobian = 0.0;
        const T theta = region.theta(piece.u0 + du * rule.nodes[i], jacobian);
        const T s = sin(theta);
        const T c = cos(theta);
        const StressSample<T> st = field.at(theta, s, c);
        const T dtheta = region.length * (jacobian * du);
        const T fx = st.tau_t * c - st.sigma * s;
        const T fz = st.sigma * c + st.tau_t * s;
        const T mx = st.tau_l * c;
        const T mz = st.tau_l * s;
        const T w = dtheta * rule.weights[i];
        k.fx += w * fx, k.fz += w * fz, k.fy += w * st.tau_l;
        k.mx += w * mx, k.my += w * st.tau_t, k.mz += w * mz;
        if (rule.gauss_weights[i] != 0.0) {
            const double wg = scalarValue(dtheta) * rule.gauss_weights[i];
            g[0] += wg * scalarValue(fx), g[1] += wg * scalarValue(fz);
            g[2] += wg * scalarValue(st.tau_l), g[3] += wg * scalarValue(mx);
            g[4] += wg * scalarValue(st.tau_t), g[5] += wg * scalarValue(mz);
        }
    }
    const double kv[6] = {scalarValue(k.fx), scalarValue(k.fz), scalarValue(k.fy),
                          scalarValue(k.mx), scalarValue(k.my), scalarValue(k.mz)};
    piece.error = 0.0;
    for (int j = 0; j < 6; ++j) piece.error = std::max(piece.error, std::abs(kv[j] - g[j]));
    piece.sums = k;
}

template <typename T>
ShearGeometry shearGeometry(const ContactParameters<T>& p, const StressField<T>& field) {
    return {scalarValue(p.radius_m),       scalarValue(field.entryAngle()),
            scalarValue(field.exitAngle()), scalarValue(field.velocityRatio()),
            scalarValue(field.lateralVelocity()), p.max_shear_deformation_m};
}

// The contact integrals ∫(τ_t cos θ − σ sin θ), ∫(σ cos θ + τ_t sin θ), ∫τ_l, ∫τ_l cos θ,
// ∫τ_t, ∫τ_l sin θ over [θ_r, θ_f]: both regions, split at the kinks, then adaptive bisection of
// the piece with the largest error estimate until every estimate is below the tolerance.
template <typename T>
ForceSums<T> integrateContact(const ContactParameters<T>& p, const StressField<T>& field,
                              const IntegrationOptions& options) {
    constexpr int kCapacity = 64;
    const Kinks kinks = findKinks(shearGeometry(p, field));
    const KronrodRule& rule = kronrodRule();
    const int q = endExponent(scalarValue(field.sinkageExponent()), options.end_exponent);
    const Region<T> regions[2] = {
        {field.maxStressAngle(), field.entryAngle(), field.entryAngle() - field.maxStressAngle(),
         true, q},
        {field.exitAngle(), field.maxStressAngle(), field.maxStressAngle() - field.exitAngle(),
         false, q}};
    std::array<Piece<T>, kCapacity> pieces;
    int count = 0;
    for (int r = 0; r < 2; ++r) {
        const Region<T>& region = regions[r];
        const double lo = scalarValue(region.theta_lo), hi = scalarValue(region.theta_hi);
        if (!(hi > lo)) continue;
        // Kinks inside the region, as break points in u (ascending).
        std::array<double, kMaxKinks + 2> breaks{};
        int n = 0;
        breaks[n++] = 0.0;
        for (int k = 0; k < kinks.count; ++k) {
            const double theta = kinks.angles[k];
            if (theta <= lo || theta >= hi) continue;
            const double distance = region.singular_at_hi ? hi - theta : theta - lo;
            breaks[n++] = std::pow(distance / (hi - lo), 1.0 / q);
        }
        breaks[n++] = 1.0;
        std::sort(breaks.begin() + 1, breaks.begin() + n - 1);
        for (int b = 0; b + 1 < n; ++b) {
            if (!(breaks[b + 1] > breaks[b])) continue;
            Piece<T>& piece = pieces[count++];
            piece.region = r;
            piece.u0 = breaks[b];
            piece.u1 = breaks[b + 1];
            evaluatePiece(field, region, rule, piece);
        }
    }
    const int limit = std::min(kCapacity, std::max(count, options.max_pieces));
    while (count > 0) {
        ForceSums<T> total;
        int worst = 0;
        for (int i = 0; i < count; ++i) {
            total += pieces[i].sums;
            if (pieces[i].error > pieces[worst].error) worst = i;
        }
        const double scale = std::abs(scalarValue(total.fz)) + std::abs(scalarValue(total.fx)) +
                             std::abs(scalarValue(total.my));
        if (pieces[worst].error <= options.tolerance * scale || count >= limit) return total;
        // Bisect the worst piece in u.
        Piece<T>& left = pieces[worst];
        Piece<T>& right = pieces[count++];
        const double middle = 0.5 * (left.u0 + left.u1);
        right.region = left.region;
        right.u0 = middle;
        right.u1 = left.u1;
        left.u1 = middle;
        evaluatePiece(field, regions[left.region], rule, left);
        evaluatePiece(field, regions[right.region], rule, right);
    }
    return {};
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
    const detail::ForceSums<T> sums = detail::integrateContact(p, field, options);
    return assembleForces(p, op, sums, bulldozing);
}

/// F_z alone (what the entry-angle solver needs); same integration as computeForces.
template <typename T>
T computeVerticalForce(const ContactParameters<T>& p, const OperatingPoint<T>& op,
                       const IntegrationOptions& options = {}) {
    return computeForces(p, op, BulldozingModel::kBekker, options).fz;
}

}  // namespace terra::contact
