// Speed of soil identification: the figures of issue #3 (docs/identification.md, performance.md).
// 91 samples (s = 0 : 0.01 : 0.9) of sandy loam on wheel A, from the full model.
#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>
#include <string>

#include "benchmarks/benchmark_support.h"
#include "core/identification/decoupled_fit.h"
#include "core/identification/full_fit.h"
#include "core/identification/identify.h"
#include "core/identification/streaming.h"
#include "core/identification/streaming_estimator.h"
#include "core/identification/synthetic.h"

namespace {

using namespace terra;
using namespace terra::identification;
using terra::benchmarks::kDeg;
const wheel::WheelParameters kWheelA{"A", "", 0.092, 0.107};

using terra::benchmarks::sandyLoam;

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

// The global identification (identify.h) with refinement and covariance, started from the thesis's
// far initial guesses (§5.2) and the space-filling design; (loads, noise %, from the load).
void globalIdentification(benchmark::State& state) {
    DataSet d = data(static_cast<int>(state.range(0)), state.range(1) * 0.01);
    IdentifyOptions options;
    options.max_shear_deformation_m = 0.02;
    const DecoupledParameters thesis;
    options.starts.push_back(
        {"thesis guess",
         {thesis.a0, thesis.a1, thesis.pressure_modulus, thesis.n0, thesis.cohesion_pa,
          thesis.friction_angle_rad, thesis.shear_modulus_m, thesis.max_shear_deformation_m}});
    if (state.range(2) == 1) {
        d.columns.entry_angle = false;
        d.columns.fz = false;
        for (Sample& s : d.samples) s.load_n = s.load_n.value_or(58.86);
    }
    IdentificationReport r;
    for (auto _ : state) {
        r = identify(d, kWheelA, options);
        benchmark::DoNotOptimize(r);
    }
    state.counters["samples"] = static_cast<double>(d.samples.size());
    state.counters["usable"] = r.usable();
    state.counters["screen_ms"] = r.timing.screening_ms;
    state.counters["descent_ms"] = r.timing.descent_ms;
    state.counters["refine_ms"] = r.timing.refinement_ms;
}
BENCHMARK(globalIdentification)
    ->Args({1, 0, 0})
    ->Args({3, 0, 0})
    ->Args({3, 1, 0})
    ->Args({3, 0, 1})
    ->Args({3, 1, 1})
    ->Unit(benchmark::kMillisecond);

// Issue 25, item 7: the global identification on several soils and both wheels, not one
// benchmark set. Soil (0 sandy loam, 1 dry sand, 2 clayey soil: Table 2.1 with their j_max of
// resources/soils), wheel (0 A, 1 B: Table 5.1), loads (1: 91 samples at W; 3: 30 + 30 + 31 at
// ½W, W, 1½W), j_max (0: held at the truth, --jmax; 1: identified, --jmax fit); 1 % noise,
// θ_f measured. W is 58.86 N on A, 98 N on B. `ok` is 1 when every parameter is within three std
// of the truth (the speed is worth nothing otherwise). Last argument: IdentifyOptions::threads
// (1 or 2); wall time (UseRealTime), the CPU column being the calling thread's alone.
struct BenchSoil {
    const char* name;
    double n, c_kpa, phi_deg, kc, kphi, k_m, jmax_m;
};
constexpr BenchSoil kBenchSoils[] = {{"sandy loam", 0.7, 1.7, 29.0, 5.3, 1515.0, 0.025, 0.02},
                                     {"dry sand", 1.1, 1.0, 30.0, 0.9, 1523.4, 0.025, 0.02},
                                     {"clayey soil", 0.5, 4.14, 13.0, 13.2, 692.2, 0.01, 0.009}};

void globalIdentificationMatrix(benchmark::State& state) {
    const BenchSoil& soil = kBenchSoils[state.range(0)];
    const bool wheel_b = state.range(1) == 1;
    const wheel::WheelParameters w =
        wheel_b ? wheel::WheelParameters{"B", "", 0.135, 0.165} : kWheelA;
    const int loads = static_cast<int>(state.range(2));
    const bool fit = state.range(3) == 1;
    contact::ContactParameters<double> p{w.radius_m,
                                         w.width_m,
                                         soil.n,
                                         0.0,
                                         soil.kc * 1e3 / w.width_m + soil.kphi * 1e3,
                                         soil.c_kpa * 1e3,
                                         soil.phi_deg * kDeg,
                                         soil.k_m,
                                         15e3,
                                         0.2,
                                         0.3,
                                         soil.jmax_m};
    const double load = wheel_b ? 98.0 : 58.86;
    SyntheticSpec spec;
    const int per_load = 91 / loads;
    for (int i = 0; i < per_load; ++i) spec.slips.push_back(0.9 * i / (per_load - 1));
    spec.loads_n =
        loads == 1 ? std::vector<double>{load} : std::vector<double>{0.5 * load, load, 1.5 * load};
    spec.noise.fx.relative = spec.noise.fz.relative = spec.noise.my.relative = 0.01;
    spec.seed = 5;
    const DataSet d = synthesize(p, spec).data;
    IdentifyOptions options;
    options.threads = static_cast<int>(state.range(4));
    if (fit) {
        options.fit_max_shear_deformation = true;
    } else {
        options.max_shear_deformation_m = soil.jmax_m;
    }
    IdentificationReport r;
    for (auto _ : state) {
        r = identify(d, w, options);
        benchmark::DoNotOptimize(r);
    }
    const ParameterVector truth{
        0.2,      0.3,        p.pressure_modulus, soil.n, soil.c_kpa * 1e3, soil.phi_deg * kDeg,
        soil.k_m, soil.jmax_m};
    bool ok = r.usable() && r.uncertainty.computed;
    for (int k = 0; k < kFullParameterCount && ok; ++k) {
        if (r.parameters[k] != truth[k])
            ok = std::abs(r.parameters[k] - truth[k]) <= 3.0 * r.uncertainty.std[k];
    }
    state.SetLabel(std::string(soil.name) + (wheel_b ? ", B" : ", A") +
                   (fit ? ", jmax fit" : ", jmax held"));
    state.counters["samples"] = static_cast<double>(d.samples.size());
    state.counters["ok"] = ok;
    state.counters["screen_ms"] = r.timing.screening_ms;
    state.counters["descent_ms"] = r.timing.descent_ms;
    state.counters["refine_ms"] = r.timing.refinement_ms;
    state.counters["cov_ms"] = r.timing.covariance_ms;
    state.counters["jmax_prior"] = r.shear_limit_prior;  // the search ran twice (identify.cpp)
}
BENCHMARK(globalIdentificationMatrix)
    ->ArgsProduct({{0, 1, 2}, {0, 1}, {1, 3}, {0, 1}, {1, 2}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

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

namespace {

// The streaming estimator (streaming_estimator.h) in steady state: slip sweeps of 50 samples at
// loads cycling 30, 58.86, 90 N, 1 % noise. Each iteration is one push; `refits` counts the
// batch refits of the arrival cost among them (every 300 samples), which the mean includes.
// Arg 1: every sample declares a slip standard error of 0.006 (a robot's observer at 0.3 m/s,
// docs/identification.md §8 "An uncertain slip"): the cost of the slip derivative and the
// whitening.
void streamingEstimatorUpdate(benchmark::State& state) {
    std::vector<Sample> samples;
    const double loads[3] = {30.0, 58.86, 90.0};
    for (int b = 0; b < 30; ++b) {
        SyntheticSpec spec;
        spec.loads_n = {loads[b % 3]};
        for (int i = 0; i < 50; ++i) spec.slips.push_back(0.05 + 0.8 * (b % 2 ? 49 - i : i) / 49.0);
        spec.noise.fx.absolute = 0.136;
        spec.noise.fz.absolute = 0.9;
        spec.noise.my.absolute = 0.0195;
        spec.seed = static_cast<std::uint64_t>(b + 1);
        for (Sample s : synthesize(sandyLoam(), spec).data.samples) {
            s.load_n = loads[b % 3];
            if (state.range(0) == 1) s.slip_std = 0.006;
            samples.push_back(s);
        }
    }
    StreamingEstimatorOptions options;
    options.fit.max_shear_deformation_m = 0.02;
    StreamingEstimator estimator(kWheelA, options);
    std::size_t i = 0;
    for (; i < 700; ++i) estimator.push(samples[i]);  // past the doubling refits (30 … 480)
    int refits = 0, pushes = 0;
    double update_ms = 0.0, refit_ms = 0.0;  // wall time of each kind (the push reports it)
    for (auto _ : state) {
        const StreamEstimate e = estimator.push(samples[i++ % samples.size()]);
        refits += e.refitted;
        ++pushes;
        (e.refitted ? refit_ms : update_ms) += e.update_ms;
        benchmark::DoNotOptimize(e);
    }
    state.counters["refits"] = refits;
    state.counters["pushes"] = pushes;
    state.counters["update_wall_ms"] = update_ms / std::max(1, pushes - refits);
    state.counters["refit_wall_ms"] = refits > 0 ? refit_ms / refits : 0.0;
}
BENCHMARK(streamingEstimatorUpdate)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace
