#pragma once
/// @file contact_parameters.h
/// What the stress model of one wheel on one soil needs, in SI units and for a generic scalar T
/// (double, or ceres::Jet when the identification differentiates the model). Soil and wheel are
/// combined here: the pressure–sinkage law only sees K_s = k_c/b + k_φ (Eq. 2.9).

#include <cmath>
#include <limits>
#include <optional>

#include "core/common/scalar.h"
#include "core/soil/soil_parameters.h"
#include "core/wheel/wheel_parameters.h"

namespace terra::contact {

/// Soil and wheel parameters of the contact model, SI.
template <typename T>
struct ContactParameters {
    T radius_m;               ///< r [m]
    T width_m;                ///< b [m]
    T sinkage_exponent;       ///< n (n₀) [-] (Eq. 2.17)
    T sinkage_exponent_slip;  ///< n₁ [-]: N = n₀ + n₁ s; 0 for the thesis's constant n
    T pressure_modulus;       ///< K_s = k_c/b + k_φ [Pa/m^n] (Eq. 2.9)
    T cohesion_pa;            ///< c [Pa]
    T friction_angle_rad;     ///< φ [rad]
    T shear_modulus_m;        ///< K [m]
    T unit_weight_n_m3;       ///< γ [N/m³] (bulldozing only)
    T max_stress_a0;          ///< a₀ [-] (Eq. 2.18)
    T max_stress_a1;          ///< a₁ [-] (Eq. 2.18)
    /// j_max [m] (Eq. 2.16), +inf for no limit. A plain double: it moves where the integrand has a
    /// kink, and is never identified.
    double max_shear_deformation_m = std::numeric_limits<double>::infinity();
    /// λ_s h_g [m]: the excess of the shearing radius over the rim, r_s = r + λ_s h_g (Ding et
    /// al.'s lug effect; docs/model.md, "Lugs"). 0: the thesis model, exactly. A plain double: it
    /// is a property of the wheel, never identified.
    double lug_shear_offset_m = 0.0;
    /// The soil's memory of earlier passes on this track (docs/compaction.md, "Repeated
    /// passes"): Wong's unload–reload law. Plain doubles, never identified; all 0 (untouched soil)
    /// is the thesis model, bit for bit.
    /// z_p [m]: the rut left by earlier passes (plastic sinkage below the untouched surface); the
    /// contact starts at the rut's bottom.
    double rut_depth_m = 0.0;
    /// δ = p_u / k_u [m]: the depth below the rut's bottom over which the soil reloads
    /// elastically, up to the deepest earlier sinkage z_u = z_p + δ. 0: no memory.
    double reload_depth_m = 0.0;
    /// k_u = k₀ + A_u z_u [Pa/m]: the reload stiffness (Wong's repetitive-loading law).
    double reload_modulus_pa_m = 0.0;
    /// j₀ [m]: shear deformation the soil already carries from earlier passes, added to the
    /// magnitude of Eq. 2.15 before the j_max limit (Eq. 2.16). 0: untouched soil.
    double shear_offset_m = 0.0;
    /// S [-]: Lyasko's slip-sinkage coefficient (soil_parameters.h; docs/model.md, Eq. S.1). It
    /// scales the reported sinkage only (slipSinkage() in sinkage.h), never a stress. 0: off.
    double slip_sinkage_coefficient = 0.0;

    /// Whether earlier passes are remembered (a reload branch or a rut).
    bool remembers() const { return reload_depth_m > 0.0 || rut_depth_m > 0.0; }

    /// Whether the lug model is on (λ_s h_g > 0).
    bool lugged() const { return lug_shear_offset_m != 0.0; }
    /// r_s = r + λ_s h_g [m]: the radius of the cylinder on which the soil shears; r when smooth.
    T shearRadius() const { return radius_m + lug_shear_offset_m; }

    /// The same parameters in another scalar type (derivatives dropped or started at zero).
    template <typename U>
    ContactParameters<U> cast() const {
        return {.radius_m = scalarCast<U>(radius_m),
                .width_m = scalarCast<U>(width_m),
                .sinkage_exponent = scalarCast<U>(sinkage_exponent),
                .sinkage_exponent_slip = scalarCast<U>(sinkage_exponent_slip),
                .pressure_modulus = scalarCast<U>(pressure_modulus),
                .cohesion_pa = scalarCast<U>(cohesion_pa),
                .friction_angle_rad = scalarCast<U>(friction_angle_rad),
                .shear_modulus_m = scalarCast<U>(shear_modulus_m),
                .unit_weight_n_m3 = scalarCast<U>(unit_weight_n_m3),
                .max_stress_a0 = scalarCast<U>(max_stress_a0),
                .max_stress_a1 = scalarCast<U>(max_stress_a1),
                .max_shear_deformation_m = max_shear_deformation_m,
                .lug_shear_offset_m = lug_shear_offset_m,
                .rut_depth_m = rut_depth_m,
                .reload_depth_m = reload_depth_m,
                .reload_modulus_pa_m = reload_modulus_pa_m,
                .shear_offset_m = shear_offset_m,
                .slip_sinkage_coefficient = slip_sinkage_coefficient};
    }
};

/// Combines validated soil and wheel parameters. Throws std::invalid_argument when either is
/// invalid or when K_s = k_c/b + k_φ ≤ 0 (a negative k_c with a narrow wheel).
ContactParameters<double> makeContactParameters(const soil::SoilParameters& soil,
                                                const wheel::WheelParameters& wheel);

/// The operating point of the wheel: kinematics and contact geometry (section 2.2).
template <typename T>
struct OperatingPoint {
    /// s [-] (Eq. 2.1): driving 0 ≤ s ≤ 1 (1: spinning in place), braking −1 ≤ s < 0 (−1: locked)
    T slip;
    T slip_angle_rad;   ///< β [rad] (Eq. 2.2), |β| < π/2
    T entry_angle_rad;  ///< θ_f [rad], 0 < θ_f ≤ π/2
    T exit_angle_rad;  ///< θ_r [rad] ≤ 0 (docs/model.md, "Angles"); below −θ_f taken as −θ_f
    /// θ_m [rad] fixed by the user (the thesis's Table 2.3 uses 15°); empty: Eq. 2.18.
    std::optional<T> max_stress_angle_rad;

    template <typename U>
    OperatingPoint<U> cast() const {
        std::optional<U> theta_m;
        if (max_stress_angle_rad) theta_m = scalarCast<U>(*max_stress_angle_rad);
        return {scalarCast<U>(slip), scalarCast<U>(slip_angle_rad), scalarCast<U>(entry_angle_rad),
                scalarCast<U>(exit_angle_rad), theta_m};
    }
};

/// Throws std::invalid_argument naming the field and the value when `op` is outside the model's
/// domain (s ∉ [−1, 1], |β| ≥ 90°, θ_f ∉ (0, 90°], θ_r ∉ [−90°, 0], θ_m ∉ [−90°, 90°]). The model
/// itself keeps θ_r ≥ −θ_f and θ_m inside [θ_r, θ_f] (contact_angles.h).
void requireValid(const OperatingPoint<double>& op);

/// Exit angle from the rut ratio λ = h_r/h_f (Eq. 2.12): θ_r = −acos(1 − λ (1 − cos θ_f)).
template <typename T>
T exitAngleFromRutRatio(const T& entry_angle_rad, double rut_ratio) {
    using std::acos;
    using std::cos;
    return -acos(1.0 - rut_ratio * (1.0 - cos(entry_angle_rad)));
}

}  // namespace terra::contact
