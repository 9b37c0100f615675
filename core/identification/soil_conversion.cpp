#include "core/identification/soil_conversion.h"

#include <cmath>

namespace terra::identification {

DecoupledParameters decoupledOf(const soil::SoilParameters& soil,
                                const wheel::WheelParameters& wheel) {
    return {.a0 = soil.max_stress_a0,
            .a1 = soil.max_stress_a1,
            .pressure_modulus = soil.cohesive_modulus / wheel.width_m + soil.frictional_modulus,
            .n0 = soil.sinkage_exponent,
            .n1 = soil.sinkage_exponent_slip,
            .cohesion_pa = soil.cohesion_pa,
            .friction_angle_rad = soil.friction_angle_rad,
            .shear_modulus_m = soil.shear_modulus_m,
            .max_shear_deformation_m = soil.max_shear_deformation_m};
}

soil::SoilParameters soilOf(const soil::SoilParameters& base, const wheel::WheelParameters& wheel,
                            const DecoupledParameters& p) {
    soil::SoilParameters s = base;
    s.max_stress_a0 = p.a0;
    s.max_stress_a1 = p.a1;
    s.sinkage_exponent = p.n0;
    s.sinkage_exponent_slip = p.n1;
    s.cohesion_pa = p.cohesion_pa;
    s.friction_angle_rad = p.friction_angle_rad;
    s.shear_modulus_m = p.shear_modulus_m;
    s.frictional_modulus = p.pressure_modulus - base.cohesive_modulus / wheel.width_m;
    // A finite j_max is the fit's (identified or held); +inf is also the decoupled fit's "not
    // seen", which keeps the base's.
    if (std::isfinite(p.max_shear_deformation_m))
        s.max_shear_deformation_m = p.max_shear_deformation_m;
    return s;
}

ParameterVector vectorOf(const DecoupledParameters& p) {
    ParameterVector out{};
    for (const ParameterField& field : parameterFields()) {
        if (const auto k = fullParameterOf(field))
            out[static_cast<std::size_t>(*k)] = p.*field.member;
    }
    return out;
}

DecoupledParameters decoupledOf(const ParameterVector& p) {
    DecoupledParameters out;
    out.n1 = 0.0;  // the full model's N is constant
    for (const ParameterField& field : parameterFields()) {
        if (const auto k = fullParameterOf(field))
            out.*field.member = p[static_cast<std::size_t>(*k)];
    }
    return out;
}

}  // namespace terra::identification
