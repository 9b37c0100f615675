#pragma once
// Contact parameters of the thesis's soils (Table 2.1) on wheel A (Table 2.2), in SI, written out
// by hand from the thesis (not loaded through the code under test).

#include <cmath>
#include <numbers>

#include "core/contact/contact_parameters.h"
#include "tests/core/test_support.h"

namespace terra::contact::testing {

using terra::testing::kDeg;
inline constexpr double kRadiusA = 0.092;  // [m]
inline constexpr double kWidthA = 0.107;   // [m]

// n, c [kPa], φ [deg], k_c [kN/m^(n+1)], k_φ [kN/m^(n+2)], K [m], γ [kN/m³], j_max [m]
inline ContactParameters<double> thesisSoil(double n, double c_kpa, double phi_deg, double kc,
                                            double kphi, double K, double gamma, double jmax,
                                            double r = kRadiusA, double b = kWidthA) {
    return {.radius_m = r,
            .width_m = b,
            .sinkage_exponent = n,
            .sinkage_exponent_slip = 0.0,
            .pressure_modulus = kc * 1e3 / b + kphi * 1e3,
            .cohesion_pa = c_kpa * 1e3,
            .friction_angle_rad = phi_deg * kDeg,
            .shear_modulus_m = K,
            .unit_weight_n_m3 = gamma * 1e3,
            .max_stress_a0 = 0.2,
            .max_stress_a1 = 0.3,
            .max_shear_deformation_m = jmax};
}
inline ContactParameters<double> sandyLoam(double jmax = 0.02) {
    return thesisSoil(0.7, 1.7, 29.0, 5.3, 1515.0, 0.025, 15.2, jmax);
}
inline ContactParameters<double> drySand(double jmax = 0.02) {
    return thesisSoil(1.1, 1.0, 30.0, 0.9, 1523.4, 0.025, 16.18, jmax);
}
inline ContactParameters<double> clayeySoil(double jmax = 0.009) {
    return thesisSoil(0.5, 4.14, 13.0, 13.2, 692.2, 0.01, 13.24, jmax);
}

// Heavy clay (WES, 25 % moisture), Wong's Table 2.3 (K, γ assumed as in
// resources/soils/heavy-clay.json): N = 0.13 makes σ rise almost like a step from the contact ends.
inline ContactParameters<double> heavyClay(double jmax = INFINITY) {
    return thesisSoil(0.13, 68.95, 34.0, 12.7, 1555.95, 0.006, 17.0, jmax);
}

}  // namespace terra::contact::testing
