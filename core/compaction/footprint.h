#pragma once
/// @file footprint.h
/// The surface load of a wheel, from the model's own contact stresses: σ(θ), τ_t(θ) and τ_l(θ)
/// of the solved contact (Eqs. 2.17–2.22) turned into point forces on the soil at their place on
/// the rim (docs/compaction.md, C3), for the stress propagation of stress_at_depth.h.

#include <string>
#include <vector>

#include "core/compaction/stress_at_depth.h"
#include "core/contact/contact_parameters.h"

namespace terra::compaction {

/// How the contact stress is spread across the wheel's width b (the model's stresses are per
/// unit width; the thesis does not say how they vary across it).
enum class WidthProfile {
    kUniform,    ///< the same at every y in [−b/2, b/2] (a rigid wheel; the default)
    kParabolic,  ///< ∝ 1 − (2y/b)², 3/2 of the mean on the centre line (a compliant tyre)
};

/// "uniform" or "parabolic".
const char* widthProfileName(WidthProfile profile);
/// The profile of that name; throws std::invalid_argument naming the choices otherwise.
WidthProfile widthProfileNamed(const std::string& name);

/// The discretisation of the footprint.
struct FootprintOptions {
    WidthProfile width = WidthProfile::kUniform;
    int nodes_along =
        10;  ///< Gauss nodes per contact region (front and rear of θ_m): 7, 10, 15, 20
    int nodes_across = 7;  ///< Gauss nodes across the width: 7, 10, 15, 20
};

/// The wheel's forces on the soil at `op`: for each Gauss node θ of [θ_r, θ_m] and [θ_m, θ_f]
/// (each mapped as the force integrator maps it, so that σ's (θ_f − θ)^N end is integrated well)
/// and each node y across the width, the force
///   F = (−(τ_t cos θ − σ sin θ), τ_l, σ cos θ + τ_t sin θ) r b w_θ w_y   (x, y, z down)
/// at x = r sin θ, y, z = z_p + r (cos θ − cos θ_f), with the shear stresses weighted by r_s/r
/// for a lugged wheel (as the integrator does). Σ F_z is the model's F_z (= W when solved) to
/// the quadrature's accuracy; Σ F_x = −F_x and Σ F_y = −F_y (the soil's reaction).
std::vector<PointLoad> wheelFootprint(const contact::ContactParameters<double>& p,
                                      const contact::OperatingPoint<double>& op,
                                      const FootprintOptions& options = {});

}  // namespace terra::compaction
