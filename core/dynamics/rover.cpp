#include "core/dynamics/rover.h"

#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <BulletDynamics/Featherstone/btMultiBodyConstraintSolver.h>
#include <BulletDynamics/Featherstone/btMultiBodyDynamicsWorld.h>
#include <BulletDynamics/Featherstone/btMultiBodyJointMotor.h>
#include <BulletDynamics/Featherstone/btMultiBodyLinkCollider.h>
#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/common/range.h"

namespace terra::dynamics {
namespace {

// Link indices of the multibody: wheel i has its steering link (parent: the chassis, the base)
// and its spin link (parent: the steering link).
int steerLink(int wheel) { return 2 * wheel; }
int spinLink(int wheel) { return 2 * wheel + 1; }

// Motor impulse bound [N·s·m]: large enough never to bind (the motors are ideal servos; a
// 10° steering step in one 1 ms step takes ~0.4 N·m·s).
constexpr double kMaxMotorImpulse = 1e6;

// A joint motor that reports the island of the multibody's base collider. Bullet 3.24's motor
// looks only at its own link's collider, finds none (the links have no shapes) and answers -1;
// the island callback then never hands it to the solver.
class JointMotor : public btMultiBodyJointMotor {
public:
    using btMultiBodyJointMotor::btMultiBodyJointMotor;
    int getIslandIdA() const override { return m_bodyA->getBaseCollider()->getIslandTag(); }
    int getIslandIdB() const override { return m_bodyB->getBaseCollider()->getIslandTag(); }
};

}  // namespace

struct Rover::Impl {
    RobotParameters robot;
    Terrain terrain;
    RoverOptions options;
    std::vector<contact::ContactParameters<double>> soils;  // per terrain soil index

    // Bullet: one Featherstone multibody (chassis base + 8 revolute links) in a world without
    // collisions; its joint motors are solved by the multibody constraint solver.
    btDefaultCollisionConfiguration collision_config;
    btCollisionDispatcher dispatcher{&collision_config};
    btDbvtBroadphase broadphase;
    btMultiBodyConstraintSolver solver;
    btMultiBodyDynamicsWorld world{&dispatcher, &broadphase, &solver, &collision_config};
    std::unique_ptr<btMultiBody> body;
    // A collision object only so that Bullet's island bookkeeping hands the joint motors to the
    // solver (with no collision object, or with islands not split, Bullet 3.24 drops every
    // multibody constraint; see JointMotor). It collides with nothing (empty filter mask).
    btSphereShape base_shape{0.05};
    std::unique_ptr<btMultiBodyLinkCollider> base_collider;
    std::array<std::unique_ptr<JointMotor>, kWheelCount> spin_motors;
    std::array<std::unique_ptr<JointMotor>, kWheelCount> steer_motors;

    double total_mass = 0.0;
    double wheel_transverse_inertia = 0.0;  // about the wheel's diameters [kg·m²]
    btVector3 com_in_base{0, 0, 0};         // composite centre of mass, chassis frame
    std::array<btVector3, kWheelCount> hubs;    // wheel centres, chassis frame (origin: its COM)
    std::array<double, kWheelCount> damping{};  // N·s/m per corner

    // What the last evaluate() found, applied by advance().
    Commands commands{};
    std::array<btVector3, kWheelCount> wheel_force;   // on the spin link, world frame [N]
    std::array<btVector3, kWheelCount> wheel_moment;  // on the spin link, world frame [N·m]
    double soil_power = 0.0;                          // W into the soil

    RoverState state;
    EnergyLedger energy;

    btMatrix3x3 basis() const { return btMatrix3x3(body->getWorldToBaseRot().inverse()); }

    // The steered wheel's axle (spin axis) in the world.
    static btVector3 axle(const btMatrix3x3& basis, double steer_rad) {
        return basis * btVector3(-std::sin(steer_rad), std::cos(steer_rad), 0.0);
    }

    // Absolute angular velocity of wheel i's spin link [rad/s], world frame.
    btVector3 wheelAngularVelocity(const btMatrix3x3& basis, int i) const {
        const btVector3 w = body->getBaseOmega();
        const double steer_rate = body->getJointVel(steerLink(i));
        const double spin_rate = body->getJointVel(spinLink(i));
        return w + steer_rate * basis.getColumn(2) +
               spin_rate * axle(basis, body->getJointPos(steerLink(i)));
    }

    // Kinetic energy of every body (chassis, the wheels' translation, spin and steering; the
    // steering links carry no mass) and potential energy m g z of every body.
    void computeEnergy(double& kinetic, double& potential) const {
        const btMatrix3x3 b = basis();
        const btVector3 v = body->getBaseVel();
        const btVector3 w = body->getBaseOmega();
        const btVector3 w_body = b.transpose() * w;
        const btVector3& ic = body->getBaseInertia();
        const double mw = robot.wheel_mass_kg;
        const double iw = robot.wheel_spin_inertia_kg_m2;
        const double it = wheel_transverse_inertia;
        kinetic = 0.5 * body->getBaseMass() * v.length2() +
                  0.5 * (ic.x() * w_body.x() * w_body.x() + ic.y() * w_body.y() * w_body.y() +
                         ic.z() * w_body.z() * w_body.z());
        double mz = body->getBaseMass() * body->getBasePos().z();
        for (int i = 0; i < kWheelCount; ++i) {
            const btVector3 arm = b * hubs[i];
            const btVector3 hub_velocity = v + w.cross(arm);
            const btVector3 omega = wheelAngularVelocity(b, i);
            const double about_axle = omega.dot(axle(b, body->getJointPos(steerLink(i))));
            // Inertia of a wheel symmetric about its axle: I_t (1 − a aᵀ) + I_w a aᵀ.
            kinetic += 0.5 * mw * hub_velocity.length2() +
                       0.5 * (it * omega.length2() + (iw - it) * about_axle * about_axle);
            mz += mw * (body->getBasePos().z() + arm.z());
        }
        potential = mz * options.gravity_m_s2;
    }

    void readBodyState() {
        const btMatrix3x3 b = basis();
        const btVector3 com_arm = b * com_in_base;
        const btVector3 p = body->getBasePos() + com_arm;
        state.position_m = {p.x(), p.y(), p.z()};
        btScalar yaw, pitch, roll;
        b.getEulerYPR(yaw, pitch, roll);
        state.yaw_rad = yaw, state.pitch_rad = pitch, state.roll_rad = roll;
        const btVector3 w = body->getBaseOmega();
        // Every mass sits at a point fixed to the chassis (the joints only turn the wheels about
        // their own centres), so the composite centre of mass moves with the chassis.
        const btVector3 v = body->getBaseVel() + w.cross(com_arm);
        state.velocity_m_s = {v.x(), v.y(), v.z()};
        state.angular_velocity_rad_s = {w.x(), w.y(), w.z()};
        const double c = std::cos(yaw), s = std::sin(yaw);
        state.forward_speed_m_s = c * v.x() + s * v.y();
        state.lateral_speed_m_s = -s * v.x() + c * v.y();
    }
};

Rover::Rover(const RobotParameters& robot, const Terrain& terrain, const RoverOptions& options,
             const InitialState& initial, const Commands& initial_commands)
    : impl_(std::make_unique<Impl>()) {
    Impl& m = *impl_;
    if (const auto issues = validate(robot, "robot."); !issues.empty()) {
        throw std::invalid_argument(formatIssues(issues));
    }
    m.robot = robot;
    m.terrain = terrain;
    m.options = options;
    for (int i = 0; i < terrain.soilCount(); ++i) {
        m.soils.push_back(contact::makeContactParameters(terrain.soil(i), robot.wheel));
    }

    // Geometry in the chassis frame (origin: the chassis centre of mass, x forward, z up).
    const double mc = robot.chassis_mass_kg, mw = robot.wheel_mass_kg;
    m.total_mass = robot.totalMass();
    const btVector3 chassis_com(robot.com_forward_m, 0.0, robot.com_height_m);
    const double half_l = 0.5 * robot.wheelbase_m, half_t = 0.5 * robot.track_m;
    const std::array<btVector3, kWheelCount> hub_geometric{
        btVector3(half_l, half_t, 0), btVector3(half_l, -half_t, 0), btVector3(-half_l, half_t, 0),
        btVector3(-half_l, -half_t, 0)};
    btVector3 hub_sum(0, 0, 0);
    for (int i = 0; i < kWheelCount; ++i) {
        m.hubs[i] = hub_geometric[i] - chassis_com;
        hub_sum += m.hubs[i];
    }
    m.com_in_base = hub_sum * (mw / m.total_mass);
    // A wheel is a disc about its diameters: I_t = I_w / 2 (docs/dynamics.md).
    m.wheel_transverse_inertia = 0.5 * robot.wheel_spin_inertia_kg_m2;

    // Static corner loads and sinkages (entry-angle estimator at s = 0, β = 0).
    const double r = robot.wheel.radius_m;
    const double weight = m.total_mass * options.gravity_m_s2;
    const double com_x = chassis_com.x() * (mc / m.total_mass);  // composite, from mid-wheelbase
    const double front_share = (half_l + com_x) / robot.wheelbase_m;
    double mean_sinkage = 0.0;
    const double c0 = std::cos(initial.yaw_rad), s0 = std::sin(initial.yaw_rad);
    for (int i = 0; i < kWheelCount; ++i) {
        const double load = 0.5 * weight * (i < 2 ? front_share : 1.0 - front_share);
        const btVector3& h = hub_geometric[i];
        const int soil = terrain.soilIndexAt(initial.x_m + c0 * h.x() - s0 * h.y(),
                                             initial.y_m + s0 * h.x() + c0 * h.y());
        contact::EntryAngleProblem problem;
        problem.load_n = load;
        problem.exit = {contact::ExitCondition::Kind::kAngle, options.contact.exit_angle_rad};
        problem.model = options.contact.model;
        problem.integration = options.contact.integration;
        const contact::SinkageSolution solution = contact::solveEntryAngle(m.soils[soil], problem);
        if (!solution.ok()) {
            throw std::invalid_argument(std::string("robot: the static load of wheel ") +
                                        kCornerNames[i] + " (" + formatNumber(load) +
                                        " N) has no equilibrium on " + terrain.soil(soil).name +
                                        ": " + solution.message);
        }
        mean_sinkage += solution.sinkage_m / kWheelCount;
        // Critical damping of a corner on the soil's tangent stiffness there. F_z grows about
        // like h^(n + 1/2) (Bekker, Eq. 2.8), so k ≈ (n + 1/2) W / h.
        const double stiffness =
            (terrain.soil(soil).sinkage_exponent + 0.5) * load / solution.sinkage_m;
        m.damping[i] =
            2.0 * robot.vertical_damping_ratio * std::sqrt(stiffness * load / options.gravity_m_s2);
    }

    // The multibody: floating base = chassis; per wheel a steering link (revolute about the
    // chassis z through the hub, massless) and a spin link (revolute about the steered axle y,
    // the wheel's mass and inertia, centre at the hub).
    const btVector3 chassis_inertia(robot.chassis_inertia_kg_m2[0],
                                    robot.chassis_inertia_kg_m2[1],
                                    robot.chassis_inertia_kg_m2[2]);
    m.body = std::make_unique<btMultiBody>(2 * kWheelCount, mc, chassis_inertia, false, false);
    const btVector3 wheel_inertia(m.wheel_transverse_inertia, robot.wheel_spin_inertia_kg_m2,
                                  m.wheel_transverse_inertia);
    const btQuaternion same(0, 0, 0, 1);
    const btVector3 zero(0, 0, 0);
    for (int i = 0; i < kWheelCount; ++i) {
        m.body->setupRevolute(steerLink(i), 0.0, zero, -1, same, btVector3(0, 0, 1), m.hubs[i],
                              zero, true);
        m.body->setupRevolute(spinLink(i), mw, wheel_inertia, steerLink(i), same,
                              btVector3(0, 1, 0), zero, zero, true);
    }
    m.body->finalizeMultiDof();
    m.body->setLinearDamping(0.0);  // Bullet's default 0.04 would be hidden dissipation
    m.body->setAngularDamping(0.0);
    m.body->setCanSleep(false);
    m.body->setHasSelfCollision(false);
    m.body->setUseGyroTerm(true);
    m.body->setMaxCoordinateVelocity(1e6);  // no clamp of joint rates (default 100 rad/s)
    m.body->setMaxAppliedImpulse(kMaxMotorImpulse);

    const btQuaternion heading(btVector3(0, 0, 1), initial.yaw_rad);
    const btMatrix3x3 start_basis(heading);
    const double hub_z = r - mean_sinkage;
    // The hubs' plane sits at hub_z; the base origin is the chassis centre of mass.
    m.body->setBasePos(btVector3(initial.x_m, initial.y_m, hub_z) + start_basis * chassis_com);
    m.body->setWorldToBaseRot(heading.inverse());
    m.body->setBaseVel(start_basis * btVector3(initial.speed_m_s, 0, 0));
    m.body->setBaseOmega(zero);
    for (int i = 0; i < kWheelCount; ++i) {
        m.body->setJointPos(steerLink(i), initial_commands[i].steer_angle_rad);
        m.body->setJointVel(steerLink(i), 0.0);
        m.body->setJointPos(spinLink(i), 0.0);
        m.body->setJointVel(spinLink(i), initial_commands[i].spin_rate_rad_s);
    }
    btAlignedObjectArray<btQuaternion> scratch_rotations;
    btAlignedObjectArray<btVector3> scratch_origins;
    m.body->forwardKinematics(scratch_rotations, scratch_origins);

    m.world.setGravity(btVector3(0, 0, -options.gravity_m_s2));
    m.world.addMultiBody(m.body.get());
    m.base_collider = std::make_unique<btMultiBodyLinkCollider>(m.body.get(), -1);
    m.base_collider->setCollisionShape(&m.base_shape);
    m.base_collider->setWorldTransform(m.body->getBaseWorldTransform());
    m.base_collider->setActivationState(DISABLE_DEACTIVATION);
    m.body->setBaseCollider(m.base_collider.get());
    m.world.addCollisionObject(m.base_collider.get(), btBroadphaseProxy::DefaultFilter, 0);
    // Motors: spin is a velocity servo (kd = 1: the joint rate reaches the target in one step),
    // steering a position servo (kp = 1, erp = 1: the angle reaches the target in one step).
    for (int i = 0; i < kWheelCount; ++i) {
        auto spin = std::make_unique<JointMotor>(
            m.body.get(), spinLink(i), 0, initial_commands[i].spin_rate_rad_s, kMaxMotorImpulse);
        spin->setVelocityTarget(initial_commands[i].spin_rate_rad_s, 1.0);
        spin->setPositionTarget(0.0, 0.0);
        auto steer =
            std::make_unique<JointMotor>(m.body.get(), steerLink(i), 0, 0.0, kMaxMotorImpulse);
        steer->setVelocityTarget(0.0, 1.0);
        steer->setPositionTarget(initial_commands[i].steer_angle_rad, 1.0);
        for (JointMotor* motor : {spin.get(), steer.get()}) {
            motor->setErp(1.0);
            motor->setRhsClamp(SIMD_INFINITY);
            motor->finalizeMultiDof();
            m.world.addMultiBodyConstraint(motor);
        }
        m.spin_motors[i] = std::move(spin);
        m.steer_motors[i] = std::move(steer);
    }

    m.commands = initial_commands;
    for (int i = 0; i < kWheelCount; ++i) {
        m.state.wheels[i].spin_rate_rad_s = initial_commands[i].spin_rate_rad_s;
        m.state.wheels[i].steer_angle_rad = initial_commands[i].steer_angle_rad;
    }
    m.readBodyState();
    m.computeEnergy(m.energy.kinetic_j, m.energy.potential_j);
    m.energy.initial_kinetic_j = m.energy.kinetic_j;
    m.energy.initial_potential_j = m.energy.potential_j;
}

Rover::~Rover() {
    if (!impl_ || !impl_->body) return;
    for (auto& motor : impl_->spin_motors)
        if (motor) impl_->world.removeMultiBodyConstraint(motor.get());
    for (auto& motor : impl_->steer_motors)
        if (motor) impl_->world.removeMultiBodyConstraint(motor.get());
    if (impl_->base_collider) impl_->world.removeCollisionObject(impl_->base_collider.get());
    impl_->world.removeMultiBody(impl_->body.get());
}

const RoverState& Rover::evaluate(const Commands& commands) {
    Impl& m = *impl_;
    const btMatrix3x3 basis = m.basis();
    const btVector3 base = m.body->getBasePos();
    const btVector3 v = m.body->getBaseVel();
    const btVector3 w = m.body->getBaseOmega();
    const btVector3 up(0, 0, 1);
    const double r = m.robot.wheel.radius_m;

    m.commands = commands;
    m.soil_power = 0.0;
    for (int i = 0; i < kWheelCount; ++i) {
        WheelState& ws = m.state.wheels[i];
        const double steer = m.body->getJointPos(steerLink(i));
        const btVector3 arm = basis * m.hubs[i];
        const btVector3 hub = base + arm;
        const btVector3 hub_velocity = v + w.cross(arm);
        const btVector3 omega = m.wheelAngularVelocity(basis, i);
        // Wheel frame of section 2.2.1 on the flat surface: x the steered wheel's heading
        // projected on the ground, z up, y = z × x.
        const btVector3 heading = basis * btVector3(std::cos(steer), std::sin(steer), 0.0);
        btVector3 x_w(heading.x(), heading.y(), 0.0);
        x_w.normalize();
        const btVector3 y_w = up.cross(x_w);

        WheelKinematics k;
        k.forward_speed_m_s = hub_velocity.dot(x_w);
        k.lateral_speed_m_s = hub_velocity.dot(y_w);
        // The rim speed from the wheel body's own spin (joint rate plus the chassis' pitch).
        k.rim_speed_m_s = r * omega.dot(y_w);
        k.sinkage_m = r - hub.z();
        ws.soil_index = m.terrain.soilIndexAt(hub.x(), hub.y());
        ws.contact = evaluateContact(m.soils[ws.soil_index], k, m.options.contact);
        ws.forward_speed_m_s = k.forward_speed_m_s;
        ws.lateral_speed_m_s = k.lateral_speed_m_s;
        ws.steer_angle_rad = steer;
        ws.spin_rate_rad_s = m.body->getJointVel(spinLink(i));

        const contact::WheelForces<double>& f = ws.contact.forces;
        // Damping only while in contact, and the soil can only push (F ≥ 0).
        ws.load_n = ws.contact.in_contact ? std::max(0.0, f.fz - m.damping[i] * hub_velocity.z())
                                          : 0.0;
        // Soil on the wheel body: forces at the hub, the resistance torque −M_y about the axle
        // (Eq. 2.34), and M_x, M_z, which the joints pass on to the chassis.
        m.wheel_force[i] = f.fx * x_w + f.fs * y_w + ws.load_n * up;
        m.wheel_moment[i] = f.mx * x_w - f.my * y_w + f.mz * up;
        m.soil_power -= m.wheel_force[i].dot(hub_velocity) + m.wheel_moment[i].dot(omega);
    }
    m.readBodyState();
    return m.state;
}

void Rover::advance(double dt_s) {
    Impl& m = *impl_;
    if (!(dt_s > 0.0)) {
        throw std::invalid_argument("Rover::advance: dt_s = " + formatNumber(dt_s) +
                                    " must be > 0");
    }
    std::array<double, kWheelCount> spin_before{}, steer_before{};
    for (int i = 0; i < kWheelCount; ++i) {
        m.body->addLinkForce(spinLink(i), m.wheel_force[i]);
        m.body->addLinkTorque(spinLink(i), m.wheel_moment[i]);
        m.spin_motors[i]->setVelocityTarget(m.commands[i].spin_rate_rad_s, 1.0);
        m.steer_motors[i]->setPositionTarget(m.commands[i].steer_angle_rad, 1.0);
        spin_before[i] = m.body->getJointVel(spinLink(i));
        steer_before[i] = m.body->getJointVel(steerLink(i));
    }
    m.world.stepSimulation(dt_s, 0, dt_s);
    // Motor work: each motor's impulse times the joint rate over the step (the mean of its rates
    // before and after, which is what the semi-implicit step integrates).
    double motor_work = 0.0;
    for (int i = 0; i < kWheelCount; ++i) {
        const double spin_impulse = m.spin_motors[i]->getAppliedImpulse(0);
        const double steer_impulse = m.steer_motors[i]->getAppliedImpulse(0);
        motor_work += spin_impulse * 0.5 * (spin_before[i] + m.body->getJointVel(spinLink(i)));
        motor_work += steer_impulse * 0.5 * (steer_before[i] + m.body->getJointVel(steerLink(i)));
        m.state.wheels[i].motor_torque_nm = spin_impulse / dt_s;
    }
    m.energy.motor_work_j += motor_work;
    m.energy.dissipated_j += m.soil_power * dt_s;
    m.state.time_s += dt_s;
    m.readBodyState();
    m.computeEnergy(m.energy.kinetic_j, m.energy.potential_j);
}

const RoverState& Rover::state() const { return impl_->state; }
const EnergyLedger& Rover::energy() const { return impl_->energy; }
double Rover::verticalDamping() const { return impl_->damping[0]; }

}  // namespace terra::dynamics
