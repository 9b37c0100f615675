#pragma once
/// @file stress_field.h
/// Normal and shear stresses along the wheel–soil contact (thesis section 2.3, Eqs. 2.13–2.22,
/// with the braking kinematics of docs/model.md, "Slip"). Header-only and templated on the scalar,
/// so that Ceres can differentiate it.
///
/// Angles are measured from the vertical through the wheel centre, positive toward the direction
/// of travel: the contact runs from the exit angle θ_r ≤ 0 to the entry angle θ_f > 0, with the
/// maximum normal stress at θ_m in between.

#include <cmath>
#include <limits>

#include "core/contact/contact_angles.h"
#include "core/contact/contact_parameters.h"
#include "core/contact/shear_deformation.h"

namespace terra::contact {

/// The stresses and shear deformation at one contact angle θ.
template <typename T>
struct StressSample {
    T sigma;    ///< σ [Pa]: normal stress (Eq. 2.17)
    T tau;      ///< τ [Pa]: shear stress magnitude (Eq. 2.20)
    T tau_t;    ///< τ_t [Pa]: tangential (longitudinal) shear stress (Eq. 2.22)
    T tau_l;    ///< τ_l [Pa]: lateral shear stress (Eq. 2.22)
    T shear_t;  ///< j_t [m]: tangential shear deformation (Eq. 2.14)
    T shear_l;  ///< j_l [m]: lateral shear deformation (Eq. 2.14)
    T shear;    ///< j [m]: √(j_t² + j_l²) limited to j_max (Eqs. 2.15, 2.16)
};

/// κ = v_x/(rω) from the slip (Eq. 2.1; docs/model.md, "Slip"): 1 − s when driving, 1/(1 + s)
/// when braking; +inf for the locked wheel (s = −1, ω = 0).
template <typename T>
T velocityRatio(const T& slip) {
    return slip >= 0.0 ? T(1.0 - slip) : T(1.0 / (1.0 + slip));
}

/// The stress distribution of one wheel at one operating point. Construction precomputes
/// everything that does not depend on θ, so `at(θ)` costs one sin/cos pair, one pow and one exp.
template <typename T>
class StressField {
public:
    StressField(const ContactParameters<T>& p, const OperatingPoint<T>& op)
        : radius_(p.radius_m),
          shear_radius_(p.lugged() ? p.shearRadius() : p.radius_m),
          lugged_(p.lugged()),
          entry_(op.entry_angle_rad),
          exit_(clampedExitAngle(op.exit_angle_rad, op.entry_angle_rad)),
          max_stress_(clampedMaxStressAngle(p, op)),
          exponent_(p.sinkage_exponent + p.sinkage_exponent_slip * op.slip),
          modulus_(p.pressure_modulus),
          cohesion_(p.cohesion_pa),
          shear_modulus_(p.shear_modulus_m),
          max_shear_(p.max_shear_deformation_m),
          driving_(op.slip >= 0.0),
          // s = −1 (requireValid keeps s ≥ −1): κ is infinite, at() takes the limit.
          locked_(!(op.slip > -1.0)),
          remembers_(p.remembers()),
          rut_depth_(p.rut_depth_m),
          reload_depth_(p.reload_depth_m),
          reload_modulus_(p.reload_modulus_pa_m),
          shear_offset_(p.shear_offset_m) {
        using std::cos;
        using std::sin;
        using std::tan;
        struct FrictionTan {};
        tan_phi_ = rememberedTan<FrictionTan>(p.friction_angle_rad);
        cos_entry_ = cos(entry_);
        sin_entry_ = sin(entry_);
        versine_entry_ = sin_entry_ * sin_entry_ / (1.0 + cos_entry_);
        slip_angle_tan_ = tan(op.slip_angle_rad);
        if (locked_) {
            // Plain constants, never used in arithmetic on T (a Jet's zero derivatives times
            // infinity would be NaN): only the kink search reads them, as doubles.
            constexpr double kInfinity = std::numeric_limits<double>::infinity();
            kappa_ = T(kInfinity);
            one_minus_kappa_ = T(-kInfinity);
            const double beta_tan = scalarValue(slip_angle_tan_);
            lateral_velocity_ = T(beta_tan == 0.0 ? 0.0 : std::copysign(kInfinity, beta_tan));
        } else {
            kappa_ = contact::velocityRatio(op.slip);
            // 1 − κ, exactly s for driving and s/(1 + s) for braking (no cancellation near s = 0;
            // at s = 1, κ = 0 and 1 − κ = 1: the wheel spins in place).
            one_minus_kappa_ = driving_ ? op.slip : T(op.slip / (1.0 + op.slip));
            lateral_velocity_ = kappa_ * slip_angle_tan_;
        }
        rear_slope_ =
            max_stress_ > exit_ ? T((entry_ - max_stress_) / (max_stress_ - exit_)) : T(0.0);
        shear_ratio_ = lugged_ ? T(shear_radius_ / radius_) : T(1.0);
    }

    const T& radiusValue() const { return radius_; }         ///< r [m]
    const T& entryAngle() const { return entry_; }           ///< θ_f [rad]
    const T& exitAngle() const { return exit_; }             ///< θ_r [rad]
    const T& maxStressAngle() const { return max_stress_; }  ///< θ_m [rad]
    const T& velocityRatio() const { return kappa_; }        ///< κ = v_x/(rω)
    const T& sinkageExponent() const { return exponent_; }   ///< N = n₀ + n₁ s
    bool driving() const { return driving_; }
    bool locked() const { return locked_; }  ///< s = −1: the wheel does not turn (ω = 0)
    double maxShearDeformation() const { return max_shear_; }
    /// r_s [m]: the radius on which the soil shears, r + λ_s h_g (docs/model.md, "Lugs"); r for
    /// a smooth wheel. j (Eq. 2.14) is computed with it; σ (Eq. 2.17) with the rim radius r.
    const T& shearRadius() const { return shear_radius_; }
    /// Whether the lug model is on (r_s > r).
    bool lugged() const { return lugged_; }
    /// r_s / r [-]: the integrators weight the shear stresses with it (docs/model.md, "Lugs").
    const T& shearRadiusRatio() const { return shear_ratio_; }

    /// cos θ_a − cos θ_f for θ_a = θ_f − 2d, as 2 sin((θ_f + θ_a)/2) sin((θ_f − θ_a)/2) =
    /// 2 sin(θ_f − d) sin d. The plain difference of cosines loses ~eps/θ_f² relative at small θ_f
    /// (2e-8 at θ_f = 1e-4 rad); this form keeps full precision given d.
    T cosineGap(const T& half_gap) const {
        using std::cos;
        using std::sin;
        const T sin_d = sin(half_gap);
        const T cos_d = cos(half_gap);
        return 2.0 * (sin_entry_ * cos_d - cos_entry_ * sin_d) * sin_d;
    }

    /// σ(θ) [Pa], Eqs. 2.17 and 2.19: the front law K_s (r (cos θ − cos θ_f))^N for θ ≥ θ_m, the
    /// same with the equivalent front angle θ_e = θ_f − (θ − θ_r)(θ_f − θ_m)/(θ_m − θ_r) behind it.
    /// Zero outside the contact and exactly at its ends.
    T normalStress(const T& theta) const {
        using std::cos;
        using std::sin;
        if (theta >= max_stress_) {
            const T sin_theta = sin(theta);
            return normalStress(theta, sin_theta * sin_theta / (1.0 + cos(theta)));
        }
        return normalStress(theta, T(0.0));
    }

    /// σ(θ) given the versine 1 − cos θ = sin²θ/(1 + cos θ) (only used in front of θ_m).
    T normalStress(const T& theta, const T& versine) const {
        // Front: cos θ − cos θ_f = (1 − cos θ_f) − (1 − cos θ), both versines exact: its error is
        // eps (1 − cos θ_f), as small as the rounding of θ itself allows (the integrator's nodes
        // carry eps θ_f), instead of eps of the plain cosines' difference (~eps/θ_f² relative).
        // Behind θ_m: the half gap (θ_f − θ_e)/2 = (θ − θ_r)(θ_f − θ_m)/(θ_m − θ_r)/2 is exact.
        const T base = theta >= max_stress_ ? T(versine_entry_ - versine)
                                            : cosineGap(T(0.5 * ((theta - exit_) * rear_slope_)));
        // Guard the ends: pow(0, N) has an infinite derivative, and the value is 0 there anyway.
        if (!(base > 0.0)) return T(0.0);
        if (remembers_) {
            // A loaded track (docs/compaction.md, R1): d below the rut's bottom reloads
            // elastically, k_u d, up to the deepest earlier sinkage (d = δ), then follows the
            // virgin curve K_s z^N at the depth z = z_p + d below the untouched surface.
            const T depth = radius_ * base;
            if (depth < reload_depth_) return reload_modulus_ * depth;
            return modulus_ * positivePow(T(rut_depth_ + depth), exponent_);
        }
        return modulus_ * positivePow(T(radius_ * base), exponent_);
    }

    /// All stresses at θ (Eqs. 2.14–2.22).
    StressSample<T> at(const T& theta) const {
        using std::cos;
        using std::sin;
        return at(theta, sin(theta), cos(theta));
    }

    /// All stresses at θ, given sin θ and cos θ (the integrator computes them once per node).
    StressSample<T> at(const T& theta, const T& sin_theta, const T& cos_theta) const {
        using std::exp;
        using std::expm1;
        using std::sqrt;
        StressSample<T> out;
        const T versine = sin_theta * sin_theta / (1.0 + cos_theta);  // 1 − cos θ, exact
        out.sigma = normalStress(theta, versine);
        if (locked_) return lockedShear(out, theta, cos_theta);

        const ShearDeformation<T> j = shearDeformation(shear_radius_, entry_, sin_entry_, kappa_,
                                                       lateral_velocity_, theta, sin_theta);
        out.shear_t = j.tangential;
        out.shear_l = j.lateral;
        const T squared = out.shear_t * out.shear_t + out.shear_l * out.shear_l;
        // sqrt(0) has an infinite derivative; j is identically 0 at θ_f whatever the parameters.
        T shear = squared > 0.0 ? T(sqrt(squared)) : T(0.0);
        if (shear_offset_ > 0.0) shear += shear_offset_;  // earlier passes (compaction.md, R3)
        if (shear > max_shear_) shear = T(max_shear_);    // Eq. 2.16
        out.shear = shear;

        // Eqs. 2.20, 2.21; −expm1(−j/K) = 1 − exp(−j/K) without cancellation for small j.
        out.tau = (cohesion_ + out.sigma * tan_phi_) * (-expm1(-shear / shear_modulus_));

        // Shear velocity direction, Eq. 2.13 divided by rω: (1 − κ cos θ, κ tan β), with
        // 1 − κ cos θ = (1 − cos θ) + (1 − κ) cos θ and 1 − cos θ = sin²θ / (1 + cos θ).
        const T tangential = versine + one_minus_kappa_ * cos_theta;
        const T speed_squared = tangential * tangential + lateral_velocity_ * lateral_velocity_;
        if (speed_squared > 0.0) {
            const T inverse_speed = 1.0 / sqrt(speed_squared);
            out.tau_t = out.tau * tangential * inverse_speed;
            out.tau_l = out.tau * lateral_velocity_ * inverse_speed;
        } else {
            // Stagnation point (s = 0, β = 0, θ = 0): the one-sided limit, along +x when driving
            // and −x when braking (docs/model.md, "Stagnation point").
            out.tau_t = driving_ ? out.tau : T(-out.tau);
            out.tau_l = T(0.0);
        }
        return out;
    }

    /// Whether the soil remembers earlier passes (ContactParameters::remembers()).
    bool remembers() const { return remembers_; }
    /// δ [m]: the elastic reload depth below the rut's bottom (0 without memory).
    double reloadDepth() const { return reload_depth_; }
    /// j₀ [m]: shear deformation carried from earlier passes.
    double shearOffset() const { return shear_offset_; }

    /// Lateral shear velocity κ tan β [-] (per unit rω); ±inf for the locked wheel with β ≠ 0.
    const T& lateralVelocity() const { return lateral_velocity_; }
    /// tan β [-].
    const T& slipAngleTangent() const { return slip_angle_tan_; }

private:
    /// The shear of the locked wheel (s = −1), the limit κ → ∞ of Eqs. 2.14–2.22 (docs/model.md,
    /// "Full slip"). j = κ r |(sin θ_f − sin θ, tan β (θ_f − θ))| + O(1) grows without bound at
    /// every θ < θ_f, so the shear is fully developed: τ = c + σ tan φ, or (c + σ tan φ)(1 −
    /// exp(−j_max/K)) with j_max; the shear velocity direction (1 − κ cos θ, κ tan β)/|…| tends
    /// to (−cos θ, tan β)/|…|, the sliding of the rim over the soil. At θ_f itself j = 0 for every
    /// κ, so τ = 0 there: the limit jumps at the contact's front end.
    StressSample<T>& lockedShear(StressSample<T>& out, const T& theta, const T& cos_theta) const {
        using std::expm1;
        using std::sqrt;
        constexpr double kInfinity = std::numeric_limits<double>::infinity();
        if (!(theta < entry_)) {
            out.tau = out.tau_t = out.tau_l = T(0.0);
            out.shear_t = out.shear_l = out.shear = T(0.0);
            return out;
        }
        const double beta_tan = scalarValue(slip_angle_tan_);
        out.shear_t = T(-kInfinity);  // −κ r (sin θ_f − sin θ), sin θ < sin θ_f inside
        out.shear_l = T(beta_tan == 0.0 ? 0.0 : std::copysign(kInfinity, beta_tan));
        const bool limited = max_shear_ < kInfinity;
        out.shear = T(max_shear_);  // Eq. 2.16 with j → ∞
        const T developed = limited ? T(-expm1(-max_shear_ / shear_modulus_)) : T(1.0);
        out.tau = (cohesion_ + out.sigma * tan_phi_) * developed;
        const T speed_squared = cos_theta * cos_theta + slip_angle_tan_ * slip_angle_tan_;
        if (speed_squared > 0.0) {
            const T inverse_speed = 1.0 / sqrt(speed_squared);
            out.tau_t = -out.tau * cos_theta * inverse_speed;
            out.tau_l = out.tau * slip_angle_tan_ * inverse_speed;
        } else {
            // θ = −90° with β = 0: the limit from inside the contact, against the travel.
            out.tau_t = -out.tau;
            out.tau_l = T(0.0);
        }
        return out;
    }

    T radius_;
    T shear_radius_;  // r_s = r + λ_s h_g
    bool lugged_;
    T entry_;
    T exit_;
    T max_stress_;
    T exponent_;
    T modulus_;
    T cohesion_;
    T shear_modulus_;
    double max_shear_;
    bool driving_;
    bool locked_;
    T tan_phi_;
    T cos_entry_;
    T sin_entry_;
    T versine_entry_;  // 1 − cos θ_f
    T kappa_;
    T one_minus_kappa_;
    T lateral_velocity_;
    T slip_angle_tan_;
    T rear_slope_;   // (θ_f − θ_m)/(θ_m − θ_r) of Eq. 2.19
    T shear_ratio_;  // r_s / r
    bool remembers_;
    double rut_depth_;       // z_p [m]
    double reload_depth_;    // δ [m]
    double reload_modulus_;  // k_u [Pa/m]
    double shear_offset_;    // j₀ [m]
};

}  // namespace terra::contact
