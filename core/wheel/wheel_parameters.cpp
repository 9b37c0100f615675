#include "core/wheel/wheel_parameters.h"

#include <stdexcept>

namespace terra::wheel {

std::vector<Issue> validate(const WheelParameters& wheel, const std::string& prefix) {
    std::vector<Issue> issues;
    checkRange(issues, prefix + "r_m", wheel.radius_m, kRadiusRange, "m");
    checkRange(issues, prefix + "b_m", wheel.width_m, kWidthRange, "m");
    return issues;
}

void requireValid(const WheelParameters& wheel) {
    const std::vector<Issue> issues = validate(wheel, "wheel.");
    if (!issues.empty()) throw std::invalid_argument(formatIssues(issues));
}

}  // namespace terra::wheel
