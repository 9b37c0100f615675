#include "core/contact/contact_parameters.h"

#include <stdexcept>
#include <string>

#include "core/common/range.h"
#include "core/common/units.h"
#include "core/contact/operating_fields.h"

namespace terra::contact {

ContactParameters<double> makeContactParameters(const soil::SoilParameters& soil,
                                                const wheel::WheelParameters& wheel) {
    soil::requireValid(soil);
    wheel::requireValid(wheel);
    const double pressure_modulus = soil.cohesive_modulus / wheel.width_m + soil.frictional_modulus;
    if (!(pressure_modulus > 0.0)) {
        throw std::invalid_argument(
            "K_s = kc/b + kphi = " + formatNumber(roundSignificant(pressure_modulus / 1e3, 6)) +
            " kN/m^(n+2) must be > 0 (kc = " +
            formatNumber(roundSignificant(soil.cohesive_modulus / 1e3)) +
            " kN/m^(n+1), kphi = " + formatNumber(roundSignificant(soil.frictional_modulus / 1e3)) +
            " kN/m^(n+2), wheel width b = " + formatNumber(wheel.width_m) + " m)");
    }
    return {.radius_m = wheel.radius_m,
            .width_m = wheel.width_m,
            .sinkage_exponent = soil.sinkage_exponent,
            .sinkage_exponent_slip = soil.sinkage_exponent_slip,
            .pressure_modulus = pressure_modulus,
            .cohesion_pa = soil.cohesion_pa,
            .friction_angle_rad = soil.friction_angle_rad,
            .shear_modulus_m = soil.shear_modulus_m,
            .unit_weight_n_m3 = soil.unit_weight_n_m3,
            .max_stress_a0 = soil.max_stress_a0,
            .max_stress_a1 = soil.max_stress_a1,
            .max_shear_deformation_m = soil.max_shear_deformation_m,
            .lug_shear_offset_m = wheel.lugShearOffset(),
            .slip_sinkage_coefficient = soil.slip_sinkage_coefficient};
}

void requireValid(const OperatingPoint<double>& op) {
    // Compare in the user's degrees, rounded so that 90° typed is 90° checked (roundedDegrees).
    std::vector<Issue> issues;
    auto check = [&](const FieldInfo& field, double value) {
        checkRange(issues, field.key, value, field.range, field.displayUnit());
    };
    check(slipField(), op.slip);
    check(slipAngleField(), roundedDegrees(op.slip_angle_rad));
    check(entryAngleField(), roundedDegrees(op.entry_angle_rad));
    // θ_r below −θ_f and θ_m outside [θ_r, θ_f] are brought inside by the model
    // (clampedExitAngle, clampedMaxStressAngle in contact_angles.h; docs/model.md), so only their
    // own ranges are checked here.
    check(exitAngleField(), roundedDegrees(op.exit_angle_rad));
    if (op.max_stress_angle_rad)
        check(maxStressAngleField(), roundedDegrees(*op.max_stress_angle_rad));
    if (!issues.empty()) throw std::invalid_argument(formatIssues(issues));
}

}  // namespace terra::contact
