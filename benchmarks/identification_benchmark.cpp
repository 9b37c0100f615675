// Speed of soil identification: the figures of issue #3 (docs/identification.md, performance.md).
// 91 samples (s = 0 : 0.01 : 0.9) of sandy loam on wheel A, from the full model.
#include <benchmark/benchmark.h>

#include <numbers>

#include "core/identification/decoupled_fit.h"
#include "core/identification/full_fit.h"
#include "core/identification/streaming.h"
#include "core/identification/synthetic.h"

namespace {

using namespace terra;
using namespace terra::identification;
constexpr double kDeg = std::numbers::pi / 180.0;
const wheel::WheelParameters kWheelA{"A", "", 0.092, 0.107};

contact::ContactParameters<double> sandyLoam() {
    return {0.092,  0.107, 0.7, 0.0, 5.3e3 / 0.107 + 1.515e6, 1.7e3, 29.0 * kDeg, 0.025,
            15.2e3, 0.2,   0.3, 0.02};
}

// 91 samples in all: one load, or three loads (30 + 30 + 31 slips).
DataSet data(int loads, double relative_noise) {
    SyntheticSpec spec;
    const int per_load = 91 / loads;
    for (int i = 0; i < per_load; ++i) spec.slips.push_back(0.9 * i / (per_load - 1));
    spec.loads_n = loads == 1 ? std::vector<double>{58.86} : std::vector<double>{30.0, 58.86, 90.0};
    spec.noise.fx.relative = spec.noise.fz.relative = spec.noise.my.relative = relative_noise;
    spec.seed = 3;
    return synthesize(sandyLoam(), spec).data;
}

void decoupledFit(benchmark::State& state) {
    const DataSet d = data(1, 0.0);
    for (auto _ : state) benchmark::DoNotOptimize(fitDecoupled(d, kWheelA, DecoupledParameters{}));
    state.counters["samples"] = static_cast<double>(d.samples.size());
}
BENCHMARK(decoupledFit)->Unit(benchmark::kMillisecond);

// Decoupled fit followed by the full-model refinement with its covariance.
void refinedFit(benchmark::State& state) {
    const DataSet d = data(static_cast<int>(state.range(0)), state.range(1) * 0.01);
    RefineOptions options;
    options.max_shear_deformation_m = 0.02;
    for (auto _ : state) {
        const DecoupledFit start = fitDecoupled(d, kWheelA, DecoupledParameters{});
        benchmark::DoNotOptimize(refineFullModel(d, kWheelA, start.parameters, options));
    }
    state.counters["samples"] = static_cast<double>(d.samples.size());
}
// (loads, noise %): noise-free single load is the thesis setting; 1 % noise on three loads is
// the setting in which every parameter is determined.
BENCHMARK(refinedFit)->Args({1, 0})->Args({3, 0})->Args({3, 1})->Unit(benchmark::kMillisecond);

// One streaming update (window of 60 samples, warm start) in steady state.
void streamingUpdate(benchmark::State& state) {
    DataSet d = data(1, 0.01);
    // A robot's slip wanders: visit the sweep in a scrambled order.
    std::vector<Sample> order;
    for (std::size_t i = 0; i < d.samples.size(); ++i)
        order.push_back(d.samples[(i * 37) % d.samples.size()]);
    StreamingIdentifier id(kWheelA);
    std::size_t i = 0;
    for (; i < 60; ++i) id.push(order[i % order.size()]);
    for (auto _ : state) benchmark::DoNotOptimize(id.push(order[i++ % order.size()]));
}
BENCHMARK(streamingUpdate)->Unit(benchmark::kMillisecond);

}  // namespace
