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
        analysis::SoilPosterior{{"phi_deg", "n"}, {29.0, 0.7}, {{4.0, -0.05}, {-0.05, 0.0025}}, {}};
    for (auto _ : state) benchmark::DoNotOptimize(analysis::computeTraction(in, s));
}
BENCHMARK(TractionRobustSlip)->Unit(benchmark::kMillisecond);

// A plan of the rover's robust optimal controller (docs/traction.md §8, "Cost"): a 30-slip curve
// over [0.05, 0.7], a seven-parameter posterior of the soil file's keys (a₀, a₁, k_φ, n, c, φ,
// K; 10–15 % std, c–φ correlated). Arg: 0 200 drawn soils, 1 the 15 sigma points.
void TractionRobustPlan(benchmark::State& state) {
    const analysis::Inputs in = sandyLoamOnA(true);
    analysis::TractionSettings s;
    s.curve_points = 30;
    s.slip_min = 0.05;
    s.slip_max = 0.7;
    const std::vector<double> sd{0.03, 0.03, 151.5, 0.04, 0.255, 1.5, 0.00375};
    analysis::SoilPosterior p{{"a0", "a1", "kphi", "n", "c_kPa", "phi_deg", "K_m"},
                              {0.2, 0.3, 1515.0, 0.7, 1.7, 29.0, 0.025},
                              {},
                              {}};
    p.covariance.assign(7, std::vector<double>(7, 0.0));
    for (std::size_t i = 0; i < 7; ++i) p.covariance[i][i] = sd[i] * sd[i];
    p.covariance[4][5] = p.covariance[5][4] = -0.6 * sd[4] * sd[5];
    s.posterior = p;
    s.posterior_method = state.range(0) == 1 ? scenario::PosteriorMethod::kSigmaPoints
                                             : scenario::PosteriorMethod::kSamples;
    for (auto _ : state) benchmark::DoNotOptimize(analysis::computeTraction(in, s));
}
BENCHMARK(TractionRobustPlan)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace
