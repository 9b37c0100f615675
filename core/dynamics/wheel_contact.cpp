#include "core/dynamics/wheel_contact.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/contact/contact_angles.h"
#include "core/contact/quadratic_model.h"

namespace terra::dynamics {

double slipRatio(double forward_speed_m_s, double rim_speed_m_s, const ContactOptions& options) {
    const double denominator =
        std::max({rim_speed_m_s, forward_speed_m_s, options.regularisation_speed_m_s});
    const double s = (rim_speed_m_s - forward_speed_m_s) / denominator;
    return std::clamp(s, -1.0, 1.0);
}

double slipAngle(double forward_speed_m_s, double lateral_speed_m_s,
                 const ContactOptions& options) {
    // 89°: the model's domain is |β| < 90°.
    constexpr double kMaxSlipAngle = 89.0 * std::numbers::pi / 180.0;
    const double beta = std::atan(lateral_speed_m_s / std::max(std::abs(forward_speed_m_s),
                                                               options.regularisation_speed_m_s));
    return std::clamp(beta, -kMaxSlipAngle, kMaxSlipAngle);
}

WheelContact evaluateContact(const contact::ContactParameters<double>& p, const WheelKinematics& k,
                             const ContactOptions& options) {
    WheelContact c;
    c.slip = slipRatio(k.forward_speed_m_s, k.rim_speed_m_s, options);
    c.slip_angle_rad = slipAngle(k.forward_speed_m_s, k.lateral_speed_m_s, options);
    c.sinkage_m = k.sinkage_m;
    if (!(k.sinkage_m > 0.0)) return c;
    c.in_contact = true;
    const double r = p.radius_m;
    c.sunk = k.sinkage_m >= r;
    c.entry_angle_rad = c.sunk ? std::numbers::pi / 2 : std::acos(1.0 - k.sinkage_m / r);
    c.exit_angle_rad =
        std::min(contact::clampedExitAngle(options.exit_angle_rad, c.entry_angle_rad), 0.0);
    const contact::OperatingPoint<double> op{c.slip, c.slip_angle_rad, c.entry_angle_rad,
                                             c.exit_angle_rad, std::nullopt};
    // A remembered track is integrated unless the closed form's reload branch is asked for
    // (compaction::solvePass integrates it too).
    const bool integrate = options.model == contact::ContactModel::kFull ||
                           (p.remembers() && !options.closed_form_reload);
    c.forces = integrate ? contact::computeForces(p, op, options.bulldozing, options.integration)
                         : contact::computeQuadraticForces(p, op, options.bulldozing);
    const double sign =
        std::clamp(c.slip_angle_rad / options.slip_angle_regularisation_rad, -1.0, 1.0);
    c.forces.fs = c.forces.fy - sign * c.forces.fb;
    return c;
}

}  // namespace terra::dynamics
