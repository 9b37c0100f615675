#pragma once
/// @file kinks.h
/// Where the contact integrands are not smooth, so the integrator can split there instead of
/// adding points: the j_max limit switching on (Eq. 2.16), and, when braking, the points where
/// the tangential shear velocity or deformation change sign (the shear direction of Eq. 2.22
/// flips; with β = 0 the integrand jumps there). Plain doubles: a kink moves with the parameters,
/// but the integrand is continuous across the j_max kink, so its position carries no derivative.

#include <array>

namespace terra::contact {

/// The θ-independent quantities of the shear deformation (Eq. 2.14, MODEL-NOTES κ form).
struct ShearGeometry {
    double radius_m;
    double entry_angle_rad;
    double exit_angle_rad;
    double velocity_ratio;       ///< κ = v_x/(rω)
    double lateral_velocity;     ///< κ tan β
    double max_shear_m;          ///< j_max, +inf for none
};

inline constexpr int kMaxKinks = 16;

/// Sorted kinks strictly inside (θ_r, θ_f).
struct Kinks {
    std::array<double, kMaxKinks> angles{};
    int count = 0;
};

/// Finds the kinks of the integrands on (θ_r, θ_f). For driving (κ ≤ 1) j(θ) is monotone, so
/// there is at most one j_max crossing; braking is searched piece by piece (see kinks.cpp).
Kinks findKinks(const ShearGeometry& geometry);

}  // namespace terra::contact
