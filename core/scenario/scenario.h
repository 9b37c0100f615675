#pragma once
/// @file scenario.h
/// A rover scenario (thesis chapter 3): the robot, the terrain, the initial state, each wheel's
/// angular speed and steering angle as functions of time, the duration and the time step. Files:
/// resources/scenarios/*.json, format in docs/dynamics.md (scenario_json.h reads them).

#include <array>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/common/issue.h"
#include "core/common/range.h"
#include "core/dynamics/field_terrain.h"
#include "core/dynamics/robot.h"
#include "core/dynamics/rover.h"
#include "core/dynamics/terrain.h"
#include "core/scenario/mission.h"
#include "core/scenario/signal.h"
#include "core/scenario/traction_control.h"

namespace terra::scenario {

/// The inputs of one wheel (SI: rad/s and rad).
struct WheelInputs {
    Signal spin_rate_rad_s;  ///< ω(t) [rad/s]
    Signal steer_angle_rad;  ///< δ(t) [rad], positive to the left
};

/// Optional: feed one wheel's (s, θ_f, F_x, F_z, M_y) samples, with sensor noise, into the
/// streaming identifier (core/identification/streaming.h), so the run shows the robot recognising
/// the soil it drives on (docs/dynamics.md, "Streaming identification").
struct StreamingHook {
    int wheel = dynamics::kFrontLeft;       ///< which wheel's sensors
    double interval_s = 0.05;               ///< sampling period [s] (20 Hz)
    double slip_noise = 0.005;              ///< standard deviation of s [-]
    double entry_angle_noise_rad = 0.0035;  ///< of θ_f [rad] (0.2°)
    double force_noise_n = 0.5;             ///< of F_x and F_z [N]
    double torque_noise_nm = 0.05;          ///< of M_y [N·m]
    unsigned seed = 1;                      ///< noise seed (runs repeat bit for bit)
    /// The samples' slip, load and M_y: the noisy truth (false; constant-speed runs by default)
    /// or the observer's estimates ŝ, Ŵ and τ − I_w ω̇ (true; always with a closed-loop
    /// controller, whose optimal set-point is planned on what this identifier finds).
    bool from_observer = false;
};

/// Allowed simulated time [s]: up to a day.
inline const Range kDurationRange{0.0, 86400.0, true, false};
/// Allowed fixed step [s]: the contact's stiffness needs ≤ 50 ms (docs/dynamics.md); a scenario's
/// robot and soils set a tighter bound (kStableStepMargin × dynamics::largestStableStep).
inline const Range kTimeStepRange{1e-6, 0.05};
/// The share of the linear stability bound (dynamics::largestStableStep) a step may use: the
/// soil stiffens as a corner sinks deeper than at rest (k ∝ h^(n − ½)) and the load moves between
/// the axles, so the bound of the static state is approached from below, not met.
inline constexpr double kStableStepMargin = 0.8;

struct Scenario {
    std::string name;
    std::string description;
    dynamics::RobotParameters robot;
    dynamics::Terrain terrain;
    /// A field (docs/field.md, "Field scenarios"): the robot drives on its surface and soils and
    /// the cells remember every pass; `terrain.base` is then the field's base soil and its patches
    /// are not used. Empty: the flat patches of `terrain`.
    std::shared_ptr<const field::FieldMap> field;
    dynamics::FieldTerrainOptions field_options;
    /// The field legend's labels by class code ("wet hollow"), for drawing its soil map.
    std::map<int, std::string> field_labels;
    dynamics::InitialState initial;
    dynamics::RoverOptions options;
    std::array<WheelInputs, dynamics::kWheelCount> wheels;
    double duration_s = 60.0;         ///< simulated time [s]
    double time_step_s = 1e-3;        ///< fixed physics step [s]
    double output_interval_s = 0.01;  ///< time-series row spacing [s] (a multiple of the step)
    std::optional<StreamingHook> streaming;
    /// How the wheels are driven (default: the ω(t) above, as the thesis).
    ControllerSpec controller;
    /// The towed implement's pull on the chassis (default none).
    DrawbarLoad drawbar_load;
    /// A path to follow (docs/field.md, "Missions"): the path controller then steers every wheel
    /// and sets its speed (the `wheels` signals are not used); a slip controller keeps each wheel
    /// at or below that speed. The run ends when the robot passes the path's end.
    std::optional<MissionSpec> mission;

    /// Every wheel's command at time t [s].
    dynamics::Commands commandsAt(double t_s) const;
    /// The soils the robot can meet, indexed as the rover's WheelState::soil_index: the patch
    /// terrain's (base, then the patches), or the field's (base, then the legend by code; a
    /// field with parameter rasters has more: dynamics::FieldTerrain's, docs/field.md F14).
    int soilCount() const;
    const soil::SoilParameters& soil(int index) const;
};

/// Every problem of a scenario built in code (the JSON reader reports the same with file paths).
std::vector<Issue> validate(const Scenario& scenario, const std::string& prefix = {});

}  // namespace terra::scenario
