#pragma once
/// @file rover.h
/// The 4WD/4WS robot driving on deformable soil (thesis chapter 3, Eq. 3.1), on Bullet's
/// Featherstone btMultiBody: a floating chassis (6 DOF, gravity) and per wheel a massless steering
/// link (revolute about the chassis z through the hub) carrying the wheel body (revolute about its
/// axle; the wheel's mass and inertia). Each joint is driven by an ideal servo, spin to the
/// commanded angular speed, steering to the commanded angle, whose impulses are solved exactly at
/// every fixed step (semi-implicit Euler). At every step each wheel's soil forces and moments come
/// from the core wheel model at the wheel body's kinematic state and act on the wheel body. Design
/// and its reasons: docs/dynamics.md. Bullet types stay in rover.cpp.

#include <array>
#include <limits>
#include <memory>
#include <string>

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

/// How Rover::advance integrates the robot over one step (docs/dynamics.md, "Integrators").
enum class Integrator {
    /// Semi-implicit Euler with the soil's forces and moments of the step's start (the thesis's
    /// scenarios at 1 ms; stable up to dynamics::largestStableStep, accurate to ≈ 2 ms at the
    /// thesis's 2 cm/s, where the slip and slip-angle forces are stiff).
    kExplicit,
    /// Linearly implicit (Rosenbrock–Euler) in the body's velocity: the same step, then the body's
    /// twist is corrected by (M − Δt J_v − Δt² J_x)⁻¹, with J_v, J_x the soil forces' Jacobians in
    /// the hubs' velocities (slip, slip angle, vertical damping) and positions (sinkage), taken by
    /// forward differences of the contact at every step. Needs the ideal spin servos
    /// (max_motor_torque_nm = +inf): a torque-limited wheel's spin is not in the correction.
    kImplicit,
};

/// Simulation options.
struct RoverOptions {
    ContactOptions contact;
    double gravity_m_s2 = 9.81;  ///< the thesis's g
    /// |τ| ≤ this for each spin servo [N·m] (a drive motor's torque limit); +inf: the ideal servo
    /// that always reaches its commanded rate (the thesis's robot, and every constant-speed run).
    double max_motor_torque_nm = std::numeric_limits<double>::infinity();
    Integrator integrator = Integrator::kExplicit;
    /// The implicit integrator's contact Jacobians (in the wheel's frame) are taken every this
    /// many steps and reused in between, while the wheel stays in contact and pushing
    /// (docs/dynamics.md, "Integrators", I6); 1: every step.
    int jacobian_every = 1;
};

/// One wheel at one instant (the quantities the forces of the coming step were computed from).
struct WheelState {
    /// s, β, θ_f, h and the model's forces (wheel frame: x along the steered heading on the
    /// local surface, z its normal; docs/field.md F5). h is the rim's depth below the untouched
    /// surface (in an earlier rut: the rut's depth plus the depth below its bottom).
    WheelContact contact;
    int soil_index = 0;            ///< TerrainModel::soilIndexAt of the contact point
    int passes_before = 0;         ///< wheels that had passed on the soil under it before [-]
    double load_n = 0.0;           ///< vertical force applied: F_z plus damping, ≥ 0 [N]
    double spin_rate_rad_s = 0.0;  ///< ω [rad/s]: the spin joint's rate (wheel vs. chassis)
    double steer_angle_rad = 0.0;  ///< δ [rad]: the steering joint's angle
    /// The spin servo's torque over the last step, impulse / dt [N·m] (≈ M_y + I_w dω/dt; 0 before
    /// the first step). evaluate() leaves it alone, so after advance() it belongs with the forces.
    double motor_torque_nm = 0.0;
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
    /// Σ over the eight joint servos of impulse × joint rate: what the drive motors (∫ τ ω dt) and
    /// the steering motors (∫ τ δ̇ dt, small) delivered.
    double motor_work_j = 0.0;
    double steering_work_j = 0.0;  ///< the steering motors' share of motor_work_j
    double dissipated_j = 0.0;  ///< ∫ power into the soil (shear, compaction, bulldozing, damping)
    /// Current kinetic energy of every body: chassis, the wheels' translation, spin and steering.
    double kinetic_j = 0.0;
    double potential_j = 0.0;  ///< current Σ m g z of every body
    /// ∫ F_d v dt: the work done against the drawbar load (Rover::setDrawbarLoad) [J]; part of
    /// the balance motor = dissipated + drawbar + ΔE_kinetic + ΔE_potential.
    double drawbar_work_j = 0.0;
    double initial_kinetic_j = 0.0;
    double initial_potential_j = 0.0;
};

/// The largest time step at which the explicit coupling of the soil's vertical forces to the
/// robot is stable (docs/dynamics.md, "Step size and stability"). Each corner rests on the soil
/// as on a spring of the soil's tangent stiffness k = (n + ½) W / h (Bekker, Eq. 2.8: F_z grows
/// like h^(n+½)) with the damper c = 2ζ √(k W / g) of the rover; the body's heave, pitch and roll
/// on these four springs are oscillators of stiffness K, damping C and mass or inertia I. The
/// semi-implicit Euler step with the forces of the step's start is stable for
/// (K/I) Δt² + 2 (C/I) Δt < 4, i.e. ω Δt < 2 (√(ζ² + 1) − ζ), ω = √(K/I), ζ = C / (2 √(K I)).
struct StepLimit {
    double max_step_s = 0.0;       ///< the smallest bound over the modes and soils [s]
    std::string mode;              ///< "heave", "pitch" or "roll"
    std::string soil;              ///< the soil's name
    double stiffness_n_m = 0.0;    ///< k of the stiffest corner there [N/m]
    double frequency_rad_s = 0.0;  ///< ω of that mode [rad/s]
    double damping_ratio = 0.0;    ///< ζ of that mode
};

/// The StepLimit of the robot on every soil of the terrain, at its static corner loads (the
/// entry-angle estimator at s = 0, as the Rover's start). A soil that cannot carry a corner load
/// has no bound (the Rover refuses to start on it). max_step_s is +inf when no soil gives one.
/// The static vertical load of corner `corner` [N]: the weight shared by the axles as the
/// composite centre of mass lies between them (what the Rover starts from).
double staticCornerLoad(const RobotParameters& robot, double gravity_m_s2, int corner);

StepLimit largestStableStep(const RobotParameters& robot, const Terrain& terrain,
                            const RoverOptions& options);
/// The same over every soil of any terrain (a field's legend).
StepLimit largestStableStep(const RobotParameters& robot, const TerrainModel& terrain,
                            const RoverOptions& options);

class Rover {
public:
    /// Builds the robot on the terrain at its static sinkage (entry-angle estimator for the static
    /// corner loads). Throws std::invalid_argument for invalid parameters or when a corner load has
    /// no equilibrium on the soil under it.
    Rover(const RobotParameters& robot, const Terrain& terrain, const RoverOptions& options,
          const InitialState& initial, const Commands& initial_commands);
    /// The same on any terrain (a field: docs/field.md), which the caller keeps alive while the
    /// rover runs and which the rover tells what each wheel did. On a slope the robot starts with
    /// its body along the surface's tangent plane at (x, y), the hubs at the static sinkage along
    /// the normal (F9).
    Rover(const RobotParameters& robot, TerrainModel& terrain, const RoverOptions& options,
          const InitialState& initial, const Commands& initial_commands);
    ~Rover();
    Rover(const Rover&) = delete;
    Rover& operator=(const Rover&) = delete;

    /// Computes every wheel's contact at the current state for these commands (no time passes).
    const RoverState& evaluate(const Commands& commands);
    /// Applies the forces of the last evaluate(), drives the joints toward its commands and
    /// advances the robot by dt [s].
    void advance(double dt_s);
    /// Replaces the commands of the last evaluate() (a controller that decides from the state
    /// evaluate() computed); the forces stay those of evaluate().
    void setCommands(const Commands& commands);
    /// The towed implement's pull from the next advance() on [N], ≥ 0: a horizontal force on the
    /// chassis' centre of mass, against its heading (0 by default). Its work is in the ledger.
    void setDrawbarLoad(double force_n);
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
    Rover(const RobotParameters& robot, std::unique_ptr<TerrainModel> owned, TerrainModel* terrain,
          const RoverOptions& options, const InitialState& initial,
          const Commands& initial_commands);

    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace terra::dynamics
