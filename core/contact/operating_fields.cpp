#include "core/contact/operating_fields.h"

#include "core/common/units.h"

namespace terra::contact {
namespace {

constexpr double kDeg = units::kPi / 180.0;

}  // namespace

const FieldInfo& slipField() {
    static const FieldInfo field{"slip",
                                 "-",
                                 "s",
                                 "slip ratio",
                                 "Slip ratio s = 1 − v/(rω) (Eq. 2.1): 0 ≤ s ≤ 1 driving (1: "
                                 "spinning in place), −1 ≤ s < 0 braking (−1: locked). "
                                 "Dimensionless.",
                                 {-1.0, 1.0}};
    return field;
}

const FieldInfo& slipAngleField() {
    static const FieldInfo field{"slip_angle_deg",
                                 "deg",
                                 "β",
                                 "slip angle",
                                 "Slip angle β between the wheel's heading and its travel "
                                 "(Eq. 2.2), in degrees.",
                                 {-90.0, 90.0, true, true},
                                 kDeg};
    return field;
}

const FieldInfo& entryAngleField() {
    static const FieldInfo field{"entry_angle_deg",
                                 "deg",
                                 "θ_f",
                                 "entry angle",
                                 "Entry angle θ_f where the wheel meets the soil; sinkage "
                                 "h = r (1 − cos θ_f) (Eq. 2.12), in degrees.",
                                 {0.0, 90.0, true, false},
                                 kDeg};
    return field;
}

const FieldInfo& exitAngleField() {
    static const FieldInfo field{"exit_angle_deg",
                                 "deg",
                                 "θ_r",
                                 "exit angle",
                                 "Exit angle θ_r where the wheel leaves the soil, ≤ 0 behind the "
                                 "bottom, in degrees (0 in the thesis's tables).",
                                 {-90.0, 0.0},
                                 kDeg};
    return field;
}

const FieldInfo& maxStressAngleField() {
    static const FieldInfo field{"max_stress_angle_deg",
                                 "deg",
                                 "θ_m",
                                 "angle of maximum stress",
                                 "Angle θ_m of the largest normal stress, fixed instead of "
                                 "θ_m = (a₀ + a₁ s) θ_f (Eq. 2.18), in degrees.",
                                 {-90.0, 90.0},
                                 kDeg};
    return field;
}

const FieldInfo& rutRatioField() {
    static const FieldInfo field{"rut_ratio",
                                 "-",
                                 "λ",
                                 "rut ratio",
                                 "Rut ratio λ = h_r/h_f of the rear to the front sinkage, giving "
                                 "θ_r = −acos(1 − λ (1 − cos θ_f)) (Eq. 2.12). Dimensionless.",
                                 {0.0, 1.0}};
    return field;
}

const FieldInfo& loadField() {
    // From 0.01 N (one gram), below which the sinkage solver finds no equilibrium worth the name
    // (1e-300 N was "F_z does not rise through the load"), up to 100 kN per wheel: far beyond any
    // field robot, and a load typed in grams is caught.
    static const FieldInfo field{"load_N",
                                 "N",
                                 "W",
                                 "wheel load",
                                 "Vertical load W on the wheel, in newtons; the entry angle is "
                                 "solved so that F_z = W (section 2.6.1).",
                                 {0.01, 1e5}};
    return field;
}

}  // namespace terra::contact
