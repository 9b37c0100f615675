#pragma once
/// @file soil_conversion.h
/// The one pair of converters between a soil and the identified (decoupled) parameters on a
/// wheel: K_s = k_c/b + k_φ (Eq. 2.9) one way, k_φ = K_s − k_c/b the other. Used by synthetic
/// truths, starting guesses, identified soils, posteriors and the rover's streaming planner.

#include "core/identification/decoupled_fit.h"
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

}  // namespace terra::identification
