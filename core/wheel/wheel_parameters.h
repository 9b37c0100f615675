#pragma once
/// @file wheel_parameters.h
/// Geometry of a rigid smooth wheel (thesis Tables 2.2 and 5.1), in metres.

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/common/field.h"
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

/// One user-facing field of the wheel (core/common/field.h).
using WheelField = Field<WheelParameters>;

/// The field table: r_m, b_m (metres in files and on screen as in SI).
std::span<const WheelField> wheelFields();
const WheelField& radiusField();
const WheelField& widthField();
/// The field of the table with this key, or nullptr.
const WheelField* findWheelField(std::string_view key);

/// Every out-of-range or non-finite field ("r_m", "b_m").
std::vector<Issue> validate(const WheelParameters& wheel, const std::string& prefix = {});

/// Throws std::invalid_argument listing every problem when `wheel` is not valid.
void requireValid(const WheelParameters& wheel);

}  // namespace terra::wheel
