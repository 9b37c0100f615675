#pragma once
/// @file rover.h
/// The 4WD/4WS robot driving on deformable soil (thesis chapter 3, Eq. 3.1), on Bullet. The chassis
/// is a Bullet rigid body (6 DOF, gravity, semi-implicit Euler at a fixed step); each wheel's
/// steering and spin joints are ideal actuators that follow the commanded angle and angular speed
/// (the thesis prescribes both), so the wheels add no stiff joint dynamics; at every step each
/// wheel's soil forces and moments come from the core wheel model at the hub's kinematic state and
/// act on the chassis at the wheel centre. Design and its reasons: docs/dynamics.md. Bullet types
/// stay in rover.cpp.

#include <array>
#include <memory>

#include "core/dynamics/robot.h"
#include "core/dynamics/terrain.h"
#include "core/dynamics/wheel_contact.h"

namespace terra::dynamics {

/// What the controller asks of one wheel.
struct WheelCommand {
    double spin_rate_rad_s = 0.0;  ///< ω [rad/s], ≥ 0 (forward travel)
    double steer_angle_rad = 0.0;  ///< δ [rad], positive to the left (about body z)
};
using Commands = std::array<WheelCommand, kWheelCount>;

/// Where the robot starts: on the surface, at static sinkage, level, moving straight ahead.
struct InitialState {
    double x_m = 0.0;
    double y_m = 0.0;
    double yaw_rad = 0.0;
    double speed_m_s = 0.0;  ///< forward speed of the chassis [m/s]
};

/// Simulation options.
struct RoverOptions {
    ContactOptions contact;
    double gravity_m_s2 = 9.81;  ///< the thesis's g
};

/// One wheel at one instant (the quantities the forces of the coming step were computed from).
struct WheelState {
    WheelContact contact;            ///< s, β, θ_f, h and the model's forces (wheel frame)
    int soil_index = 0;              ///< Terrain::soilIndexAt of the hub
    double load_n = 0.0;             ///< vertical force applied: F_z plus damping, ≥ 0 [N]
    double spin_rate_rad_s = 0.0;    ///< ω [rad/s]
    double steer_angle_rad = 0.0;    ///< δ [rad]
    double motor_torque_nm = 0.0;    ///< M_y + I_w dω/dt [N·m]
    double forward_speed_m_s = 0.0;  ///< v_x of the hub [m/s]
    double lateral_speed_m_s = 0.0;  ///< v_y of the hub [m/s]
};

/// The whole robot at one instant. World frame: x, y on the surface, z up.
struct RoverState {
    double time_s = 0.0;
    std::array<double, 3> position_m{};                     ///< centre of mass [m]
    double roll_rad = 0.0, pitch_rad = 0.0, yaw_rad = 0.0;  ///< Z-Y-X Euler angles
    std::array<double, 3> velocity_m_s{};                   ///< of the centre of mass, world [m/s]
    std::array<double, 3> angular_velocity_rad_s{};         ///< world [rad/s]
    double forward_speed_m_s = 0.0;                         ///< velocity along the heading [m/s]
    double lateral_speed_m_s = 0.0;  ///< velocity to the left of the heading [m/s]
    std::array<WheelState, kWheelCount> wheels;
};

/// Energy bookkeeping since the start [J].
struct EnergyLedger {
    double motor_work_j = 0.0;  ///< ∫ Σ (M_y + I_w ω̇) ω dt: what the drive motors delivered
    double dissipated_j = 0.0;  ///< ∫ power into the soil (shear, compaction, bulldozing, damping)
    double kinetic_j = 0.0;     ///< current kinetic energy (chassis, wheels' spin)
    double potential_j = 0.0;   ///< current m g z
    double initial_kinetic_j = 0.0;
    double initial_potential_j = 0.0;
};

class Rover {
public:
    /// Builds the robot on the terrain at its static sinkage (entry-angle estimator for the static
    /// corner loads). Throws std::invalid_argument for invalid parameters or when a corner load has
    /// no equilibrium on the soil under it.
    Rover(const RobotParameters& robot, const Terrain& terrain, const RoverOptions& options,
          const InitialState& initial, const Commands& initial_commands);
    ~Rover();
    Rover(const Rover&) = delete;
    Rover& operator=(const Rover&) = delete;

    /// Computes every wheel's contact at the current state for these commands (no time passes).
    const RoverState& evaluate(const Commands& commands);
    /// Applies the forces of the last evaluate() and advances the chassis by dt [s].
    void advance(double dt_s);
    /// evaluate() then advance().
    void step(double dt_s, const Commands& commands) {
        evaluate(commands);
        advance(dt_s);
    }

    const RoverState& state() const;
    const EnergyLedger& energy() const;
    /// Vertical damping coefficient of each corner [N·s/m] (docs/dynamics.md).
    double verticalDamping() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace terra::dynamics
