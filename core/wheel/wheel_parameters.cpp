#include "core/wheel/wheel_parameters.h"

#include <array>
#include <cmath>
#include <stdexcept>

namespace terra::wheel {
namespace {

WheelField make(FieldInfo info, double WheelParameters::*member, bool required = true) {
    WheelField field{info};
    field.member = member;
    field.required = required;
    return field;
}

// From 1 cm (r) and 5 mm (b), below the smallest wheels run on soil (micro-rover and soil-bin
// wheels are several cm), so that an absurd magnitude (r = 5e-324 m, 1e-300 m) is an input error,
// not "no equilibrium"; up to 5 m: any wheel of a vehicle, and a value typed in millimetres is
// caught (docs/reliability.md, "Physical ranges"). Grousers: up to 0.5 m high and thick (a lug
// typed in millimetres is caught), up to 360 of them.
const std::array<WheelField, 6> kFields{{
    make({"r_m",
          "m",
          "r",
          "wheel radius",
          "Radius r of the rigid wheel, in metres (Tables 2.2, 5.1); sinkage h = r (1 − cos θ_f) "
          "(Eq. 2.12).",
          {0.01, 5.0}},
         &WheelParameters::radius_m),
    make({"b_m",
          "m",
          "b",
          "wheel width",
          "Width b of the rigid wheel, in metres (Tables 2.2, 5.1); it enters Bekker's modulus "
          "K_s = k_c/b + k_φ (Eq. 2.9).",
          {0.005, 5.0}},
         &WheelParameters::width_m),
    make({"grouser_height_m",
          "m",
          "h_g",
          "grouser height",
          "Height h_g of the grousers (lugs) above the rim, in metres; 0 or absent: a smooth "
          "wheel. The thesis model ignores it; the lug model (lug_effect_coefficient > 0) reads "
          "it (docs/model.md, \"Lugs\").",
          {0.0, 0.5}},
         &WheelParameters::grouser_height_m, false),
    make({"grouser_count",
          "-",
          "N_g",
          "grouser count",
          "Number N_g of grousers around the rim, a whole number; 0 or absent: a smooth wheel.",
          {0.0, 360.0}},
         &WheelParameters::grouser_count, false),
    make({"grouser_thickness_m",
          "m",
          "t_g",
          "grouser thickness",
          "Thickness t_g of one grouser along the rim, in metres; 0 or absent: not given.",
          {0.0, 0.5}},
         &WheelParameters::grouser_thickness_m, false),
    // λ_s in [0, 1]: the equivalent shearing surface lies between the rim and the grouser tips.
    make({"lug_effect_coefficient",
          "-",
          "λ_s",
          "lug-effect coefficient",
          "Ding et al.'s lug-effect coefficient λ_s: the soil shears on a cylinder of radius "
          "r_s = r + λ_s h_g (docs/model.md, \"Lugs\"). 0 or absent: the lug model is off (the "
          "thesis model, every wheel smooth); it acts only on a wheel with grousers.",
          {0.0, 1.0}},
         &WheelParameters::lug_effect_coefficient, false),
}};

}  // namespace

std::span<const WheelField> wheelFields() { return kFields; }
const WheelField& radiusField() { return kFields[0]; }
const WheelField& widthField() { return kFields[1]; }

const WheelField* findWheelField(std::string_view key) { return findField(wheelFields(), key); }

std::vector<Issue> validate(const WheelParameters& wheel, const std::string& prefix) {
    std::vector<Issue> issues;
    for (const WheelField& field : kFields) {
        checkRange(issues, prefix + field.key, wheel.*field.member, field.range,
                   field.displayUnit());
    }
    if (std::isfinite(wheel.grouser_count) &&
        wheel.grouser_count != std::floor(wheel.grouser_count))
        issues.push_back({prefix + "grouser_count",
                          formatNumber(wheel.grouser_count) + " is not a whole number"});
    if (issues.empty() && wheel.grouser_height_m >= wheel.radius_m) {
        issues.push_back({prefix + "grouser_height_m", formatNumber(wheel.grouser_height_m) +
                                                           " m is not below the radius r_m = " +
                                                           formatNumber(wheel.radius_m) + " m"});
    }
    return issues;
}

void requireValid(const WheelParameters& wheel) {
    const std::vector<Issue> issues = validate(wheel, "wheel.");
    if (!issues.empty()) throw std::invalid_argument(formatIssues(issues));
}

}  // namespace terra::wheel
