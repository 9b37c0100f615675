#pragma once
/// @file contact_angles.h
/// The exit angle and the angle of maximum normal stress as the stress model uses them: the two
/// clamps of docs/model.md ("θ_r clamp", "θ_m clamp"), written once. The stress field, the
/// entry-angle solver, the sweeps and the rover's wheels all take θ_r and θ_m from here, so that
/// the angles they report are the ones the forces were computed with.

#include "core/contact/contact_parameters.h"

namespace terra::contact {

/// θ_r [rad] as the model uses it: max(θ_r, −θ_f). A rut deeper than the entry sinkage
/// (θ_r < −θ_f) is not physical; the contact then ends where the rim meets the original soil
/// surface again, θ_r = −θ_f (Eq. 2.12 with λ = 1).
template <typename T>
T clampedExitAngle(const T& exit_angle_rad, const T& entry_angle_rad) {
    return exit_angle_rad < -entry_angle_rad ? T(-entry_angle_rad) : exit_angle_rad;
}

/// θ_m [rad] as the model uses it: the user's fixed angle, or (a₀ + a₁ s) θ_f (Eq. 2.18), kept
/// inside [θ_r, θ_f] with θ_r from clampedExitAngle. a₀ + a₁ s < 0 (strong braking) gives θ_r; a
/// fixed θ_m above θ_f (Table 2.3's 15° on a shallow wheel) gives θ_f.
template <typename T>
T clampedMaxStressAngle(const ContactParameters<T>& p, const OperatingPoint<T>& op) {
    T theta_m = op.max_stress_angle_rad
                    ? *op.max_stress_angle_rad
                    : T((p.max_stress_a0 + p.max_stress_a1 * op.slip) * op.entry_angle_rad);
    const T exit = clampedExitAngle(op.exit_angle_rad, op.entry_angle_rad);
    if (theta_m < exit) theta_m = exit;
    if (theta_m > op.entry_angle_rad) theta_m = op.entry_angle_rad;
    return theta_m;
}

}  // namespace terra::contact
