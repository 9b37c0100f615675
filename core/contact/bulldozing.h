#pragma once
/// @file bulldozing.h
/// Bulldozing resistance on the wheel's side wall (thesis Eqs. 2.26–2.30, as corrected in
/// docs/model.md, E1), in closed form. The derivation is in docs/model.md, section "Bulldozing".

#include <cmath>
#include <numbers>

#include "core/contact/contact_parameters.h"

namespace terra::contact {

/// Coefficients of the side-wall pressure σ = a_s h + b_s (Eq. 2.27).
enum class BulldozingModel {
    kBekker,   ///< a_s = γ c_s², b_s = 2 c c_s (Bekker [3])
    kHegedus,  ///< a_s = 2 γ c_s (c_s + c_s² tan φ), b_s = 2 c c_s (Hegedus [11])
};

/// a_s [N/m³] and b_s [Pa] of Eq. 2.27, with c_s = tan(π/4 + φ/2).
template <typename T>
void bulldozingCoefficients(const ContactParameters<T>& p, BulldozingModel model, T& a_s, T& b_s) {
    using std::tan;
    struct PassiveTan {};
    const T c_s = rememberedTan<PassiveTan>(std::numbers::pi / 4.0 + p.friction_angle_rad / 2.0);
    b_s = 2.0 * p.cohesion_pa * c_s;
    if (model == BulldozingModel::kBekker) {
        a_s = p.unit_weight_n_m3 * c_s * c_s;
    } else {
        a_s = 2.0 * p.unit_weight_n_m3 * c_s * (c_s + c_s * c_s * tan(p.friction_angle_rad));
    }
}

/// F_b [N]: the bulldozing resistance of one side wall over the submerged circular segment
/// (−θ_f..θ_f), Eq. 2.29 integrated in closed form (Eq. 2.30 corrected, E1):
///   F_b = a_s r³ G(θ_f) + b_s r² H(θ_f),
///   H(θ) = θ − sin θ cos θ          (segment area / r²),
///   G(θ) = ⅔ sin³θ − cos θ · H(θ)   (first moment of the depth / r³).
/// Both cancel badly for small θ_f (G ~ 2θ⁵/15), so below 0.25 rad their Taylor series are used.
template <typename T>
T bulldozingForce(const ContactParameters<T>& p, const T& entry_angle_rad, BulldozingModel model) {
    using std::cos;
    using std::sin;
    T a_s, b_s;
    bulldozingCoefficients(p, model, a_s, b_s);
    const T& t = entry_angle_rad;
    T h, g;
    if (t < 0.25) {
        const T t2 = t * t;
        const T t3 = t2 * t;
        const T t5 = t3 * t2;
        // Series to O(t^15) and O(t^17): truncation below 1e-16 relative for t < 0.25.
        h = t3 *
            (2.0 / 3.0 +
             t2 * (-2.0 / 15.0 +
                   t2 * (4.0 / 315.0 +
                         t2 * (-2.0 / 2835.0 + t2 * (4.0 / 155925.0 + t2 * (-4.0 / 6081075.0))))));
        g = t5 * (2.0 / 15.0 +
                  t2 * (-11.0 / 315.0 +
                        t2 * (17.0 / 3780.0 +
                              t2 * (-461.0 / 1247400.0 + t2 * (8303.0 / 389188800.0 +
                                                               t2 * (-24911.0 / 27243216000.0))))));
    } else {
        const T s = sin(t);
        const T c = cos(t);
        h = t - s * c;
        g = (2.0 / 3.0) * s * s * s - c * h;
    }
    const T& r = p.radius_m;
    return a_s * r * r * r * g + b_s * r * r * h;
}

}  // namespace terra::contact
