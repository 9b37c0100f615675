#include "core/dynamics/robot.h"

#include <array>

#include "core/common/range.h"

namespace terra::dynamics {
namespace {

RobotField make(FieldInfo info, double RobotParameters::*member, bool required) {
    RobotField field{info};
    field.member = member;
    field.required = required;
    return field;
}

const std::array<RobotField, 8> kFields{{
    make({"chassis_mass_kg",
          "kg",
          "m_c",
          "chassis mass",
          "Mass of the chassis without its wheels, in kg (docs/dynamics.md).",
          {0.01, 1e6}},
         &RobotParameters::chassis_mass_kg, true),
    make({"wheel_mass_kg",
          "kg",
          "m_w",
          "wheel mass",
          "Mass of one wheel with its motors, in kg.",
          {0.0, 1e6}},
         &RobotParameters::wheel_mass_kg, true),
    // > 0: the wheel is a body on a spin joint (a massless, inertia-free wheel has no dynamics).
    make({"wheel_spin_inertia_kg_m2",
          "kg·m²",
          "I_w",
          "wheel spin inertia",
          "Moment of inertia of one wheel about its axle, in kg·m²; about its diameters the rover "
          "takes half of it (a disc).",
          {1e-6, 1e6}},
         &RobotParameters::wheel_spin_inertia_kg_m2, false),
    make({"wheelbase_m",
          "m",
          "L",
          "wheelbase",
          "Distance from the front to the rear axle, in m.",
          {0.01, 100.0}},
         &RobotParameters::wheelbase_m, true),
    make({"track_m",
          "m",
          "T",
          "track",
          "Distance between the left and right wheel centres, in m.",
          {0.01, 100.0}},
         &RobotParameters::track_m, true),
    make({"com_height_m",
          "m",
          "h_c",
          "centre-of-mass height",
          "Height of the chassis centre of mass above the plane of the wheel centres, in m.",
          {-10.0, 10.0}},
         &RobotParameters::com_height_m, false),
    make({"com_forward_m",
          "m",
          "x_c",
          "centre-of-mass offset",
          "Forward offset of the chassis centre of mass from the middle of the wheelbase, in m; "
          "within half the wheelbase.",
          {-50.0, 50.0}},
         &RobotParameters::com_forward_m, false),
    make({"vertical_damping_ratio",
          "-",
          "ζ",
          "vertical damping ratio",
          "Ratio of the vertical soil damping of one corner to its critical value "
          "(docs/dynamics.md). Dimensionless.",
          {0.0, 10.0}},
         &RobotParameters::vertical_damping_ratio, false),
}};

const FieldInfo kInertia{"chassis_inertia_kg_m2",
                         "kg·m²",
                         "I_c",
                         "chassis inertia",
                         "Principal moments [Ixx, Iyy, Izz] of the chassis about its centre of "
                         "mass, body axes x forward, y left, z up, in kg·m².",
                         {1e-6, 1e6}};

}  // namespace

std::span<const RobotField> robotFields() { return kFields; }
const FieldInfo& chassisInertiaField() { return kInertia; }

std::vector<Issue> validate(const RobotParameters& robot, const std::string& prefix) {
    std::vector<Issue> issues = wheel::validate(robot.wheel, prefix + "wheel.");
    bool com_in_range = true;
    for (const RobotField& field : kFields) {
        const bool ok = checkRange(issues, prefix + field.key, robot.*field.member, field.range,
                                   field.displayUnit());
        if (field.member == &RobotParameters::com_forward_m) com_in_range = ok;
    }
    for (int i = 0; i < 3; ++i) {
        checkRange(issues, prefix + kInertia.key + "[" + std::to_string(i) + "]",
                   robot.chassis_inertia_kg_m2[i], kInertia.range, kInertia.displayUnit());
    }
    // The centre of mass stays between the axles.
    const double half = 0.5 * robot.wheelbase_m;
    if (com_in_range && half > 0.0) {
        checkRange(issues, prefix + "com_forward_m", robot.com_forward_m, {-half, half, true, true},
                   "m");
    }
    return issues;
}

}  // namespace terra::dynamics
