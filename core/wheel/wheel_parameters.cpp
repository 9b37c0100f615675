#include "core/wheel/wheel_parameters.h"

#include <array>
#include <stdexcept>

namespace terra::wheel {
namespace {

WheelField make(FieldInfo info, double WheelParameters::*member) {
    WheelField field{info};
    field.member = member;
    return field;
}

// From 1 cm (r) and 5 mm (b), below the smallest wheels run on soil (micro-rover and soil-bin
// wheels are several cm), so that an absurd magnitude (r = 5e-324 m, 1e-300 m) is an input error,
// not "no equilibrium"; up to 5 m: any wheel of a vehicle, and a value typed in millimetres is
// caught (docs/reliability.md, "Physical ranges").
const std::array<WheelField, 2> kFields{{
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
    return issues;
}

void requireValid(const WheelParameters& wheel) {
    const std::vector<Issue> issues = validate(wheel, "wheel.");
    if (!issues.empty()) throw std::invalid_argument(formatIssues(issues));
}

}  // namespace terra::wheel
