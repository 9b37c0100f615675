#include "core/dynamics/rover.h"

#include <BulletDynamics/Featherstone/btMultiBody.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "core/common/range.h"

namespace terra::dynamics {
namespace {

// Link indices of the multibody: wheel i has its steering link (parent: the chassis, the base)
// and its spin link (parent: the steering link).
int steerLink(int wheel) { return 2 * wheel; }
int spinLink(int wheel) { return 2 * wheel + 1; }

// One corner at rest on its soil: the static load, the entry-angle estimator's sinkage at s = 0,
// and the vertical spring and damper the soil is to the body there.
struct StaticCorner {
    contact::SinkageSolution solution;
    double stiffness_n_m = 0.0;  // k = (n + 1/2) W / h
    double damping_n_s_m = 0.0;  // c = 2 ζ √(k W / g)
};

StaticCorner staticCorner(const contact::ContactParameters<double>& params,
                          const soil::SoilParameters& soil, double load_n,
                          const RobotParameters& robot, const RoverOptions& options) {
    StaticCorner c;
    contact::EntryAngleProblem problem;
    problem.load_n = load_n;
    problem.exit = {contact::ExitCondition::Kind::kAngle, options.contact.exit_angle_rad};
    problem.model = options.contact.model;
    problem.integration = options.contact.integration;
    c.solution = contact::solveEntryAngle(params, problem);
    if (!c.solution.ok()) return c;
    // Critical damping of a corner on the soil's tangent stiffness there. F_z grows about like
    // h^(n + 1/2) (Bekker, Eq. 2.8), so k ≈ (n + 1/2) W / h.
    c.stiffness_n_m = (soil.sinkage_exponent + 0.5) * load_n / c.solution.sinkage_m;
    c.damping_n_s_m = 2.0 * robot.vertical_damping_ratio *
                      std::sqrt(c.stiffness_n_m * load_n / options.gravity_m_s2);
    return c;
}

// The static load of corner i (0, 1 front; 2, 3 rear): the weight shared by the axles as the
// composite centre of mass lies between them.
double staticLoad(const RobotParameters& robot, const RoverOptions& options, int i) {
    return staticCornerLoad(robot, options.gravity_m_s2, i);
}

// ω Δt < 2 (√(ζ² + 1) − ζ): the stability bound of the semi-implicit Euler step on
// I ẍ + C ẋ + K x = 0 with the force of the step's start (docs/dynamics.md).
double oscillatorStep(double stiffness, double damping, double inertia, double& omega,
                      double& zeta) {
    omega = std::sqrt(stiffness / inertia);
    zeta = damping / (2.0 * std::sqrt(stiffness * inertia));
    return 2.0 * (std::sqrt(zeta * zeta + 1.0) - zeta) / omega;
}

Eigen::Vector3d toEigen(const btVector3& v) { return {v.x(), v.y(), v.z()}; }
btVector3 toBullet(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

// [a]×: the matrix of a × (·).
Eigen::Matrix3d crossMatrix(const btVector3& a) {
    Eigen::Matrix3d m;
    m << 0.0, -a.z(), a.y(), a.z(), 0.0, -a.x(), -a.y(), a.x(), 0.0;
    return m;
}

// The forward-difference step of the implicit integrator's contact Jacobians, relative to the
// speed (or sinkage) it perturbs: far above the quadrature's 1e-7 relative tolerance (the
// integrated contact), far below the scales on which the forces bend (slip, β, θ_f).
constexpr double kJacobianStep = 1e-3;

}  // namespace

double staticCornerLoad(const RobotParameters& robot, double gravity_m_s2, int corner) {
    const double mass = robot.totalMass();
    const double com_x = robot.com_forward_m * (robot.chassis_mass_kg / mass);
    const double front_share = (0.5 * robot.wheelbase_m + com_x) / robot.wheelbase_m;
    return 0.5 * mass * gravity_m_s2 * (corner < 2 ? front_share : 1.0 - front_share);
}

StepLimit largestStableStep(const RobotParameters& robot, const Terrain& terrain,
                            const RoverOptions& options) {
    return largestStableStep(robot, PatchTerrain(terrain), options);
}

StepLimit largestStableStep(const RobotParameters& robot, const TerrainModel& terrain,
                            const RoverOptions& options) {
    StepLimit out;
    out.max_step_s = std::numeric_limits<double>::infinity();
    // The body about its composite centre of mass (chassis frame at mid-wheelbase on the hubs'
    // plane): the corners at (±L/2, ±T/2, 0), the chassis' centre of mass at (x_c, 0, z_c).
    const double mc = robot.chassis_mass_kg, mw = robot.wheel_mass_kg;
    const double mass = robot.totalMass();
    const double xc = robot.com_forward_m, zc = robot.com_height_m;
    const double cx = xc * mc / mass, cz = zc * mc / mass;  // composite centre of mass
    const double half_l = 0.5 * robot.wheelbase_m, half_t = 0.5 * robot.track_m;
    const double iw = robot.wheel_spin_inertia_kg_m2, it = 0.5 * iw;
    // Pitch: the wheels turn with the chassis (the spin servos hold their rate), so I_w counts;
    // roll: their inertia about a diameter, I_t.
    double pitch_inertia =
        robot.chassis_inertia_kg_m2[1] + mc * ((xc - cx) * (xc - cx) + (zc - cz) * (zc - cz));
    double roll_inertia = robot.chassis_inertia_kg_m2[0] + mc * (zc - cz) * (zc - cz);
    std::array<double, kWheelCount> arm_x{}, arm_y{};
    for (int i = 0; i < kWheelCount; ++i) {
        arm_x[i] = (i < 2 ? half_l : -half_l) - cx;
        arm_y[i] = (i % 2 == 0 ? half_t : -half_t);
        pitch_inertia += mw * (arm_x[i] * arm_x[i] + cz * cz) + iw;
        roll_inertia += mw * (arm_y[i] * arm_y[i] + cz * cz) + it;
    }
    for (const soil::SoilParameters& soil : terrain.stepLimitSoils()) {
        const auto params = contact::makeContactParameters(soil, robot.wheel);
        double k = 0.0, c = 0.0, kx = 0.0, cx2 = 0.0, ky = 0.0, cy2 = 0.0, stiffest = 0.0;
        bool carried = true;
        for (int i = 0; i < kWheelCount; ++i) {
            const StaticCorner corner =
                staticCorner(params, soil, staticLoad(robot, options, i), robot, options);
            if (!corner.solution.ok()) {
                carried = false;
                break;
            }
            k += corner.stiffness_n_m;
            c += corner.damping_n_s_m;
            kx += corner.stiffness_n_m * arm_x[i] * arm_x[i];
            cx2 += corner.damping_n_s_m * arm_x[i] * arm_x[i];
            ky += corner.stiffness_n_m * arm_y[i] * arm_y[i];
            cy2 += corner.damping_n_s_m * arm_y[i] * arm_y[i];
            stiffest = std::max(stiffest, corner.stiffness_n_m);
        }
        if (!carried) continue;
        const std::array<std::tuple<const char*, double, double, double>, 3> modes{
            std::tuple{"heave", k, c, mass}, std::tuple{"pitch", kx, cx2, pitch_inertia},
            std::tuple{"roll", ky, cy2, roll_inertia}};
        for (const auto& [name, stiffness, damping, inertia] : modes) {
            double omega = 0.0, zeta = 0.0;
            const double step = oscillatorStep(stiffness, damping, inertia, omega, zeta);
            if (step < out.max_step_s) {
                out = {step, name, soil.name, stiffest, omega, zeta};
            }
        }
    }
    return out;
}

struct Rover::Impl {
    RobotParameters robot;
    std::unique_ptr<TerrainModel> owned_terrain;  // the patch terrain of the Terrain constructor
    TerrainModel* terrain = nullptr;
    RoverOptions options;
    std::vector<contact::ContactParameters<double>> soils;  // per terrain soil index

    // Bullet: one Featherstone multibody, chassis base + 8 revolute links (docs/dynamics.md).
    std::unique_ptr<btMultiBody> body;
    btAlignedObjectArray<btScalar> scratch_r;
    btAlignedObjectArray<btVector3> scratch_v;
    btAlignedObjectArray<btMatrix3x3> scratch_m;

    double total_mass = 0.0;
    double wheel_transverse_inertia = 0.0;      // about the wheel's diameters [kg·m²]
    btVector3 com_in_base{0, 0, 0};             // composite centre of mass, chassis frame
    std::array<btVector3, kWheelCount> hubs;    // wheel centres, chassis frame (origin: its COM)
    std::array<double, kWheelCount> damping{};  // N·s/m per corner

    // What the last evaluate() found, applied by advance().
    Commands commands{};
    std::array<btVector3, kWheelCount> wheel_force;   // on the spin link, world frame [N]
    std::array<btVector3, kWheelCount> wheel_moment;  // on the spin link, world frame [N·m]
    double soil_power = 0.0;                          // W into the soil
    double drawbar_n = 0.0;                           // towed load on the chassis [N]

    // The implicit integrator (Integrator::kImplicit): per wheel, what evaluate() found of the
    // soil's force on the hub (world frame) against the hub's velocity and position.
    std::array<Eigen::Matrix3d, kWheelCount> force_by_velocity;  // ∂F/∂v_hub [N·s/m]
    std::array<Eigen::Matrix3d, kWheelCount> force_by_position;  // ∂F/∂x_hub [N/m]
    // I6: the last Jacobians taken in the wheel's frame (∂(F_x, F_s, F_z)/∂(v_x, v_y) with the
    // damper, and ∂/∂h), the evaluations since (−1: none to reuse), and whether the wheel was
    // pushing and on a band then.
    std::array<Eigen::Matrix3d, kWheelCount> local_jacobian;
    std::array<Eigen::Vector3d, kWheelCount> sinkage_jacobian;
    std::array<int, kWheelCount> jacobian_age{-1, -1, -1, -1};
    std::array<bool, kWheelCount> jacobian_pushing{};
    // What the wheel met when its Jacobians were taken: its soil, and untouched soil, a track
    // (the reload law) or a band of parts (F15) — a change of either changes the stiffness.
    struct ContactRegime {
        int soil_index = -1;
        int kind = 0;           // 0 untouched, 1 on a track, 2 a band
        std::size_t parts = 0;  // the band's parts
        bool operator==(const ContactRegime&) const = default;
    };
    std::array<ContactRegime, kWheelCount> jacobian_regime{};

    RoverState state;
    // The ledger's kinetic and potential energy are computed when asked for (energy()), not at
    // every step: the runner reads them once.
    mutable EnergyLedger energy;
    mutable bool energy_current = false;

    btMatrix3x3 basis() const { return btMatrix3x3(body->getWorldToBaseRot().inverse()); }

    // The untouched surface under a hub (docs/field.md, F4–F6).
    struct Ground {
        double x = 0.0, y = 0.0;          // the contact point c on the map [m]
        btVector3 normal{0.0, 0.0, 1.0};  // n at c
        double distance = 0.0;            // D = n · (hub − c) [m]
    };
    Ground groundUnder(const btVector3& hub) const {
        Ground g;
        g.x = hub.x(), g.y = hub.y();
        std::array<double, 2> slope = terrain->gradientAt(g.x, g.y);
        if (slope[0] == 0.0 && slope[1] == 0.0) {
            // Flat here: n = up and c right below the hub (bit for bit the flat rover).
            g.distance = hub.z() - terrain->heightAt(g.x, g.y);
            return g;
        }
        // F4: n = (−z_x, −z_y, 1)/√(1 + |∇z|²) below the hub; F5: c = hub − D n on the tangent
        // plane, where the surface is sampled again (the foot moves by D sin α ≈ r sin α).
        btVector3 n = btVector3(-slope[0], -slope[1], 1.0).normalized();
        const double d0 = n.z() * (hub.z() - terrain->heightAt(g.x, g.y));
        g.x = hub.x() - d0 * n.x();
        g.y = hub.y() - d0 * n.y();
        slope = terrain->gradientAt(g.x, g.y);
        g.normal = btVector3(-slope[0], -slope[1], 1.0).normalized();
        g.distance = g.normal.dot(hub - btVector3(g.x, g.y, terrain->heightAt(g.x, g.y)));
        return g;
    }

    // ∂F/∂v_hub and ∂F/∂x_hub of wheel i (docs/dynamics.md, "Integrators", I2): the force
    // (F_x, F_s, load) in the wheel frame R = [x_w y_w n] by forward differences of the contact
    // in v_x, v_y and the sinkage h (h = r − n·(hub − c), so ∂h/∂x_hub = −n), and the corner's
    // damper −c n nᵀ; the load's parts only while the soil pushes (load > 0).
    // `forcesAt(q)`: the wheel's forces at kinematics q (one soil, or a band's parts, F15).
    template <class ForcesAt>
    void contactJacobians(int i, const ForcesAt& forcesAt, const WheelKinematics& k,
                          const WheelState& ws, const btVector3& x_w, const btVector3& y_w,
                          const btVector3& n, const ContactRegime& regime) {
        force_by_velocity[i].setZero();
        force_by_position[i].setZero();
        if (!ws.contact.in_contact) {
            jacobian_age[i] = -1;
            return;
        }
        const bool pushing = ws.load_n > 0.0;
        // I6: the wheel-frame Jacobians of the last evaluation that took them, while they are
        // younger than jacobian_every evaluations and the wheel still pushes alike and meets the
        // same soil the same way; the frame below is this evaluation's.
        const bool reuse = jacobian_age[i] >= 0 && jacobian_age[i] + 1 < options.jacobian_every &&
                           jacobian_pushing[i] == pushing && jacobian_regime[i] == regime;
        if (reuse) {
            ++jacobian_age[i];
        } else {
            auto forces = [&](const contact::WheelForces<double>& f) {
                return Eigen::Vector3d(f.fx, f.fs, pushing ? f.fz : 0.0);
            };
            const Eigen::Vector3d f0 = forces(ws.contact.forces);
            auto derivative = [&](WheelKinematics q, double WheelKinematics::*of, double delta) {
                q.*of += delta;
                return Eigen::Vector3d((forces(forcesAt(q)) - f0) / delta);
            };
            const double dv =
                kJacobianStep * std::max({std::abs(k.forward_speed_m_s), std::abs(k.rim_speed_m_s),
                                          options.contact.regularisation_speed_m_s});
            local_jacobian[i].col(0) = derivative(k, &WheelKinematics::forward_speed_m_s, dv);
            local_jacobian[i].col(1) = derivative(k, &WheelKinematics::lateral_speed_m_s, dv);
            local_jacobian[i].col(2) = Eigen::Vector3d(0.0, 0.0, pushing ? -damping[i] : 0.0);
            sinkage_jacobian[i] =
                derivative(k, &WheelKinematics::sinkage_m, kJacobianStep * k.sinkage_m);
            jacobian_age[i] = 0;
            jacobian_pushing[i] = pushing;
            jacobian_regime[i] = regime;
        }
        const Eigen::Matrix3d& local = local_jacobian[i];
        const Eigen::Vector3d& by_sinkage = sinkage_jacobian[i];
        Eigen::Matrix3d frame;
        frame.col(0) = toEigen(x_w);
        frame.col(1) = toEigen(y_w);
        frame.col(2) = toEigen(n);
        force_by_velocity[i] = frame * local * frame.transpose();
        force_by_position[i] = -(frame * by_sinkage) * toEigen(n).transpose();
    }

    // F15 (docs/field.md): a wheel whose width meets different memories (a rut's edge). Each part
    // of the band is the section model on its own memory — its rut z_p lowers its surface, so its
    // sinkage is h − z_p — and carries its share of the width of each force and moment; the
    // rigid wheel sinks to one h across its width. band_params[i] holds each part's contact
    // parameters, band_largest[i] the part that carries the most load (share × F_z; the first of
    // equals): its θ_f, θ_r and memory stand for the wheel's in the imprint (F11), its footprint
    // scaled by band_scale[i] to the wheel's F_z.
    std::array<std::vector<contact::ContactParameters<double>>, kWheelCount> band_params;
    std::array<std::vector<double>, kWheelCount> band_rut;
    std::array<std::size_t, kWheelCount> band_largest{};
    std::array<double, kWheelCount> band_scale{};

    void bandContact(int i, const contact::ContactParameters<double>& untouched,
                     std::span<const BandShare> band, double depth, WheelKinematics& k,
                     WheelState& ws) {
        auto& params = band_params[i];
        auto& rut = band_rut[i];
        params.clear();
        rut.clear();
        for (const BandShare& part : band) {
            params.push_back(
                part.memory ? compaction::onTrack(untouched, *part.memory, terrain->reloadLaw())
                            : untouched);
            rut.push_back(part.memory ? part.memory->rut_depth_m : 0.0);
        }
        k.sinkage_m = depth;
        ws.contact = bandForces(i, band, k, &band_largest[i], &band_scale[i]);
    }

    // The band's contact at kinematics q, q.sinkage_m the depth below the untouched surface.
    // `representative`: where the part that carries the most load is written; `scale`: the
    // band's F_z over that part's F_z for the whole width (WheelImprint::footprint_scale).
    WheelContact bandForces(int i, std::span<const BandShare> band, const WheelKinematics& q,
                            std::size_t* representative = nullptr, double* scale = nullptr) const {
        WheelContact out;
        double representative_fz = 0.0;
        contact::WheelForces<double>& f = out.forces;
        double most = -1.0;
        for (std::size_t g = 0; g < band.size(); ++g) {
            WheelKinematics part = q;
            part.sinkage_m = q.sinkage_m - band_rut[i][g];
            const WheelContact c = evaluateContact(band_params[i][g], part, options.contact);
            const double w = band[g].share;
            f.fx += w * c.forces.fx, f.fy += w * c.forces.fy, f.fz += w * c.forces.fz;
            f.mx += w * c.forces.mx, f.my += w * c.forces.my, f.mz += w * c.forces.mz;
            f.fb += w * c.forces.fb, f.fs += w * c.forces.fs;
            out.in_contact = out.in_contact || c.in_contact;
            out.sunk = out.sunk || c.sunk;
            // slip and β are the kinematics' (the same in every part); the angles the part's.
            if (w * c.forces.fz > most) {
                most = w * c.forces.fz;
                out.slip = c.slip, out.slip_angle_rad = c.slip_angle_rad;
                out.entry_angle_rad = c.entry_angle_rad, out.exit_angle_rad = c.exit_angle_rad;
                representative_fz = c.forces.fz;
                if (representative) *representative = g;
            }
        }
        out.sinkage_m = q.sinkage_m;
        if (scale) *scale = representative_fz > 0.0 ? f.fz / representative_fz : 1.0;
        return out;
    }

    // The composite's twist: its centre of mass' velocity and the chassis' angular velocity.
    Eigen::Matrix<double, 6, 1> twist() const {
        const btVector3 w = body->getBaseOmega();
        Eigen::Matrix<double, 6, 1> out;
        out << toEigen(body->getBaseVel() + w.cross(basis() * com_in_base)), toEigen(w);
        return out;
    }

    // The linearly implicit step (docs/dynamics.md, "Integrators", I1–I4). With the ideal servos
    // the robot moves over a step as one rigid body of mass m and inertia I_C about its centre of
    // mass, whose twist v (the centre of mass' velocity, the angular velocity) the explicit step
    // and the servos took from v_n to v_e = v_n + Δ_e. With the soil's forces at the step's end,
    // F(x_n + Δt v_n+1, v_n+1) ≈ F_n + J_x Δt v_n+1 + J_v Δ, the change is Δ of
    //   (M − Δt J_v − Δt² J_x) Δ = M Δ_e + Δt² J_x v_n,   M = diag(m 1, I_C),
    // with J = Σ_i G_iᵀ ∂F_i G_i, G_i = [1, −[a_i]×] (v_hub = V + Ω × a_i, a_i from the centre of
    // mass to hub i); solved as the correction δ = Δ − Δ_e of
    //   (M − J′) δ = J′ Δ_e + Δt² J_x v_n,   J′ = Δt J_v + Δt² J_x,
    // without the steering servos' share of Δ_e on the right (the chassis' reaction to a one-step
    // steering swing, several rad/s for that step alone, far outside the forces' linear range: it
    // stays explicit, as before). The correction's impulse P = M δ is the soil's: its work
    // P · (v_n + v_n+1)/2 leaves the soil's ledger; the spin servos hold the wheels' rates
    // against the chassis' change of Ω with I_w â_i·δΩ more, at their commanded rate.
    void implicitCorrection(double dt, const Eigen::Matrix<double, 6, 1>& twist_before,
                            const btVector3& steering_omega, const btMatrix3x3& composite,
                            const std::array<btVector3, kWheelCount>& axles, double& motor_work) {
        btMultiBody& b = *body;
        const btVector3 base = b.getBasePos();
        const btVector3 com_arm = basis() * com_in_base;
        const btVector3 com = base + com_arm;
        const btVector3 w1 = b.getBaseOmega();
        const Eigen::Matrix<double, 6, 1> twist_explicit = twist();
        Eigen::Matrix<double, 6, 6> mass = Eigen::Matrix<double, 6, 6>::Zero();
        mass.topLeftCorner<3, 3>().diagonal().setConstant(total_mass);
        for (int r = 0; r < 3; ++r) {
            for (int c = 0; c < 3; ++c) mass(3 + r, 3 + c) = composite[r][c];
        }
        Eigen::Matrix<double, 6, 6> by_velocity = Eigen::Matrix<double, 6, 6>::Zero();
        Eigen::Matrix<double, 6, 6> by_position = Eigen::Matrix<double, 6, 6>::Zero();
        const btMatrix3x3 rotation = basis();
        for (int i = 0; i < kWheelCount; ++i) {
            Eigen::Matrix<double, 3, 6> g;
            g.leftCols<3>().setIdentity();
            g.rightCols<3>() = -crossMatrix(base + rotation * hubs[i] - com);
            by_velocity += g.transpose() * force_by_velocity[i] * g;
            by_position += g.transpose() * force_by_position[i] * g;
        }
        const Eigen::Matrix<double, 6, 6> stiffness = dt * by_velocity + dt * dt * by_position;
        Eigen::Matrix<double, 6, 1> change = twist_explicit - twist_before;
        change.tail<3>() -= toEigen(steering_omega);
        const Eigen::Matrix<double, 6, 1> rhs =
            stiffness * change + dt * dt * (by_position * twist_before);
        const Eigen::Matrix<double, 6, 1> correction = (mass - stiffness).partialPivLu().solve(rhs);
        const Eigen::Matrix<double, 6, 1> next = twist_explicit + correction;
        const Eigen::Matrix<double, 6, 1> impulse = mass * correction;
        energy.dissipated_j -= impulse.dot(0.5 * (twist_before + next));
        const btVector3 omega = toBullet(next.tail<3>());
        const btVector3 omega_change = omega - w1;
        for (int i = 0; i < kWheelCount; ++i) {
            const double spin_impulse = robot.wheel_spin_inertia_kg_m2 * axles[i].dot(omega_change);
            motor_work += spin_impulse * b.getJointVel(spinLink(i));
            state.wheels[i].motor_torque_nm += spin_impulse / dt;
        }
        b.setBaseOmega(omega);
        b.setBaseVel(toBullet(next.head<3>()) - omega.cross(com_arm));
    }

    // The implicit integrator's steering servos stop every wheel at its commanded angle at the
    // step's end (docs/dynamics.md, "Integrators", I5): the steering rates go to 0 by the same
    // exact, internal impulses as the servos' (the momentum balance of advance(), with the spin
    // rates held), so the chassis' reaction to a swing acts over the step that makes it and the
    // next contact does not see it. At 5–6 ms a 10° one-step swing otherwise turned the chassis at
    // 20°/s into the next step, where the saturated lateral forces (β ≈ −75°) kept a yaw error.
    void stopSteering(const btMatrix3x3& composite, double& motor_work, double& steering_work) {
        btMultiBody& b = *body;
        const btMatrix3x3 rotation = basis();
        const btVector3 z = rotation.getColumn(2);
        const double it = wheel_transverse_inertia, iw = robot.wheel_spin_inertia_kg_m2;
        btVector3 momentum(0, 0, 0);
        std::array<double, kWheelCount> rate{};
        for (int i = 0; i < kWheelCount; ++i) {
            rate[i] = b.getJointVel(steerLink(i));
            momentum -= (it * rate[i]) * z;
        }
        if (momentum.isZero()) return;
        const btVector3 omega_change = -(composite.inverse() * momentum);
        const btVector3 com_arm = rotation * com_in_base;
        b.setBaseOmega(b.getBaseOmega() + omega_change);
        b.setBaseVel(b.getBaseVel() - omega_change.cross(com_arm));
        for (int i = 0; i < kWheelCount; ++i) {
            const double steer_impulse = it * (z.dot(omega_change) - rate[i]);
            const double spin_impulse =
                iw * axle(rotation, b.getJointPos(steerLink(i))).dot(omega_change);
            b.setJointVel(steerLink(i), 0.0);
            steering_work += steer_impulse * 0.5 * rate[i];
            motor_work += spin_impulse * b.getJointVel(spinLink(i));
        }
    }

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
    : Rover(robot, std::make_unique<PatchTerrain>(terrain), nullptr, options, initial,
            initial_commands) {}

Rover::Rover(const RobotParameters& robot, TerrainModel& terrain, const RoverOptions& options,
             const InitialState& initial, const Commands& initial_commands)
    : Rover(robot, nullptr, &terrain, options, initial, initial_commands) {}

Rover::Rover(const RobotParameters& robot, std::unique_ptr<TerrainModel> owned,
             TerrainModel* terrain_model, const RoverOptions& options, const InitialState& initial,
             const Commands& initial_commands)
    : impl_(std::make_unique<Impl>()) {
    Impl& m = *impl_;
    if (const auto issues = validate(robot, "robot."); !issues.empty()) {
        throw std::invalid_argument(formatIssues(issues));
    }
    if (options.integrator == Integrator::kImplicit && std::isfinite(options.max_motor_torque_nm)) {
        throw std::invalid_argument(
            "Rover: the implicit integrator needs the ideal spin servos (max_motor_torque_nm = "
            "+inf), got max_motor_torque_nm = " +
            formatNumber(options.max_motor_torque_nm));
    }
    m.robot = robot;
    m.owned_terrain = std::move(owned);
    m.terrain = m.owned_terrain ? m.owned_terrain.get() : terrain_model;
    const TerrainModel& terrain = *m.terrain;
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
    double mean_sinkage = 0.0;
    const double c0 = std::cos(initial.yaw_rad), s0 = std::sin(initial.yaw_rad);
    for (int i = 0; i < kWheelCount; ++i) {
        const double load = staticLoad(robot, options, i);
        const btVector3& h = hub_geometric[i];
        const int soil = terrain.soilIndexAt(initial.x_m + c0 * h.x() - s0 * h.y(),
                                             initial.y_m + s0 * h.x() + c0 * h.y());
        // (on a slope the corner's footprint moves by < r sin α: the soil is looked up at the
        // corner's map position)
        const StaticCorner corner =
            staticCorner(m.soils[soil], terrain.soil(soil), load, robot, options);
        const contact::SinkageSolution& solution = corner.solution;
        if (!solution.ok()) {
            throw std::invalid_argument(std::string("robot: the static load of wheel ") +
                                        kCornerNames[i] + " (" + formatNumber(load) +
                                        " N) has no equilibrium on " + terrain.soil(soil).name +
                                        ": " + solution.message);
        }
        mean_sinkage += solution.sinkage_m / kWheelCount;
        m.damping[i] = corner.damping_n_s_m;
    }

    // The multibody: floating base = chassis; per wheel a steering link (revolute about the
    // chassis z through the hub, massless) and a spin link (revolute about the steered axle y,
    // the wheel's mass and inertia, centre at the hub).
    const btVector3 chassis_inertia(robot.chassis_inertia_kg_m2[0], robot.chassis_inertia_kg_m2[1],
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

    btQuaternion heading(btVector3(0, 0, 1), initial.yaw_rad);
    btMatrix3x3 start_basis(heading);
    const std::array<double, 2> slope = terrain.gradientAt(initial.x_m, initial.y_m);
    if (slope[0] == 0.0 && slope[1] == 0.0) {
        const double hub_z = terrain.heightAt(initial.x_m, initial.y_m) + r - mean_sinkage;
        // The hubs' plane sits at hub_z; the base origin is the chassis centre of mass.
        m.body->setBasePos(btVector3(initial.x_m, initial.y_m, hub_z) + start_basis * chassis_com);
    } else {
        // On a slope (F9): the body's z along the surface normal n at (x, y), its x the heading
        // projected on the tangent plane, the hubs' plane r − h̄ above the surface along n.
        const btVector3 n = btVector3(-slope[0], -slope[1], 1.0).normalized();
        const btVector3 along(c0, s0, 0.0);
        const btVector3 x_b = (along - along.dot(n) * n).normalized();
        const btVector3 y_b = n.cross(x_b);
        start_basis =
            btMatrix3x3(x_b.x(), y_b.x(), n.x(), x_b.y(), y_b.y(), n.y(), x_b.z(), y_b.z(), n.z());
        start_basis.getRotation(heading);
        const btVector3 ground(initial.x_m, initial.y_m,
                               terrain.heightAt(initial.x_m, initial.y_m));
        m.body->setBasePos(ground + (r - mean_sinkage) * n + start_basis * chassis_com);
    }
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

    m.commands = initial_commands;
    m.wheel_force.fill(btVector3(0, 0, 0));
    m.wheel_moment.fill(btVector3(0, 0, 0));
    for (int i = 0; i < kWheelCount; ++i) {
        m.state.wheels[i].spin_rate_rad_s = initial_commands[i].spin_rate_rad_s;
        m.state.wheels[i].steer_angle_rad = initial_commands[i].steer_angle_rad;
    }
    m.readBodyState();
    m.computeEnergy(m.energy.kinetic_j, m.energy.potential_j);
    m.energy.initial_kinetic_j = m.energy.kinetic_j;
    m.energy.initial_potential_j = m.energy.potential_j;
    m.energy_current = true;
}

Rover::~Rover() = default;

const RoverState& Rover::evaluate(const Commands& commands) {
    Impl& m = *impl_;
    const btMatrix3x3 basis = m.basis();
    const btVector3 base = m.body->getBasePos();
    const btVector3 v = m.body->getBaseVel();
    const btVector3 w = m.body->getBaseOmega();
    const double r = m.robot.wheel.radius_m;
    // The slip is defined on the shearing radius r_s = r + λ_s h_g (docs/model.md, "Lugs"); r
    // for a smooth wheel.
    const double shear_radius = r + m.robot.wheel.lugShearOffset();

    m.commands = commands;
    m.soil_power = 0.0;
    for (int i = 0; i < kWheelCount; ++i) {
        WheelState& ws = m.state.wheels[i];
        const double steer = m.body->getJointPos(steerLink(i));
        const double cos_steer = std::cos(steer), sin_steer = std::sin(steer);
        const btVector3 arm = basis * m.hubs[i];
        const btVector3 hub = base + arm;
        const btVector3 hub_velocity = v + w.cross(arm);
        // The wheel body's angular velocity: chassis + steering rate + spin rate about the axle.
        const btVector3 omega =
            w + m.body->getJointVel(steerLink(i)) * basis.getColumn(2) +
            m.body->getJointVel(spinLink(i)) * (basis * btVector3(-sin_steer, cos_steer, 0.0));
        // The ground under the wheel (docs/field.md, F4–F6): the untouched surface's normal n,
        // the contact point c at the foot of the perpendicular from the hub on the tangent plane
        // (one re-sample there), and the hub's distance D from that plane; on flat ground n = up,
        // c is below the hub and D = hub.z − z(c), exactly as before.
        const Impl::Ground ground = m.groundUnder(hub);
        const btVector3& n = ground.normal;
        // Wheel frame of section 2.2.1 on the local surface (F5): x the steered wheel's heading
        // projected on the tangent plane, z = n, y = z × x.
        const btVector3 heading = basis * btVector3(cos_steer, sin_steer, 0.0);
        btVector3 x_w = heading - heading.dot(n) * n;
        x_w.normalize();
        const btVector3 y_w = n.cross(x_w);

        WheelKinematics k;
        k.forward_speed_m_s = hub_velocity.dot(x_w);
        k.lateral_speed_m_s = hub_velocity.dot(y_w);
        // The rim speed from the wheel body's own spin (joint rate plus the chassis' pitch).
        k.rim_speed_m_s = shear_radius * omega.dot(y_w);
        // h = r − D below the untouched surface (F6); in an earlier rut the contact starts at its
        // bottom z_p and meets the remembered soil (Wong's reload law, docs/compaction.md R1–R3).
        const double depth = r - ground.distance;
        ws.soil_index = m.terrain->soilIndexAt(ground.x, ground.y);
        const compaction::TrackMemory* memory = m.terrain->memoryUnder(i, ground.x, ground.y);
        ws.passes_before = memory ? memory->passes : 0;
        const contact::ContactParameters<double>* soil = &m.soils[ws.soil_index];
        contact::ContactParameters<double> on_track;
        const std::span<const BandShare> band = m.terrain->memoriesAcross(i);
        if (!band.empty()) {
            // F15: the width's parts meet different memories (a rut's edge); each part carries
            // its share of the section's forces, and the imprint is the most loaded part's.
            m.bandContact(i, *soil, band, depth, k, ws);
            soil = &m.band_params[i][m.band_largest[i]];
        } else if (memory == nullptr || memory->untouched()) {
            k.sinkage_m = depth;
            ws.contact = evaluateContact(*soil, k, m.options.contact);
        } else {
            on_track = compaction::onTrack(*soil, *memory, m.terrain->reloadLaw());
            soil = &on_track;
            k.sinkage_m = depth - memory->rut_depth_m;
            ws.contact = evaluateContact(on_track, k, m.options.contact);
            ws.contact.sinkage_m = depth;
        }
        ws.forward_speed_m_s = k.forward_speed_m_s;
        ws.lateral_speed_m_s = k.lateral_speed_m_s;
        ws.steer_angle_rad = steer;
        ws.spin_rate_rad_s = m.body->getJointVel(spinLink(i));

        const contact::WheelForces<double>& f = ws.contact.forces;
        // Damping only while in contact, and the soil can only push (F ≥ 0).
        ws.load_n =
            ws.contact.in_contact ? std::max(0.0, f.fz - m.damping[i] * hub_velocity.dot(n)) : 0.0;
        // Soil on the wheel body: forces at the hub, the resistance torque −M_y about the axle
        // (Eq. 2.34), and M_x, M_z, which the joints pass on to the chassis (F7).
        m.wheel_force[i] = f.fx * x_w + f.fs * y_w + ws.load_n * n;
        m.wheel_moment[i] = f.mx * x_w - f.my * y_w + f.mz * n;
        const double power = -(m.wheel_force[i].dot(hub_velocity) + m.wheel_moment[i].dot(omega));
        m.soil_power += power;
        if (m.options.integrator == Integrator::kImplicit) {
            const Impl::ContactRegime regime{
                ws.soil_index,
                !band.empty() ? 2 : (memory == nullptr || memory->untouched() ? 0 : 1),
                band.size()};
            if (band.empty()) {
                const auto forcesAt = [&](const WheelKinematics& q) {
                    return evaluateContact(*soil, q, m.options.contact).forces;
                };
                m.contactJacobians(i, forcesAt, k, ws, x_w, y_w, n, regime);
            } else {
                const auto forcesAt = [&](const WheelKinematics& q) {
                    return m.bandForces(i, band, q).forces;
                };
                m.contactJacobians(i, forcesAt, k, ws, x_w, y_w, n, regime);
            }
        }
        if (m.terrain->remembers()) {
            WheelImprint imprint;
            imprint.in_contact = ws.contact.in_contact;
            imprint.soil_index = ws.soil_index;
            imprint.depth_m = depth;
            imprint.load_n = ws.load_n;
            imprint.power_w = power;
            imprint.params = *soil;
            imprint.op = {ws.contact.slip, ws.contact.slip_angle_rad, ws.contact.entry_angle_rad,
                          ws.contact.exit_angle_rad, std::nullopt};
            const double axle_xy = std::hypot(y_w.x(), y_w.y());
            if (axle_xy > 0.0) imprint.axle = {y_w.x() / axle_xy, y_w.y() / axle_xy};
            if (!band.empty()) imprint.footprint_scale = m.band_scale[i];
            m.terrain->imprint(i, imprint);
        }
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
    btMultiBody& body = *m.body;
    const btVector3 gravity(0, 0, -m.options.gravity_m_s2);
    const double mw = m.robot.wheel_mass_kg;
    const double iw = m.robot.wheel_spin_inertia_kg_m2;
    const double it = m.wheel_transverse_inertia;
    std::array<double, kWheelCount> spin_before{}, steer_before{};
    for (int i = 0; i < kWheelCount; ++i) {
        spin_before[i] = body.getJointVel(spinLink(i));
        steer_before[i] = body.getJointVel(steerLink(i));
    }
    const bool implicit = m.options.integrator == Integrator::kImplicit;
    // The implicit integrator's twist at the step's start (v_n).
    Eigen::Matrix<double, 6, 1> twist_before;
    if (implicit) twist_before = m.twist();

    // 1. Free step of the articulated body (Featherstone's algorithm, Bullet): gravity and the
    //    soil's forces and moments on the wheel links, joints unactuated; v += a dt.
    body.addBaseForce(body.getBaseMass() * gravity);
    // The towed implement pulls the chassis back along its heading, horizontally.
    btVector3 pull_direction(0, 0, 0);
    if (m.drawbar_n != 0.0) {
        const btVector3 heading = m.basis().getColumn(0);
        pull_direction = btVector3(heading.x(), heading.y(), 0.0).normalized();
        body.addBaseForce(-m.drawbar_n * pull_direction);
    }
    for (int i = 0; i < kWheelCount; ++i) {
        body.addLinkForce(spinLink(i), m.wheel_force[i] + mw * gravity);
        body.addLinkTorque(spinLink(i), m.wheel_moment[i]);
    }
    body.computeAccelerationsArticulatedBodyAlgorithmMultiDof(dt_s, m.scratch_r, m.scratch_v,
                                                              m.scratch_m, false, false, false);
    body.clearForcesAndTorques();

    // 2. The joint servos: impulses about the eight joint axes that bring every joint rate to its
    //    target at the end of the step (spin: ω(t); steering: (δ(t) − δ)/dt, so the angle reaches
    //    δ(t)). Solved exactly, not iterated: the impulses are internal, so the composite centre
    //    of mass keeps its velocity and the total angular momentum about it is unchanged:
    //      I_C ΔΩ + Σ_i (I_t Δδ̇_i ẑ + I_w Δω_i â_i) = 0,   ΔV_base = −ΔΩ × (c − p_base),
    //    and each servo's impulse is the change of the wheel's angular momentum about its axis:
    //      λ_spin = I_w (â·ΔΩ + Δω),   λ_steer = I_t (ẑ·ΔΩ + Δδ̇)
    //    (the steering links are massless; a wheel's inertia is I_w about â, I_t about ẑ).
    const btMatrix3x3 b = m.basis();
    const btVector3 z = b.getColumn(2);
    const btVector3 base = body.getBasePos();
    const btVector3 com = base + b * m.com_in_base;
    auto parallelAxis = [](double mass, const btVector3& d) {
        const double d2 = d.length2();
        return btMatrix3x3(
            mass * (d2 - d.x() * d.x()), -mass * d.x() * d.y(), -mass * d.x() * d.z(),
            -mass * d.y() * d.x(), mass * (d2 - d.y() * d.y()), -mass * d.y() * d.z(),
            -mass * d.z() * d.x(), -mass * d.z() * d.y(), mass * (d2 - d.z() * d.z()));
    };
    const btVector3& ic = body.getBaseInertia();
    btMatrix3x3 composite =
        b.scaled(ic) * b.transpose() + parallelAxis(body.getBaseMass(), base - com);
    btVector3 momentum(0, 0, 0);
    std::array<btVector3, kWheelCount> axles;
    std::array<double, kWheelCount> spin_change{}, steer_change{};
    for (int i = 0; i < kWheelCount; ++i) {
        const double steer = body.getJointPos(steerLink(i));
        const btVector3 a = Impl::axle(b, steer);
        axles[i] = a;
        const btMatrix3x3 wheel(
            it + (iw - it) * a.x() * a.x(), (iw - it) * a.x() * a.y(), (iw - it) * a.x() * a.z(),
            (iw - it) * a.y() * a.x(), it + (iw - it) * a.y() * a.y(), (iw - it) * a.y() * a.z(),
            (iw - it) * a.z() * a.x(), (iw - it) * a.z() * a.y(), it + (iw - it) * a.z() * a.z());
        composite = composite + wheel + parallelAxis(mw, base + b * m.hubs[i] - com);
        spin_change[i] = m.commands[i].spin_rate_rad_s - body.getJointVel(spinLink(i));
        steer_change[i] =
            (m.commands[i].steer_angle_rad - steer) / dt_s - body.getJointVel(steerLink(i));
        momentum += (it * steer_change[i]) * z + (iw * spin_change[i]) * a;
    }
    btVector3 omega_change = -(composite.inverse() * momentum);
    // Motor torque limits: a spin servo that would need more than τ_max dt is held at that impulse
    // λ̄_i, and its rate change follows from it, I_w Δω_i = λ̄_i − I_w â_i·ΔΩ; substituted into the
    // momentum balance (I_C − Σ_clamped I_w â_i â_iᵀ) ΔΩ = −(Σ_free … + Σ_clamped λ̄_i â_i). The
    // set of clamped servos grows until no free one exceeds its limit (at most four passes).
    if (std::isfinite(m.options.max_motor_torque_nm)) {
        const double limit = m.options.max_motor_torque_nm * dt_s;
        std::array<bool, kWheelCount> clamped{};
        std::array<double, kWheelCount> held{};
        for (int pass = 0; pass < kWheelCount; ++pass) {
            bool grown = false;
            for (int i = 0; i < kWheelCount; ++i) {
                const double impulse = iw * (axles[i].dot(omega_change) + spin_change[i]);
                if (!clamped[i] && std::abs(impulse) > limit) {
                    clamped[i] = true;
                    held[i] = std::copysign(limit, impulse);
                    grown = true;
                }
            }
            if (!grown) break;
            btMatrix3x3 reduced = composite;
            btVector3 rhs = momentum;
            for (int i = 0; i < kWheelCount; ++i) {
                if (!clamped[i]) continue;
                const btVector3& a = axles[i];
                reduced = reduced -
                          btMatrix3x3(iw * a.x() * a.x(), iw * a.x() * a.y(), iw * a.x() * a.z(),
                                      iw * a.y() * a.x(), iw * a.y() * a.y(), iw * a.y() * a.z(),
                                      iw * a.z() * a.x(), iw * a.z() * a.y(), iw * a.z() * a.z());
                rhs += (held[i] - iw * spin_change[i]) * a;
            }
            omega_change = -(reduced.inverse() * rhs);
        }
        for (int i = 0; i < kWheelCount; ++i) {
            if (clamped[i]) spin_change[i] = held[i] / iw - axles[i].dot(omega_change);
        }
    }
    body.setBaseOmega(body.getBaseOmega() + omega_change);
    body.setBaseVel(body.getBaseVel() - omega_change.cross(com - base));
    double motor_work = 0.0, steering_work = 0.0;
    for (int i = 0; i < kWheelCount; ++i) {
        const double spin_impulse = iw * (axles[i].dot(omega_change) + spin_change[i]);
        const double steer_impulse = it * (z.dot(omega_change) + steer_change[i]);
        body.setJointVel(spinLink(i), body.getJointVel(spinLink(i)) + spin_change[i]);
        body.setJointVel(steerLink(i), body.getJointVel(steerLink(i)) + steer_change[i]);
        // Work: impulse × the joint rate over the step (the mean of the rates before and after,
        // which is what the semi-implicit step integrates).
        motor_work += spin_impulse * 0.5 * (spin_before[i] + body.getJointVel(spinLink(i)));
        steering_work += steer_impulse * 0.5 * (steer_before[i] + body.getJointVel(steerLink(i)));
        m.state.wheels[i].motor_torque_nm = spin_impulse / dt_s;
    }
    if (implicit) {
        // The steering servos' share of the chassis' change of Ω (the momentum balance above,
        // linear in the servos' rate changes).
        btVector3 steering(0, 0, 0);
        for (int i = 0; i < kWheelCount; ++i) steering += (it * steer_change[i]) * z;
        const btVector3 steering_omega = -(composite.inverse() * steering);
        m.implicitCorrection(dt_s, twist_before, steering_omega, composite, axles, motor_work);
    }

    // 3. Positions from the new velocities (semi-implicit Euler; Bullet's quaternion update).
    body.stepPositionsMultiDof(dt_s);
    if (implicit) m.stopSteering(composite, motor_work, steering_work);

    if (m.drawbar_n != 0.0) {
        // F v dt with the step's new velocity: the displacement the semi-implicit step takes.
        m.energy.drawbar_work_j += m.drawbar_n * body.getBaseVel().dot(pull_direction) * dt_s;
    }
    m.energy.motor_work_j += motor_work + steering_work;
    m.energy.steering_work_j += steering_work;
    m.energy.dissipated_j += m.soil_power * dt_s;
    m.terrain->advanced(dt_s);
    m.state.time_s += dt_s;
    m.readBodyState();
    m.energy_current = false;
}

void Rover::setCommands(const Commands& commands) { impl_->commands = commands; }

void Rover::setDrawbarLoad(double force_n) {
    if (!(force_n >= 0.0) || !std::isfinite(force_n)) {
        throw std::invalid_argument("Rover::setDrawbarLoad: force_n = " + formatNumber(force_n) +
                                    " must be finite and >= 0");
    }
    impl_->drawbar_n = force_n;
}

const RoverState& Rover::state() const { return impl_->state; }
const EnergyLedger& Rover::energy() const {
    const Impl& m = *impl_;
    if (!m.energy_current) {
        m.computeEnergy(m.energy.kinetic_j, m.energy.potential_j);
        m.energy_current = true;
    }
    return m.energy;
}
double Rover::verticalDamping() const { return impl_->damping[0]; }

}  // namespace terra::dynamics
