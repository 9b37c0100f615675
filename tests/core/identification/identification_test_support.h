#pragma once
/// @file identification_test_support.h
/// What the identification tests share: the true parameter vector of a soil on a wheel, and
/// synthetic sweeps as a robot sees them (from the load: no θ_f, no F_z, the rim's sinkage).

#include <cmath>
#include <vector>

#include "core/contact/contact_parameters.h"
#include "core/identification/data_set.h"
#include "core/identification/decoupled_fit.h"
#include "core/identification/full_fit.h"
#include "core/identification/parameters.h"
#include "core/identification/synthetic.h"

namespace terra::identification::testing {

/// The identified parameters (a₀, a₁, K_s, n, c, φ, K, j_max) of the soil-on-wheel `p`, in SI.
inline ParameterVector truthOf(const contact::ContactParameters<double>& p) {
    return {p.max_stress_a0, p.max_stress_a1,      p.pressure_modulus, p.sinkage_exponent,
            p.cohesion_pa,   p.friction_angle_rad, p.shear_modulus_m,  p.max_shear_deformation_m};
}

/// Wheel A of the thesis (Table 5.1).
inline const wheel::WheelParameters kWheelA{"A", "", 0.092, 0.107};

/// The decoupled parameters in the order of `truthOf` (n as n₀).
inline ParameterVector valuesOf(const DecoupledParameters& p) { return vectorOf(p); }

/// Noise-free sweeps s = 0 : 0.05 : 0.75 of `soil` at each load as a robot sees them: W per
/// sample, the rim's sinkage r (1 − cos θ_f) measured, no θ_f and no F_z.
inline DataSet fromLoad(const contact::ContactParameters<double>& soil,
                        const std::vector<double>& loads) {
    SyntheticSpec spec;
    for (int i = 0; i <= 15; ++i) spec.slips.push_back(0.05 * i);
    spec.loads_n = loads;
    DataSet data = synthesize(soil, spec).data;
    data.columns.entry_angle = false;
    data.columns.fz = false;
    for (Sample& s : data.samples) {
        s.sinkage_m = soil.radius_m * (1.0 - std::cos(s.entry_angle_rad));
        s.load_n = s.load_n.value_or(loads.front());
        s.entry_angle_rad = 0.0;
        s.fz_n = 0.0;
    }
    return data;
}

}  // namespace terra::identification::testing
