// Speed of the wheel–soil model: the figures of issue #2 (docs/performance.md).
//   terra_benchmarks --benchmark_repetitions=9 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <numbers>

#include "benchmarks/benchmark_support.h"
#include "core/analysis/sweep.h"
#include "core/contact/quadratic_model.h"
#include "core/contact/sinkage.h"
#include "core/contact/wheel_forces.h"

namespace {

using namespace terra::contact;
using terra::benchmarks::kDeg;

// Table 2.1 sandy loam / clayey soil on wheel A (Table 2.2), Table 2.6 j_max.
using terra::benchmarks::sandyLoam;
ContactParameters<double> clayeySoil() {
    return {0.092,   0.107, 0.5, 0.0,  13.2e3 / 0.107 + 692.2e3, 4.14e3, 13.0 * kDeg, 0.01,
            13.24e3, 0.2,   0.3, 0.009};
}

// The same soil under wheel A with 12 mm grousers and λ_s = 0.5 (docs/model.md, "Lugs").
ContactParameters<double> lugged(ContactParameters<double> p) {
    p.lug_shear_offset_m = 0.5 * 0.012;
    return p;
}

// A spread of operating points so that the branch predictor and caches see realistic variety.
std::vector<OperatingPoint<double>> points() {
    std::vector<OperatingPoint<double>> out;
    for (double s : {0.0, 0.1, 0.3, 0.6, 0.9}) {
        for (double beta : {0.0, 15.0, 30.0}) {
            out.push_back({s, beta * kDeg, (20.0 + 10.0 * s) * kDeg, 0.0, std::nullopt});
        }
    }
    return out;
}

void fullForces(benchmark::State& state, ContactParameters<double> p) {
    const auto ops = points();
    std::size_t i = 0;
    for (auto _ : state) {
        benchmark::DoNotOptimize(computeForces(p, ops[i++ % ops.size()]));
    }
}
BENCHMARK_CAPTURE(fullForces, sandy_loam, sandyLoam());
BENCHMARK_CAPTURE(fullForces, clayey_soil, clayeySoil());
BENCHMARK_CAPTURE(fullForces, sandy_loam_lugged, lugged(sandyLoam()));

void quadraticForces(benchmark::State& state, ContactParameters<double> p) {
    const auto ops = points();
    std::size_t i = 0;
    for (auto _ : state) {
        benchmark::DoNotOptimize(computeQuadraticForces(p, ops[i++ % ops.size()]));
    }
}
BENCHMARK_CAPTURE(quadraticForces, sandy_loam, sandyLoam());
BENCHMARK_CAPTURE(quadraticForces, clayey_soil, clayeySoil());
BENCHMARK_CAPTURE(quadraticForces, sandy_loam_lugged, lugged(sandyLoam()));

// A cold entry-angle solve (no warm start): bracket from Bekker's static sinkage, then TOMS 748.
void entryAngle(benchmark::State& state, ContactModel model) {
    const ContactParameters<double> p = sandyLoam();
    const double slips[] = {0.0, 0.2, 0.5, 0.8};
    std::size_t i = 0;
    int evaluations = 0, solves = 0;
    for (auto _ : state) {
        EntryAngleProblem problem;
        problem.load_n = terra::contact::kDefaultLoadN;
        problem.slip = slips[i++ % 4];
        problem.slip_angle_rad = 15.0 * kDeg;
        problem.model = model;
        const SinkageSolution solution = solveEntryAngle(p, problem);
        evaluations += solution.evaluations;
        ++solves;
        benchmark::DoNotOptimize(solution);
    }
    state.counters["evaluations"] = static_cast<double>(evaluations) / solves;
}
BENCHMARK_CAPTURE(entryAngle, full, ContactModel::kFull);
BENCHMARK_CAPTURE(entryAngle, quadratic, ContactModel::kQuadratic);

// The GUI's forces panel: 6 slip angles × 101 slips with an entry-angle solve at every point.
void thesisSweep(benchmark::State& state) {
    terra::analysis::SweepSpec spec;
    spec.slips = terra::analysis::linspace(0.0, 0.99, 101);
    for (double beta : {5.0, 10.0, 15.0, 20.0, 25.0, 30.0})
        spec.slip_angles_rad.push_back(beta * kDeg);
    spec.threads = static_cast<int>(state.range(0));
    const ContactParameters<double> p = sandyLoam();
    for (auto _ : state) {
        benchmark::DoNotOptimize(terra::analysis::sweepSlip(p, spec));
    }
}
BENCHMARK(thesisSweep)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
