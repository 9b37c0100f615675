#include "core/scenario/traction_control.h"

#include <algorithm>
#include <cmath>

namespace terra::scenario {
namespace {

struct NamedController {
    ControllerType type;
    const char* name;
};
constexpr std::array<NamedController, 4> kControllers{
    {{ControllerType::kConstantSpeed, "constant-speed"},
     {ControllerType::kFixedSlip, "fixed-slip"},
     {ControllerType::kOptimal, "optimal"},
     {ControllerType::kOracle, "oracle"}}};

// Below this rim speed the slip is not defined (0/0): the wheel counts as not slipping [m/s].
constexpr double kStillRim = 1e-3;

}  // namespace

const char* controllerName(ControllerType type) {
    for (const NamedController& c : kControllers)
        if (c.type == type) return c.name;
    return "?";
}

std::optional<ControllerType> controllerFromName(const std::string& name) {
    for (const NamedController& c : kControllers)
        if (name == c.name) return c.type;
    return std::nullopt;
}

const char* robustSlipName(RobustSlip robust) {
    switch (robust) {
        case RobustSlip::kExpected:
            return "expected";
        case RobustSlip::kQuantile:
            return "quantile";
        case RobustSlip::kNone:
            break;
    }
    return "none";
}

const char* soilIdentifierName(SoilIdentifier identifier) {
    return identifier == SoilIdentifier::kFull ? "full" : "decoupled";
}

const char* posteriorMethodName(PosteriorMethod method) {
    return method == PosteriorMethod::kSamples ? "samples" : "sigma-points";
}

const FieldInfo& robustQuantileField() {
    static const FieldInfo field{
        "quantile",
        "-",
        "q",
        "robust quantile",
        "The robust s* maximises this quantile of the objective over the posterior's soils "
        "(0.1: the slip whose objective is at least that good on 90 % of them; 0.5: the median)",
        Range{0.01, 0.99}};
    return field;
}

const std::vector<std::string>& controllerNames() {
    static const std::vector<std::string> names{"constant-speed", "fixed-slip", "optimal",
                                                "oracle"};
    return names;
}

long ticksPerFix(const SensorSpec& sensors, double tick_s) {
    return std::max<long>(1, std::lround(1.0 / (sensors.gnss_rate_hz * tick_s)));
}

namespace {

// The complementary filter's gains at a fix: the speed's k = 2ζω_c Δt_g (ζ = 1, at most 1) and the
// bias's c = ω_c² Δt_g, ω_c = 1/τ (docs/traction.md §4).
struct FilterGains {
    double k, c;
};
FilterGains filterGains(const SensorSpec& sensors, double fix_dt) {
    const double wc = 1.0 / sensors.filter_time_constant_s;
    return {std::min(1.0, 2.0 * wc * fix_dt), wc * wc * fix_dt};
}

// The complementary filter's error e = (e_v, e_b) (speed, and bias minus its estimate) evolves
// linearly: each tick e_v += (e_b + n_a) Δt; at a fix (innovation n_g − e_v) e_v ← (1 − k) e_v +
// k n_g and e_b ← e_b + c (n_g − e_v), k = min(1, 2 ω_c Δt_g), c = ω_c² Δt_g. Its covariance
// P ← A P Aᵀ + Q is iterated over GNSS periods until the period's mean variance settles; the
// stationary standard deviation is its square root (docs/traction.md §4).
double stationarySpeedStd(const SensorSpec& sensors, double dt, long gnss_every) {
    if (gnss_every <= 0) return std::numeric_limits<double>::infinity();
    const auto [k, c] = filterGains(sensors, static_cast<double>(gnss_every) * dt);
    const double qa = std::pow(sensors.accel_noise_m_s2 * dt, 2);
    const double qg = std::pow(sensors.gnss_speed_noise_m_s, 2);
    double pvv = 0.0, pvb = 0.0, pbb = 0.0, mean = 0.0;
    for (int period = 0; period < 100000; ++period) {
        double sum = 0.0;
        for (long tick = 1; tick <= gnss_every; ++tick) {
            // A = [[1, Δt], [0, 1]], Q = diag(σ_a² Δt², 0).
            pvv += 2.0 * dt * pvb + dt * dt * pbb + qa;
            pvb += dt * pbb;
            if (tick == gnss_every) {
                // F = [[1 − k, 0], [−c, 1]], noise (k, c) n_g.
                const double vv = (1 - k) * (1 - k) * pvv + k * k * qg;
                const double vb = (1 - k) * (pvb - c * pvv) + k * c * qg;
                const double bb = pbb - 2.0 * c * pvb + c * c * pvv + c * c * qg;
                pvv = vv, pvb = vb, pbb = bb;
            }
            sum += pvv;
        }
        const double next = sum / static_cast<double>(gnss_every);
        // An unstable filter (a time constant too short for the fix rate: at 5 Hz below ~0.14 s)
        // grows without bound: its error has no stationary σ.
        if (!std::isfinite(next)) return std::numeric_limits<double>::infinity();
        if (std::abs(next - mean) <= 1e-12 * next) return std::sqrt(next);
        mean = next;
    }
    return std::numeric_limits<double>::infinity();  // did not settle
}

}  // namespace

Observer::Observer(const dynamics::RobotParameters& robot, const SensorSpec& sensors,
                   double gravity_m_s2, double interval_s, const dynamics::RoverState& start,
                   double initial_speed_m_s)
    : robot_(robot),
      sensors_(sensors),
      interval_s_(interval_s),
      shear_radius_m_(robot.wheel.radius_m + robot.wheel.lugShearOffset()),
      random_(sensors.seed) {
    // The hubs about the composite centre of mass (chassis COM x-offset weighted by its mass).
    const double com_x = robot.com_forward_m * robot.chassis_mass_kg / robot.totalMass();
    for (int i = 0; i < dynamics::kWheelCount; ++i) {
        static_load_n_[i] = dynamics::staticCornerLoad(robot, gravity_m_s2, i);
        hub_x_m_[i] = (i < 2 ? 0.5 : -0.5) * robot.wheelbase_m - com_x;
        hub_y_m_[i] = (i % 2 == 0 ? 0.5 : -0.5) * robot.track_m;
    }
    if (sensors.gnss_rate_hz > 0.0) {
        gnss_every_ = ticksPerFix(sensors, interval_s);
    }
    speed_std_m_s_ = stationarySpeedStd(sensors, interval_s, gnss_every_);
    // The robot knows it starts as told (at rest, or at the scenario's initial speed).
    est_.speed_m_s = initial_speed_m_s;
    previous_speed_m_s_ = start.forward_speed_m_s;
    est_.load_n = static_load_n_;
    for (int i = 0; i < dynamics::kWheelCount; ++i)
        est_.spin_rate_rad_s[i] = start.wheels[i].spin_rate_rad_s;
}

double Observer::measure(double truth, double sigma) {
    return sigma > 0.0 ? truth + sigma * normal_(random_) : truth;
}

const Estimates& Observer::update(const dynamics::RoverState& truth, double drawbar_n) {
    const double dt = interval_s_;
    // IMU: forward acceleration (finite difference of the true speed over the tick) with bias
    // and noise; yaw rate with noise.
    const double true_accel = first_ ? 0.0 : (truth.forward_speed_m_s - previous_speed_m_s_) / dt;
    previous_speed_m_s_ = truth.forward_speed_m_s;
    const double accel = measure(true_accel, sensors_.accel_noise_m_s2) + sensors_.accel_bias_m_s2;
    est_.yaw_rate_rad_s = measure(truth.angular_velocity_rad_s[2], sensors_.gyro_noise_rad_s);
    est_.accel_m_s2 = accel - bias_estimate_m_s2_;
    // Complementary filter, second order: integrate the IMU; at each GNSS fix pull the speed
    // toward the fix with gain 2ζω_c Δt_g and the bias with ω_c² Δt_g (ζ = 1): IMU at high
    // frequency, GNSS at low, crossover ω_c = 1/τ (docs/traction.md §4).
    if (!first_) est_.speed_m_s += est_.accel_m_s2 * dt;
    ++ticks_;
    if (gnss_every_ > 0 && ticks_ % gnss_every_ == 0) {
        const double fix = measure(truth.forward_speed_m_s, sensors_.gnss_speed_noise_m_s);
        const auto [k, c] = filterGains(sensors_, static_cast<double>(gnss_every_) * dt);
        const double innovation = fix - est_.speed_m_s;
        est_.speed_m_s += k * innovation;
        bias_estimate_m_s2_ -= c * innovation;
    }
    for (int i = 0; i < dynamics::kWheelCount; ++i) {
        const dynamics::WheelState& w = truth.wheels[i];
        const double previous_rate = est_.spin_rate_rad_s[i];
        const double rate = measure(w.spin_rate_rad_s, sensors_.encoder_noise_rad_s);
        est_.spin_rate_rad_s[i] = rate;
        const double delta = w.steer_angle_rad;  // the steering encoder (taken as exact)
        const double cos_d = std::cos(delta), sin_d = std::sin(delta);
        // Hub velocity v + ψ̇ ẑ × arm, along the steered wheel's heading.
        const double vx = est_.speed_m_s - est_.yaw_rate_rad_s * hub_y_m_[i];
        const double vy = est_.yaw_rate_rad_s * hub_x_m_[i];
        est_.hub_speed_m_s[i] = vx * cos_d + vy * sin_d;
        const double rim = shear_radius_m_ * rate;
        est_.slip[i] =
            rim > kStillRim ? std::clamp(1.0 - est_.hub_speed_m_s[i] / rim, -1.0, 1.0) : 0.0;
        // σ_ŝ² = (σ_hub / (r ω))² + (v̂_hub σ_ω / (r ω²))², σ_hub² = σ_v² cos² δ +
        // σ_ψ̇² (x sin δ − y cos δ)² (v̂_hub = v̂ cos δ + ψ̇ (x sin δ − y cos δ)).
        const double arm = hub_x_m_[i] * sin_d - hub_y_m_[i] * cos_d;
        const double hub_var =
            std::pow(speed_std_m_s_ * cos_d, 2) + std::pow(sensors_.gyro_noise_rad_s * arm, 2);
        est_.slip_std[i] = rim > kStillRim
                               ? std::sqrt(hub_var / (rim * rim) +
                                           std::pow(est_.hub_speed_m_s[i] / rim *
                                                        sensors_.encoder_noise_rad_s / rate,
                                                    2))
                               : 1.0;
        est_.torque_nm[i] = measure(w.motor_torque_nm, sensors_.torque_noise_nm);
        est_.resistance_nm[i] =
            est_.torque_nm[i] -
            (first_ ? 0.0 : robot_.wheel_spin_inertia_kg_m2 * (rate - previous_rate) / dt);
    }
    // Loads: the static share plus the longitudinal transfer. The pitch balance of the whole robot
    // about the middle of the wheelbase at the hubs' height (docs/traction.md §4): the wheels'
    // forces act at the hubs (no arm), the chassis' inertia m_c â and the implement's pull F_d at
    // the chassis' centre of mass, d above the hubs, and the soil's resistance torques on the
    // wheels with the wheels' spin-up, Σ (M_y + I_w ω̇) = Σ τ (the motors' torques). So the front
    // axle loses and the rear gains [d (m_c â + F_d) + Σ τ̂] / L.
    double torques = 0.0;
    for (double t : est_.torque_nm) torques += t;
    const double transfer =
        (robot_.com_height_m * (robot_.chassis_mass_kg * est_.accel_m_s2 + drawbar_n) + torques) /
        robot_.wheelbase_m;
    for (int i = 0; i < dynamics::kWheelCount; ++i)
        est_.load_n[i] = std::max(0.0, static_load_n_[i] + (i < 2 ? -0.5 : 0.5) * transfer);
    first_ = false;
    return est_;
}

SlipController::SlipController(const ControllerSpec& spec, double shear_radius_m)
    : spec_(spec), shear_radius_m_(shear_radius_m) {}

double SlipController::command(int wheel, double set_point, const Estimates& est, double dt_s,
                               double max_rate_rad_s) {
    const double feed_forward =
        std::max(0.0, est.hub_speed_m_s[wheel]) / (shear_radius_m_ * (1.0 - set_point));
    const double error = set_point - est.slip[wheel];
    double& integral = integral_[wheel];
    const double raw = feed_forward * (1.0 + spec_.kp * error + integral);
    const double ceiling =
        std::max(spec_.min_spin_rate_rad_s, std::min(spec_.max_spin_rate_rad_s, max_rate_rad_s));
    const double out = std::clamp(raw, spec_.min_spin_rate_rad_s, ceiling);
    // Conditional integration (anti-windup): no integration that would push further into the
    // output clamps or further against a motor at its torque limit.
    const bool torque_limited = std::abs(est.torque_nm[wheel]) >= 0.98 * spec_.max_torque_nm;
    const bool pushing_up = error > 0.0;
    const bool saturated_up = raw >= ceiling || torque_limited;
    const bool saturated_down = raw <= spec_.min_spin_rate_rad_s;
    if (!((pushing_up && saturated_up) || (!pushing_up && saturated_down)))
        integral += spec_.ki_per_s * error * dt_s;
    return out;
}

TractionLimiter::TractionLimiter(const ControllerSpec& spec, double mass_kg, double interval_s)
    : spec_(spec),
      mass_kg_(mass_kg),
      interval_s_(interval_s),
      engage_ticks_(std::max<long>(1, std::lround(kEngageTime_s / interval_s))) {}

double TractionLimiter::update(double time_s,
                               const std::array<double, dynamics::kWheelCount>& planned,
                               const std::array<double, dynamics::kWheelCount>& applied,
                               const std::array<bool, dynamics::kWheelCount>& at_floor,
                               const Estimates& est, double drawbar_n) {
    const double dt = interval_s_;
    // P = F_d + m â = ΣF_x − G (the chassis' forward balance), low-passed.
    const double pull = drawbar_n + mass_kg_ * est.accel_m_s2;
    if (!pull_started_) {
        pull_ = pull;
        hitch_ = drawbar_n;
        speed_ = est.speed_m_s;
        pull_started_ = true;
    } else {
        const double gain = std::min(1.0, dt / kPullTime_s);
        pull_ += gain * (pull - pull_);
        hitch_ += gain * (drawbar_n - hitch_);
        speed_ += gain * (est.speed_m_s - speed_);
    }
    if (time_s < 1.0) return floor_;  // spin-up from rest: every command starts at the floor
    constexpr double n = dynamics::kWheelCount;
    double over = 0.0, slip = 0.0, plan = 0.0;
    bool all_at_floor = true;
    for (int i = 0; i < dynamics::kWheelCount; ++i) {
        over += (est.slip[i] - applied[i]) / n;
        slip += est.slip[i] / n;
        plan += planned[i] / n;
        all_at_floor = all_at_floor && at_floor[i];
    }
    // Time at the floor: a leaky count (up a tick at the floor, down a tick otherwise) and the
    // window of every tick since it left 0 — not only those at the floor: the PI drops the
    // command to the floor when ŝ is high and lifts it when ŝ is low, so the floor's ticks alone
    // would average the observer's noise into a slip too high (measured: +0.05 on the slope).
    if (all_at_floor) {
        ++stall_ticks_;
    } else if (stall_ticks_ > 0 && --stall_ticks_ == 0) {
        resetStallWindow();
    }
    if (stall_ticks_ > 0) {
        stall_over_sum_ += over;
        stall_slip_sum_ += slip;
        stall_pull_sum_ += pull_;
        stall_hitch_sum_ += hitch_;
        stall_speed_sum_ += speed_;
        ++stall_samples_;
    }
    if (stall_ticks_ >= engage_ticks_) {
        const double samples = static_cast<double>(stall_samples_);
        if (stall_over_sum_ / samples <= kStallMargin) {
            // At the floor with the slip at (or below) the set-point: slow, not traction-limited.
            resetStallWindow();
            return stepFloor(plan);
        }
        // Engage, or raise further while engaged (the need grew): the floor from the applied
        // set-points' mean toward the slip the robot needs plus the margin.
        need_ = stall_slip_sum_ / samples;
        stall_pull_ = stall_pull_sum_ / samples;
        stall_hitch_ = stall_hitch_sum_ / samples;
        stall_speed_ = stall_speed_sum_ / samples;
        if (!engaged()) {
            ++switches_;
            double mean_applied = 0.0;
            for (double a : applied) mean_applied += a / n;
            floor_ = std::max(floor_, mean_applied);
        }
        target_ = std::max(target_, std::min(need_ + spec_.limit_margin, 0.95));
        at_target_s_ = 0.0;
        bought_.reset();
        resetStallWindow();
    }
    stepFloor(plan);
    if (!engaged()) return floor_;
    if (floor_ != target_) return floor_;
    at_target_s_ += dt;
    if (at_target_s_ < kSettleTime_s) return floor_;
    if (!bought_) {
        // What the margin bought at the same need: k = (P − P_stall) / (s_floor − s_need), and
        // the implement's pull per speed it went into, ĉ = ΔF_d / Δv̂.
        const double gained = pull_ - stall_pull_;
        const double faster = speed_ - stall_speed_;
        if (gained >= kMinBoughtPull_n && floor_ > need_ && faster >= kMinFaster_m_s) {
            bought_ = gained / (floor_ - need_);
            per_speed_ = (hitch_ - stall_hitch_) / faster;
        }
        return floor_;
    }
    // Release: the reserve over the need at rest, R = ĉ (v̂ − v̂_stall) + m â, less what the plans
    // give up, k (s_floor − s̄_plan), is at least the margin's reserve k δ.
    const double reserve = per_speed_ * (speed_ - stall_speed_) + (pull_ - hitch_);
    if (reserve >= *bought_ * (floor_ - plan + spec_.limit_margin)) {
        target_ = 0.0;
        ++switches_;
        bought_.reset();
    }
    return floor_;
}

void TractionLimiter::resetStallWindow() {
    stall_ticks_ = 0;
    stall_over_sum_ = stall_slip_sum_ = stall_pull_sum_ = stall_hitch_sum_ = stall_speed_sum_ = 0.0;
    stall_samples_ = 0;
}

double TractionLimiter::stepFloor(double mean_plan) {
    // The floor's rate limit.
    const double step = kRaiseRate_per_s * interval_s_;
    floor_ = std::abs(target_ - floor_) <= step ? target_
                                                : floor_ + std::copysign(step, target_ - floor_);
    if (floor_ > mean_plan) limited_s_ += interval_s_;
    return floor_;
}

long stepsPerTick(double interval_s, double time_step_s) {
    return std::max<long>(1, std::lround(interval_s / time_step_s));
}

std::vector<Issue> validate(const ControllerSpec& spec, const DrawbarLoad& load,
                            const std::string& prefix, double time_step_s) {
    std::vector<Issue> issues;
    const std::string c = prefix + "controller.";
    const ControllerRanges& r = kControllerRanges;
    checkRange(issues, c + "slip", spec.slip, r.slip);
    checkRange(issues, c + "slip_min", spec.slip_min, r.slip);
    checkRange(issues, c + "slip_max", spec.slip_max, r.slip);
    if (!(spec.slip_min < spec.slip_max)) {
        issues.push_back(
            {c + "slip_max", formatNumber(spec.slip_max) +
                                 " must be above slip_min = " + formatNumber(spec.slip_min)});
    }
    checkRange(issues, c + "max_torque_Nm", spec.max_torque_nm, r.torque, "N·m");
    checkRange(issues, c + "max_omega_rad_s", spec.max_spin_rate_rad_s, r.spin_rate, "rad/s");
    checkRange(issues, c + "min_omega_rad_s", spec.min_spin_rate_rad_s, r.min_spin_rate, "rad/s");
    if (spec.min_spin_rate_rad_s >= spec.max_spin_rate_rad_s) {
        issues.push_back({c + "min_omega_rad_s", formatNumber(spec.min_spin_rate_rad_s) +
                                                     " must be below max_omega_rad_s = " +
                                                     formatNumber(spec.max_spin_rate_rad_s)});
    }
    checkRange(issues, c + "kp", spec.kp, r.gain);
    checkRange(issues, c + "ki_per_s", spec.ki_per_s, r.gain, "1/s");
    checkRange(issues, c + "interval_s", spec.interval_s, r.interval, "s");
    checkRange(issues, c + "replan_interval_s", spec.replan_interval_s, r.replan_interval, "s");
    checkRange(issues, c + "dither", spec.dither, {0.0, 0.3});
    checkRange(issues, c + "dither_period_s", spec.dither_period_s, {0.01, 1000.0}, "s");
    checkRange(issues, c + "limit_margin", spec.limit_margin, r.limit_margin);
    if (spec.replan_samples < 1 || spec.replan_samples > 10000) {
        issues.push_back(
            {c + "replan_samples", std::to_string(spec.replan_samples) + " is outside [1, 10000]"});
    }
    checkRange(issues, c + robustQuantileField().key, spec.quantile, robustQuantileField().range);
    if (spec.posterior_samples < kMinPosteriorSamples ||
        spec.posterior_samples > kMaxPosteriorSamples) {
        issues.push_back({c + "posterior_samples", std::to_string(spec.posterior_samples) +
                                                       " is outside [" +
                                                       std::to_string(kMinPosteriorSamples) + ", " +
                                                       std::to_string(kMaxPosteriorSamples) + "]"});
    }
    const SensorSpec& s = spec.sensors;
    const std::string n = c + "sensors.";
    const Range noise{0.0, 100.0};
    checkRange(issues, n + "encoder_noise_rad_s", s.encoder_noise_rad_s, noise, "rad/s");
    checkRange(issues, n + "torque_noise_Nm", s.torque_noise_nm, noise, "N·m");
    checkRange(issues, n + "accel_noise_m_s2", s.accel_noise_m_s2, noise, "m/s²");
    checkRange(issues, n + "accel_bias_m_s2", s.accel_bias_m_s2, {-10.0, 10.0}, "m/s²");
    checkRange(issues, n + "gyro_noise_rad_s", s.gyro_noise_rad_s, noise, "rad/s");
    checkRange(issues, n + "gnss_rate_Hz", s.gnss_rate_hz, {0.0, 100.0}, "Hz");
    checkRange(issues, n + "gnss_speed_noise_m_s", s.gnss_speed_noise_m_s, noise, "m/s");
    checkRange(issues, n + "filter_time_constant_s", s.filter_time_constant_s, {0.01, 100.0}, "s");
    checkRange(issues, n + "sinkage_noise_m", s.sinkage_noise_m, {0.0, 0.1}, "m");
    checkRange(issues, n + "hub_force_noise_N", s.hub_force_noise_n, {0.0, 1e4}, "N");
    // The control tick as the run takes it: a whole number of physics steps.
    const double tick =
        time_step_s > 0.0
            ? static_cast<double>(stepsPerTick(spec.interval_s, time_step_s)) * time_step_s
            : spec.interval_s;
    if (s.gnss_rate_hz > 0.0 && tick > 0.0 && 1.0 / s.gnss_rate_hz < tick) {
        issues.push_back({n + "gnss_rate_Hz", formatNumber(s.gnss_rate_hz) +
                                                  " Hz is faster than the control rate " +
                                                  formatNumber(1.0 / tick) + " Hz"});
    } else if (s.gnss_rate_hz > 0.0 && tick > 0.0 && s.filter_time_constant_s > 0.0) {
        // The complementary filter is stable only for τ > Δt_g/√2 (docs/traction.md §4, "How
        // well the slip is known"): a shorter one makes the speed estimate diverge.
        const double fix_dt = static_cast<double>(ticksPerFix(s, tick)) * tick;
        const double shortest = fix_dt / std::sqrt(2.0);
        if (!(s.filter_time_constant_s > shortest)) {
            // Shown rounded up to four digits: every value of the range printed is accepted.
            const double scale = std::pow(10.0, 3.0 - std::floor(std::log10(shortest)));
            const std::string bound = formatNumber(std::ceil(shortest * scale) / scale);
            issues.push_back({n + "filter_time_constant_s",
                              formatNumber(s.filter_time_constant_s) +
                                  " s makes the speed filter unstable with a GNSS fix every " +
                                  formatNumber(roundSignificant(fix_dt, 6)) +
                                  " s (it needs more than that over √2; docs/traction.md §4); "
                                  "allowed range (" +
                                  bound + ", 100] s"});
        }
    }
    checkRange(issues, prefix + "drawbar_load.per_speed_N_s_m", load.per_speed_n_s_m, {0.0, 1e5},
               "N·s/m");
    return issues;
}

}  // namespace terra::scenario
