#pragma once
/// @file wheel_parameters.h
/// Geometry of a rigid wheel (thesis Tables 2.2 and 5.1), in metres, with its grousers (lugs)
/// described for the lug extensions of the literature. The thesis model treats every wheel as
/// smooth: it ignores the grouser fields.

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/common/field.h"
#include "core/common/issue.h"
#include "core/common/range.h"

namespace terra::wheel {

/// A rigid cylindrical wheel, optionally with grousers (lugs) across its rim.
struct WheelParameters {
    std::string name;         ///< "wheel A"
    std::string source;       ///< where the values come from
    double radius_m = 0.092;  ///< r [m], to the rim (the grousers stand on it)
    double width_m = 0.107;   ///< b [m]
    /// h_g [m]: height of the grousers above the rim; 0: a smooth wheel.
    double grouser_height_m = 0.0;
    /// N_g [-]: grousers around the rim, a whole number (stored as a double so that the field
    /// table holds it like every other field); 0: a smooth wheel.
    double grouser_count = 0.0;
    /// t_g [m]: thickness of a grouser along the rim; 0: not given.
    double grouser_thickness_m = 0.0;

    /// Whether the wheel has grousers (a height and a count both above 0).
    bool lugged() const { return grouser_height_m > 0.0 && grouser_count > 0.0; }
};

/// One user-facing field of the wheel (core/common/field.h).
using WheelField = Field<WheelParameters>;

/// The field table: r_m, b_m (required), grouser_height_m, grouser_count, grouser_thickness_m
/// (optional; absent: 0, a smooth wheel). Metres in files and on screen as in SI.
std::span<const WheelField> wheelFields();
const WheelField& radiusField();
const WheelField& widthField();
/// The field of the table with this key, or nullptr.
const WheelField* findWheelField(std::string_view key);

/// Every out-of-range or non-finite field ("r_m", "b_m", …), a grouser count that is not a whole
/// number, and grousers as high as the radius.
std::vector<Issue> validate(const WheelParameters& wheel, const std::string& prefix = {});

/// Throws std::invalid_argument listing every problem when `wheel` is not valid.
void requireValid(const WheelParameters& wheel);

}  // namespace terra::wheel
