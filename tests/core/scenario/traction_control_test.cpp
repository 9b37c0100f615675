// The closed loop in the rover (docs/traction.md §4–§5): the observer against the truth it does
// not see, the slip controllers against their set-points, the motor torque limit, the drawbar
// load's work in the energy balance, and the constant-speed default untouched. The set-points
// here come from a stand-in planner (a fixed slip per soil name): what is tested is the loop, not
// computeTraction (tests/core/analysis/traction_control_run_test.cpp runs the real one).
#include "core/scenario/traction_control.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <optional>

#include "core/io/parameters_json.h"
#include "core/scenario/runner.h"
#include "core/scenario/scenario_json.h"
#include "tests/core/test_support.h"

namespace terra::scenario {
namespace {

using terra::testing::kLocations;

// The straight-line scenario on sandy loam (quadratic model: fast), towing an implement whose
// pull grows with speed, so that every slip set-point has a steady speed.
Scenario towing(ControllerType type, double duration_s = 12.0) {
    Result<Scenario> s = resolveScenario(kLocations, "straight");
    EXPECT_TRUE(s.ok()) << s.message();
    Scenario out = s.value();
    out.duration_s = duration_s;
    out.drawbar_load.force_n = Signal::constant(0.5);
    out.drawbar_load.per_speed_n_s_m = 100.0;
    out.controller.type = type;
    out.controller.slip = 0.5;
    return out;
}

// A stand-in for computeTraction: 0.55 on sandy loam, 0.6 on anything else (slips where the
// thesis's soils give wheel A a positive drawbar pull at its load).
std::optional<SlipPlan> standInPlanner(const SlipPlanRequest& request) {
    return SlipPlan{request.soil.name == "sandy loam" ? 0.55 : 0.6, std::nullopt};
}

RunResult run(const Scenario& s) {
    RunOptions options;
    options.slip_planner = standInPlanner;
    return runScenario(s, options);
}

// The values of a column over the rows with t ≥ from_s.
std::vector<double> after(const RunResult& r, const std::string& column, double from_s) {
    std::vector<double> out;
    const std::size_t t = r.series.column("t_s"), c = r.series.column(column);
    for (const auto& row : r.series.rows)
        if (row[t] >= from_s) out.push_back(row[c]);
    return out;
}

double mean(const std::vector<double>& v) {
    return std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
}

double rmsDifference(const std::vector<double>& a, const std::vector<double>& b) {
    double sum = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i) sum += (a[i] - b[i]) * (a[i] - b[i]);
    return std::sqrt(sum / static_cast<double>(a.size()));
}

// How far the slip of each wheel may sit from its set-point on average once settled: the
// observer's speed error (a few mm/s against ~5 cm/s of rim speed) shifts ŝ by ~0.02 at most.
constexpr double kSlipHeld = 0.02;

TEST(TractionControl, FixedSlipHoldsItsSetPointOnUniformSoil) {
    const Scenario s = towing(ControllerType::kFixedSlip);
    const RunResult r = run(s);
    ASSERT_EQ(r.status, RunResult::Status::kCompleted) << r.message;
    for (const char* w : dynamics::kCornerNames) {
        const std::vector<double> slip = after(r, std::string(w) + "_slip", 6.0);
        EXPECT_NEAR(mean(slip), 0.5, kSlipHeld) << w;
        for (double set : after(r, std::string(w) + "_slip_set", 0.0)) EXPECT_EQ(set, 0.5);
    }
    ASSERT_TRUE(r.summary.slip_tracking_rms.has_value());
    EXPECT_LT(*r.summary.slip_tracking_rms, 0.05);
    // Moving at the speed where the implement's pull meets the wheels' drawbar pull.
    EXPECT_GT(r.summary.distance_m, 0.1);
}

TEST(TractionControl, OracleHoldsThePlannedSlipOfTheSoilUnderEachWheel) {
    const RunResult r = run(towing(ControllerType::kOracle));
    ASSERT_EQ(r.status, RunResult::Status::kCompleted) << r.message;
    for (const char* w : dynamics::kCornerNames) {
        for (double set : after(r, std::string(w) + "_slip_set", 0.5)) EXPECT_EQ(set, 0.55) << w;
        EXPECT_NEAR(mean(after(r, std::string(w) + "_slip", 6.0)), 0.55, kSlipHeld) << w;
    }
}

// The estimate-driven controller (docs/traction.md §5): no plan before the identifier's window
// holds a usable estimate — one dither period of samples (40 at 10 Hz from t = 1 s, the end of
// spin-up: the 40th at t = 4.9 s); until then the fixed `slip`. Then each wheel at its plan
// (the stand-in's 0.6 for any estimated soil), holding it as fixed-slip holds its set-point:
// the true slip's mean offset from the applied set-point (with the dither) within kSlipHeld.
TEST(TractionControl, OptimalWaitsForAUsableEstimateThenHoldsItsSetPoint) {
    Scenario s = towing(ControllerType::kOptimal, 16.0);
    StreamingHook hook;
    hook.interval_s = 0.1;
    s.streaming = hook;
    const RunResult r = run(s);
    ASSERT_EQ(r.status, RunResult::Status::kCompleted) << r.message;
    const std::size_t t = r.series.column("t_s");
    for (const char* w : dynamics::kCornerNames) {
        const std::size_t plan = r.series.column(std::string(w) + "_slip_plan");
        std::optional<double> first_plan_s;
        for (const auto& row : r.series.rows) {
            if (row[plan] != 0.5 && !first_plan_s) first_plan_s = row[t];
            if (row[t] < 4.85) {
                EXPECT_EQ(row[plan], 0.5) << w << " at t = " << row[t];
            }
        }
        ASSERT_TRUE(first_plan_s.has_value()) << w;
        EXPECT_LT(*first_plan_s, 6.0) << w;
        EXPECT_EQ(r.series.rows.back()[plan], 0.6) << w;
        const std::vector<double> slip = after(r, std::string(w) + "_slip", 8.0);
        const std::vector<double> set = after(r, std::string(w) + "_slip_set", 8.0);
        double offset = 0.0;
        for (std::size_t i = 0; i < slip.size(); ++i) offset += slip[i] - set[i];
        EXPECT_NEAR(offset / static_cast<double>(slip.size()), 0.0, kSlipHeld) << w;
    }
}

TEST(TractionControl, OracleSwitchesAtTheBorderAndHasNoSettlingDelay) {
    Scenario s = towing(ControllerType::kOracle, 20.0);
    soil::SoilParameters clay = s.terrain.base;
    clay.name = "clayey soil";
    s.terrain.patches.push_back({clay, 0.5});
    const RunResult r = run(s);
    ASSERT_EQ(r.status, RunResult::Status::kCompleted) << r.message;
    ASSERT_TRUE(r.traction.border_time_s.has_value());
    // The front-left hub crosses x = 0.5 m at the border time (it starts 0.25 m ahead of the
    // centre of mass), and its set-point changes at the same control tick.
    const std::size_t t = r.series.column("t_s"), x = r.series.column("x_m");
    for (const auto& row : r.series.rows) {
        if (row[t] + 0.011 < *r.traction.border_time_s) {
            EXPECT_LT(row[x] + 0.25, 0.5 + 1e-3);
        }
    }
    ASSERT_TRUE(r.traction.settling_time_s.has_value());
    EXPECT_EQ(*r.traction.settling_time_s, 0.0);
}

TEST(TractionControl, ObserverTracksTheTruthItDoesNotSee) {
    const Scenario s = towing(ControllerType::kFixedSlip);
    const RunResult r = run(s);
    const std::vector<double> speed = after(r, "forward_m_s", 2.0);
    const std::vector<double> estimate = after(r, "speed_est_m_s", 2.0);
    // GNSS speed σ = 3 mm/s at 5 Hz through a filter of 1 s: the estimate's error stays below σ.
    const double sigma = SensorSpec{}.gnss_speed_noise_m_s;
    EXPECT_LT(rmsDifference(speed, estimate), sigma);
    for (const char* w : dynamics::kCornerNames) {
        const auto slip = after(r, std::string(w) + "_slip", 2.0);
        const auto slip_est = after(r, std::string(w) + "_slip_est", 2.0);
        // ŝ = 1 − v̂/(rω): a speed error δv moves it by δv/(rω); with δv below σ and the state
        // up to one control tick older than the row's, within 1.5 σ/(r ω̄).
        const double rim =
            s.robot.wheel.radius_m * mean(after(r, std::string(w) + "_omega_rad_s", 2.0));
        EXPECT_LT(rmsDifference(slip, slip_est), 1.5 * sigma / rim) << w;
    }
}

TEST(TractionControl, ObserverKnowsHowWellItKnowsTheSpeedAndTheSlip) {
    // The speed estimate's stationary σ_v comes from the complementary filter's error covariance
    // (docs/traction.md §4); here it is checked against the filter itself, run for 2000 s on a
    // robot at a constant 0.1 m/s with every wheel at a slip of 0.3: the RMS of v̂ − v, and the
    // RMS of (ŝ − s)/σ_ŝ, which is 1 when σ_ŝ is right.
    const Scenario s = towing(ControllerType::kFixedSlip);
    constexpr double kSpeed = 0.1, kSlip = 0.3, kDt = 0.01;
    const double shear_radius = s.robot.wheel.radius_m + s.robot.wheel.lugShearOffset();
    dynamics::RoverState truth;
    truth.forward_speed_m_s = kSpeed;
    for (dynamics::WheelState& w : truth.wheels)
        w.spin_rate_rad_s = kSpeed / (shear_radius * (1.0 - kSlip));
    Observer observer(s.robot, s.controller.sensors, 9.81, kDt, truth, kSpeed);
    const double sigma_v = observer.speedStd();
    double speed_error = 0.0, z = 0.0;
    long n = 0;
    for (long tick = 0; tick < 200000; ++tick) {
        truth.time_s = tick * kDt;
        const Estimates& e = observer.update(truth, 0.0);
        if (tick < 2000) continue;  // the bias estimate settles (time constant 1 s)
        speed_error += std::pow(e.speed_m_s - kSpeed, 2);
        z += std::pow((e.slip[1] - kSlip) / e.slip_std[1], 2);
        ++n;
    }
    // Σ of ~2000 correlation times: the RMS within 5 %.
    EXPECT_NEAR(std::sqrt(speed_error / n), sigma_v, 0.05 * sigma_v);
    EXPECT_NEAR(std::sqrt(z / n), 1.0, 0.05);
    // GNSS at 5 Hz with σ = 3 mm/s through a 1 s filter: ≈ 2 mm/s, below one fix's noise.
    EXPECT_GT(sigma_v, 1e-3);
    EXPECT_LT(sigma_v, s.controller.sensors.gnss_speed_noise_m_s);
    // Without GNSS the speed's error has no bound.
    SensorSpec dead_reckoning = s.controller.sensors;
    dead_reckoning.gnss_rate_hz = 0.0;
    EXPECT_TRUE(std::isinf(Observer(s.robot, dead_reckoning, 9.81, kDt, truth, kSpeed).speedStd()));
    // Nor with a filter too fast for its fixes: stable only for τ > Δt_g/√2 (the eigenvalues of
    // one period's transition, docs/traction.md §4), 0.1414 s at 5 Hz. The covariance recursion
    // settles just above that and grows without bound just below it.
    const double shortest = 0.2 / std::sqrt(2.0);
    for (double factor : {0.98, 1.02, 0.35}) {
        SensorSpec sensors = s.controller.sensors;
        sensors.filter_time_constant_s = factor * shortest;
        const double sd = Observer(s.robot, sensors, 9.81, kDt, truth, kSpeed).speedStd();
        EXPECT_EQ(std::isinf(sd), factor < 1.0) << factor << " " << sd;
    }
}

TEST(TractionControl, ObserverLoadCarriesTheDriveTorquesPitchMoment) {
    // The streaming samples of a closed-loop run carry the observer's load Ŵ of the front-left
    // wheel as F_z (docs/traction.md §4); the truth is the series' FL_Fz_N at the same instant.
    // Towing ~10 N with ~3.5 N·m of drive torque, the front wheels lose ~4.7 N each: the pull at
    // the chassis' centre of mass alone explains 2.3 N of it, the torques' reaction the rest.
    Scenario s = towing(ControllerType::kFixedSlip, 10.0);
    s.streaming = StreamingHook{};
    s.streaming->interval_s = 0.1;
    const RunResult r = run(s);
    const std::size_t t = r.series.column("t_s"), fz = r.series.column("FL_Fz_N");
    const std::size_t st = r.streaming.column("t_s"), load = r.streaming.column("Fz_N");
    double error = 0.0, drop = 0.0;
    int n = 0;
    for (const auto& sample : r.streaming.rows) {
        if (sample[st] < 3.0) continue;
        for (const auto& row : r.series.rows) {
            if (std::abs(row[t] - sample[st]) > 1e-9) continue;
            error += sample[load] - row[fz];
            drop += dynamics::staticCornerLoad(s.robot, s.options.gravity_m_s2, 0) - row[fz];
            ++n;
        }
    }
    ASSERT_GT(n, 30);
    EXPECT_GT(drop / n, 3.0);  // the transfer is real and large
    // Unbiased to 0.3 N (the pull alone at the centre of mass left it 2.6 N high).
    EXPECT_LT(std::abs(error / n), 0.3) << "drop " << drop / n;
}

TEST(TractionControl, WithoutGnssTheAccelerometerBiasMakesTheSpeedDrift) {
    Scenario s = towing(ControllerType::kFixedSlip);
    s.controller.sensors.gnss_rate_hz = 0.0;
    s.controller.sensors.accel_bias_m_s2 = 0.01;
    const RunResult r = run(s);
    const std::vector<double> speed = after(r, "forward_m_s", 10.0);
    const std::vector<double> estimate = after(r, "speed_est_m_s", 10.0);
    // Integrating a 0.01 m/s² bias for 10 s: about 0.1 m/s off.
    EXPECT_GT(std::abs(mean(estimate) - mean(speed)), 0.05);
}

TEST(TractionControl, MotorTorqueLimitIsRespected) {
    Result<Scenario> loaded = resolveScenario(kLocations, "straight");
    ASSERT_TRUE(loaded.ok());
    const Scenario& s = loaded.value();
    constexpr double kLimit = 1.0;  // N·m, above the rolling resistance's M_y (≈ 0.15 N·m)
    dynamics::RoverOptions options = s.options;
    options.max_motor_torque_nm = kLimit;
    dynamics::Commands commands = s.commandsAt(0.0);
    for (auto& c : commands) c.spin_rate_rad_s = 0.0;
    dynamics::Rover limited(s.robot, s.terrain, options, s.initial, commands);
    dynamics::Rover ideal(s.robot, s.terrain, s.options, s.initial, commands);
    for (auto& c : commands) c.spin_rate_rad_s = 3.0;  // a jump the limit cannot follow
    constexpr int kSteps = 10;
    double largest_ideal = 0.0;
    for (int step = 0; step < kSteps; ++step) {
        limited.step(1e-3, commands);
        ideal.step(1e-3, commands);
        for (int i = 0; i < dynamics::kWheelCount; ++i) {
            EXPECT_LE(std::abs(limited.state().wheels[i].motor_torque_nm), kLimit * (1 + 1e-12));
            largest_ideal =
                std::max(largest_ideal, std::abs(ideal.state().wheels[i].motor_torque_nm));
        }
    }
    EXPECT_GT(largest_ideal, 3.0 * kLimit);  // the ideal servo takes the jump in one step
    // The limited wheels spin up at most at τ_max / I_w (less the soil's resistance): after ten
    // steps they are still short of the command, and turning.
    const double bound = kSteps * 1e-3 * kLimit / s.robot.wheel_spin_inertia_kg_m2;
    ASSERT_LT(bound, 3.0);
    for (int i = 0; i < dynamics::kWheelCount; ++i) {
        EXPECT_LT(limited.state().wheels[i].spin_rate_rad_s, bound * 1.01);
        EXPECT_GT(limited.state().wheels[i].spin_rate_rad_s, 0.0);
    }
}

TEST(TractionControl, DrawbarWorkClosesTheEnergyBalance) {
    Scenario s = towing(ControllerType::kConstantSpeed, 8.0);
    s.drawbar_load.per_speed_n_s_m = 0.0;
    s.drawbar_load.force_n = Signal::constant(1.0);
    const RunResult r = run(s);
    ASSERT_EQ(r.status, RunResult::Status::kCompleted);
    // A constant force along a straight path: its work is F × the distance.
    EXPECT_NEAR(r.traction.drawbar_work_j, 1.0 * r.summary.distance_m,
                1e-3 * r.traction.drawbar_work_j);
    EXPECT_LT(std::abs(r.summary.energy_balance_error), 1e-3);
    // The same run without the pull drives farther.
    Scenario free = s;
    free.drawbar_load = {};
    EXPECT_GT(run(free).summary.distance_m, r.summary.distance_m);
}

TEST(TractionControl, ConstantSpeedIgnoresTheControllerSettings) {
    Scenario plain = towing(ControllerType::kConstantSpeed, 3.0);
    plain.drawbar_load = {};
    Scenario tuned = plain;
    tuned.controller.slip = 0.5;
    tuned.controller.kp = 9.0;
    tuned.controller.max_torque_nm = 0.01;
    const RunResult a = runScenario(plain);
    const RunResult b = runScenario(tuned);
    EXPECT_EQ(a.series.columns, b.series.columns);
    EXPECT_EQ(a.series.rows, b.series.rows);
    EXPECT_FALSE(a.summary.slip_tracking_rms.has_value());
    // Energy per metre: the drive motors' work over the path (nothing steers here).
    ASSERT_TRUE(a.summary.energy_per_m_j.has_value());
    EXPECT_DOUBLE_EQ(*a.summary.energy_per_m_j, a.summary.energy_j / a.summary.distance_m);
    // No column of the closed loop is added to a constant-speed run.
    EXPECT_THROW(a.series.column("FL_slip_set"), std::out_of_range);
}

TEST(TractionControl, OptimalAndOracleNeedAPlanner) {
    EXPECT_THROW(runScenario(towing(ControllerType::kOracle, 1.0)), std::invalid_argument);
}

// The traction-limited supervisor on synthetic ticks (docs/traction.md §5): four wheels planned
// at 0.45, stalled at the floor with ŝ = 0.55 from t = 1 s. It engages after kEngageTime_s at
// the floor, and its floor climbs from the applied 0.45 at kRaiseRate_per_s to 0.55 + margin:
// (0.6 − 0.45) / 0.05 = 3 s. The wheels then run at 0.6: the robot speeds up from rest to
// 0.02 m/s and the hitch pull shows what the margin bought (F_d = P from 1 N to 3 N: k = 2 N /
// 0.05 = 40 N, ĉ = 2 N / 0.02 m/s = 100 N·s/m). The need falls: at 0.06 m/s the reserve
// R = ĉ v = 6 N is below k (0.6 − 0.45 + 0.05) = 8 N (the plan would give only 2 N of reserve),
// at 0.1 m/s (10 N) it releases; the floor ramps back under the plan.
TEST(TractionLimiter, EngagesOnAStallRaisesAtItsRateAndReleasesWhenTheNeedFalls) {
    ControllerSpec spec;
    spec.traction_limited = true;
    spec.limit_margin = 0.05;
    const double dt = 0.01;
    TractionLimiter limiter(spec, 20.0, dt);
    std::array<double, dynamics::kWheelCount> planned{0.45, 0.45, 0.45, 0.45};
    std::array<double, dynamics::kWheelCount> applied = planned;
    std::array<bool, dynamics::kWheelCount> floor{true, true, true, true};
    Estimates est;
    est.slip.fill(0.55);
    double t = 0.0;
    auto tick = [&](double pull_n, double speed_m_s = 0.0) {
        est.speed_m_s = speed_m_s;
        limiter.update(t, planned, applied, floor, est, pull_n);
        for (double& a : applied) a = limiter.effective(0.45, 0.7);
        t += dt;
    };
    // Spin-up (t < 1 s) never counts; then a stall of kEngageTime_s.
    while (t < 1.0 + TractionLimiter::kEngageTime_s - 1.5 * dt) tick(1.0);
    EXPECT_FALSE(limiter.engaged());
    tick(1.0);
    EXPECT_TRUE(limiter.engaged());
    EXPECT_EQ(limiter.switches(), 1);
    // The command leaves the floor; the floor climbs at its rate to 0.6 in 3 s.
    floor.fill(false);
    est.slip.fill(0.6);
    const double engaged_at = t;
    while (limiter.floor() < 0.6 - 1e-12) tick(1.0);
    EXPECT_NEAR(t - engaged_at, 0.15 / TractionLimiter::kRaiseRate_per_s, 2.0 * dt);
    EXPECT_NEAR(limiter.effective(0.45, 0.7), 0.6, 1e-12);
    EXPECT_EQ(limiter.effective(0.45, 0.58), 0.58);  // the cap
    EXPECT_EQ(limiter.effective(0.65, 0.7), 0.65);   // a plan above the floor
    // Settled at 0.02 m/s and 3 N (low-passed: long enough for both to get there).
    for (int i = 0; i < 3000; ++i) tick(3.0, 0.02);
    EXPECT_TRUE(limiter.engaged());
    for (int i = 0; i < 1500; ++i) tick(7.0, 0.06);
    EXPECT_TRUE(limiter.engaged());  // R = 6 N < 8 N: not yet
    for (int i = 0; i < 2000 && limiter.engaged(); ++i) tick(11.0, 0.1);
    EXPECT_FALSE(limiter.engaged());
    EXPECT_EQ(limiter.switches(), 2);
    for (int i = 0; i < 400; ++i) tick(11.0, 0.1);
    EXPECT_DOUBLE_EQ(limiter.effective(0.45, 0.7), 0.45);
}

// At the floor with the slip at the set-point (a slow robot, not a traction-limited one): the
// window's mean ŝ − s_set is not above kStallMargin, so it never engages.
TEST(TractionLimiter, AtTheFloorWithTheSlipAtItsSetPointItDoesNotEngage) {
    ControllerSpec spec;
    spec.traction_limited = true;
    const double dt = 0.01;
    TractionLimiter limiter(spec, 20.0, dt);
    const std::array<double, dynamics::kWheelCount> planned{0.45, 0.45, 0.45, 0.45};
    const std::array<bool, dynamics::kWheelCount> floor{true, true, true, true};
    Estimates est;
    // ŝ alternating 0.45 ± 0.1 (the observer's noise at the crawl): mean at the set-point.
    for (int i = 0; i < 2000; ++i) {
        est.slip.fill(i % 2 == 0 ? 0.55 : 0.35);
        limiter.update(0.01 * i, planned, planned, floor, est, 1.0);
    }
    EXPECT_FALSE(limiter.engaged());
    EXPECT_EQ(limiter.switches(), 0);
    EXPECT_EQ(limiter.limitedTime(), 0.0);
}

nlohmann::json withController(const nlohmann::json& controller) {
    nlohmann::json j = nlohmann::json::parse(R"({
        "duration_s": 1, "time_step_s": 0.001, "terrain": "sandy-loam",
        "wheels": {"all": {"omega_rad_s": 0.4}}})");
    j["controller"] = controller;
    return j;
}

TEST(TractionControl, ReaderNamesTheFieldAndItsRange) {
    auto message = [](const nlohmann::json& j) {
        return scenarioFromJson(j, "x.json", kLocations).message();
    };
    EXPECT_NE(message(withController({{"type", "cruise"}})).find("controller.type"),
              std::string::npos);
    EXPECT_NE(message(withController({{"type", "cruise"}})).find("oracle"), std::string::npos);
    const std::string slip = message(withController({{"type", "fixed-slip"}, {"slip", 1.5}}));
    EXPECT_NE(slip.find("controller.slip"), std::string::npos) << slip;
    EXPECT_NE(slip.find("0.95"), std::string::npos) << slip;
    EXPECT_NE(message(withController({{"slip", 0.2}})).find("controller.type"), std::string::npos);
    EXPECT_NE(message(withController({{"type", "oracle"}, {"gain", 1}})).find("controller.gain"),
              std::string::npos);
    const std::string replan =
        message(withController({{"type", "optimal"}, {"replan_interval_s", 0.01}}));
    EXPECT_NE(replan.find("controller.replan_interval_s"), std::string::npos) << replan;
    EXPECT_NE(replan.find("[0.1, 10000]"), std::string::npos) << replan;
    const std::string limited =
        message(withController({{"type", "fixed-slip"}, {"traction_limited", "yes"}}));
    EXPECT_NE(limited.find("controller.traction_limited"), std::string::npos) << limited;
    const std::string margin =
        message(withController({{"type", "fixed-slip"}, {"limit_margin", 0}}));
    EXPECT_NE(margin.find("controller.limit_margin"), std::string::npos) << margin;
    EXPECT_NE(margin.find("(0, 0.3]"), std::string::npos) << margin;
    // The robust set-point's keys (docs/traction.md §8): a choice, and traction's ranges.
    const std::string robust = message(withController({{"type", "optimal"}, {"robust", "mean"}}));
    EXPECT_NE(robust.find("controller.robust"), std::string::npos) << robust;
    EXPECT_NE(robust.find("quantile"), std::string::npos) << robust;
    const std::string quantile =
        message(withController({{"type", "optimal"}, {"robust", "quantile"}, {"quantile", 1.5}}));
    EXPECT_NE(quantile.find("controller.quantile"), std::string::npos) << quantile;
    EXPECT_NE(quantile.find("[0.01, 0.99]"), std::string::npos) << quantile;
    // A speed filter too fast for its GNSS fixes diverges: refused, with the shortest stable τ.
    const std::string filter = message(
        withController({{"type", "fixed-slip"}, {"sensors", {{"filter_time_constant_s", 0.1}}}}));
    EXPECT_NE(filter.find("controller.sensors.filter_time_constant_s"), std::string::npos)
        << filter;
    EXPECT_NE(filter.find("(0.1415, 100] s"), std::string::npos) << filter;  // 0.14142 rounded up
    // The tick the run takes: 0.01 s on 4 ms steps is 12 ms, a fix every 17 ticks (0.204 s), so
    // 0.142 s, stable on 1 ms steps, is refused there (the bound 0.1443 s).
    nlohmann::json coarse =
        withController({{"type", "fixed-slip"}, {"sensors", {{"filter_time_constant_s", 0.142}}}});
    EXPECT_TRUE(scenarioFromJson(coarse, "x.json", kLocations).ok());
    coarse["time_step_s"] = 0.004;
    const std::string on_steps = message(coarse);
    EXPECT_NE(on_steps.find("(0.1443, 100] s"), std::string::npos) << on_steps;
    EXPECT_TRUE(scenarioFromJson(withController({{"type", "fixed-slip"},
                                                 {"sensors", {{"filter_time_constant_s", 0.15}}}}),
                                 "x.json", kLocations)
                    .ok());
    const std::string samples =
        message(withController({{"type", "optimal"}, {"posterior_samples", 5}}));
    EXPECT_NE(samples.find("controller.posterior_samples"), std::string::npos) << samples;
    EXPECT_NE(samples.find("[10, "), std::string::npos) << samples;
    const Result<Scenario> read = scenarioFromJson(
        withController({{"type", "optimal"}, {"robust", "expected"}, {"quantile", 0.25}}), "x.json",
        kLocations);
    ASSERT_TRUE(read.ok()) << read.message();
    EXPECT_EQ(read.value().controller.robust, RobustSlip::kExpected);
    EXPECT_EQ(read.value().controller.quantile, 0.25);
    EXPECT_EQ(read.value().controller.posterior_method, PosteriorMethod::kSigmaPoints);
    EXPECT_EQ(read.value().controller.identifier, SoilIdentifier::kDecoupled);
    // The soil estimator and the posterior's method (docs/traction.md §8): choices.
    const std::string identifier =
        message(withController({{"type", "optimal"}, {"identifier", "kalman"}}));
    EXPECT_NE(identifier.find("controller.identifier"), std::string::npos) << identifier;
    EXPECT_NE(identifier.find("decoupled"), std::string::npos) << identifier;
    const std::string method =
        message(withController({{"type", "optimal"}, {"posterior_method", "grid"}}));
    EXPECT_NE(method.find("controller.posterior_method"), std::string::npos) << method;
    EXPECT_NE(method.find("sigma-points"), std::string::npos) << method;
    const Result<Scenario> chosen = scenarioFromJson(
        withController(
            {{"type", "optimal"}, {"identifier", "full"}, {"posterior_method", "samples"}}),
        "x.json", kLocations);
    ASSERT_TRUE(chosen.ok()) << chosen.message();
    EXPECT_EQ(chosen->controller.identifier, SoilIdentifier::kFull);
    EXPECT_EQ(chosen->controller.posterior_method, PosteriorMethod::kSamples);
    nlohmann::json load = withController({{"type", "fixed-slip"}});
    load["drawbar_load"] = {{"force_N", -1}};
    EXPECT_NE(message(load).find("drawbar_load.force_N"), std::string::npos) << message(load);

    nlohmann::json good = withController({{"type", "optimal"},
                                          {"slip", 0.2},
                                          {"max_torque_Nm", 3},
                                          {"replan_interval_s", 2},
                                          {"sensors", {{"seed", 7}}}});
    good["drawbar_load"] = {
        {"force_N", {{"type", "step"}, {"value", 1}, {"amplitude", 2}, {"start_s", 5}}},
        {"per_speed_N_s_m", 50}};
    const Result<Scenario> s = scenarioFromJson(good, "x.json", kLocations);
    ASSERT_TRUE(s.ok()) << s.message();
    EXPECT_EQ(s->controller.type, ControllerType::kOptimal);
    EXPECT_EQ(s->controller.slip, 0.2);
    EXPECT_EQ(s->controller.max_torque_nm, 3.0);
    EXPECT_EQ(s->controller.replan_interval_s, 2.0);
    EXPECT_EQ(s->controller.sensors.seed, 7u);
    EXPECT_FALSE(s->controller.traction_limited);  // off unless asked for
    nlohmann::json on = withController(
        {{"type", "fixed-slip"}, {"traction_limited", true}, {"limit_margin", 0.08}});
    const Result<Scenario> limited_on = scenarioFromJson(on, "x.json", kLocations);
    ASSERT_TRUE(limited_on.ok()) << limited_on.message();
    EXPECT_TRUE(limited_on->controller.traction_limited);
    EXPECT_EQ(limited_on->controller.limit_margin, 0.08);
    EXPECT_EQ(s->drawbar_load.force_n.at(6.0), 3.0);
    EXPECT_EQ(s->drawbar_load.per_speed_n_s_m, 50.0);
}

}  // namespace
}  // namespace terra::scenario
