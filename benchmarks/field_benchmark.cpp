// Speed of the field's lookups (core/field/; docs/performance.md, "Field"): what a wheel asks of
// the terrain every step — the height and its gradient, the soil under it, its cell's state — on
// the shipped sloped field. The ≥ 1000× real-time rover of issue 23 has ~1 µs per wheel and step
// for all of its terrain work at a 1 ms step.
//   terra_benchmarks --benchmark_filter=Field
#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <memory>
#include <random>
#include <stdexcept>

#include "core/dynamics/field_terrain.h"
#include "core/dynamics/rover.h"
#include "core/field/cell_grid.h"
#include "core/io/field_json.h"
#include "core/scenario/runner.h"
#include "core/scenario/scenario_json.h"

namespace {

using namespace terra;

const io::FieldFile& slopedField() {
    static const io::FieldFile file =
        io::loadField(std::string(TERRA_RESOURCE_DIR) + "/fields/sloped-wet/field.json",
                      io::PresetLocations{{TERRA_RESOURCE_DIR}})
            .value();
    return file;
}

// Points along a wheel's path: 1 m/s sampled at 1 ms, across the field.
std::vector<Eigen::Vector2d> path() {
    std::vector<Eigen::Vector2d> p;
    for (int i = 0; i < 50000; ++i) p.emplace_back(5.0 + 0.001 * i, 10.0 + 0.0003 * i);
    return p;
}

void FieldHeightAndGradient(benchmark::State& state) {
    const field::FieldMap& map = slopedField().map;
    const std::vector<Eigen::Vector2d> p = path();
    std::size_t i = 0;
    for (auto _ : state) {
        const Eigen::Vector2d& q = p[i++ % p.size()];
        benchmark::DoNotOptimize(map.heightAt(q.x(), q.y()));
        benchmark::DoNotOptimize(map.gradientAt(q.x(), q.y()));
    }
}
BENCHMARK(FieldHeightAndGradient)->Unit(benchmark::kNanosecond);

void FieldSoilAt(benchmark::State& state) {
    const field::FieldMap& map = slopedField().map;
    const std::vector<Eigen::Vector2d> p = path();
    std::size_t i = 0;
    for (auto _ : state) {
        const Eigen::Vector2d& q = p[i++ % p.size()];
        benchmark::DoNotOptimize(map.soilAt(q.x(), q.y()));
    }
}
BENCHMARK(FieldSoilAt)->Unit(benchmark::kNanosecond);

void FieldClassAt(benchmark::State& state) {
    const field::FieldMap& map = slopedField().map;
    const std::vector<Eigen::Vector2d> p = path();
    std::size_t i = 0;
    for (auto _ : state) {
        const Eigen::Vector2d& q = p[i++ % p.size()];
        benchmark::DoNotOptimize(map.classAt(q.x(), q.y()));
    }
}
BENCHMARK(FieldClassAt)->Unit(benchmark::kNanosecond);

// A wheel's contact patch on 5 cm cells: ~ 0.1 m × 0.3 m, 12 cells touched per step.
void FieldTouchContactCells(benchmark::State& state) {
    field::CellGrid grid(0.05);
    const std::vector<Eigen::Vector2d> p = path();
    std::size_t i = 0;
    for (auto _ : state) {
        const Eigen::Vector2d& q = p[i++ % p.size()];
        for (int a = 0; a < 2; ++a)
            for (int b = 0; b < 6; ++b)
                grid.touch(q.x() + 0.05 * a, q.y() + 0.05 * b).track.passes++;
    }
    state.counters["tiles"] = static_cast<double>(grid.tileCount());
}
BENCHMARK(FieldTouchContactCells)->Unit(benchmark::kNanosecond);

}  // namespace

// The rover on a field (issue 23's figure; docs/performance.md, "Rover on a field"): the default
// 4-wheel robot drives 20 s straight up a 50 m × 20 m field of 2 cm cells (height: a 2 % grade
// with a 5 cm swell; classes: sandy loam with a clayey strip) at 1 ms steps, quadratic contact.
// Arg: 0 the same run on today's flat patch terrain; 1 the field, every wheel on untouched soil
// (repeated_passes off); 2 the field with the memory (rear wheels in the front ruts: their
// contact is integrated, the quadratic model has no reload branch); 3 as 2 without the stress at
// depth; 4 as 2 with the quadratic closed form's reload branch in the ruts; 5 as 4 without the
// stress at depth; 6 as 4 writing each passage to the cell under the contact point only, not
// across the wheel's width (docs/field.md F13); 7 as 4 with a cohesion raster of 0.5 m cells
// (100 × 40 distinct values from 1 to 3 kPa: 4,000 soils, F14); 8 as 4 with each wheel reading
// the memory of its contact point's cell for its whole width (F15 off); 9 as 4 with the full
// scan for σ_z's peak at every passage (F16 off); 10 as 4 with the contact Jacobians every
// other step (docs/dynamics.md I6). Second arg: the step in
// ms; third: 1 for the implicit integrator (docs/dynamics.md, "Integrators"). Counters: real-time
// factor, bytes of cell state, cells touched.
scenario::Scenario fieldRun(int kind) {
    auto loaded = scenario::resolveScenario(io::PresetLocations{{TERRA_RESOURCE_DIR}}, "straight");
    if (!loaded) throw std::runtime_error(loaded.message());
    scenario::Scenario s = loaded.value();
    s.duration_s = 20.0;
    s.options.contact.model = contact::ContactModel::kQuadratic;
    s.initial = {2.0, 10.0, 0.0, 0.0};
    for (auto& w : s.wheels) w.spin_rate_rad_s = scenario::Signal::constant(1.0);
    if (kind == 0) return s;
    static const std::shared_ptr<const field::FieldMap> map = [] {
        auto m = std::make_shared<field::FieldMap>();
        constexpr double kCell = 0.02;
        m->height = field::makeRaster(2500, 1000, 0.0, 0.0, kCell);
        m->soil_class = field::makeRaster(2500, 1000, 0.0, 0.0, kCell);
        for (int row = 0; row < 1000; ++row) {
            for (int col = 0; col < 2500; ++col) {
                const double x = m->height->centreX(col), y = m->height->centreY(row);
                m->height->value(col, row) =
                    0.02 * x + 0.05 * std::sin(0.5 * x) * std::cos(0.3 * y);
                m->soil_class->value(col, row) = y > 9.5 && y < 9.7 ? 2 : 1;
            }
        }
        auto soils = io::PresetLocations{{TERRA_RESOURCE_DIR}};
        m->base = io::resolveSoil(soils, "sandy-loam").value();
        m->legend[1] = m->base;
        m->legend[2] = io::resolveSoil(soils, "clayey-soil").value();
        return m;
    }();
    s.field = map;
    if (kind == 7) {
        static const std::shared_ptr<const field::FieldMap> with_cohesion = [] {
            auto m = std::make_shared<field::FieldMap>(*map);
            field::ParameterRaster c{soil::findSoilField("c_kPa"),
                                     field::makeRaster(100, 40, 0.0, 0.0, 0.5)};
            for (std::size_t i = 0; i < c.raster.values.size(); ++i)
                c.raster.values[i] = 1.0 + 2.0 * static_cast<double>(i) / 4000.0;
            m->parameters.push_back(std::move(c));
            return m;
        }();
        s.field = with_cohesion;
    }
    s.terrain.base = map->base;
    s.field_options.cell_m = 0.02;
    s.field_options.repeated_passes = kind >= 2;
    if (kind == 3 || kind == 5) s.field_options.stress_depths_m.clear();
    s.options.contact.closed_form_reload = kind >= 4;
    s.field_options.across_width = kind != 6;
    s.field_options.read_across_width = kind != 8;  // 8: kind 4 read at the contact point (F15)
    if (kind == 9) s.field_options.full_scan_every = 1;  // kind 4 without F16
    if (kind == 10) s.options.jacobian_every = 2;        // kind 4 with I6
    return s;
}

double cpuSeconds() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// The field run of `kind` at the step and integrator of the benchmark's 2nd and 3rd argument.
scenario::Scenario fieldRun(const benchmark::State& state) {
    scenario::Scenario s = fieldRun(static_cast<int>(state.range(0)));
    s.time_step_s = 1e-3 * static_cast<double>(state.range(1));
    s.output_interval_s = std::max(s.output_interval_s, s.time_step_s);
    s.options.integrator =
        state.range(2) == 1 ? dynamics::Integrator::kImplicit : dynamics::Integrator::kExplicit;
    return s;
}

void RoverOnField(benchmark::State& state) {
    const scenario::Scenario s = fieldRun(state);
    double wall = 0.0, loop = 0.0;
    long cells = 0;
    for (auto _ : state) {
        const auto start = std::chrono::steady_clock::now();
        scenario::RunResult r = scenario::runScenario(s);
        wall += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        if (r.status != scenario::RunResult::Status::kCompleted)
            state.SkipWithError(r.message.c_str());
        // The stepping loop's own time (the summary's factor), without the maps of the run.
        loop += s.duration_s / r.summary.real_time_factor.value_or(0.0);
        cells = r.summary.cells_touched.value_or(0);
        benchmark::DoNotOptimize(r.summary.x_m);
    }
    const double n = static_cast<double>(state.iterations());
    state.counters["real_time_factor"] = s.duration_s * n / wall;
    state.counters["loop_real_time_factor"] = s.duration_s * n / loop;
    state.counters["maps_ms"] = 1e3 * (wall - loop) / n;
    state.counters["cells_touched"] = static_cast<double>(cells);
    // The rover's own stepping loop again, outside the runner (no series rows, no divergence
    // watch, no maps), timed in CPU seconds: the real-time factor the load of a shared machine
    // does not move (wall ≈ CPU on an idle one). On the field, also the memory
    // (CellGrid::stateBytes).
    std::unique_ptr<dynamics::FieldTerrain> terrain;
    if (s.field) {
        const double build_start = cpuSeconds();
        terrain = std::make_unique<dynamics::FieldTerrain>(s.field, s.robot, s.field_options);
        state.counters["terrain_build_ms"] = 1e3 * (cpuSeconds() - build_start);
        state.counters["soils"] = terrain->soilCount();
    }
    std::unique_ptr<dynamics::Rover> rover =
        terrain ? std::make_unique<dynamics::Rover>(s.robot, *terrain, s.options, s.initial,
                                                    s.commandsAt(0.0))
                : std::make_unique<dynamics::Rover>(s.robot, s.terrain, s.options, s.initial,
                                                    s.commandsAt(0.0));
    const long steps = std::lround(s.duration_s / s.time_step_s);
    const double cpu_start = cpuSeconds();
    for (long k = 0; k < steps; ++k) rover->step(s.time_step_s, s.commandsAt(0.0));
    state.counters["cpu_real_time_factor"] = s.duration_s / (cpuSeconds() - cpu_start);
    if (terrain) {
        terrain->finish();
        state.counters["cell_state_bytes"] = static_cast<double>(terrain->cells().stateBytes());
    }
}
BENCHMARK(RoverOnField)
    ->Args({0, 1, 0})
    ->Args({1, 1, 0})
    ->Args({2, 1, 0})
    ->Args({3, 1, 0})
    ->Args({0, 10, 1})
    ->Args({1, 10, 1})
    ->Args({2, 10, 1})
    ->Args({4, 10, 1})
    ->Args({0, 20, 1})
    ->Args({1, 20, 1})
    ->Args({2, 20, 1})
    ->Args({4, 20, 1})
    ->Args({5, 20, 1})
    ->Args({6, 20, 1})
    ->Args({7, 20, 1})
    ->Args({8, 20, 1})
    ->Args({10, 20, 1})
    ->Args({4, 40, 1})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(2);

// Runs a 1-hour field mission as the benchmark's iterations: wall and CPU seconds, the loop's
// real-time factor, cells touched, distance, and the process's peak resident memory.
void timeMission(benchmark::State& state, const scenario::Scenario& s) {
    double wall = 0.0, loop = 0.0, cpu = 0.0;
    for (auto _ : state) {
        const auto start = std::chrono::steady_clock::now();
        const double cpu_start = cpuSeconds();
        scenario::RunResult r = scenario::runScenario(s);
        wall += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        cpu += cpuSeconds() - cpu_start;
        if (r.status != scenario::RunResult::Status::kCompleted)
            state.SkipWithError(r.message.c_str());
        loop += s.duration_s / r.summary.real_time_factor.value_or(0.0);
        state.counters["cells_touched"] = static_cast<double>(r.summary.cells_touched.value_or(0));
        state.counters["distance_m"] = r.summary.distance_m;
        benchmark::DoNotOptimize(r.summary.x_m);
    }
    const double n = static_cast<double>(state.iterations());
    state.counters["wall_s"] = wall / n;
    state.counters["cpu_s"] = cpu / n;
    state.counters["loop_real_time_factor"] = s.duration_s * n / loop;
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    state.counters["peak_rss_MB"] = static_cast<double>(usage.ru_maxrss) / 1024.0;
}

// A 1-hour mission on the 2 cm field (issue 23: ≤ 4 s wall, ≤ 200 MB): the robot circles on
// the field (front wheels steered 4°: a circle of ≈ 7 m radius, ≈ 4 laps in the hour, so from
// the second lap on every wheel is in a remembered cell), at the step and integrator of the 2nd
// and 3rd argument, with the memory (kind 2 or 4: first argument). One run: wall time, the loop's
// real-time factor, and the process's peak resident memory (getrusage; it includes the field's
// rasters, built once for all the benchmarks of this program, and the run's maps).
void RoverFieldMission(benchmark::State& state) {
    scenario::Scenario s = fieldRun(state);
    s.duration_s = 3600.0;
    s.output_interval_s = 1.0;
    s.initial = {25.0, 3.0, 0.0, 0.0};
    for (int i = 0; i < 2; ++i)
        s.wheels[i].steer_angle_rad = scenario::Signal::constant(4.0 * M_PI / 180.0);
    timeMission(state, s);
}
BENCHMARK(RoverFieldMission)
    ->Args({2, 20, 1})
    ->Args({4, 20, 1})
    ->Args({5, 20, 1})
    ->Args({6, 20, 1})
    ->Args({7, 20, 1})
    ->Args({8, 20, 1})
    ->Args({9, 20, 1})
    ->Args({10, 20, 1})
    ->Args({4, 40, 1})
    ->Unit(benchmark::kSecond)
    ->Iterations(1);

// The 1-hour mission that covers the field (issue 23's memory figure; docs/performance.md,
// "Memory"): on the 50 m × 20 m field of 2 cm cells, twelve 46 m lanes 1.6 m apart joined by
// headland turns, followed by the pure-pursuit controller at 0.14 m/s (≈ 500 m in the hour, as
// far as the circling mission above but over new ground almost all the way, so the cell state
// grows with every metre). Args as RoverFieldMission. Counters: wall and CPU seconds, the
// loop's real-time factor, cells touched, the cell state's bytes, and the process's peak
// resident memory (run it alone: --benchmark_filter=RoverFieldLanes, since the peak is the
// process's whole life).
void RoverFieldLanes(benchmark::State& state) {
    scenario::Scenario s = fieldRun(state);
    s.duration_s = 3600.0;
    s.output_interval_s = 1.0;
    s.initial = {2.0, 1.5, 0.0, 0.0};
    scenario::MissionSpec mission;
    scenario::LanesSpec lanes;
    lanes.start_m = {2.0, 1.5};
    lanes.length_m = 46.0;
    lanes.spacing_m = 1.6;
    lanes.count = 12;
    lanes.turn_radius_m = 0.8;
    mission.lanes = lanes;
    mission.speed_m_s = 0.14;
    s.mission = mission;
    if (const std::vector<Issue> issues = scenario::validate(mission, s.robot); !issues.empty()) {
        state.SkipWithError(issues.front().message.c_str());
        return;
    }
    timeMission(state, s);
}
BENCHMARK(RoverFieldLanes)->Args({4, 20, 1})->Unit(benchmark::kSecond)->Iterations(1);

namespace {

// A mission run (issue 23, item 3; docs/performance.md, "Missions"): the shipped missions, whole.
// Arg: 0 mission-controlled-traffic (two 16 m lanes and a U-turn, constant speed, 0.1 m cells);
// 1 mission-slope-lanes (three 20 m lanes across the sloped field with a fixed-slip controller).
// Counters: the real-time factor of the whole run and of its stepping loop, the simulated time
// the mission took, its path length.
void MissionOnField(benchmark::State& state) {
    const char* name = state.range(0) == 0 ? "mission-controlled-traffic" : "mission-slope-lanes";
    auto loaded = scenario::resolveScenario(io::PresetLocations{{TERRA_RESOURCE_DIR}}, name);
    if (!loaded) throw std::runtime_error(loaded.message());
    const scenario::Scenario s = loaded.value();
    double wall = 0.0, loop = 0.0, simulated = 0.0, path = 0.0;
    for (auto _ : state) {
        const auto start = std::chrono::steady_clock::now();
        scenario::RunResult r = scenario::runScenario(s);
        wall += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        if (r.status != scenario::RunResult::Status::kCompleted || !r.summary.mission ||
            !r.summary.mission->completed) {
            state.SkipWithError("the mission did not complete");
            break;
        }
        simulated = r.summary.duration_s;
        path = r.summary.mission->path_length_m;
        loop += simulated / r.summary.real_time_factor.value_or(0.0);
        benchmark::DoNotOptimize(r.summary.x_m);
    }
    const double n = static_cast<double>(state.iterations());
    state.counters["real_time_factor"] = simulated * n / wall;
    state.counters["loop_real_time_factor"] = simulated * n / loop;
    state.counters["mission_s"] = simulated;
    state.counters["path_m"] = path;
}
BENCHMARK(MissionOnField)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace
