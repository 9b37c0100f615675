#include "core/scenario/scenario.h"

#include <cmath>
#include <iterator>
#include <optional>
#include <stdexcept>
#include <string>

#include "core/common/range.h"
#include "core/dynamics/field_terrain.h"
#include "core/dynamics/rover.h"
#include "core/soil/soil_parameters.h"

namespace terra::scenario {
namespace {

// `value` > 0 rounded down to `digits` significant digits (a bound named in a message must itself
// be allowed).
double floorSignificant(double value, int digits) {
    const double scale = std::pow(10.0, std::floor(std::log10(value)) - (digits - 1));
    return roundSignificant(std::floor(value / scale) * scale);
}

}  // namespace

dynamics::Commands Scenario::commandsAt(double t_s) const {
    dynamics::Commands commands;
    for (int i = 0; i < dynamics::kWheelCount; ++i) {
        commands[i].spin_rate_rad_s = wheels[i].spin_rate_rad_s.at(t_s);
        commands[i].steer_angle_rad = wheels[i].steer_angle_rad.at(t_s);
    }
    return commands;
}

int Scenario::soilCount() const {
    return field ? static_cast<int>(field->legend.size()) + 1 : terrain.soilCount();
}

const soil::SoilParameters& Scenario::soil(int index) const {
    if (!field) return terrain.soil(index);
    if (index == 0) return field->base;
    // The soils of a field's parameter rasters are its FieldTerrain's (F14), not the map's.
    if (index < 0 || static_cast<std::size_t>(index) > field->legend.size())
        throw std::out_of_range("Scenario::soil: index " + std::to_string(index) +
                                " is not one of the field's classes (FieldTerrain::soil has the "
                                "soils of its parameter rasters)");
    return std::next(field->legend.begin(), index - 1)->second;
}

std::vector<Issue> validate(const Scenario& s, const std::string& prefix) {
    std::vector<Issue> issues = dynamics::validate(s.robot, prefix + "robot.");
    checkRange(issues, prefix + "duration_s", s.duration_s, kDurationRange, "s");
    checkRange(issues, prefix + "time_step_s", s.time_step_s, kTimeStepRange, "s");
    // A run shorter than one step would compute nothing (it has lround(T / Δt) = 0 steps) and
    // report the initial state as a result: a duration typed in the wrong unit.
    if (kTimeStepRange.contains(s.time_step_s) && kDurationRange.contains(s.duration_s) &&
        s.duration_s < s.time_step_s) {
        const Range at_least{s.time_step_s, kDurationRange.high};
        issues.push_back({prefix + "duration_s",
                          formatNumber(s.duration_s) + " is shorter than one time step (" +
                              formatNumber(s.time_step_s) + " s); allowed range " +
                              at_least.describe() + " s"});
    }
    if (s.time_step_s > 0.0) {
        checkRange(issues, prefix + "output_interval_s", s.output_interval_s,
                   {s.time_step_s, 3600.0}, "s");
    }
    for (Issue& issue : soil::validate(s.terrain.base, prefix + "terrain.soil."))
        issues.push_back(std::move(issue));
    if (s.field) {
        for (const auto& [code, soil] : s.field->legend) {
            for (Issue& issue :
                 soil::validate(soil, prefix + "terrain.legend." + std::to_string(code) + ".soil."))
                issues.push_back(std::move(issue));
        }
    }
    for (std::size_t i = 0; i < s.terrain.patches.size(); ++i) {
        const std::string at = prefix + "terrain.patches[" + std::to_string(i) + "].";
        for (Issue& issue : soil::validate(s.terrain.patches[i].soil, at + "soil."))
            issues.push_back(std::move(issue));
        const dynamics::SoilPatch& p = s.terrain.patches[i];
        if (!(p.x_min_m < p.x_max_m)) {
            issues.push_back(
                {at + "x_min_m", "x_min_m = " + formatNumber(p.x_min_m) +
                                     " must be < x_max_m = " + formatNumber(p.x_max_m)});
        }
        if (!(p.y_min_m < p.y_max_m)) {
            issues.push_back(
                {at + "y_min_m", "y_min_m = " + formatNumber(p.y_min_m) +
                                     " must be < y_max_m = " + formatNumber(p.y_max_m)});
        }
    }
    for (Issue& issue : validate(s.controller, s.drawbar_load, prefix, s.time_step_s))
        issues.push_back(std::move(issue));
    if (s.mission) {
        for (Issue& issue : validate(*s.mission, s.robot, prefix + "mission."))
            issues.push_back(std::move(issue));
    }
    checkRange(issues, prefix + "initial.speed_m_s", s.initial.speed_m_s, {0.0, 100.0}, "m/s");
    const bool implicit = s.options.integrator == dynamics::Integrator::kImplicit;
    if (s.options.jacobian_every != 1 && !implicit) {
        issues.push_back({prefix + "jacobian_every",
                          "only the implicit integrator takes contact Jacobians: with "
                          "\"integrator\": \"explicit\" the allowed value is 1"});
    }
    checkRange(issues, prefix + "jacobian_every", s.options.jacobian_every, {1, 10}, "");
    if (implicit && s.controller.closedLoop()) {
        issues.push_back({prefix + "integrator",
                          "\"implicit\" needs the ideal spin servos, and a closed-loop "
                          "controller limits the motors' torque (a wheel's spin then is a state "
                          "the correction does not hold); allowed with this controller: "
                          "\"explicit\""});
    }
    // A step the dynamics cannot take stably sent the robot 150 m and flipped it, reported as a
    // completed run (issue 28): refused here, with the largest stable step named. The implicit
    // integrator takes the vertical stiffness and damping into its step: no such bound.
    // A field's soils (F14: parameter rasters may make too many, named here rather than thrown
    // from the run).
    std::optional<dynamics::FieldTerrain> field_terrain;
    if (issues.empty() && s.field && (!implicit || !s.field->parameters.empty())) {
        try {
            field_terrain.emplace(s.field, s.robot, s.field_options);
        } catch (const std::invalid_argument& e) {
            issues.push_back(
                {prefix + "terrain." + (s.field->parameters.empty() ? "cell_m" : "parameters"),
                 e.what()});
        }
    }
    if (issues.empty() && !implicit) {
        const dynamics::StepLimit limit =
            field_terrain ? dynamics::largestStableStep(s.robot, *field_terrain, s.options)
                          : dynamics::largestStableStep(s.robot, s.terrain, s.options);
        const double allowed = kStableStepMargin * limit.max_step_s;
        if (std::isfinite(allowed) && s.time_step_s > allowed) {
            const Range range{kTimeStepRange.low, floorSignificant(allowed, 2)};
            issues.push_back(
                {prefix + "time_step_s",
                 formatNumber(s.time_step_s) +
                     " s is above the largest stable step of this robot on " + limit.soil + ", " +
                     formatNumber(range.high) + " s (" +
                     formatNumber(roundSignificant(100.0 * kStableStepMargin, 3)) + " % of the " +
                     formatNumber(roundSignificant(limit.max_step_s, 3)) + " s at which its " +
                     limit.mode + " on the soil's vertical stiffness, up to " +
                     formatNumber(roundSignificant(limit.stiffness_n_m, 3)) +
                     " N/m per wheel, turns unstable; docs/dynamics.md, \"Step size and "
                     "stability\"); allowed range " +
                     range.describe() + " s"});
        }
    }
    return issues;
}

}  // namespace terra::scenario
