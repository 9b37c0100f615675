#pragma once
/// @file traction_control.h
/// Predictive traction control in the rover (docs/traction.md §4–§6): what a robot measures
/// (encoders, motor torques, an IMU, GNSS at a few Hz, all with seeded noise), the observer that
/// turns it into ground speed, per-wheel slip ŝ = 1 − v̂_hub/(r ω) and wheel loads, and the
/// per-wheel slip controller (PI with anti-windup, feed-forward ω = v̂_hub / (r (1 − s_set)),
/// under the motors' torque limit) with its set-point: fixed, optimal from the streaming soil
/// estimate, or the oracle's from the true soil.

#include <algorithm>
#include <array>
#include <functional>
#include <limits>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "core/common/field.h"
#include "core/common/issue.h"
#include "core/common/range.h"
#include "core/contact/contact_parameters.h"
#include "core/dynamics/robot.h"
#include "core/dynamics/rover.h"
#include "core/scenario/signal.h"
#include "core/soil/soil_parameters.h"
#include "core/soil/soil_posterior.h"

namespace terra::scenario {

/// How each wheel's spin rate is chosen.
enum class ControllerType {
    kConstantSpeed,  ///< the scenario's ω(t) per wheel, ideal servos (the thesis; the default)
    kFixedSlip,      ///< slip held at a fixed set-point (tractor practice, 8–16 %)
    kOptimal,        ///< s* of the streaming identifier's soil estimate, re-planned on a change
    kOracle,         ///< s* of the true soil under each wheel (cached per soil patch)
};
const char* controllerName(ControllerType type);
/// "constant-speed", "fixed-slip", "optimal", "oracle"; nullopt for anything else.
std::optional<ControllerType> controllerFromName(const std::string& name);
const std::vector<std::string>& controllerNames();

/// What s* maximises (analysis::TractionObjective, without including analysis/).
enum class SlipObjective { kEfficiency, kDrawbar };

/// Which slip the optimal controller plans from its soil estimate (docs/traction.md §8):
/// s* of the estimate itself, or a robust s* over the estimate's posterior (the streaming
/// identifier's covariance) as `terrastudio traction --posterior` computes it.
enum class RobustSlip {
    kNone,      ///< "none": s* of the point estimate (`optimal_slip`)
    kExpected,  ///< "expected": the slip of the largest expected objective (`expected_slip`)
    kQuantile,  ///< "quantile": the largest `quantile` of the objective (`robust_slip`)
};
const char* robustSlipName(RobustSlip robust);

/// The streaming soil estimator whose estimate the optimal controller plans on (key
/// "identifier", docs/traction.md §8): the thesis's decoupled model refitted on a sliding window
/// (identification/streaming.h), or the seven-parameter wheel model of the scenario's contact
/// model as a moving-horizon estimate (identification/streaming_estimator.h).
enum class SoilIdentifier {
    kDecoupled,  ///< "decoupled"
    kFull,       ///< "full"
};
const char* soilIdentifierName(SoilIdentifier identifier);

/// How a robust s* carries the posterior through the objective (key "posterior_method",
/// docs/traction.md §8, "Cost"): soils drawn at random (`posterior_samples` of them), or the
/// 2d + 1 sigma points of a second-order divided-difference transform (Nørgaard, Poulsen & Ravn
/// 2000), whose mean and variance of the objective give its quantile as a normal's.
enum class PosteriorMethod {
    kSigmaPoints,  ///< "sigma-points"
    kSamples,      ///< "samples"
};
const char* posteriorMethodName(PosteriorMethod method);
/// The robust s*'s quantile q (key "quantile"): declared once for the controller's object and
/// `traction`'s settings (analysis/traction.h), range [0.01, 0.99].
const FieldInfo& robustQuantileField();
/// Soils drawn from the posterior for a robust s* ("posterior_samples", as `traction`'s).
inline constexpr int kMinPosteriorSamples = 10, kMaxPosteriorSamples = 100000;

/// The robot's sensors. Noise is Gaussian, standard deviations; the seed makes runs repeat.
struct SensorSpec {
    double encoder_noise_rad_s = 0.002;   ///< ω per wheel [rad/s]
    double torque_noise_nm = 0.02;        ///< motor torque (from the current) per wheel [N·m]
    double accel_noise_m_s2 = 0.02;       ///< IMU forward acceleration [m/s²]
    double accel_bias_m_s2 = 0.01;        ///< its constant bias [m/s²] (what GNSS corrects)
    double gyro_noise_rad_s = 0.002;      ///< IMU yaw rate [rad/s]
    double gnss_rate_hz = 5.0;            ///< GNSS speed fixes per second; 0: no GNSS
    double gnss_speed_noise_m_s = 0.003;  ///< GNSS (Doppler) ground speed [m/s]
    double filter_time_constant_s = 1.0;  ///< complementary filter crossover 1/ω_c [s]
    double sinkage_noise_m = 0.0005;      ///< θ_f from a sinkage sensor, as h [m]
    double hub_force_noise_n = 0.2;       ///< F_x from a hub load cell [N]
    unsigned seed = 1;
};

/// The scenario's "controller" object (docs/traction.md §5).
struct ControllerSpec {
    ControllerType type = ControllerType::kConstantSpeed;
    double slip = 0.15;  ///< fixed-slip set-point; optimal's until its first estimate [-]
    SlipObjective objective = SlipObjective::kEfficiency;
    double slip_min = 0.05;  ///< planned set-points are kept in [slip_min, slip_max] [-]
    double slip_max = 0.7;
    double max_torque_nm = 4.0;        ///< each drive motor's torque limit [N·m]
    double max_spin_rate_rad_s = 4.0;  ///< each drive motor's speed limit [rad/s]
    /// Start-up floor of the command [rad/s]: at rest the feed-forward is 0 and the slip of a
    /// barely turning wheel jumps between 0 and 1; the wheel turns at least this fast.
    double min_spin_rate_rad_s = 0.2;
    double kp = 0.2;           ///< proportional gain [per unit slip, relative to ω_ff]
    double ki_per_s = 0.5;     ///< integral gain [1/s per unit slip, relative to ω_ff]
    double interval_s = 0.01;  ///< control period [s] (100 Hz)
    /// optimal: samples of a soil in the identifier's window before its estimate is planned on
    /// (the first plan, and the first after a confirmed change: the estimate of the old soil is
    /// no plan for the new one). With a dither the window must also span one dither period
    /// (both halves of the square wave), capped at the window's length.
    int replan_samples = 20;
    /// optimal: once planned, the set-points are re-planned on the current estimate this often
    /// [s] (the estimate keeps improving as the window fills; a first plan is never final).
    double replan_interval_s = 4.0;
    /// optimal: a square wave of ± this added to the planned set-point [-] (period
    /// `dither_period_s`): persistent excitation, without which every sample of the identifier's
    /// window sits at one slip and the slip-dependent parameters are not identifiable.
    double dither = 0.1;
    double dither_period_s = 4.0;  ///< [s]
    /// The traction-limited mode (docs/traction.md §5, "Traction-limited"): when the wheels stall
    /// at the command's floor with their slip above the set-point (the set-point's pull is below
    /// what the robot needs), every set-point is raised to the slip measured there plus
    /// `limit_margin`, capped at the drawbar-maximising slip; back to the plan when the hitch pull
    /// shows the need has fallen. Off by default (a plain slip controller, as before).
    bool traction_limited = false;
    double limit_margin = 0.05;  ///< the raise above the slip the robot needs [-]
    /// optimal: plan s* of the estimate (none) or a robust s* over its posterior (expected,
    /// quantile), with `quantile` and `posterior_samples` as `traction --posterior` (§8).
    RobustSlip robust = RobustSlip::kNone;
    double quantile = 0.1;
    int posterior_samples = 200;
    /// optimal, robust: how the posterior is carried through the objective.
    PosteriorMethod posterior_method = PosteriorMethod::kSigmaPoints;
    /// optimal: the streaming soil estimator planned on (docs/traction.md §9: the full model's
    /// plans are far closer to the oracle's after the border, and with the observer's σ_ŝ it
    /// raised no false change on uniform soil over eight seeds; the decoupled identifier stays
    /// the default).
    SoilIdentifier identifier = SoilIdentifier::kDecoupled;
    SensorSpec sensors;

    bool closedLoop() const { return type != ControllerType::kConstantSpeed; }
};

/// Allowed ranges of the controller's fields (the JSON reader and validate() name them).
struct ControllerRanges {
    Range slip{0.0, 0.95, true, false};  ///< (0, 0.95]
    Range torque{0.0, 1e4, false, true};
    Range spin_rate{0.0, 1000.0, false, true};
    Range min_spin_rate{0.0, 100.0};
    Range gain{0.0, 100.0};
    Range interval{1e-4, 1.0};
    Range replan_interval{0.1, 1e4};            ///< optimal's re-planning period [s]
    Range limit_margin{0.0, 0.3, true, false};  ///< (0, 0.3]
};
inline const ControllerRanges kControllerRanges{};

/// The towed implement: F_d(t) = force(t) + per_speed × v [N], v the forward speed (≥ 0).
struct DrawbarLoad {
    Signal force_n = Signal::constant(0.0);  ///< [N], ≥ 0
    double per_speed_n_s_m = 0.0;            ///< [N·s/m], ≥ 0
    bool active() const {
        return per_speed_n_s_m != 0.0 || force_n.kind != Signal::Kind::kConstant ||
               force_n.value != 0.0;
    }
};

/// A slip to plan: s* for this soil, wheel and load (docs/traction.md §1).
struct SlipPlanRequest {
    soil::SoilParameters soil;
    wheel::WheelParameters wheel;
    double load_n = 0.0;
    SlipObjective objective = SlipObjective::kEfficiency;
    double slip_min = 0.05, slip_max = 0.7;
    contact::ContactModel model = contact::ContactModel::kQuadratic;
    /// With a posterior (the soil's parameters as a normal about `soil`'s values): which slip,
    /// its quantile and the soils drawn (TractionSettings' posterior, quantile,
    /// posterior_samples; seed 1, as `traction`'s default).
    std::optional<soil::SoilPosterior> posterior;
    RobustSlip robust = RobustSlip::kNone;
    double quantile = 0.1;
    int posterior_samples = 200;
    PosteriorMethod posterior_method = PosteriorMethod::kSamples;
};
/// A planned slip: the set-point, and with a posterior the spread of s* over it (the standard
/// deviation of the drawn soils' own s*, docs/traction.md §6 "Settling").
struct SlipPlan {
    double slip = 0.0;
    std::optional<double> spread;
};
/// s*, or nullopt when the soil cannot carry the load. analysis::runRover passes
/// computeTraction (core/scenario may not include analysis/).
using SlipPlanner = std::function<std::optional<SlipPlan>(const SlipPlanRequest&)>;

/// What the observer believes at one control tick.
struct Estimates {
    double speed_m_s = 0.0;       ///< v̂ of the centre of mass along the heading [m/s]
    double yaw_rate_rad_s = 0.0;  ///< measured ψ̇ [rad/s]
    double accel_m_s2 = 0.0;      ///< measured forward acceleration minus the estimated bias
    std::array<double, dynamics::kWheelCount> spin_rate_rad_s{};  ///< encoders [rad/s]
    std::array<double, dynamics::kWheelCount> hub_speed_m_s{};    ///< v̂_hub [m/s]
    std::array<double, dynamics::kWheelCount> slip{};             ///< ŝ [-]
    /// σ_ŝ [-]: the standard error of ŝ from the speed estimate's and the encoder's (∞ with no
    /// GNSS: the speed's error then grows without bound; 1 for a wheel at rest).
    std::array<double, dynamics::kWheelCount> slip_std{};
    std::array<double, dynamics::kWheelCount> load_n{};         ///< Ŵ [N]
    std::array<double, dynamics::kWheelCount> torque_nm{};      ///< measured motor torque
    std::array<double, dynamics::kWheelCount> resistance_nm{};  ///< M̂_y = τ − I_w ω̇ [N·m]
};

/// The control ticks of `tick_s` between GNSS fixes as the observer takes them (≥ 1; the rate
/// must be positive).
long ticksPerFix(const SensorSpec& sensors, double tick_s);

/// The simulated sensors and the observer (docs/traction.md §4). update() is called at every
/// control tick with the true state; it draws the measurements and updates the estimates.
class Observer {
public:
    Observer(const dynamics::RobotParameters& robot, const SensorSpec& sensors, double gravity_m_s2,
             double interval_s, const dynamics::RoverState& start, double initial_speed_m_s);

    /// `drawbar_n`: the hitch load cell's reading (the implement's pull) [N].
    const Estimates& update(const dynamics::RoverState& truth, double drawbar_n);
    const Estimates& estimates() const { return est_; }
    /// A noisy reading of the true value, σ = `sigma` (for the identifier's measured channels).
    double measure(double truth, double sigma);
    /// The stationary standard deviation of the speed estimate's error, averaged over a GNSS
    /// period [m/s] (docs/traction.md §4, "How well the slip is known"); ∞ without GNSS or when
    /// the filter is unstable (a time constant too short for the fix rate).
    double speedStd() const { return speed_std_m_s_; }

private:
    dynamics::RobotParameters robot_;
    SensorSpec sensors_;
    double interval_s_;
    double shear_radius_m_;
    std::array<double, dynamics::kWheelCount> static_load_n_{};
    std::array<double, dynamics::kWheelCount> hub_x_m_{}, hub_y_m_{};  // from the composite COM
    std::mt19937_64 random_;
    std::normal_distribution<double> normal_{0.0, 1.0};
    Estimates est_;
    double previous_speed_m_s_ = 0.0;  // truth, for the IMU's acceleration
    double bias_estimate_m_s2_ = 0.0;
    long ticks_ = 0;
    long gnss_every_ = 0;  // ticks between GNSS fixes; 0: none
    double speed_std_m_s_ = 0.0;
    bool first_ = true;
};

/// The per-wheel slip controller: ω_cmd = sat[ω_min, ω_max](ω_ff (1 + k_p e + I)), e = s_set − ŝ,
/// I ← I + k_i e Δt, ω_ff = v̂_hub / (r_s (1 − s_set)) (Eq. 2.1 solved for ω). The gains are
/// relative to ω_ff, so the loop's gain does not grow as the robot slows (∂s/∂ω = (1 − s)/ω).
/// The integral is updated only when that does not push further into a saturation (conditional
/// integration: the output clamps, or a motor at its torque limit).
class SlipController {
public:
    SlipController(const ControllerSpec& spec, double shear_radius_m);
    /// The spin rate to command for wheel `wheel` until the next tick [rad/s], at most
    /// `max_rate_rad_s` (a mission's speed for the wheel; never below the start-up floor), which
    /// counts as a saturation for the anti-windup as the motor's own limit does.
    double command(int wheel, double set_point, const Estimates& est, double dt_s,
                   double max_rate_rad_s = std::numeric_limits<double>::infinity());
    void reset(int wheel) { integral_[wheel] = 0.0; }

private:
    ControllerSpec spec_;
    double shear_radius_m_;
    std::array<double, dynamics::kWheelCount> integral_{};
};

/// The traction-limited mode's supervisor (docs/traction.md §5, "Traction-limited"): a floor
/// s_floor under every wheel's set-point, s_eff,i = max(s_plan,i, min(cap_i, s_floor)).
/// - Engage: every wheel's command at the start-up floor for kEngageTime_s (a leaky count, from
///   t = 1 s) with the wheels' mean slip ŝ over the count's window above their mean applied
///   set-point by kStallMargin: the set-point cannot be held and the robot crawls at the slip it
///   needs, s_need (that mean ŝ). The floor's target is s_need + `limit_margin`.
/// - Release: P = F_d + m â (hitch load cell and IMU) is the wheels' pull beyond the slope's
///   need G, ΣF_x(s) − G, low-passed. Settled (kSettleTime_s at its target), the robot measures
///   what the margin bought, k = (P − P_stall) / (s_floor − s_need) [N per unit slip], and the
///   implement's pull per speed it went into, ĉ = (F_d − F_d,stall) / (v̂ − v̂_stall). Its reserve
///   over the need at rest is then R = ĉ (v̂ − v̂_stall) + m â (k δ when settled); a fall of the
///   slope's or the implement's static pull speeds the robot up and raises R. The plans carry the
///   robot with the same reserve once R ≥ k (s_floor − s̄_plan + margin).
/// - s_floor moves toward its target at kRaiseRate_per_s (no steps, no chattering).
class TractionLimiter {
public:
    static constexpr double kStallMargin = 0.05;      ///< mean ŝ − s_set of a stall [-]
    static constexpr double kEngageTime_s = 3.0;      ///< at the floor this long (leaky) [s]
    static constexpr double kSettleTime_s = 5.0;      ///< at the target before a release [s]
    static constexpr double kRaiseRate_per_s = 0.05;  ///< the floor's rate limit [1/s]
    static constexpr double kPullTime_s = 2.0;        ///< low-pass of P [s]
    static constexpr double kMinBoughtPull_n = 0.1;   ///< below: k unknown, no release [N]
    static constexpr double kMinFaster_m_s = 0.01;    ///< below: ĉ unknown, no release [m/s]

    /// `mass_kg`: the robot's (m in P = F_d + m â); `interval_s`: the control period [s].
    TractionLimiter(const ControllerSpec& spec, double mass_kg, double interval_s);

    /// One control tick at `time_s`: the planned and applied set-points, whether each command
    /// sits at its floor, the estimates and the hitch pull [N]. Returns s_floor.
    double update(double time_s, const std::array<double, dynamics::kWheelCount>& planned,
                  const std::array<double, dynamics::kWheelCount>& applied,
                  const std::array<bool, dynamics::kWheelCount>& at_floor, const Estimates& est,
                  double drawbar_n);

    /// The set-point floor s_floor [-] (0 when the mode is off).
    double floor() const { return floor_; }
    /// wheel i's effective set-point: max(plan, min(cap, s_floor)).
    double effective(double plan, double cap) const {
        return std::max(plan, std::min(cap, floor_));
    }
    bool engaged() const { return target_ > 0.0; }
    int switches() const { return switches_; }         ///< engagements plus releases
    double limitedTime() const { return limited_s_; }  ///< time with s_floor above the plans [s]

private:
    ControllerSpec spec_;
    double mass_kg_, interval_s_;
    void resetStallWindow();
    double stepFloor(double mean_plan);

    double floor_ = 0.0, target_ = 0.0;
    long engage_ticks_;
    long stall_ticks_ = 0;  // leaky count of ticks at the floor
    double stall_over_sum_ = 0.0, stall_slip_sum_ = 0.0, stall_pull_sum_ = 0.0;
    double stall_hitch_sum_ = 0.0, stall_speed_sum_ = 0.0;
    long stall_samples_ = 0;
    double need_ = 0.0;         // s_need
    double stall_pull_ = 0.0;   // P_stall [N]
    double stall_hitch_ = 0.0;  // F_d at the stall [N]
    double stall_speed_ = 0.0;  // v̂ at the stall [m/s]
    double pull_ = 0.0;         // P low-passed [N]
    double hitch_ = 0.0;        // F_d low-passed [N]
    double speed_ = 0.0;        // v̂ low-passed [m/s]
    double per_speed_ = 0.0;    // ĉ [N·s/m], once settled
    bool pull_started_ = false;
    double at_target_s_ = 0.0;      // time at the target since the last engagement [s]
    std::optional<double> bought_;  // k [N per unit slip], once settled
    int switches_ = 0;
    double limited_s_ = 0.0;
};

/// One plan of the optimal controller: what it asked the planner and what it got.
struct PlanRecord {
    double time_s = 0.0;
    int wheel = 0;
    SlipPlanRequest request;
    SlipPlan plan;
};

/// The drive's figures of merit of a run (summary.json and the comparison table).
struct TractionMetrics {
    double drive_energy_j = 0.0;     ///< ∫ Σ τ ω dt of the spin motors [J]
    double wheel_output_j = 0.0;     ///< ∫ Σ F_x v_x dt [J]
    double wheel_input_j = 0.0;      ///< ∫ Σ M_y ω dt [J]
    double drawbar_work_j = 0.0;     ///< ∫ F_d v dt [J]
    double slip_error_sq_sum = 0.0;  ///< Σ (s − s_set)² over wheel-ticks
    long slip_error_count = 0;
    double rear_sinkage_sum_m = 0.0;  ///< Σ h of the rear wheels over steps (the rut)
    long rear_sinkage_count = 0;
    /// After the first soil change under the front-left wheel: when it happened and how long its
    /// set-point took to come within kSettleTolerance of the oracle's for the new soil, for good
    /// (optimal and oracle controllers; the oracle's own is 0).
    std::optional<double> border_time_s;
    std::optional<double> settling_time_s;
    /// The same within the band its posterior supports, max(kSettleTolerance, 2 σ_s*) with σ_s*
    /// the spread of the plan in force (SlipPlan::spread; optimal with a robust set-point only).
    std::optional<double> settling_band_time_s;
    std::optional<double> settle_band;  ///< that tolerance at the end of the run [-]
    /// The optimal controller's plans of the efficiency (or drawbar) set-points, in order.
    std::vector<PlanRecord> plans;
    /// The traction-limited mode (when enabled): engagements plus releases, and the time with a
    /// raised set-point [s].
    std::optional<int> limit_switches;
    std::optional<double> limited_time_s;
};
/// |s_set − s*_oracle| within which a set-point counts as settled [-].
inline constexpr double kSettleTolerance = 0.03;

/// The physics steps of `time_step_s` (> 0) in a control period of `interval_s`, as a run takes
/// it: the nearest whole number, at least 1.
long stepsPerTick(double interval_s, double time_step_s);

/// Every problem of the controller and the drawbar load (names under `prefix`); the sensors'
/// checks take the control tick on physics steps of `time_step_s` (stepsPerTick; `interval_s`
/// itself when the step is not positive).
std::vector<Issue> validate(const ControllerSpec& spec, const DrawbarLoad& load,
                            const std::string& prefix = {}, double time_step_s = 0.0);

}  // namespace terra::scenario
