#pragma once
/// @file shear_deformation.h
/// The shear deformation of the soil at one contact angle (Eq. 2.14 in the κ form of
/// docs/model.md, "Slip"), written once for the stress field (any scalar, stress_field.h) and for
/// the search of the integrand's kinks (double, kinks.cpp).

namespace terra::contact {

/// The tangential and lateral shear deformations at one angle θ.
template <typename T>
struct ShearDeformation {
    T tangential;  ///< j_t [m]
    T lateral;     ///< j_l [m]
};

/// j_t = r [(θ_f − θ) − κ (sin θ_f − sin θ)] and j_l = r κ tan β (θ_f − θ), given
/// `lateral_velocity` = κ tan β and the sines of θ_f and θ (callers have them already).
template <typename T>
ShearDeformation<T> shearDeformation(const T& radius_m, const T& entry_angle_rad,
                                     const T& sin_entry, const T& velocity_ratio,
                                     const T& lateral_velocity, const T& theta,
                                     const T& sin_theta) {
    const T arc = entry_angle_rad - theta;
    return {radius_m * (arc - velocity_ratio * (sin_entry - sin_theta)),
            radius_m * lateral_velocity * arc};
}

}  // namespace terra::contact
