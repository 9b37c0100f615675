#pragma once
/// @file kinks.h
/// Where the contact integrands are not smooth, so the integrator can split there instead of
/// adding points: the j_max limit switching on (Eq. 2.16), and, when braking, the points where
/// the tangential shear velocity or deformation change sign (the shear direction of Eq. 2.22
/// flips; with β = 0 the integrand jumps there). Plain doubles: a kink moves with the parameters,
/// but the integrand is continuous across the j_max kink, so its position carries no derivative.

#include <array>

namespace terra::contact {

/// The θ-independent quantities of the shear deformation (Eq. 2.14 in the κ form of
/// docs/model.md, "Slip"; shear_deformation.h).
struct ShearGeometry {
    double radius_m;
    double entry_angle_rad;
    double exit_angle_rad;
    double velocity_ratio;       ///< κ = v_x/(rω); +inf for the locked wheel (s = −1)
    double lateral_velocity;     ///< κ tan β
    double max_shear_m;          ///< j_max, +inf for none
    double shear_modulus_m = 0;  ///< K [m] of 1 − exp(−j/K) (Eq. 2.20); 0: no rise-layer splits
    double slip_angle_tan = 0;   ///< tan β (the locked wheel's shear direction)
};

inline constexpr int kMaxKinks = 32;

/// Sorted break points strictly inside (θ_r, θ_f).
struct Kinks {
    std::array<double, kMaxKinks> angles{};
    int count = 0;
};

/// Finds the kinks of the integrands on (θ_r, θ_f). For driving (κ ≤ 1) j(θ) is monotone, so
/// there is at most one j_max crossing; braking is searched piece by piece (see kinks.cpp). The
/// locked wheel (κ = ∞) has none: j is infinite all over the contact and the shear direction
/// (−cos θ, tan β) keeps its sign.
Kinks findKinks(const ShearGeometry& geometry);

/// Break points at the length scales of smooth but narrow features, so that each gets pieces of
/// its own size (the integrator's error estimate cannot see a feature that falls between the
/// nodes of a long piece). Around each feature centre c with width w the points c and c ± 8^k w
/// (k = 0…5) that lie inside (θ_r, θ_f) are returned, only when w is small against the contact
/// (w < (θ_f − θ_r)/4; /16 for the rise layer, which the end mapping resolves otherwise):
/// - the turn of the shear direction (1 − κ cos θ, κ tan β) (Eq. 2.22) at small κ tan β: driving,
///   centre θ = 0, w = √(2 |(1 − κ, κ tan β)|); braking, centres ±θ* = ±acos(1/κ),
///   w = κ tan β / (κ sin θ* + √(2κ · κ tan β)), which for the locked wheel (κ = ∞) is
///   tan β / (1 + √(2 tan β)) at ±90°;
/// - the rise of 1 − exp(−j/K) behind θ_f (Eq. 2.20): one-sided below θ_f, w = min(K, j_max) /
///   (r |(1 − κ cos θ_f, κ tan β)|), the angle over which j grows by K (or reaches j_max); K
///   alone when j stays below j_max over the whole contact (peakShearDeformation), so that the
///   pieces then do not depend on j_max at all (such a rise is not thin anyway for a driven
///   wheel: the guarantee costs nothing where it does not act).
Kinks findScaleSplits(const ShearGeometry& geometry);

/// The largest shear deformation |j| over the contact [θ_r, θ_f] (before the j_max limit, without
/// j₀) of a driven wheel (κ ≤ 1): |j(θ_r)|, since j_t ≥ r (1 − κ)(θ_f − θ) ≥ 0 falls with θ
/// (dj_t/dθ = r (κ cos θ − 1) ≤ 0) and so does |j_l| = r κ |tan β| (θ_f − θ). +inf when braking
/// or locked (κ > 1), where it is not bounded here.
double peakShearDeformation(const ShearGeometry& geometry);

}  // namespace terra::contact
