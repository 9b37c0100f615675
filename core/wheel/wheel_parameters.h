#pragma once
/// @file wheel_parameters.h
/// Geometry of a rigid wheel (thesis Tables 2.2 and 5.1), in metres, with its grousers (lugs)
/// and the lug-effect coefficient λ_s of Ding et al.'s shearing radius r_s = r + λ_s h_g
/// (docs/model.md, "Lugs"). With λ_s = 0 (the default) the model is the thesis's and treats every
/// wheel as smooth.

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
    /// λ_s [-]: Ding et al.'s lug-effect coefficient in r_s = r + λ_s h_g, in [0, 1] (0: the
    /// soil shears at the rim, the thesis model; 1: at the grouser tips). 0 (the default) switches
    /// the lug model off.
    double lug_effect_coefficient = 0.0;

    /// Whether the wheel has grousers (a height and a count both above 0).
    bool lugged() const { return grouser_height_m > 0.0 && grouser_count > 0.0; }

    /// λ_s h_g [m], the shearing radius' excess over the rim, r_s − r; 0 for a smooth wheel or
    /// λ_s = 0 (the thesis model).
    double lugShearOffset() const {
        return lugged() ? lug_effect_coefficient * grouser_height_m : 0.0;
    }
};

/// One user-facing field of the wheel (core/common/field.h).
using WheelField = Field<WheelParameters>;

/// The field table: r_m, b_m (required), grouser_height_m, grouser_count, grouser_thickness_m,
/// lug_effect_coefficient (optional; absent: 0, a smooth wheel or the lug model off). Metres in
/// files and on screen as in SI.
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
