#include "core/scenario/runner.h"

#include <algorithm>
#include <cmath>
#include <random>

#include "core/common/range.h"
#include "core/common/units.h"
#include "core/identification/streaming.h"
#include "core/io/atomic_file.h"
#include "core/io/csv.h"

namespace terra::scenario {
namespace {

std::vector<std::string> seriesColumns() {
    std::vector<std::string> c{"t_s",         "x_m",         "y_m",           "z_m",    "roll_deg",
                               "pitch_deg",   "yaw_deg",     "vx_m_s",        "vy_m_s", "vz_m_s",
                               "forward_m_s", "lateral_m_s", "yaw_rate_deg_s"};
    for (const char* w : dynamics::kCornerNames) {
        const std::string p = std::string(w) + "_";
        for (const char* name : {"omega_rad_s", "steer_deg", "vx_m_s", "vy_m_s", "slip",
                                 "slip_angle_deg", "theta_f_deg", "sinkage_m", "load_N", "Fx_N",
                                 "Fy_N", "Fz_N", "Mx_Nm", "My_Nm", "Mz_Nm", "Fs_N", "soil"}) {
            c.push_back(p + name);
        }
    }
    return c;
}

std::vector<double> seriesRow(const dynamics::RoverState& s) {
    using units::radToDeg;
    std::vector<double> row{s.time_s,
                            s.position_m[0],
                            s.position_m[1],
                            s.position_m[2],
                            radToDeg(s.roll_rad),
                            radToDeg(s.pitch_rad),
                            radToDeg(s.yaw_rad),
                            s.velocity_m_s[0],
                            s.velocity_m_s[1],
                            s.velocity_m_s[2],
                            s.forward_speed_m_s,
                            s.lateral_speed_m_s,
                            radToDeg(s.angular_velocity_rad_s[2])};
    for (const dynamics::WheelState& w : s.wheels) {
        const auto& f = w.contact.forces;
        for (double v : {w.spin_rate_rad_s, radToDeg(w.steer_angle_rad), w.forward_speed_m_s,
                         w.lateral_speed_m_s, w.contact.slip, radToDeg(w.contact.slip_angle_rad),
                         radToDeg(w.contact.entry_angle_rad), w.contact.sinkage_m, w.load_n, f.fx,
                         f.fy, f.fz, f.mx, f.my, f.mz, f.fs, static_cast<double>(w.soil_index)}) {
            row.push_back(v);
        }
    }
    return row;
}

bool finite(const dynamics::RoverState& s) {
    for (double v : s.position_m)
        if (!std::isfinite(v)) return false;
    for (double v : s.velocity_m_s)
        if (!std::isfinite(v)) return false;
    for (double v : s.angular_velocity_rad_s)
        if (!std::isfinite(v)) return false;
    return true;
}

// (energy − dissipated − ΔE_kinetic − ΔE_potential) over the motors' work, or, when the motors
// delivered nothing or took energy in (braking, or a diverged run), over the largest of the
// other terms: the balance reported is always the one computed.
double energyBalanceError(double energy, double dissipated, double kinetic, double potential) {
    const double residual = energy - dissipated - kinetic - potential;
    const double scale = energy > 0.0 ? energy
                                      : std::max({std::abs(energy), std::abs(dissipated),
                                                  std::abs(kinetic) + std::abs(potential)});
    return scale > 0.0 ? residual / scale : 0.0;
}

// Watches a run for states no robot on flat soil reaches: a step too large for the contact's
// stiffness shows in them long before it turns into NaN (issue 28: 0.05 s sent the robot 150 m,
// flipped it and reported negative motor energy as a completed run).
class DivergenceWatch {
public:
    DivergenceWatch(const Scenario& scenario, const dynamics::RoverState& start)
        : z0_(start.position_m[2]),
          radius_(scenario.robot.wheel.radius_m),
          shear_radius_(scenario.robot.wheel.radius_m + scenario.robot.wheel.lugShearOffset()),
          fastest_(scenario.initial.speed_m_s),
          energy_floor_(1e-3 * scenario.robot.totalMass() * scenario.options.gravity_m_s2 *
                        scenario.robot.wheel.radius_m) {}

    // The rims' speeds commanded so far bound the robot's: on flat ground nothing else drives it.
    void commanded(const dynamics::Commands& commands) {
        for (const dynamics::WheelCommand& c : commands)
            fastest_ = std::max(fastest_, shear_radius_ * std::abs(c.spin_rate_rad_s));
    }

    // Why the state is beyond physical bounds, or "".
    std::string check(const dynamics::RoverState& s) const {
        constexpr double kTipped = 60.0 * units::kPi / 180.0;
        const double speed = std::hypot(s.velocity_m_s[0], s.velocity_m_s[1], s.velocity_m_s[2]);
        const double speed_bound = 2.0 * fastest_ + 0.5;
        if (speed > speed_bound) {
            return "the speed " + formatNumber(roundSignificant(speed, 3)) +
                   " m/s is beyond what the wheels drive (rims at most " +
                   formatNumber(roundSignificant(fastest_, 3)) + " m/s)";
        }
        if (std::abs(s.roll_rad) > kTipped || std::abs(s.pitch_rad) > kTipped) {
            return "the robot tipped over on flat ground (roll " +
                   formatNumber(roundSignificant(units::radToDeg(s.roll_rad), 3)) + "°, pitch " +
                   formatNumber(roundSignificant(units::radToDeg(s.pitch_rad), 3)) + "°)";
        }
        const double rise = s.position_m[2] - z0_;
        if (rise > 1.0 || rise < -radius_) {
            return "the robot " + std::string(rise > 0.0 ? "left the ground" : "sank through it") +
                   " (its centre of mass moved " + formatNumber(roundSignificant(rise, 3)) +
                   " m vertically)";
        }
        return {};
    }

    // An energy balance off by more than half of the energy involved: energy created or lost by
    // the integration, not by any physics of the model.
    std::string check(const dynamics::EnergyLedger& e) const {
        const double kinetic = e.kinetic_j - e.initial_kinetic_j;
        const double potential = e.potential_j - e.initial_potential_j;
        const double residual = e.motor_work_j - e.dissipated_j - kinetic - potential;
        const double error = energyBalanceError(e.motor_work_j, e.dissipated_j, kinetic, potential);
        if (std::abs(residual) > energy_floor_ && std::abs(error) > 0.5) {
            return "the energy balance is off by " +
                   formatNumber(roundSignificant(100.0 * error, 3)) + " % (" +
                   formatNumber(roundSignificant(residual, 3)) + " J)";
        }
        return {};
    }

private:
    double z0_, radius_, shear_radius_, fastest_, energy_floor_;
};

// The streaming identifier of one wheel, fed with noisy samples at its own rate.
class StreamingFeed {
public:
    StreamingFeed(const StreamingHook& hook, const wheel::WheelParameters& wheel, double dt)
        : hook_(hook),
          identifier_(wheel),
          random_(hook.seed),
          every_(std::max<long>(1, std::lround(hook.interval_s / dt))) {
        table_.columns = {"t_s",  "slip",  "theta_f_deg",    "Fx_N",
                          "Fz_N", "My_Nm", "estimated",      "Ks_Pa_mN",
                          "n0",   "c_Pa",  "phi_deg",        "K_m",
                          "a0",   "a1",    "residual_score", "change_detected",
                          "soil"};
    }

    void observe(long step, const dynamics::RoverState& state) {
        if (step % every_ != 0) return;
        const dynamics::WheelState& w = state.wheels[hook_.wheel];
        if (!w.contact.in_contact || w.contact.sunk) return;
        identification::Sample sample;
        sample.slip = std::clamp(w.contact.slip + noise(hook_.slip_noise), -0.98, 0.98);
        sample.entry_angle_rad =
            std::clamp(w.contact.entry_angle_rad + noise(hook_.entry_angle_noise_rad), 1e-3, 1.5);
        sample.fx_n = w.contact.forces.fx + noise(hook_.force_noise_n);
        sample.fz_n = w.contact.forces.fz + noise(hook_.force_noise_n);
        sample.my_nm = w.contact.forces.my + noise(hook_.torque_noise_nm);
        sample.time_s = state.time_s;
        const identification::StreamUpdate u = identifier_.push(sample);
        const auto& p = u.parameters;
        table_.rows.push_back(
            {state.time_s, sample.slip, units::radToDeg(sample.entry_angle_rad), sample.fx_n,
             sample.fz_n, sample.my_nm, u.estimated ? 1.0 : 0.0, p.pressure_modulus, p.n0,
             p.cohesion_pa, units::radToDeg(p.friction_angle_rad), p.shear_modulus_m, p.a0, p.a1,
             u.residual_score, u.change_detected ? 1.0 : 0.0, static_cast<double>(w.soil_index)});
    }

    Table take() { return std::move(table_); }

private:
    double noise(double sigma) { return sigma > 0.0 ? sigma * normal_(random_) : 0.0; }

    StreamingHook hook_;
    identification::StreamingIdentifier identifier_;
    std::mt19937_64 random_;
    std::normal_distribution<double> normal_{0.0, 1.0};
    long every_;
    Table table_;
};

}  // namespace

RunResult runScenario(const Scenario& scenario, const RunOptions& options) {
    const double dt = scenario.time_step_s;
    const long steps = std::lround(scenario.duration_s / dt);
    const long output_every = std::max<long>(1, std::lround(scenario.output_interval_s / dt));
    const long progress_every = std::max<long>(1, steps / 100);

    dynamics::Rover rover(scenario.robot, scenario.terrain, scenario.options, scenario.initial,
                          scenario.commandsAt(0.0));
    std::optional<StreamingFeed> feed;
    if (scenario.streaming) feed.emplace(*scenario.streaming, scenario.robot.wheel, dt);

    RunResult result;
    result.series.columns = seriesColumns();
    Summary& sum = result.summary;
    DivergenceWatch watch(scenario, rover.state());
    // Said with a divergence: whether the step is above the vertical modes' bound or, below it,
    // meets the stiffer lateral and longitudinal forces of slow driving (docs/dynamics.md).
    auto stepHint = [&] {
        const dynamics::StepLimit limit =
            dynamics::largestStableStep(scenario.robot, scenario.terrain, scenario.options);
        const double allowed = kStableStepMargin * limit.max_step_s;
        if (dt > allowed) {
            return "the time step " + formatNumber(dt) + " s is above the largest stable step " +
                   formatNumber(roundSignificant(allowed, 2)) + " s (docs/dynamics.md)";
        }
        return "try a smaller time step than " + formatNumber(dt) +
               " s (docs/dynamics.md, \"Step size and stability\")";
    };
    std::array<double, 2> last_xy{rover.state().position_m[0], rover.state().position_m[1]};
    long step = 0;
    for (;; ++step) {
        // Time from the step count (no accumulated rounding): bit-identical reruns and exact
        // signal switching times.
        const double t = static_cast<double>(step) * dt;
        const dynamics::Commands commands = scenario.commandsAt(t);
        watch.commanded(commands);
        const dynamics::RoverState& state = rover.evaluate(commands);
        if (!finite(state)) {
            result.status = RunResult::Status::kDiverged;
            result.message = "the simulation diverged at t = " + formatNumber(t) + " s";
            break;
        }
        if (step % output_every == 0 || step == steps)
            result.series.rows.push_back(seriesRow(state));
        if (feed) feed->observe(step, state);
        if (step == steps) break;
        if (options.cancel && options.cancel->load(std::memory_order_relaxed)) {
            result.status = RunResult::Status::kCancelled;
            result.message = "cancelled at t = " + formatNumber(t) + " s";
            break;
        }
        for (int i = 0; i < dynamics::kWheelCount; ++i) {
            const dynamics::WheelContact& c = state.wheels[i].contact;
            sum.mean_slip[i] += c.slip;
            sum.max_sinkage_m = std::max(sum.max_sinkage_m, c.sinkage_m);
            sum.sunk_steps += c.sunk ? 1 : 0;
        }
        rover.advance(dt);
        // The state every step (cheap); the energy ledger every 100 steps (it sums every body).
        std::string diverged = watch.check(rover.state());
        if (diverged.empty() && (step + 1) % 100 == 0) diverged = watch.check(rover.energy());
        if (!diverged.empty()) {
            ++step;
            result.series.rows.push_back(seriesRow(rover.state()));
            result.status = RunResult::Status::kDiverged;
            result.message = "the simulation diverged at t = " +
                             formatNumber(roundSignificant(rover.state().time_s, 6)) +
                             " s: " + diverged + "; " + stepHint();
            break;
        }
        const auto& p = rover.state().position_m;
        sum.distance_m += std::hypot(p[0] - last_xy[0], p[1] - last_xy[1]);
        last_xy = {p[0], p[1]};
        if (options.progress && (step + 1) % progress_every == 0) {
            options.progress(static_cast<double>(step + 1) / static_cast<double>(steps));
        }
    }
    const dynamics::RoverState& final_state = rover.state();
    sum.steps = step;
    sum.duration_s = static_cast<double>(step) * dt;
    sum.x_m = final_state.position_m[0];
    sum.y_m = final_state.position_m[1];
    sum.yaw_rad = final_state.yaw_rad;
    for (double& s : sum.mean_slip) s = step > 0 ? s / static_cast<double>(step) : 0.0;
    const dynamics::EnergyLedger& e = rover.energy();
    sum.energy_j = e.motor_work_j;
    sum.dissipated_j = e.dissipated_j;
    sum.kinetic_change_j = e.kinetic_j - e.initial_kinetic_j;
    sum.potential_change_j = e.potential_j - e.initial_potential_j;
    sum.energy_balance_error = energyBalanceError(sum.energy_j, sum.dissipated_j,
                                                  sum.kinetic_change_j, sum.potential_change_j);
    if (feed) result.streaming = feed->take();
    return result;
}

nlohmann::json toJson(const RunResult& result, const Scenario& scenario) {
    const Summary& s = result.summary;
    nlohmann::json slip;
    for (int i = 0; i < dynamics::kWheelCount; ++i)
        slip[dynamics::kCornerNames[i]] = s.mean_slip[i];
    const char* status = result.status == RunResult::Status::kCompleted   ? "completed"
                         : result.status == RunResult::Status::kCancelled ? "cancelled"
                                                                          : "diverged";
    nlohmann::json j{
        {"scenario", scenario.name},
        {"status", status},
        {"duration_s", s.duration_s},
        {"x_m", s.x_m},
        {"y_m", s.y_m},
        {"yaw_rad", s.yaw_rad},
        {"distance_m", s.distance_m},
        {"mean_slip", slip},
        {"energy_J", s.energy_j},
        {"dissipated_J", s.dissipated_j},
        {"kinetic_change_J", s.kinetic_change_j},
        {"potential_change_J", s.potential_change_j},
        {"max_sinkage_m", s.max_sinkage_m},
        {"sunk_wheel_steps", s.sunk_steps},
        {"steps", s.steps},
        {"time_step_s", scenario.time_step_s},
        {"model",
         scenario.options.contact.model == contact::ContactModel::kFull ? "full" : "quadratic"}};
    j["energy_balance_error"] = s.energy_balance_error;
    if (std::abs(s.energy_balance_error) > kEnergyBalanceTolerance) {
        j["warning"] = "the energy balance is off by " +
                       formatNumber(roundSignificant(100.0 * s.energy_balance_error, 3)) +
                       " %: the time step is too large for this scenario (docs/dynamics.md)";
    }
    if (!result.message.empty()) j["message"] = result.message;
    return j;
}

std::optional<std::string> writeResults(const RunResult& result, const Scenario& scenario,
                                        const std::filesystem::path& directory) {
    std::error_code ec;
    std::filesystem::create_directories(directory, ec);
    if (ec) return "cannot create " + directory.string() + ": " + ec.message();
    // A folder used before may hold a streaming.csv of an earlier run; this run writes none, so
    // the old one would pass for this run's. Removed first: a run killed while writing leaves the
    // earlier results without it, never with a stale one beside new results.
    if (result.streaming.columns.empty()) {
        const std::filesystem::path stale = directory / "streaming.csv";
        std::filesystem::remove(stale, ec);
        if (ec) return "cannot remove the earlier " + stale.string() + ": " + ec.message();
    }
    if (auto error =
            io::writeFileAtomically(directory / "timeseries.csv", io::toCsv(result.series))) {
        return error;
    }
    if (!result.streaming.columns.empty()) {
        if (auto error =
                io::writeFileAtomically(directory / "streaming.csv", io::toCsv(result.streaming))) {
            return error;
        }
    }
    return io::writeFileAtomically(directory / "summary.json",
                                   toJson(result, scenario).dump(2) + "\n");
}

}  // namespace terra::scenario
