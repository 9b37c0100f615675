#pragma once
/// @file wheel_parameters.h
/// Geometry of a rigid smooth wheel (thesis Tables 2.2 and 5.1), in metres.

#include <string>
#include <vector>

#include "core/common/issue.h"
#include "core/common/range.h"

namespace terra::wheel {

/// A rigid cylindrical wheel.
struct WheelParameters {
    std::string name;         ///< "wheel A"
    std::string source;       ///< where the values come from
    double radius_m = 0.092;  ///< r [m]
    double width_m = 0.107;   ///< b [m]
};

inline const Range kRadiusRange{0.0, 5.0, true, false};  ///< r_m, [m]
inline const Range kWidthRange{0.0, 5.0, true, false};   ///< b_m, [m]

/// Every out-of-range or non-finite field ("r_m", "b_m").
std::vector<Issue> validate(const WheelParameters& wheel, const std::string& prefix = {});

/// Throws std::invalid_argument listing every problem when `wheel` is not valid.
void requireValid(const WheelParameters& wheel);

}  // namespace terra::wheel
