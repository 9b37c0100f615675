#pragma once
/// @file robot.h
/// The 4WD/4WS robot of thesis chapter 3 (Fig. 3.1): a chassis carried by four driven, steered
/// rigid wheels at the corners of a rectangle (wheelbase × track). SI units; the robot file
/// (resources/robots/*.json, docs/dynamics.md) uses the same units with suffixed keys.

#include <array>
#include <span>
#include <string>
#include <vector>

#include "core/common/field.h"
#include "core/common/issue.h"
#include "core/wheel/wheel_parameters.h"

namespace terra::dynamics {

/// The corners, in the order used everywhere (arrays, CSV columns): front-left, front-right,
/// rear-left, rear-right (thesis ij = LF, RF, LR, RR).
enum Corner : int { kFrontLeft = 0, kFrontRight = 1, kRearLeft = 2, kRearRight = 3 };
inline constexpr int kWheelCount = 4;
/// Short names of the corners ("FL", "FR", "RL", "RR"), used as JSON keys and CSV prefixes.
inline constexpr std::array<const char*, kWheelCount> kCornerNames{"FL", "FR", "RL", "RR"};

/// Mass, inertia and geometry of the robot.
struct RobotParameters {
    std::string name = "4WD/4WS robot";
    std::string source;
    wheel::WheelParameters wheel;   ///< r, b of all four wheels
    double chassis_mass_kg = 20.0;  ///< chassis without wheels [kg]
    /// Principal moments of the chassis about its centre of mass, body axes x forward, y left,
    /// z up [kg·m²].
    std::array<double, 3> chassis_inertia_kg_m2{0.4, 0.6, 0.8};
    double wheel_mass_kg = 1.0;  ///< one wheel with its motors [kg]
    /// One wheel about its axle [kg·m²], > 0; about its diameters the rover takes half of it
    /// (a disc).
    double wheel_spin_inertia_kg_m2 = 0.005;
    double wheelbase_m = 0.5;  ///< front axle to rear axle [m]
    double track_m = 0.4;      ///< left to right wheel centre [m]
    /// Height of the chassis centre of mass above the plane of the wheel centres [m].
    double com_height_m = 0.1;
    /// Forward offset of the chassis centre of mass from the middle of the wheelbase [m].
    double com_forward_m = 0.0;
    /// Ratio ζ of the vertical soil damping to its critical value for one corner
    /// (docs/dynamics.md).
    double vertical_damping_ratio = 1.0;

    double totalMass() const { return chassis_mass_kg + kWheelCount * wheel_mass_kg; }
};

/// One number of the robot file (core/common/field.h); SI in the file as in memory.
using RobotField = Field<RobotParameters>;

/// The field table of the scalar numbers: chassis_mass_kg, wheel_mass_kg,
/// wheel_spin_inertia_kg_m2, wheelbase_m, track_m, com_height_m, com_forward_m,
/// vertical_damping_ratio. (The wheel is a wheel file; the inertia is chassisInertiaField().)
std::span<const RobotField> robotFields();
/// Each principal moment of chassis_inertia_kg_m2 [Ixx, Iyy, Izz].
const FieldInfo& chassisInertiaField();

/// Every out-of-range field, named with `prefix` ("robot.wheelbase_m = -1 ...").
std::vector<Issue> validate(const RobotParameters& robot, const std::string& prefix = {});

}  // namespace terra::dynamics
