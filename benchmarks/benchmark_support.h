#pragma once
/// @file benchmark_support.h
/// What several benchmarks share (one definition each, for the unity build's batches).

#include <numbers>

#include "core/contact/contact_parameters.h"

namespace terra::benchmarks {

inline constexpr double kDeg = std::numbers::pi / 180.0;  ///< [rad/deg]

/// Table 2.1's sandy loam on wheel A (Table 2.2), Table 2.6's a₀, a₁ and j_max.
inline contact::ContactParameters<double> sandyLoam() {
    return {0.092,  0.107, 0.7, 0.0, 5.3e3 / 0.107 + 1.515e6, 1.7e3, 29.0 * kDeg, 0.025,
            15.2e3, 0.2,   0.3, 0.02};
}

}  // namespace terra::benchmarks
