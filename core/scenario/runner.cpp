#include "core/scenario/runner.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <initializer_list>
#include <limits>
#include <random>
#include <stdexcept>
#include <utility>

#include "core/common/range.h"
#include "core/common/units.h"
#include "core/field/field_summary.h"
#include "core/identification/parameters.h"
#include "core/identification/soil_conversion.h"
#include "core/identification/streaming.h"
#include "core/identification/streaming_estimator.h"
#include "core/io/atomic_file.h"
#include "core/io/csv.h"
#include "core/io/raster_io.h"
#include "core/scenario/map_image.h"
#include "core/soil/soil_profile.h"

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
double energyBalanceError(double energy, double dissipated, double kinetic, double potential,
                          double drawbar = 0.0) {
    const double residual = energy - dissipated - kinetic - potential - drawbar;
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
    DivergenceWatch(const Scenario& scenario, const dynamics::RoverState& start,
                    const dynamics::TerrainModel* terrain = nullptr)
        : terrain_(terrain),
          z0_(start.position_m[2] -
              (terrain ? terrain->heightAt(start.position_m[0], start.position_m[1]) : 0.0)),
          z_start_(start.position_m[2]),
          gravity_(scenario.options.gravity_m_s2),
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
        double speed_bound = 2.0 * fastest_ + 0.5;
        // On a field gravity drives the robot too: at most the speed of a free fall through the
        // height it lost since the start.
        if (terrain_ != nullptr && s.position_m[2] < z_start_)
            speed_bound += std::sqrt(2.0 * gravity_ * (z_start_ - s.position_m[2]));
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
        // Above the ground under the centre of mass (a field's surface rises and falls).
        const double ground = terrain_ ? terrain_->heightAt(s.position_m[0], s.position_m[1]) : 0.0;
        const double rise = s.position_m[2] - ground - z0_;
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
        const double residual =
            e.motor_work_j - e.dissipated_j - kinetic - potential - e.drawbar_work_j;
        const double error = energyBalanceError(e.motor_work_j, e.dissipated_j, kinetic, potential,
                                                e.drawbar_work_j);
        if (std::abs(residual) > energy_floor_ && std::abs(error) > 0.5) {
            return "the energy balance is off by " +
                   formatNumber(roundSignificant(100.0 * error, 3)) + " % (" +
                   formatNumber(roundSignificant(residual, 3)) + " J)";
        }
        return {};
    }

private:
    const dynamics::TerrainModel* terrain_;
    double z0_, z_start_, gravity_, radius_, shear_radius_, fastest_, energy_floor_;
};

// The soil the streaming identifier's estimate describes: K_s carried by k_φ with k_c = 0, which
// gives the same σ on this wheel; j_max the estimate's (+inf: none).
soil::SoilParameters soilOfEstimate(const identification::DecoupledParameters& p,
                                    const wheel::WheelParameters& wheel) {
    soil::SoilParameters base;
    base.name = "streaming estimate";
    base.cohesive_modulus = 0.0;
    return identification::soilOf(base, wheel, p);
}

// A streaming estimate's covariance as a posterior in the soil file's keys and units
// (docs/traction.md §8): `keys` are the soil fields of the covariance's rows (SI), in order. A
// parameter without variance (held by the estimator) is no part of it.
template <std::size_t N, typename Matrix>
soil::SoilPosterior posteriorOf(const std::array<const char*, N>& keys, const Matrix& covariance,
                                const soil::SoilParameters& soil) {
    soil::SoilPosterior out;
    std::array<double, N> to_si{};
    std::vector<std::size_t> kept;
    for (std::size_t k = 0; k < N; ++k) {
        if (!(covariance[k][k] > 0.0)) continue;
        const soil::SoilField& field = *soil::findSoilField(keys[k]);
        out.parameters.emplace_back(keys[k]);
        out.mean.push_back(field.userValue(soil));
        to_si[k] = field.to_si;
        kept.push_back(k);
    }
    for (std::size_t i : kept) {
        std::vector<double> row;
        for (std::size_t j : kept) row.push_back(covariance[i][j] / (to_si[i] * to_si[j]));
        out.covariance.push_back(std::move(row));
    }
    return out;
}

// What the streaming identifier of a closed-loop run hands the controller after a sample.
struct SoilUpdate {
    std::size_t index = 0;  // 0-based sample number
    bool estimated = false;
    bool change_detected = false;
    std::optional<std::size_t> change_at;      // the sample where a confirmed change began
    std::size_t samples = 0;                   // samples of the current soil behind the estimate
    std::optional<soil::SoilParameters> soil;  // the estimate as a soil (when estimated)
    std::optional<soil::SoilPosterior> posterior;  // its covariance (when asked for)
};

// The streaming identifier of one wheel, fed with noisy samples at its own rate: the decoupled
// sliding-window refit (identification/streaming.h) or the full-model moving-horizon estimator
// (identification/streaming_estimator.h), ControllerSpec::identifier (docs/traction.md §8).
class StreamingFeed {
public:
    StreamingFeed(const StreamingHook& hook, const wheel::WheelParameters& wheel, double dt,
                  const identification::StreamingOptions& options, bool posterior)
        : StreamingFeed(hook, wheel, dt, posterior, "residual_score") {
        decoupled_.emplace(wheel, options);
    }
    StreamingFeed(const StreamingHook& hook, const wheel::WheelParameters& wheel, double dt,
                  const identification::StreamingEstimatorOptions& options, bool posterior)
        : StreamingFeed(hook, wheel, dt, posterior, "nis") {
        full_.emplace(wheel, options);
    }

    // With `estimates` (a closed-loop run) the sample's slip, load and M_y are the observer's,
    // θ_f and F_x the sinkage sensor's and hub load cell's noisy readings; without, the noisy
    // truth as before.
    std::optional<SoilUpdate> observe(long step, const dynamics::RoverState& state,
                                      const Estimates* estimates = nullptr) {
        if (step % every_ != 0) return std::nullopt;
        const dynamics::WheelState& w = state.wheels[hook_.wheel];
        if (!w.contact.in_contact || w.contact.sunk) return std::nullopt;
        identification::Sample sample;
        if (estimates != nullptr) {
            const int i = hook_.wheel;
            // Only a wheel that drives and grips: not before the first second (spin-up), not
            // spinning in place (ŝ > 0.9, a stalled robot at the command's floor).
            if (state.time_s < 1.0 || !(estimates->slip[i] > 0.0 && estimates->slip[i] < 0.9))
                return std::nullopt;
            sample.slip = std::clamp(estimates->slip[i], -0.98, 0.98);
            // How well ŝ is known (∞ without GNSS: then the slip is taken as given, as before).
            if (std::isfinite(estimates->slip_std[i])) sample.slip_std = estimates->slip_std[i];
            sample.entry_angle_rad = std::clamp(
                w.contact.entry_angle_rad + noise(hook_.entry_angle_noise_rad), 1e-3, 1.5);
            sample.fx_n = w.contact.forces.fx + noise(hook_.force_noise_n);
            sample.fz_n = estimates->load_n[i];
            sample.my_nm = estimates->resistance_nm[i];
        } else {
            sample.slip = std::clamp(w.contact.slip + noise(hook_.slip_noise), -0.98, 0.98);
            sample.entry_angle_rad = std::clamp(
                w.contact.entry_angle_rad + noise(hook_.entry_angle_noise_rad), 1e-3, 1.5);
            sample.fx_n = w.contact.forces.fx + noise(hook_.force_noise_n);
            sample.fz_n = w.contact.forces.fz + noise(hook_.force_noise_n);
            sample.my_nm = w.contact.forces.my + noise(hook_.torque_noise_nm);
        }
        sample.time_s = state.time_s;
        SoilUpdate out;
        identification::DecoupledParameters p;
        double score = 0.0;
        if (decoupled_) {
            const identification::StreamUpdate u = decoupled_->push(sample);
            p = u.parameters;
            score = u.residual_score;
            out.index = u.index;
            out.estimated = u.estimated;
            out.change_detected = u.change_detected;
            out.change_at = u.change_at;
            out.samples = u.window_size;
            if (u.estimated) {
                // The decoupled estimate carries no j_max: the planner's soil has none.
                identification::DecoupledParameters estimate = p;
                estimate.max_shear_deformation_m = std::numeric_limits<double>::infinity();
                out.soil = soilOfEstimate(estimate, wheel_);
                if (posterior_) {
                    // The streaming identifier's eight parameters are the table's first
                    // eight fields, in its order (a₀ … K).
                    std::array<const char*, identification::kDecoupledParameterCount> keys{};
                    for (std::size_t k = 0; k < keys.size(); ++k)
                        keys[k] = identification::soilKeyOf(identification::parameterFields()[k]);
                    out.posterior = posteriorOf(keys, u.covariance, *out.soil);
                }
            }
        } else {
            const identification::StreamEstimate u = full_->push(sample);
            score = u.nis;
            out.index = u.index;
            out.estimated = u.estimated;
            out.change_detected = u.change_detected;
            out.change_at = u.change_at;
            // Samples of this soil: from the start, or from where the last change began.
            if (u.change_detected)
                soil_start_ = u.change_at && *u.change_at <= u.index ? *u.change_at : u.index;
            out.samples = u.index + 1 - soil_start_;
            if (u.estimated) {
                p = identification::decoupledOf(u.parameters);
                out.soil = soilOfEstimate(p, wheel_);
                if (posterior_) {
                    // The seven parameters of the soil (j_max is held, not estimated).
                    std::array<const char*, identification::kJmax> keys{};
                    for (std::size_t k = 0; k < keys.size(); ++k) {
                        keys[k] = identification::soilKeyOf(
                            identification::fieldOf(static_cast<identification::FullParameter>(k)));
                    }
                    out.posterior = posteriorOf(keys, full_->covariance(), *out.soil);
                }
            }
        }
        table_.rows.push_back(
            {state.time_s, sample.slip, units::radToDeg(sample.entry_angle_rad), sample.fx_n,
             sample.fz_n, sample.my_nm, out.estimated ? 1.0 : 0.0, p.pressure_modulus, p.n0,
             p.cohesion_pa, units::radToDeg(p.friction_angle_rad), p.shear_modulus_m, p.a0, p.a1,
             score, out.change_detected ? 1.0 : 0.0, static_cast<double>(w.soil_index)});
        return out;
    }

    int wheel() const { return hook_.wheel; }

    Table take() { return std::move(table_); }

private:
    // What both identifiers share; `score` names the series' column of the fit's score.
    StreamingFeed(const StreamingHook& hook, const wheel::WheelParameters& wheel, double dt,
                  bool posterior, const char* score)
        : hook_(hook),
          wheel_(wheel),
          posterior_(posterior),
          random_(hook.seed),
          every_(std::max<long>(1, std::lround(hook.interval_s / dt))) {
        table_.columns = columns(score);
    }
    static std::vector<std::string> columns(const char* score) {
        return {
            "t_s", "slip", "theta_f_deg", "Fx_N", "Fz_N", "My_Nm", "estimated", "Ks_Pa_mN",
            "n0",  "c_Pa", "phi_deg",     "K_m",  "a0",   "a1",    score,       "change_detected",
            "soil"};
    }
    double noise(double sigma) { return sigma > 0.0 ? sigma * normal_(random_) : 0.0; }

    StreamingHook hook_;
    wheel::WheelParameters wheel_;
    bool posterior_ = false;
    std::optional<identification::StreamingIdentifier> decoupled_;
    std::optional<identification::StreamingEstimator> full_;
    std::size_t soil_start_ = 0;
    std::mt19937_64 random_;
    std::normal_distribution<double> normal_{0.0, 1.0};
    long every_;
    Table table_;
};

// The closed loop of a slip controller (docs/traction.md §4–§5): at every control tick the
// observer reads the sensors, each wheel gets its set-point (fixed, planned on the streaming
// estimate, or the oracle's for the soil under it) and the PI its command.
class ClosedLoop {
    // How far below the slip the speed limit allows the dither's upper half stays [-].
    static constexpr double kReachMargin = 0.02;

public:
    // `field`: the field the rover drives on (its soils, F14), or none (the scenario's patches).
    ClosedLoop(const Scenario& scenario, const SlipPlanner& planner, double dt,
               const dynamics::RoverState& start, const dynamics::FieldTerrain* field)
        : scenario_(scenario),
          field_(field),
          spec_(scenario.controller),
          planner_(planner),
          shear_radius_m_(scenario.robot.wheel.radius_m + scenario.robot.wheel.lugShearOffset()),
          every_(stepsPerTick(spec_.interval_s, dt)),
          observer_(scenario.robot, spec_.sensors, scenario.options.gravity_m_s2,
                    static_cast<double>(every_) * dt, start, scenario.initial.speed_m_s),
          controller_(spec_, shear_radius_m_) {
        if (spec_.traction_limited) {
            limiter_.emplace(spec_, scenario.robot.totalMass(),
                             static_cast<double>(every_) * scenario.time_step_s);
        }
        if ((spec_.type == ControllerType::kOptimal || spec_.type == ControllerType::kOracle) &&
            !planner_) {
            throw std::invalid_argument(std::string("controller.type = ") +
                                        controllerName(spec_.type) +
                                        " needs a slip planner (analysis::runRover passes "
                                        "computeTraction)");
        }
        set_points_.fill(spec_.slip);
        applied_.fill(spec_.slip);
        for (int i = 0; i < dynamics::kWheelCount; ++i) {
            static_load_n_[i] =
                dynamics::staticCornerLoad(scenario.robot, scenario.options.gravity_m_s2, i);
            hub_x_m_[i] = (i < 2 ? 0.5 : -0.5) * scenario.robot.wheelbase_m;
        }
        const int soils = field_ ? field_->soilCount() : scenario.soilCount();
        oracle_.resize(static_cast<std::size_t>(soils) * dynamics::kWheelCount);
        oracle_cap_.resize(oracle_.size());
        cap_.fill(spec_.slip_max);
    }

    // The first commands: rolling at the set-point's rate for the initial speed.
    dynamics::Commands initial(dynamics::Commands commands) const {
        for (auto& c : commands) {
            c.spin_rate_rad_s =
                std::clamp(scenario_.initial.speed_m_s / (shear_radius_m_ * (1.0 - spec_.slip)),
                           spec_.min_spin_rate_rad_s, spec_.max_spin_rate_rad_s);
        }
        return commands;
    }

    bool tick(long step) const { return step % every_ == 0; }

    // A control tick on the state evaluate() just computed: new spin commands, each at most
    // `demand`'s (a mission's wheel speeds; docs/field.md M7) when given.
    void control(const dynamics::RoverState& state, double drawbar_n, dynamics::Commands& commands,
                 const dynamics::Commands* demand = nullptr) {
        const Estimates& est = observer_.update(state, drawbar_n);
        const double dt = static_cast<double>(every_) * scenario_.time_step_s;
        // optimal: the square-wave dither that keeps the identifier's samples informative.
        double dither = 0.0;
        if (spec_.type == ControllerType::kOptimal && spec_.dither > 0.0) {
            const double phase = std::fmod(state.time_s / spec_.dither_period_s, 1.0);
            dither = phase < 0.5 ? spec_.dither : -spec_.dither;
        }
        if (spec_.type == ControllerType::kOptimal) followSegments(est, dt, state.time_s);
        // The traction-limited mode judges the set-points in force since the last tick.
        if (limiter_)
            limiter_->update(state.time_s, set_points_, applied_, at_floor_, est, drawbar_n);
        for (int i = 0; i < dynamics::kWheelCount; ++i) {
            if (spec_.type == ControllerType::kOracle)
                set_points_[i] = oracle(i, state.wheels[i].soil_index);
            // The plan, or above it the traction-limited floor (up to the drawbar-maximising
            // slip: beyond it more slip pulls less).
            double effective = set_points_[i];
            if (limiter_) {
                if (spec_.type == ControllerType::kOracle)
                    cap_[i] = oracleCap(i, state.wheels[i].soil_index);
                effective = limiter_->effective(set_points_[i], cap_[i]);
            }
            // Raised, the dither's lower half would give back the pull the robot needs.
            double set = effective + (effective > set_points_[i] ? std::max(0.0, dither) : dither);
            if (dither > 0.0) {
                // The upper half of the dither only as far as the motor's speed limit lets the
                // wheel slip at the hub's speed (Eq. 2.1: s = 1 − v_hub / (r_s ω_max)), never below
                // the plan: a set-point the wheel cannot reach is tracking error, not excitation.
                const double reachable =
                    1.0 - est.hub_speed_m_s[i] / (shear_radius_m_ * spec_.max_spin_rate_rad_s) -
                    kReachMargin;
                set = std::max(effective, std::min(set, reachable));
            }
            applied_[i] = std::clamp(set, 0.01, 0.95);
            omega_[i] =
                demand ? controller_.command(i, applied_[i], est, dt, (*demand)[i].spin_rate_rad_s)
                       : controller_.command(i, applied_[i], est, dt);
            commands[i].spin_rate_rad_s = omega_[i];
            at_floor_[i] = omega_[i] <= spec_.min_spin_rate_rad_s;
            if (state.time_s >= 1.0) {
                const double e = state.wheels[i].contact.slip - applied_[i];
                metrics_.slip_error_sq_sum += e * e;
                ++metrics_.slip_error_count;
            }
        }
        watchBorder(state);
    }

    // The identifier's sampling (optimal): its period [s], its window's length, and its wheel.
    void streaming(double interval_s, std::size_t window, int wheel) {
        sample_interval_s_ = interval_s;
        wheel_ = wheel;
        // A usable estimate: `replan_samples` of its soil and, with a dither, one dither period
        // of them (both halves of the square wave), as far as the window holds.
        std::size_t needed = static_cast<std::size_t>(spec_.replan_samples);
        if (spec_.dither > 0.0) {
            needed = std::max(needed, static_cast<std::size_t>(
                                          std::ceil(spec_.dither_period_s / interval_s - 1e-9)));
        }
        usable_samples_ = std::min(needed, window);
    }

    // A streaming update (optimal, docs/traction.md §5): the estimate of the soil under the
    // identifier's wheel is planned on once the window is usable, then every replan_interval_s;
    // a confirmed change opens a new stretch of soil, planned on once the window is usable again.
    // Each wheel takes a stretch's plan, at its own estimated load, once it has reached it.
    void streamed(const SoilUpdate& u, double time_s) {
        if (spec_.type != ControllerType::kOptimal) return;
        if (u.change_detected) {
            // Where the change began: the odometer less the samples since its first far-off one.
            const double lag = u.change_at && *u.change_at <= u.index
                                   ? static_cast<double>(u.index - *u.change_at)
                                   : 0.0;
            Segment segment;
            segment.start_m =
                odometer_m_ - lag * sample_interval_s_ * std::max(0.0, estimates().speed_m_s);
            segments_.push_back(std::move(segment));
            last_plan_s_.reset();
        }
        if (!u.estimated || !u.soil || u.samples < usable_samples_) return;
        if (last_plan_s_ && time_s < *last_plan_s_ + spec_.replan_interval_s) return;
        Segment& segment = segments_.back();
        segment.soil = u.soil;
        if (spec_.robust != RobustSlip::kNone) segment.posterior = u.posterior;
        ++segment.revision;
        last_plan_s_ = time_s;
    }

    void apply(dynamics::Commands& commands) const {
        for (int i = 0; i < dynamics::kWheelCount; ++i) commands[i].spin_rate_rad_s = omega_[i];
    }

    const Estimates& estimates() const { return observer_.estimates(); }
    /// The planned set-points (without the dither) and the applied ones.
    const std::array<double, dynamics::kWheelCount>& setPoints() const { return set_points_; }
    const std::array<double, dynamics::kWheelCount>& applied() const { return applied_; }
    TractionMetrics& metrics() { return metrics_; }

    // The settling times: from the border to the start of the last stretch within tolerance
    // (0.03, and the band the plan's posterior supports).
    void finish() {
        if (metrics_.border_time_s && settled_from_)
            metrics_.settling_time_s = *settled_from_ - *metrics_.border_time_s;
        if (metrics_.border_time_s && band_settled_from_)
            metrics_.settling_band_time_s = *band_settled_from_ - *metrics_.border_time_s;
        if (plan_spread_[dynamics::kFrontLeft])
            metrics_.settle_band = settleBand(*plan_spread_[dynamics::kFrontLeft]);
        if (limiter_) {
            metrics_.limit_switches = limiter_->switches();
            metrics_.limited_time_s = limiter_->limitedTime();
        }
    }

private:
    std::optional<SlipPlan> plan(const soil::SoilParameters& soil, double load_n,
                                 const soil::SoilPosterior* posterior = nullptr) const {
        return plan(soil, load_n, spec_.objective, posterior);
    }
    std::optional<SlipPlan> plan(const soil::SoilParameters& soil, double load_n,
                                 SlipObjective objective,
                                 const soil::SoilPosterior* posterior = nullptr) const {
        SlipPlanRequest request = planRequest(soil, load_n, objective, posterior);
        std::optional<SlipPlan> s = planner_(request);
        if (s) s->slip = std::clamp(s->slip, spec_.slip_min, spec_.slip_max);
        return s;
    }
    SlipPlanRequest planRequest(const soil::SoilParameters& soil, double load_n,
                                SlipObjective objective,
                                const soil::SoilPosterior* posterior) const {
        SlipPlanRequest request;
        request.soil = soil;
        request.wheel = scenario_.robot.wheel;
        request.load_n = load_n;
        request.objective = objective;
        request.slip_min = spec_.slip_min;
        request.slip_max = spec_.slip_max;
        request.model = scenario_.options.contact.model;  // the model the rover drives on
        if (posterior != nullptr) {
            request.posterior = *posterior;
            request.robust = spec_.robust;
            request.quantile = spec_.quantile;
            request.posterior_samples = spec_.posterior_samples;
            request.posterior_method = spec_.posterior_method;
        }
        return request;
    }

    // The settling band: max(0.03, 2 σ_s*) for a plan whose s* spreads by σ_s* over its posterior.
    static double settleBand(double spread) { return std::max(kSettleTolerance, 2.0 * spread); }

    // optimal: the odometer (the estimated speed integrated), each wheel's stretch of soil, and
    // a new plan for a wheel that reached another stretch or whose stretch has a new estimate.
    // A wheel ρ_x behind the identifier's reaches a change ρ_x after it; its load is the mean of
    // its estimated load Ŵ_i since its last plan.
    void followSegments(const Estimates& est, double dt, double time_s) {
        odometer_m_ += std::max(0.0, est.speed_m_s) * dt;
        for (int i = 0; i < dynamics::kWheelCount; ++i) {
            load_sum_n_[i] += est.load_n[i];
            ++load_count_[i];
            const double behind = hub_x_m_[wheel_] - hub_x_m_[i];
            std::size_t k = 0;
            while (k + 1 < segments_.size() && odometer_m_ >= segments_[k + 1].start_m + behind)
                ++k;
            const Segment& segment = segments_[k];
            if (!segment.soil) continue;  // not yet planned: the wheel keeps its set-point
            if (k == wheel_segment_[i] && segment.revision == wheel_revision_[i]) continue;
            const double load = load_sum_n_[i] / static_cast<double>(load_count_[i]);
            const soil::SoilPosterior* posterior =
                segment.posterior ? &*segment.posterior : nullptr;
            if (const std::optional<SlipPlan> s = plan(*segment.soil, load, posterior)) {
                set_points_[i] = s->slip;
                plan_spread_[i] = s->spread;
                metrics_.plans.push_back(
                    {time_s, i, planRequest(*segment.soil, load, spec_.objective, posterior), *s});
            }
            // The traction-limited mode's cap: the drawbar-maximising slip of the same estimate.
            if (limiter_) {
                const std::optional<SlipPlan> cap =
                    plan(*segment.soil, load, SlipObjective::kDrawbar);
                cap_[i] = cap ? cap->slip : spec_.slip_max;
            }
            wheel_segment_[i] = k;
            wheel_revision_[i] = segment.revision;
            load_sum_n_[i] = 0.0;
            load_count_[i] = 0;
        }
    }

    // The soil of the rover's index (WheelState::soil_index).
    const soil::SoilParameters& soilOf(int soil_index) const {
        return field_ ? field_->soil(soil_index) : scenario_.soil(soil_index);
    }

    // The oracle's set-point for wheel i on soil `soil_index` (planned once per soil and wheel;
    // the previous set-point where the soil cannot carry the wheel).
    double oracle(int i, int soil_index) {
        std::optional<double>& cached =
            oracle_[static_cast<std::size_t>(soil_index) * dynamics::kWheelCount + i];
        if (!cached) {
            const std::optional<SlipPlan> s = plan(soilOf(soil_index), static_load_n_[i]);
            cached = s ? s->slip : set_points_[i];
        }
        return *cached;
    }

    // The drawbar-maximising slip of wheel i on soil `soil_index` (the traction-limited mode's
    // cap under the oracle; planned once per soil and wheel, slip_max where none).
    double oracleCap(int i, int soil_index) {
        std::optional<double>& cached =
            oracle_cap_[static_cast<std::size_t>(soil_index) * dynamics::kWheelCount + i];
        if (!cached) {
            const std::optional<SlipPlan> s =
                plan(soilOf(soil_index), static_load_n_[i], SlipObjective::kDrawbar);
            cached = s ? s->slip : spec_.slip_max;
        }
        return *cached;
    }

    // The front-left wheel's first soil change, and when its set-point settles at the oracle's
    // for the new soil (optimal and oracle).
    void watchBorder(const dynamics::RoverState& state) {
        if (spec_.type != ControllerType::kOptimal && spec_.type != ControllerType::kOracle) return;
        const int soil = state.wheels[dynamics::kFrontLeft].soil_index;
        if (!start_soil_) start_soil_ = soil;
        if (!metrics_.border_time_s) {
            if (soil == *start_soil_) return;
            metrics_.border_time_s = state.time_s;
            border_soil_ = soil;
        }
        const double target = oracle(dynamics::kFrontLeft, border_soil_);
        const double off = std::abs(set_points_[dynamics::kFrontLeft] - target);
        if (off > kSettleTolerance) {
            settled_from_.reset();
        } else if (!settled_from_) {
            settled_from_ = state.time_s;
        }
        // Within the band the plan's posterior supports (a plan with a spread only).
        const std::optional<double>& spread = plan_spread_[dynamics::kFrontLeft];
        if (!spread || off > settleBand(*spread)) {
            band_settled_from_.reset();
        } else if (!band_settled_from_) {
            band_settled_from_ = state.time_s;
        }
    }

    const Scenario& scenario_;
    const dynamics::FieldTerrain* field_ = nullptr;
    ControllerSpec spec_;
    SlipPlanner planner_;
    double shear_radius_m_;
    long every_;
    Observer observer_;
    SlipController controller_;
    std::array<double, dynamics::kWheelCount> set_points_{};
    std::array<double, dynamics::kWheelCount> applied_{};  // with the dither
    std::array<double, dynamics::kWheelCount> omega_{};
    std::array<double, dynamics::kWheelCount> static_load_n_{};
    std::optional<int> start_soil_;
    std::vector<std::optional<double>> oracle_;
    // The traction-limited mode (when enabled): its supervisor, each wheel's cap (the
    // drawbar-maximising slip of its soil, slip_max without one) and whether its last command
    // sat at the start-up floor.
    std::optional<TractionLimiter> limiter_;
    std::vector<std::optional<double>> oracle_cap_;
    std::array<double, dynamics::kWheelCount> cap_{};
    std::array<bool, dynamics::kWheelCount> at_floor_{};
    // optimal: stretches of soil between confirmed changes along the odometer, each with the
    // latest usable estimate of its soil (none before the first).
    struct Segment {
        double start_m = 0.0;
        std::optional<soil::SoilParameters> soil;
        std::optional<soil::SoilPosterior> posterior;  // with a robust set-point
        int revision = 0;
    };
    std::array<std::optional<double>, dynamics::kWheelCount> plan_spread_{};
    std::vector<Segment> segments_{Segment{}};
    std::array<std::size_t, dynamics::kWheelCount> wheel_segment_{};
    std::array<int, dynamics::kWheelCount> wheel_revision_{};
    std::array<double, dynamics::kWheelCount> load_sum_n_{};
    std::array<long, dynamics::kWheelCount> load_count_{};
    std::array<double, dynamics::kWheelCount> hub_x_m_{};
    double odometer_m_ = 0.0;
    double sample_interval_s_ = 0.1;
    std::size_t usable_samples_ = 1;
    int wheel_ = dynamics::kFrontLeft;
    std::optional<double> last_plan_s_;
    int border_soil_ = 0;
    std::optional<double> settled_from_;
    std::optional<double> band_settled_from_;
    TractionMetrics metrics_;
};

// A mission's path controller (docs/field.md, "Missions"): at every tick the pure pursuit's
// curvature for the robot's centre, turned into each wheel's steering angle and speed (M1–M9).
class MissionFollower {
    // The forward speed from which the crab angle counts in full (M9) [m/s].
    static constexpr double kCourseSpeed = 0.01;

public:
    MissionFollower(const Scenario& scenario, double dt)
        : robot_(scenario.robot),
          spec_(*scenario.mission),
          pursuit_(Path::ofMission(spec_), spec_.lookahead_m,
                   maxCurvature(scenario.robot, spec_.max_steer_rad)),
          every_(stepsPerTick(spec_.interval_s, dt)),
          // The centre between the axles lies com_x behind the composite centre of mass.
          com_x_m_(robot_.com_forward_m * robot_.chassis_mass_kg / robot_.totalMass()) {
        outcome_.path_length_m = pursuit_.path().length();
        steer(Eigen::Vector2d(scenario.initial.x_m, scenario.initial.y_m), scenario.initial.yaw_rad,
              scenario.initial.yaw_rad);
    }

    bool tick(long step) const { return step % every_ == 0; }

    // A tick on the state evaluate() just computed.
    void control(const dynamics::RoverState& state) {
        const Eigen::Vector2d com(state.position_m[0], state.position_m[1]);
        const double yaw = state.yaw_rad;
        // M9: the course, the heading plus the crab angle β of the centre's velocity (the centre
        // lies com_x behind the centre of mass: its lateral speed is less ψ̇ com_x), faded in
        // from rest to kCourseSpeed, below which β is the angle of a barely moving robot.
        double direction = yaw;
        if (spec_.follow_course && state.forward_speed_m_s > 0.0) {
            const double lateral =
                state.lateral_speed_m_s - state.angular_velocity_rad_s[2] * com_x_m_;
            const double weight = std::min(1.0, state.forward_speed_m_s / kCourseSpeed);
            direction += weight * std::atan2(lateral, state.forward_speed_m_s);
        }
        const PursuitStep& step = steer(com, yaw, direction);
        const double e = step.projection.error_m;
        error_sq_sum_ += e * e;
        ++error_count_;
        outcome_.error_max_m = std::max(outcome_.error_max_m, std::abs(e));
        if (step.done && !outcome_.completed) {
            outcome_.completed = true;
            outcome_.time_s = state.time_s;
        }
    }

    const dynamics::Commands& commands() const { return commands_; }
    bool done() const { return outcome_.completed; }
    // The time series' columns: path_s_m, path_error_m, curvature_1_m.
    std::array<double, 3> row() const {
        return {last_.projection.s_m, last_.projection.error_m, last_.curvature_1_m};
    }

    MissionOutcome outcome() const {
        MissionOutcome o = outcome_;
        o.progress_m = std::min(pursuit_.progress(), o.path_length_m);
        if (error_count_ > 0)
            o.error_rms_m = std::sqrt(error_sq_sum_ / static_cast<double>(error_count_));
        return o;
    }

private:
    // The centre between the axles from the centre of mass at heading `yaw`; α measured from
    // `direction` (the heading, or the course: M9).
    const PursuitStep& steer(const Eigen::Vector2d& com, double yaw, double direction) {
        const Eigen::Vector2d centre =
            com - com_x_m_ * Eigen::Vector2d(std::cos(yaw), std::sin(yaw));
        last_ = pursuit_.update(centre, direction);
        commands_ = fourWheelSteering(robot_, last_.curvature_1_m, spec_.speed_m_s);
        return last_;
    }

    dynamics::RobotParameters robot_;
    MissionSpec spec_;
    PurePursuit pursuit_;
    long every_;
    double com_x_m_;
    PursuitStep last_;
    dynamics::Commands commands_{};
    MissionOutcome outcome_;
    double error_sq_sum_ = 0.0;
    long error_count_ = 0;
};

std::vector<std::string> closedLoopColumns() {
    std::vector<std::string> c{"drawbar_N", "speed_est_m_s", "drive_energy_J"};
    for (const char* w : dynamics::kCornerNames) {
        for (const char* name : {"slip_set", "slip_plan", "slip_est", "torque_Nm"})
            c.push_back(std::string(w) + "_" + name);
    }
    return c;
}

// σ_pc at the compaction risk's depth (the grid's first stress depth) of each soil of the terrain:
// its profile's layer there, or NaN (no profile reaching that depth, or no stress depth).
std::vector<double> precompressionBySoil(const dynamics::FieldTerrain& terrain) {
    const std::vector<double>& depths = terrain.cells().stressDepths();
    std::vector<double> precompression(static_cast<std::size_t>(terrain.soilCount()),
                                       std::numeric_limits<double>::quiet_NaN());
    for (int i = 0; i < terrain.soilCount(); ++i) {
        const soil::SoilParameters& soil = terrain.soil(i);
        if (depths.empty() || !soil.profile) continue;
        if (const soil::SoilLayer* layer = soil.profile->layerAt(depths.front()))
            precompression[static_cast<std::size_t>(i)] = soil::precompressionStress(*layer);
    }
    return precompression;
}

// F11–F12 of a cell: the largest |s| of the wheels that passed, and the energy lost there per
// metre travelled over it; no data (NaN) where no wheel passed.
// (A cell's state and a recorded passage, CellPassage, carry the same fields.)
double slipOver(int passes, float max_slip) {
    return passes > 0 ? static_cast<double>(max_slip) : std::numeric_limits<double>::quiet_NaN();
}
double energyPerMetreOver(int passes, float energy_j, float travel_m) {
    return passes > 0 && travel_m > 0.0f
               ? static_cast<double>(energy_j) / static_cast<double>(travel_m)
               : std::numeric_limits<double>::quiet_NaN();
}
double cellSlip(const field::CellState& c) { return slipOver(c.track.passes, c.max_slip); }
double cellEnergyPerMetre(const field::CellState& c) {
    return energyPerMetreOver(c.track.passes, c.energy_j, c.travel_m);
}

// The history of the maps (MapHistory): each recorded passage inside the maps (of the geometry
// of `grid`) with the value of every map at its cell after it, by the same rules as fieldMaps.
// Takes the terrain's passages and frees them once drawn.
MapHistory mapHistory(dynamics::FieldTerrain& terrain, const field::Raster& grid,
                      const std::vector<double>& precompression) {
    MapHistory h;
    const std::deque<dynamics::CellPassage> log = terrain.takePassages();
    const field::CellGrid& cells = terrain.cells();
    std::vector<double>& rut = h.values["rut_depth_m"];
    std::vector<double>& passes = h.values["passes"];
    std::vector<double>& risk = h.values["compaction_risk"];
    std::vector<double>& slip = h.values["slip"];
    std::vector<double>& energy = h.values["energy_per_m_J"];
    for (std::vector<double>* v : {&h.time_s, &rut, &passes, &risk, &slip, &energy})
        v->reserve(log.size());
    const double nan = std::numeric_limits<double>::quiet_NaN();
    h.cell.reserve(log.size());
    for (const dynamics::CellPassage& p : log) {
        const double x = cells.centreX(p.key.ix), y = cells.centreY(p.key.iy);
        const std::optional<field::CellIndex> at = grid.cellAt(x, y);
        if (!at) continue;  // driven off the maps: not drawn on them either
        h.time_s.push_back(p.time_s);
        h.cell.push_back(static_cast<std::int32_t>(at->row * grid.cols + at->col));
        rut.push_back(p.rut_depth_m);
        passes.push_back(static_cast<double>(p.passes));
        const double sigma_pc = precompression[static_cast<std::size_t>(terrain.soilIndexAt(x, y))];
        risk.push_back(sigma_pc > 0.0 ? static_cast<double>(p.max_stress_pa) / sigma_pc : nan);
        slip.push_back(slipOver(p.passes, p.max_slip));
        energy.push_back(energyPerMetreOver(p.passes, p.energy_j, p.travel_m));
    }
    return h;
}

// The maps of a field run over the field's extent (or the cells touched, for a field without
// rasters), on the memory's cells. The history is drawn first, from the terrain's passages, which
// are then freed: the run's peak memory holds the passages or the other four maps, not both.
FieldMaps fieldMaps(dynamics::FieldTerrain& terrain) {
    const field::CellGrid& cells = terrain.cells();
    std::array<double, 4> box{0.0, 0.0, cells.cellSize(), cells.cellSize()};
    if (const auto e = field::extent(terrain.map())) {
        box = *e;
    } else if (const auto [lo, hi] = cells.touchedBounds(); hi.ix >= lo.ix) {
        const double h = cells.cellSize();
        box = {cells.xOrigin() + lo.ix * h, cells.yOrigin() + lo.iy * h,
               cells.xOrigin() + (hi.ix + 1) * h, cells.yOrigin() + (hi.iy + 1) * h};
    }
    FieldMaps maps;
    maps.rut_depth_m =
        cells.toRaster(box[0], box[1], box[2], box[3],
                       [](const field::CellState& c) { return c.track.rut_depth_m; });
    const std::vector<double> precompression = precompressionBySoil(terrain);
    maps.history = mapHistory(terrain, maps.rut_depth_m, precompression);
    maps.passes = cells.toRaster(box[0], box[1], box[2], box[3], [](const field::CellState& c) {
        return static_cast<double>(c.track.passes);
    });
    // F11–F12: no data where no wheel passed (a cell of a touched tile that none crossed).
    maps.slip = cells.toRaster(box[0], box[1], box[2], box[3], cellSlip);
    maps.energy_per_m_j = cells.toRaster(box[0], box[1], box[2], box[3], cellEnergyPerMetre);
    maps.compaction_risk = cells.toRaster(
        box[0], box[1], box[2], box[3],
        [](const field::CellState& c) { return static_cast<double>(c.max_stress_pa[0]); });
    const std::vector<double>& depths = cells.stressDepths();
    maps.risk_depth_m = depths.empty() ? std::numeric_limits<double>::quiet_NaN() : depths.front();
    const double nan = std::numeric_limits<double>::quiet_NaN();
    field::Raster& risk = maps.compaction_risk;
    // When every soil has σ_pc (or none has) the cells no wheel touched need no soil lookup: their
    // stress is 0, their risk 0 (or no data).
    const bool all =
        std::all_of(precompression.begin(), precompression.end(), [](double p) { return p > 0.0; });
    const bool none = std::none_of(precompression.begin(), precompression.end(),
                                   [](double p) { return p > 0.0; });
    for (int row = 0; row < risk.rows; ++row) {
        for (int col = 0; col < risk.cols; ++col) {
            double& v = risk.value(col, row);
            if (none || (all && v == 0.0)) {
                v = none ? nan : 0.0;
                continue;
            }
            const double sigma_pc = precompression[static_cast<std::size_t>(
                terrain.soilIndexAt(risk.centreX(col), risk.centreY(row)))];
            v = sigma_pc > 0.0 ? v / sigma_pc : nan;
        }
    }
    // The maps lie in the field's coordinate system (their GeoTIFFs say so).
    const std::optional<int> epsg = field::epsgCode(terrain.map());
    for (const auto& entry : mapRasters(maps)) entry.second->epsg = epsg;
    return maps;
}

}  // namespace

RunResult runScenario(const Scenario& scenario, const RunOptions& options) {
    const double dt = scenario.time_step_s;
    const long steps = std::lround(scenario.duration_s / dt);
    const long output_every = std::max<long>(1, std::lround(scenario.output_interval_s / dt));
    const long progress_every = std::max<long>(1, steps / 100);

    const ControllerSpec& control = scenario.controller;
    const bool closed = control.closedLoop();
    dynamics::RoverOptions rover_options = scenario.options;
    if (closed) rover_options.max_motor_torque_nm = control.max_torque_nm;
    std::optional<StreamingHook> hook = scenario.streaming;
    // The optimal set-point needs a soil estimate: the default hook when the scenario has none.
    if (control.type == ControllerType::kOptimal && !hook) hook = StreamingHook{};
    if (closed && hook) hook->from_observer = true;

    dynamics::Commands first = scenario.commandsAt(0.0);
    // A mission steers and drives the wheels from its path (docs/field.md, "Missions").
    std::optional<MissionFollower> mission;
    if (scenario.mission) {
        mission.emplace(scenario, dt);
        first = mission->commands();
    }
    // A field: its terrain, which the rover tells every wheel's passage (docs/field.md).
    std::unique_ptr<dynamics::FieldTerrain> field;
    if (scenario.field) {
        // Every passage is kept for the maps' history (MapHistory: 56 bytes a passage while the
        // run goes on, 52 in the result: its time, cell and the five maps' values).
        dynamics::FieldTerrainOptions field_options = scenario.field_options;
        field_options.record_passages = true;
        field = std::make_unique<dynamics::FieldTerrain>(scenario.field, scenario.robot,
                                                         std::move(field_options));
    }
    std::optional<ClosedLoop> loop;
    if (closed) {
        // The start state only matters for the observer's first reading; the rover takes the
        // controller's first commands.
        dynamics::RoverState start;
        loop.emplace(scenario, options.slip_planner, dt, start, field.get());
        first = loop->initial(first);
    }
    const std::unique_ptr<dynamics::Rover> rover_on =
        field ? std::make_unique<dynamics::Rover>(scenario.robot, *field, rover_options,
                                                  scenario.initial, first)
              : std::make_unique<dynamics::Rover>(scenario.robot, scenario.terrain, rover_options,
                                                  scenario.initial, first);
    dynamics::Rover& rover = *rover_on;
    std::optional<StreamingFeed> feed;
    if (hook) {
        // A robust set-point plans on the estimate's posterior (docs/traction.md §8).
        const bool posterior =
            control.type == ControllerType::kOptimal && control.robust != RobustSlip::kNone;
        // The expected soil (the map's base soil) on this wheel, without j_max.
        identification::DecoupledParameters expected =
            identification::decoupledOf(scenario.terrain.base, scenario.robot.wheel);
        expected.max_shear_deformation_m = std::numeric_limits<double>::infinity();
        if (closed && control.identifier == SoilIdentifier::kFull) {
            // The full-model estimator (docs/traction.md §8): it fits the model the rover drives
            // on and its planner plans on, starts its search from the expected soil too, and
            // estimates the noise levels at each (re)initialisation. j_max is unknown to the
            // robot: none.
            identification::StreamingEstimatorOptions estimator;
            estimator.fit.model = scenario.options.contact.model;
            // Its estimate is planned on as a soil (k_c = 0, k_φ = K_s): the bounds are held
            // inside the soil fields' ranges (n ≥ 0.1, where the identification allows 0.05).
            for (const auto& [parameter, key] : std::initializer_list<std::pair<int, const char*>>{
                     {identification::kA0, "a0"},
                     {identification::kA1, "a1"},
                     {identification::kKs, "kphi"},
                     {identification::kN, "n"},
                     {identification::kC, "c_kPa"},
                     {identification::kPhi, "phi_deg"},
                     {identification::kK, "K_m"}}) {
                const Range range = soil::findSoilField(key)->siRange();
                double& low = estimator.fit.bounds.lower[parameter];
                double& high = estimator.fit.bounds.upper[parameter];
                const double inward = 1e-9 * (range.high - range.low);
                low = std::max(low, range.low + (range.low_open ? inward : 0.0));
                high = std::min(high, range.high - (range.high_open ? inward : 0.0));
            }
            estimator.fit.starts.push_back({"expected soil", identification::vectorOf(expected)});
            feed.emplace(*hook, scenario.robot.wheel, dt, estimator, posterior);
            if (loop) loop->streaming(hook->interval_s, estimator.history, hook->wheel);
        } else {
            identification::StreamingOptions streaming;
            // A closed-loop robot starts from the soil it expects (the map's base soil): at a
            // single load and a narrow band of slip the window cannot tell K_s from n
            // (docs/traction.md §6), and the thesis's generic first guess leaves the fit at its
            // bounds. The streaming estimator never sees j_max: its start carries none.
            if (closed) streaming.initial = expected;
            streaming.covariance = posterior;
            feed.emplace(*hook, scenario.robot.wheel, dt, streaming, posterior);
            if (loop) loop->streaming(hook->interval_s, streaming.window, hook->wheel);
        }
    }
    const bool loaded = scenario.drawbar_load.active();
    double drawbar_n = 0.0;

    RunResult result;
    result.series.columns = seriesColumns();
    if (closed) {
        for (std::string& c : closedLoopColumns()) result.series.columns.push_back(std::move(c));
    }
    if (mission) {
        for (const char* c : {"path_s_m", "path_error_m", "curvature_1_m"})
            result.series.columns.emplace_back(c);
    }
    TractionMetrics metrics;
    auto closedRow = [&](std::vector<double> row) {
        if (closed) {
            const Estimates& est = loop->estimates();
            row.push_back(drawbar_n);
            row.push_back(est.speed_m_s);
            const dynamics::EnergyLedger& e = rover.energy();
            row.push_back(e.motor_work_j - e.steering_work_j);
            for (int i = 0; i < dynamics::kWheelCount; ++i) {
                row.push_back(loop->applied()[i]);
                row.push_back(loop->setPoints()[i]);
                row.push_back(est.slip[i]);
                row.push_back(est.torque_nm[i]);
            }
        }
        if (mission) {
            for (double v : mission->row()) row.push_back(v);
        }
        return row;
    };
    Summary& sum = result.summary;
    DivergenceWatch watch(scenario, rover.state(), field.get());
    // Said with a divergence: whether the step is above the vertical modes' bound or, below it,
    // meets the stiffer lateral and longitudinal forces of slow driving (docs/dynamics.md).
    auto stepHint = [&] {
        const dynamics::StepLimit limit =
            field ? dynamics::largestStableStep(scenario.robot, *field, scenario.options)
                  : dynamics::largestStableStep(scenario.robot, scenario.terrain, scenario.options);
        const double allowed = kStableStepMargin * limit.max_step_s;
        if (dt > allowed) {
            return "the time step " + formatNumber(dt) + " s is above the largest stable step " +
                   formatNumber(roundSignificant(allowed, 2)) + " s (docs/dynamics.md)";
        }
        return "try a smaller time step than " + formatNumber(dt) +
               " s (docs/dynamics.md, \"Step size and stability\")";
    };
    std::array<double, 2> last_xy{rover.state().position_m[0], rover.state().position_m[1]};
    const auto wall_start = std::chrono::steady_clock::now();
    long step = 0;
    for (;; ++step) {
        // Time from the step count (no accumulated rounding): bit-identical reruns and exact
        // signal switching times.
        const double t = static_cast<double>(step) * dt;
        dynamics::Commands commands = mission ? mission->commands() : scenario.commandsAt(t);
        if (loop) loop->apply(commands);
        if (loaded) {
            drawbar_n = std::max(0.0, scenario.drawbar_load.force_n.at(t)) +
                        scenario.drawbar_load.per_speed_n_s_m *
                            std::max(0.0, rover.state().forward_speed_m_s);
            rover.setDrawbarLoad(drawbar_n);
        }
        const dynamics::RoverState& state = rover.evaluate(commands);
        bool commanded = false;
        if (mission && mission->tick(step) && step < steps) {
            mission->control(state);
            // The mission's steering; its wheel speeds unless a slip controller drives them (it
            // keeps each wheel at or below them: M7).
            for (int i = 0; i < dynamics::kWheelCount; ++i) {
                commands[i].steer_angle_rad = mission->commands()[i].steer_angle_rad;
                if (!loop) commands[i].spin_rate_rad_s = mission->commands()[i].spin_rate_rad_s;
            }
            commanded = true;
        }
        if (loop && loop->tick(step) && step < steps) {
            loop->control(state, drawbar_n, commands, mission ? &mission->commands() : nullptr);
            commanded = true;
        }
        if (commanded) rover.setCommands(commands);
        // A mission ends the run when the robot has passed its path's end.
        const bool last = step == steps || (mission && mission->done());
        watch.commanded(commands);
        if (!finite(state)) {
            result.status = RunResult::Status::kDiverged;
            result.message = "the simulation diverged at t = " + formatNumber(t) + " s";
            break;
        }
        if (step % output_every == 0 || last)
            result.series.rows.push_back(closedRow(seriesRow(state)));
        if (feed) {
            const auto update = feed->observe(step, state, loop ? &loop->estimates() : nullptr);
            if (update && loop) loop->streamed(*update, state.time_s);
        }
        if (last) break;
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
            if (c.in_contact) {
                metrics.wheel_output_j += c.forces.fx * state.wheels[i].forward_speed_m_s * dt;
                metrics.wheel_input_j += c.forces.my * state.wheels[i].spin_rate_rad_s * dt;
            }
            if (i >= dynamics::kRearLeft) {
                metrics.rear_sinkage_sum_m += c.sinkage_m;
                ++metrics.rear_sinkage_count;
            }
        }
        rover.advance(dt);
        // The state every step (cheap); the energy ledger every 100 steps (it sums every body).
        std::string diverged = watch.check(rover.state());
        if (diverged.empty() && (step + 1) % 100 == 0) diverged = watch.check(rover.energy());
        if (!diverged.empty()) {
            ++step;
            result.series.rows.push_back(closedRow(seriesRow(rover.state())));
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
    const double wall_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
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
    sum.energy_balance_error =
        energyBalanceError(sum.energy_j, sum.dissipated_j, sum.kinetic_change_j,
                           sum.potential_change_j, e.drawbar_work_j);
    if (feed) result.streaming = feed->take();
    if (loop) {
        loop->finish();
        const TractionMetrics& m = loop->metrics();
        metrics.slip_error_sq_sum = m.slip_error_sq_sum;
        metrics.slip_error_count = m.slip_error_count;
        metrics.border_time_s = m.border_time_s;
        metrics.settling_time_s = m.settling_time_s;
        metrics.settling_band_time_s = m.settling_band_time_s;
        metrics.settle_band = m.settle_band;
        metrics.plans = m.plans;
        metrics.limit_switches = m.limit_switches;
        metrics.limited_time_s = m.limited_time_s;
        sum.traction_limited_switches = m.limit_switches;
        sum.traction_limited_s = m.limited_time_s;
        if (m.slip_error_count > 0) {
            sum.slip_tracking_rms =
                std::sqrt(m.slip_error_sq_sum / static_cast<double>(m.slip_error_count));
        }
    }
    metrics.drive_energy_j = e.motor_work_j - e.steering_work_j;
    metrics.drawbar_work_j = e.drawbar_work_j;
    if (sum.distance_m > 1e-6) sum.energy_per_m_j = metrics.drive_energy_j / sum.distance_m;
    if (metrics.wheel_input_j > 0.0)
        sum.mean_efficiency = metrics.wheel_output_j / metrics.wheel_input_j;
    result.traction = metrics;
    if (mission) sum.mission = mission->outcome();
    if (wall_s > 0.0 && sum.duration_s > 0.0) sum.real_time_factor = sum.duration_s / wall_s;
    if (field) {
        field->finish();
        sum.cells_touched = field->cellsTouched();
        result.maps = fieldMaps(*field);
    }
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
    auto optional = [](const std::optional<double>& v) {
        return v ? nlohmann::json(*v) : nlohmann::json(nullptr);
    };
    j["controller"] = controllerName(scenario.controller.type);  // the one that drove the run
    j["energy_per_m_J"] = optional(s.energy_per_m_j);
    j["mean_efficiency"] = optional(s.mean_efficiency);
    j["slip_tracking_rms"] = optional(s.slip_tracking_rms);
    if (s.traction_limited_switches) j["traction_limited_switches"] = *s.traction_limited_switches;
    if (s.traction_limited_s) j["traction_limited_s"] = *s.traction_limited_s;
    j["real_time_factor"] = optional(s.real_time_factor);
    if (s.cells_touched) j["cells_touched"] = *s.cells_touched;
    if (s.mission) {
        const MissionOutcome& m = *s.mission;
        j["mission_completed"] = m.completed;
        j["mission_time_s"] = m.time_s ? nlohmann::json(*m.time_s) : nlohmann::json(nullptr);
        j["path_length_m"] = m.path_length_m;
        j["path_progress_m"] = m.progress_m;
        j["path_error_rms_m"] = m.error_rms_m;
        j["path_error_max_m"] = m.error_max_m;
    }
    if (result.maps) {
        j["risk_depth_m"] = result.maps->risk_depth_m;
        const auto [lo, hi] = result.maps->rut_depth_m.valueRange();
        (void)lo;
        j["max_rut_depth_m"] = hi;
        // The largest compaction risk over the touched cells; null on a field without a profile.
        const double risk = result.maps->compaction_risk.valueRange().second;
        j["max_compaction_risk"] =
            std::isnan(risk) ? nlohmann::json(nullptr) : nlohmann::json(risk);
    }
    if (std::abs(s.energy_balance_error) > kEnergyBalanceTolerance) {
        j["warning"] = "the energy balance is off by " +
                       formatNumber(roundSignificant(100.0 * s.energy_balance_error, 3)) +
                       " %: the time step is too large for this scenario (docs/dynamics.md)";
    }
    if (!result.message.empty()) j["message"] = result.message;
    return j;
}

namespace {

// The one list of a run's maps, in kMapFiles' order (for both constnesses of mapRasters).
template <typename Maps>
auto namedRasters(Maps& maps) {
    const std::array rasters{&maps.rut_depth_m, &maps.passes, &maps.compaction_risk, &maps.slip,
                             &maps.energy_per_m_j};
    static_assert(rasters.size() == kMapFiles.size(), "a map for each of kMapFiles");
    std::vector<std::pair<std::string, typename decltype(rasters)::value_type>> out;
    for (std::size_t i = 0; i < rasters.size(); ++i) {
        const std::string file = kMapFiles[i];
        out.emplace_back(file.substr(0, file.rfind('.')), rasters[i]);
    }
    return out;
}

}  // namespace

std::vector<std::string> mapFileNames() {
    std::vector<std::string> names;
    for (const char* file : kMapFiles) {
        const std::string name = file;
        const std::string stem = name.substr(0, name.rfind('.'));
        for (const char* extension : kMapFormats) names.push_back(stem + extension);
    }
    names.emplace_back(kMapTableFile);
    return names;
}

Table touchedCells(const FieldMaps& maps) {
    const auto rasters = mapRasters(maps);
    Table table;
    table.columns = {"x_m", "y_m"};
    for (const auto& [key, raster] : rasters) table.columns.push_back(key);
    const field::Raster& passes = maps.passes;
    for (int row = 0; row < passes.rows; ++row) {
        for (int col = 0; col < passes.cols; ++col) {
            const double passed = passes.value(col, row);
            if (!(passed > 0.0)) continue;  // never touched, or no data (NaN)
            std::vector<double> values{passes.centreX(col), passes.centreY(row)};
            for (const auto& [key, raster] : rasters) values.push_back(raster->value(col, row));
            table.rows.push_back(std::move(values));
        }
    }
    return table;
}

std::vector<std::pair<std::string, const field::Raster*>> mapRasters(const FieldMaps& maps) {
    return namedRasters(maps);
}

std::vector<std::pair<std::string, field::Raster*>> mapRasters(FieldMaps& maps) {
    return namedRasters(maps);
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
    // Maps of an earlier field run would pass for this run's likewise.
    if (!result.maps) {
        for (const std::string& name : mapFileNames()) {
            std::filesystem::remove(directory / name, ec);
            if (ec)
                return "cannot remove the earlier " + (directory / name).string() + ": " +
                       ec.message();
        }
    }
    if (auto error =
            io::writeFileAtomically(directory / "timeseries.csv", io::toCsv(result.series))) {
        return error;
    }
    if (result.maps) {
        for (const auto& [stem, raster] : mapRasters(*result.maps)) {
            if (auto error = io::writeRaster(directory / (stem + ".asc"), *raster)) return error;
            if (auto error = io::writeRaster(directory / (stem + ".tif"), *raster)) return error;
        }
        if (auto error = writeMapPngs(*result.maps, directory)) return error;
        if (auto error = io::writeFileAtomically(directory / kMapTableFile,
                                                 io::toCsv(touchedCells(*result.maps)))) {
            return error;
        }
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
