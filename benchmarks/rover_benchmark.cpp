// Rover dynamics cost (docs/performance.md, "Rover"): the thesis's 60 s steering scenario at 1 ms
// with both contact models, a single step split into its parts, and the cost against the step.
#include <benchmark/benchmark.h>

#include <array>
#include <cstdint>
#include <stdexcept>

#include "core/analysis/rover.h"
#include "core/contact/quadratic_model.h"
#include "core/dynamics/rover.h"
#include "core/dynamics/wheel_contact.h"
#include "core/scenario/runner.h"
#include "core/scenario/scenario_json.h"

namespace {

using namespace terra;

scenario::Scenario pulseSteering(contact::ContactModel model, double duration_s, double dt_s) {
    auto loaded =
        scenario::resolveScenario(io::PresetLocations{{TERRA_RESOURCE_DIR}}, "pulse-steering");
    if (!loaded) throw std::runtime_error(loaded.message());
    scenario::Scenario s = loaded.value();
    s.options.contact.model = model;
    s.duration_s = duration_s;
    s.time_step_s = dt_s;
    s.output_interval_s = std::max(0.01, dt_s);
    return s;
}

// The figure: 60 s of the pulse-steering scenario at 1 ms, ≤ 0.5 s wall.
void BM_PulseSteering60s(benchmark::State& state) {
    const auto model =
        state.range(0) == 0 ? contact::ContactModel::kFull : contact::ContactModel::kQuadratic;
    const scenario::Scenario s = pulseSteering(model, 60.0, 1e-3);
    for (auto _ : state) {
        scenario::RunResult r = scenario::runScenario(s);
        benchmark::DoNotOptimize(r.summary.x_m);
    }
}
// Arg: contact model, 0 full, 1 quadratic. (A looser integration tolerance, 1e-4 instead of
// 1e-7, changes nothing here: at these operating points no piece is ever bisected.)
BENCHMARK(BM_PulseSteering60s)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->Iterations(3);

// Cost against the step: 10 s of the same scenario (quadratic model) at 0.5, 1, 2, 5 ms.
void BM_PulseSteeringStep(benchmark::State& state) {
    const double dt = static_cast<double>(state.range(0)) * 1e-4;
    const scenario::Scenario s = pulseSteering(contact::ContactModel::kQuadratic, 10.0, dt);
    for (auto _ : state) {
        scenario::RunResult r = scenario::runScenario(s);
        benchmark::DoNotOptimize(r.summary.x_m);
    }
}
BENCHMARK(BM_PulseSteeringStep)->Arg(5)->Arg(10)->Arg(20)->Arg(50)->Unit(benchmark::kMillisecond);

// One rover step (4 wheel contacts + the Bullet step), steady straight driving.
void BM_RoverStep(benchmark::State& state) {
    const auto model =
        state.range(0) == 0 ? contact::ContactModel::kFull : contact::ContactModel::kQuadratic;
    const scenario::Scenario s = pulseSteering(model, 1.0, 1e-3);
    dynamics::Rover rover(s.robot, s.terrain, s.options, s.initial, s.commandsAt(0.0));
    const dynamics::Commands commands = s.commandsAt(0.0);
    for (int i = 0; i < 3000; ++i) rover.step(1e-3, commands);  // settle
    for (auto _ : state) rover.step(1e-3, commands);
}
BENCHMARK(BM_RoverStep)->Arg(0)->Arg(1);

// Advancing the chassis alone (Bullet step and bookkeeping, forces held from one evaluation):
// the part of a step that does not grow with the number of wheels.
void BM_ChassisAdvance(benchmark::State& state) {
    const scenario::Scenario s = pulseSteering(contact::ContactModel::kQuadratic, 1.0, 1e-3);
    dynamics::Rover rover(s.robot, s.terrain, s.options, s.initial, s.commandsAt(0.0));
    rover.evaluate(s.commandsAt(0.0));
    for (auto _ : state) rover.advance(1e-3);
}
BENCHMARK(BM_ChassisAdvance);

// The implicit integrator (docs/dynamics.md, "Integrators"): one step and its parts, at its step.
// Arg: 0 a whole step (evaluate with the contact Jacobians, 16 contact evaluations; advance with
// the 6 × 6 correction and the steering stop), 1 evaluate alone, 2 advance alone.
void BM_ImplicitRoverStep(benchmark::State& state) {
    scenario::Scenario s = pulseSteering(contact::ContactModel::kQuadratic, 1.0, 0.02);
    s.options.integrator = dynamics::Integrator::kImplicit;
    dynamics::Rover rover(s.robot, s.terrain, s.options, s.initial, s.commandsAt(0.0));
    const dynamics::Commands commands = s.commandsAt(0.0);
    for (int i = 0; i < 150; ++i) rover.step(0.02, commands);  // settle
    for (auto _ : state) {
        if (state.range(0) == 0) rover.step(0.02, commands);
        if (state.range(0) == 1) rover.evaluate(commands);
        if (state.range(0) == 2) rover.advance(0.02);
    }
}
BENCHMARK(BM_ImplicitRoverStep)->Arg(0)->Arg(1)->Arg(2);

// 60 s of pulse steering with the implicit integrator at 10, 20 and 40 ms (quadratic contact):
// the thesis's scenario at ≥ 1000× real time.
void BM_PulseSteeringImplicit(benchmark::State& state) {
    const double dt = static_cast<double>(state.range(0)) * 1e-3;
    scenario::Scenario s = pulseSteering(contact::ContactModel::kQuadratic, 60.0, dt);
    s.options.integrator = dynamics::Integrator::kImplicit;
    for (auto _ : state) {
        scenario::RunResult r = scenario::runScenario(s);
        benchmark::DoNotOptimize(r.summary.x_m);
    }
    state.counters["real_time_factor"] = benchmark::Counter(
        60.0 * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_PulseSteeringImplicit)
    ->Arg(10)
    ->Arg(20)
    ->Arg(40)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(5);

// The closed loop's cost (docs/traction.md, docs/performance.md "Rover"): 20 s of straight towing
// on sandy loam (quadratic model, the cheapest rover: the largest relative overhead) under each
// controller. Arg 0: controller (0 constant-speed, 1 fixed-slip, 2 oracle, 3 optimal); arg 1:
// with (1) or without (0) the streaming identifier on the front-left wheel, which the optimal
// controller needs and which costs the same under any controller.
void BM_ClosedLoop(benchmark::State& state) {
    auto loaded = scenario::resolveScenario(io::PresetLocations{{TERRA_RESOURCE_DIR}}, "straight");
    if (!loaded) throw std::runtime_error(loaded.message());
    scenario::Scenario s = loaded.value();
    s.duration_s = 20.0;
    s.options.contact.model = contact::ContactModel::kQuadratic;
    s.drawbar_load.force_n = scenario::Signal::constant(1.0);
    s.drawbar_load.per_speed_n_s_m = 60.0;
    constexpr std::array<scenario::ControllerType, 8> kTypes{
        scenario::ControllerType::kConstantSpeed, scenario::ControllerType::kFixedSlip,
        scenario::ControllerType::kOracle,        scenario::ControllerType::kOptimal,
        scenario::ControllerType::kOptimal,       scenario::ControllerType::kOptimal,
        scenario::ControllerType::kOptimal,       scenario::ControllerType::kOptimal};
    const std::int64_t arg = state.range(0);
    s.controller.type = kTypes[static_cast<std::size_t>(arg)];
    // 4: robust (quantile) on the sigma points, 5: on 200 drawn soils (before docs/traction.md
    // §8's "Cost"); 6: the full-model estimator, point estimate; 7: it with the robust set-point.
    if (arg == 4 || arg == 5 || arg == 7) s.controller.robust = scenario::RobustSlip::kQuantile;
    if (arg == 5) s.controller.posterior_method = scenario::PosteriorMethod::kSamples;
    if (arg == 6 || arg == 7) s.controller.identifier = scenario::SoilIdentifier::kFull;
    if (state.range(1) == 1) s.streaming = scenario::StreamingHook{};
    scenario::RunOptions options;
    options.slip_planner = analysis::tractionPlanner();
    for (auto _ : state) {
        scenario::RunResult r = scenario::runScenario(s, options);
        benchmark::DoNotOptimize(r.summary.x_m);
    }
}
BENCHMARK(BM_ClosedLoop)
    ->Args({0, 0})
    ->Args({1, 0})
    ->Args({2, 0})
    ->Args({0, 1})
    ->Args({3, 1})
    ->Args({4, 1})
    ->Args({5, 1})
    ->Args({6, 1})
    ->Args({7, 1})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);

// The traction-limited mode's cost (docs/traction.md §5, docs/performance.md "The closed loop"):
// 20 s of traction-slope (a field: the 3 % slope of gentle-slope, the implement) without its
// streaming identifier, where the mode engages. Arg: 0 constant-speed, 1 fixed-slip (crawls at
// the floor), 2 fixed-slip traction-limited (stalls, raises its set-point, climbs), 3 oracle and
// 4 oracle traction-limited (its plan is above the need: the same run, so 4 − 3 is the mode's own
// cost: the supervisor at every control tick and the caps' plans).
void BM_TractionLimited(benchmark::State& state) {
    auto loaded =
        scenario::resolveScenario(io::PresetLocations{{TERRA_RESOURCE_DIR}}, "traction-slope");
    if (!loaded) throw std::runtime_error(loaded.message());
    scenario::Scenario s = loaded.value();
    s.duration_s = 20.0;
    s.streaming.reset();
    const std::int64_t arg = state.range(0);
    s.controller.type = arg == 0   ? scenario::ControllerType::kConstantSpeed
                        : arg <= 2 ? scenario::ControllerType::kFixedSlip
                                   : scenario::ControllerType::kOracle;
    s.controller.traction_limited = arg == 2 || arg == 4;
    scenario::RunOptions options;
    options.slip_planner = analysis::tractionPlanner();
    for (auto _ : state) {
        scenario::RunResult r = scenario::runScenario(s, options);
        benchmark::DoNotOptimize(r.summary.x_m);
    }
}
BENCHMARK(BM_TractionLimited)->DenseRange(0, 4)->Unit(benchmark::kMillisecond)->Iterations(3);

// One wheel's contact evaluation at the straight-line operating point.
void BM_WheelContact(benchmark::State& state) {
    const auto model =
        state.range(0) == 0 ? contact::ContactModel::kFull : contact::ContactModel::kQuadratic;
    const scenario::Scenario s = pulseSteering(model, 1.0, 1e-3);
    const auto p = contact::makeContactParameters(s.terrain.base, s.robot.wheel);
    dynamics::ContactOptions o = s.options.contact;
    const dynamics::WheelKinematics k{0.0216, 0.0, 0.0368, 0.0038};
    for (auto _ : state) benchmark::DoNotOptimize(dynamics::evaluateContact(p, k, o).forces.fx);
}
BENCHMARK(BM_WheelContact)->Arg(0)->Arg(1);

}  // namespace
