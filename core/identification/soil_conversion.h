#pragma once
/// @file soil_conversion.h
/// The converters between the three forms of the identified parameters: a soil on a wheel, the
/// decoupled parameters (DecoupledParameters, the hub) and the full model's parameter vector
/// (ParameterVector, FullParameter order). Soil ↔ decoupled: K_s = k_c/b + k_φ (Eq. 2.9) one way,
/// k_φ = K_s − k_c/b the other; decoupled ↔ vector: n = n₀ (the full model's exponent is
/// constant, n₁ = 0). Every conversion in the program is one of these four (issue 26).

#include "core/identification/decoupled_fit.h"
#include "core/identification/parameters.h"
#include "core/soil/soil_parameters.h"
#include "core/wheel/wheel_parameters.h"

namespace terra::identification {

/// The soil's own values of the identified parameters on this wheel (K_s = k_c/b + k_φ,
/// Eq. 2.9; j_max the soil's, +inf for none): the truth of synthetic data, or a starting guess.
DecoupledParameters decoupledOf(const soil::SoilParameters& soil,
                                const wheel::WheelParameters& wheel);

/// The soil an identification found: `base` with a₀, a₁, n₀, n₁, c, φ, K set to the identified
/// values and k_φ = K_s − k_c/b (k_c kept, b the wheel's width; Eq. 2.9), and j_max the fit's
/// when finite (else the base's).
soil::SoilParameters soilOf(const soil::SoilParameters& base, const wheel::WheelParameters& wheel,
                            const DecoupledParameters& identified);

/// The full model's vector of decoupled parameters (n = n₀; n₁ dropped: the full model's n is
/// constant).
ParameterVector vectorOf(const DecoupledParameters& p);

/// The decoupled parameters of a full-model vector (n₀ = n, n₁ = 0).
DecoupledParameters decoupledOf(const ParameterVector& p);

}  // namespace terra::identification
