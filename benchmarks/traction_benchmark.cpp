// Speed of the best-slip search (core/analysis/traction.h; docs/performance.md, "Traction"): s*
// for one wheel (goal ≤ 1 ms with the quadratic model), and with a 200-soil posterior.
//   terra_benchmarks --benchmark_filter=Traction
#include <benchmark/benchmark.h>

#include "core/analysis/traction.h"
#include "core/io/parameters_json.h"

namespace {

using namespace terra;

analysis::Inputs sandyLoamOnA(bool quadratic) {
    const io::PresetLocations locations{{TERRA_RESOURCE_DIR}};
    analysis::Inputs in;
    in.soil = io::resolveSoil(locations, "sandy-loam").value();
    in.wheel = io::resolveWheel(locations, "A").value();
    in.conditions.quadratic = quadratic;
    return in;
}

// s* of the efficiency: a 60-slip curve and Brent's refinement. Args: 1 quadratic, 0 full model.
void TractionOptimalSlip(benchmark::State& state) {
    const analysis::Inputs in = sandyLoamOnA(state.range(0) == 1);
    const analysis::TractionSettings s;
    for (auto _ : state) benchmark::DoNotOptimize(analysis::computeTraction(in, s));
}
BENCHMARK(TractionOptimalSlip)->Arg(1)->Arg(0)->Unit(benchmark::kMicrosecond);

// The same with the curve cut to 20 slips (the s* a controller re-plans).
void TractionOptimalSlipCoarse(benchmark::State& state) {
    const analysis::Inputs in = sandyLoamOnA(true);
    analysis::TractionSettings s;
    s.curve_points = 20;
    for (auto _ : state) benchmark::DoNotOptimize(analysis::computeTraction(in, s));
}
BENCHMARK(TractionOptimalSlipCoarse)->Unit(benchmark::kMicrosecond);

// A robust s* over 200 posterior soils (φ, n correlated), quadratic model.
void TractionRobustSlip(benchmark::State& state) {
    const analysis::Inputs in = sandyLoamOnA(true);
    analysis::TractionSettings s;
    s.posterior =
        analysis::SoilPosterior{{"phi_deg", "n"}, {29.0, 0.7}, {{4.0, -0.05}, {-0.05, 0.0025}}};
    for (auto _ : state) benchmark::DoNotOptimize(analysis::computeTraction(in, s));
}
BENCHMARK(TractionRobustSlip)->Unit(benchmark::kMillisecond);

}  // namespace
