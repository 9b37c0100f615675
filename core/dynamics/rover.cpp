#include "core/dynamics/rover.h"

#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/common/range.h"

namespace terra::dynamics {
namespace {

btVector3 toBt(const std::array<double, 3>& v) { return {v[0], v[1], v[2]}; }

}  // namespace

struct Rover::Impl {
    RobotParameters robot;
    Terrain terrain;
    RoverOptions options;
    std::vector<contact::ContactParameters<double>> soils;  // per terrain soil index

    // Bullet: one rigid body (the chassis with the wheels' masses) in a world without collisions.
    btDefaultCollisionConfiguration collision_config;
    btCollisionDispatcher dispatcher{&collision_config};
    btDbvtBroadphase broadphase;
    btSequentialImpulseConstraintSolver solver;
    btDiscreteDynamicsWorld world{&dispatcher, &broadphase, &solver, &collision_config};
    std::unique_ptr<btBoxShape> shape;
    std::unique_ptr<btRigidBody> body;

    double mass = 0.0;
    std::array<btVector3, kWheelCount> hubs;    // wheel centres in the body frame (origin: COM)
    std::array<double, kWheelCount> damping{};  // N·s/m per corner
    std::array<double, kWheelCount> previous_spin{};
    bool have_previous_spin = false;
    double last_dt = 0.0;

    // Forces and moments of the last evaluate(), world frame, about the COM.
    btVector3 force{0, 0, 0};
    btVector3 torque{0, 0, 0};
    double motor_power = 0.0;         // W
    double soil_power = 0.0;          // W into the soil
    double spin_inertial_work = 0.0;  // J, ½ I (ω₁² − ω₀²) of this evaluate

    RoverState state;
    EnergyLedger energy;

    void computeEnergy(double& kinetic, double& potential) const {
        const btVector3 v = body->getLinearVelocity();
        const btVector3 w = body->getAngularVelocity();
        const btMatrix3x3 inv = body->getInvInertiaTensorWorld();
        const btVector3 l = inv.inverse() * w;
        double spin = 0.0;
        for (int i = 0; i < kWheelCount; ++i) {
            const double omega = state.wheels[i].spin_rate_rad_s;
            spin += 0.5 * robot.wheel_spin_inertia_kg_m2 * omega * omega;
        }
        kinetic = 0.5 * mass * v.length2() + 0.5 * w.dot(l) + spin;
        potential = mass * options.gravity_m_s2 * body->getCenterOfMassPosition().z();
    }

    void readBodyState() {
        const btTransform& t = body->getCenterOfMassTransform();
        const btVector3 p = t.getOrigin();
        state.position_m = {p.x(), p.y(), p.z()};
        btScalar yaw, pitch, roll;
        t.getBasis().getEulerYPR(yaw, pitch, roll);
        state.yaw_rad = yaw, state.pitch_rad = pitch, state.roll_rad = roll;
        const btVector3 v = body->getLinearVelocity();
        const btVector3 w = body->getAngularVelocity();
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

    // Composite centre of mass and inertia (wheels as point masses at the hubs; the diagonal of
    // the composite tensor about the COM, products of inertia dropped: docs/dynamics.md).
    const double mc = robot.chassis_mass_kg, mw = robot.wheel_mass_kg;
    m.mass = robot.totalMass();
    const btVector3 chassis_com(robot.com_forward_m, 0.0, robot.com_height_m);
    const btVector3 com = chassis_com * (mc / m.mass);
    const double half_l = 0.5 * robot.wheelbase_m, half_t = 0.5 * robot.track_m;
    const std::array<btVector3, kWheelCount> hub_geometric{
        btVector3(half_l, half_t, 0), btVector3(half_l, -half_t, 0), btVector3(-half_l, half_t, 0),
        btVector3(-half_l, -half_t, 0)};
    btVector3 inertia = toBt(robot.chassis_inertia_kg_m2);
    auto addPoint = [&](double mass, const btVector3& at) {
        const btVector3 d = at - com;
        inertia += mass * btVector3(d.y() * d.y() + d.z() * d.z(), d.x() * d.x() + d.z() * d.z(),
                                    d.x() * d.x() + d.y() * d.y());
    };
    addPoint(mc, chassis_com);
    for (int i = 0; i < kWheelCount; ++i) {
        m.hubs[i] = hub_geometric[i] - com;
        addPoint(mw, hub_geometric[i]);
    }
    inertia.setY(inertia.y() + 2.0 * robot.wheel_spin_inertia_kg_m2);  // wheel discs, roughly

    // Static corner loads and sinkages (entry-angle estimator at s = 0, β = 0).
    const double r = robot.wheel.radius_m;
    const double weight = m.mass * options.gravity_m_s2;
    const double front_share = (half_l + com.x()) / robot.wheelbase_m;
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

    // The body: a box only for Bullet's bookkeeping (nothing collides with it).
    m.shape = std::make_unique<btBoxShape>(btVector3(half_l, half_t, 0.05));
    btTransform start;
    start.setIdentity();
    start.setRotation(btQuaternion(btVector3(0, 0, 1), initial.yaw_rad));
    const double hub_z = r - mean_sinkage;
    start.setOrigin(btVector3(initial.x_m, initial.y_m, hub_z) +
                    start.getBasis() * btVector3(com.x(), com.y(), com.z()));
    // Hub positions are relative to the COM, so the start origin is the COM in the world.
    btRigidBody::btRigidBodyConstructionInfo info(m.mass, nullptr, m.shape.get(), inertia);
    info.m_startWorldTransform = start;
    info.m_linearDamping = 0.0;
    info.m_angularDamping = 0.0;
    info.m_friction = 0.0;
    m.body = std::make_unique<btRigidBody>(info);
    m.body->setActivationState(DISABLE_DEACTIVATION);
    m.body->setSleepingThresholds(0.0, 0.0);
    m.body->setLinearVelocity(start.getBasis() * btVector3(initial.speed_m_s, 0, 0));
    m.world.setGravity(btVector3(0, 0, -options.gravity_m_s2));
    m.world.addRigidBody(m.body.get());

    for (int i = 0; i < kWheelCount; ++i) {
        m.state.wheels[i].spin_rate_rad_s = initial_commands[i].spin_rate_rad_s;
        m.previous_spin[i] = initial_commands[i].spin_rate_rad_s;
    }
    m.have_previous_spin = true;
    m.readBodyState();
    m.computeEnergy(m.energy.kinetic_j, m.energy.potential_j);
    m.energy.initial_kinetic_j = m.energy.kinetic_j;
    m.energy.initial_potential_j = m.energy.potential_j;
}

Rover::~Rover() {
    if (impl_ && impl_->body) impl_->world.removeRigidBody(impl_->body.get());
}

const RoverState& Rover::evaluate(const Commands& commands) {
    Impl& m = *impl_;
    const btTransform& t = m.body->getCenterOfMassTransform();
    const btMatrix3x3& basis = t.getBasis();
    const btVector3 com = t.getOrigin();
    const btVector3 v = m.body->getLinearVelocity();
    const btVector3 w = m.body->getAngularVelocity();
    const btVector3 up(0, 0, 1);
    const double r = m.robot.wheel.radius_m;
    const double inertia = m.robot.wheel_spin_inertia_kg_m2;

    m.force.setZero();
    m.torque.setZero();
    m.motor_power = 0.0;
    m.soil_power = 0.0;
    m.spin_inertial_work = 0.0;
    for (int i = 0; i < kWheelCount; ++i) {
        WheelState& ws = m.state.wheels[i];
        const WheelCommand& cmd = commands[i];
        const btVector3 arm = basis * m.hubs[i];
        const btVector3 hub = com + arm;
        const btVector3 hub_velocity = v + w.cross(arm);
        // Wheel frame of section 2.2.1 on the flat surface: x the steered heading projected on the
        // ground, z up, y = z × x.
        const btVector3 heading =
            basis * btVector3(std::cos(cmd.steer_angle_rad), std::sin(cmd.steer_angle_rad), 0.0);
        btVector3 x_w(heading.x(), heading.y(), 0.0);
        x_w.normalize();
        const btVector3 y_w = up.cross(x_w);

        WheelKinematics k;
        k.forward_speed_m_s = hub_velocity.dot(x_w);
        k.lateral_speed_m_s = hub_velocity.dot(y_w);
        k.rim_speed_m_s = r * cmd.spin_rate_rad_s;
        k.sinkage_m = r - hub.z();
        ws.soil_index = m.terrain.soilIndexAt(hub.x(), hub.y());
        ws.contact = evaluateContact(m.soils[ws.soil_index], k, m.options.contact);
        ws.forward_speed_m_s = k.forward_speed_m_s;
        ws.lateral_speed_m_s = k.lateral_speed_m_s;
        ws.steer_angle_rad = cmd.steer_angle_rad;

        const contact::WheelForces<double>& f = ws.contact.forces;
        const double vz = hub_velocity.z();
        // Damping only while in contact, and the soil can only push (F ≥ 0).
        ws.load_n = ws.contact.in_contact ? std::max(0.0, f.fz - m.damping[i] * vz) : 0.0;

        // Motor: holds ω; its torque balances the soil's resistance torque M_y and spins the
        // wheel up. Work of the spin-up counted exactly as ½ I (ω₁² − ω₀²).
        const double spin_rate_change = cmd.spin_rate_rad_s - m.previous_spin[i];
        const double angular_acceleration = m.last_dt > 0.0 ? spin_rate_change / m.last_dt : 0.0;
        ws.motor_torque_nm = f.my + inertia * angular_acceleration;
        m.spin_inertial_work +=
            0.5 * inertia *
            (cmd.spin_rate_rad_s * cmd.spin_rate_rad_s - m.previous_spin[i] * m.previous_spin[i]);
        m.previous_spin[i] = cmd.spin_rate_rad_s;
        ws.spin_rate_rad_s = cmd.spin_rate_rad_s;

        const btVector3 hub_force = f.fx * x_w + f.fs * y_w + ws.load_n * up;
        // Soil moments M_x, M_z reach the chassis through the wheel bearings; about the axle the
        // chassis feels the motor's reaction −(M_y + I ω̇).
        const btVector3 moment =
            f.mx * x_w - (f.my + inertia * angular_acceleration) * y_w + f.mz * up;
        m.force += hub_force;
        m.torque += arm.cross(hub_force) + moment;

        const double axle_rate = cmd.spin_rate_rad_s + w.dot(y_w);  // absolute spin about y_w
        m.motor_power += f.my * cmd.spin_rate_rad_s;
        m.soil_power +=
            f.my * axle_rate - hub_force.dot(hub_velocity) - f.mx * w.dot(x_w) - f.mz * w.dot(up);
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
    m.body->applyCentralForce(m.force);
    m.body->applyTorque(m.torque);
    m.world.stepSimulation(dt_s, 0, dt_s);
    m.energy.motor_work_j += m.motor_power * dt_s + m.spin_inertial_work;
    m.energy.dissipated_j += m.soil_power * dt_s;
    m.spin_inertial_work = 0.0;
    m.last_dt = dt_s;
    m.state.time_s += dt_s;
    m.readBodyState();
    m.computeEnergy(m.energy.kinetic_j, m.energy.potential_j);
}

const RoverState& Rover::state() const { return impl_->state; }
const EnergyLedger& Rover::energy() const { return impl_->energy; }
double Rover::verticalDamping() const { return impl_->damping[0]; }

}  // namespace terra::dynamics
