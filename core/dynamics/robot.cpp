#include "core/dynamics/robot.h"

#include "core/common/range.h"

namespace terra::dynamics {

std::vector<Issue> validate(const RobotParameters& robot, const std::string& prefix) {
    std::vector<Issue> issues = wheel::validate(robot.wheel, prefix + "wheel.");
    const Range positive{0.0, 1e6, true, false};
    checkRange(issues, prefix + "chassis_mass_kg", robot.chassis_mass_kg, positive, "kg");
    for (int i = 0; i < 3; ++i) {
        checkRange(issues, prefix + "chassis_inertia_kg_m2[" + std::to_string(i) + "]",
                   robot.chassis_inertia_kg_m2[i], positive, "kg·m²");
    }
    checkRange(issues, prefix + "wheel_mass_kg", robot.wheel_mass_kg, {0.0, 1e6}, "kg");
    // > 0: the wheel is a body on a spin joint (a massless, inertia-free wheel has no dynamics).
    checkRange(issues, prefix + "wheel_spin_inertia_kg_m2", robot.wheel_spin_inertia_kg_m2,
               positive, "kg·m²");
    checkRange(issues, prefix + "wheelbase_m", robot.wheelbase_m, {0.0, 100.0, true, false}, "m");
    checkRange(issues, prefix + "track_m", robot.track_m, {0.0, 100.0, true, false}, "m");
    checkRange(issues, prefix + "com_height_m", robot.com_height_m, {-10.0, 10.0}, "m");
    const double half = 0.5 * robot.wheelbase_m;
    checkRange(issues, prefix + "com_forward_m", robot.com_forward_m, {-half, half, true, true},
               "m");
    checkRange(issues, prefix + "vertical_damping_ratio", robot.vertical_damping_ratio,
               {0.0, 10.0});
    return issues;
}

}  // namespace terra::dynamics
