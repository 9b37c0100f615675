#pragma once
/// @file wheel_contact.h
/// One wheel's terramechanics contact from its kinematic state: slip (Eq. 2.1), slip angle
/// (Eq. 2.2), entry angle from the sinkage (Eq. 2.12) and the six forces and moments of the core
/// wheel model (Eqs. 2.23–2.35), with the regularisations a time-stepping simulation needs near
/// zero speed (docs/dynamics.md, "Contact"). Plain functions, no Bullet: testable on their own.

#include "core/contact/bulldozing.h"
#include "core/contact/contact_parameters.h"
#include "core/contact/sinkage.h"
#include "core/contact/wheel_forces.h"

namespace terra::dynamics {

/// How the contact is evaluated.
struct ContactOptions {
    contact::ContactModel model = contact::ContactModel::kFull;  ///< full or quadratic closed form
    contact::BulldozingModel bulldozing = contact::BulldozingModel::kBekker;
    contact::IntegrationOptions integration;  ///< full model only
    double exit_angle_rad = 0.0;  ///< θ_r [rad] ≤ 0 (Table 2.6: 0); kept ≥ −θ_f (θ_r clamp)
    /// v_reg [m/s]: the slip and slip-angle denominators never drop below it, so both stay finite
    /// and continuous when the wheel stands still.
    double regularisation_speed_m_s = 1e-3;
    /// β_reg [rad]: sign(β) in F_s = F_y − sign(β) F_b is replaced by clamp(β/β_reg, −1, 1), so the
    /// bulldozing force does not chatter between ±F_b while β crosses zero.
    double slip_angle_regularisation_rad = 0.00872664626;  // 0.5°
    /// With the quadratic model, a remembered track (ContactParameters::remembers()) is evaluated
    /// by the quadratic closed form split at the reload law's kink (docs/model.md, "The quadratic
    /// reload branch"; ≈ 4× cheaper) instead of being integrated (false, the default).
    bool closed_form_reload = false;
};

/// The kinematic state of one wheel, in its (steered, non-spinning) frame of section 2.2.1.
struct WheelKinematics {
    double forward_speed_m_s = 0.0;  ///< v_x [m/s] of the hub along the wheel heading
    double lateral_speed_m_s = 0.0;  ///< v_y [m/s] of the hub to the wheel's left
    /// r ω [m/s]; r_s ω with the lug model (r_s = r + λ_s h_g, docs/model.md, "Lugs")
    double rim_speed_m_s = 0.0;
    double sinkage_m = 0.0;  ///< h [m]: depth of the rim's lowest point below the surface
};

/// The contact of one wheel at one instant.
struct WheelContact {
    bool in_contact = false;              ///< h > 0
    bool sunk = false;                    ///< h ≥ r: θ_f clamped to 90° (axle in the soil)
    double slip = 0.0;                    ///< s [-] (Eq. 2.1, regularised, in [−1, 1])
    double slip_angle_rad = 0.0;          ///< β [rad] (Eq. 2.2, regularised)
    double entry_angle_rad = 0.0;         ///< θ_f = acos(1 − h/r) [rad] (Eq. 2.12)
    double exit_angle_rad = 0.0;          ///< θ_r [rad]
    double sinkage_m = 0.0;               ///< h [m]
    contact::WheelForces<double> forces;  ///< soil on wheel, wheel frame; fs with smoothed sign
};

/// s of Eq. 2.1 in one expression: s = (rω − v_x) / max(rω, v_x, v_reg). Driving (rω > v_x) gives
/// 1 − v_x/(rω), braking gives rω/v_x − 1 (docs/model.md, "Slip"). A stalled wheel (v_x = 0,
/// rω > v_reg) gives s = 1, a locked one (ω = 0, v_x > v_reg) s = −1, both inside the model's
/// domain [−1, 1]; s is clamped to it, which only acts when v_x < 0 or ω < 0 (rolling backwards),
/// outside the forward-only model (docs/dynamics.md).
double slipRatio(double forward_speed_m_s, double rim_speed_m_s, const ContactOptions& options);

/// β of Eq. 2.2: atan(v_y / max(|v_x|, v_reg)), positive for v_y > 0 (docs/model.md, "Lateral
/// signs").
double slipAngle(double forward_speed_m_s, double lateral_speed_m_s, const ContactOptions& options);

/// The contact of a wheel with kinematics `k` on soil `p`. Out of contact: all forces zero.
WheelContact evaluateContact(const contact::ContactParameters<double>& p, const WheelKinematics& k,
                             const ContactOptions& options);

}  // namespace terra::dynamics
