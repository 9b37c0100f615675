// Speed of the global-sensitivity layer (core/gsa): batch throughput and a Sobol' study of the
// wheel model (docs/performance.md, "Global sensitivity"). The study benchmark also prints its
// indices once to stderr: the first study of docs/sensitivity.md.
//   terra_benchmarks --benchmark_filter='Batch|SobolStudy'
#include <benchmark/benchmark.h>

#include <cstdio>
#include <numbers>
#include <vector>

#include "benchmarks/benchmark_support.h"
#include "core/gsa/batch.h"
#include "core/gsa/uncertainty_bands.h"
#include "core/gsa/wheel_studies.h"
#include "core/io/parameters_json.h"

namespace {

using namespace terra::gsa;
using terra::benchmarks::kDeg;

terra::soil::SoilParameters sandyLoamPreset() {
    return terra::io::resolveSoil(terra::io::PresetLocations{{TERRA_RESOURCE_DIR}}, "sandy-loam")
        .value();
}
terra::wheel::WheelParameters wheelAPreset() {
    return terra::io::resolveWheel(terra::io::PresetLocations{{TERRA_RESOURCE_DIR}}, "A").value();
}

// N samples with all four soil fields varied per sample over the study's ranges (an evenly
// spread, deterministic pattern), slips over [0.05, 0.9].
struct Samples {
    std::vector<double> slip, phi, c, k, n;
    explicit Samples(std::size_t count) {
        for (std::size_t i = 0; i < count; ++i) {
            const double t = (i + 0.5) / count;
            slip.push_back(0.05 + 0.85 * t);
            phi.push_back(20.0 + 15.0 * ((i * 7) % count) / count);
            c.push_back(5.0 * ((i * 13) % count) / count);
            k.push_back(0.005 + 0.035 * ((i * 17) % count) / count);
            n.push_back(0.5 + 0.6 * ((i * 23) % count) / count);
        }
    }
    BatchInput input(const double* load, const double* entry) const {
        BatchInput in{slip.size(), slip, {},
                      {},          {},   {{"phi_deg", phi}, {"c_kPa", c}, {"K_m", k}, {"n", n}}};
        if (load) in.load_n = {load, 1};
        if (entry) in.entry_angle_rad = {entry, 1};
        return in;
    }
};

// Evaluations per second of the batch with θ_f given (args: samples, threads).
void BatchForces(benchmark::State& state) {
    const Samples samples(static_cast<std::size_t>(state.range(0)));
    const double entry = 25 * kDeg;
    const BatchInput input = samples.input(nullptr, &entry);
    const auto soil = sandyLoamPreset();
    const auto wheel = wheelAPreset();
    RunControl control;
    control.threads = static_cast<int>(state.range(1));
    std::vector<double> fx(input.count), fz(input.count), my(input.count);
    std::vector<SampleStatus> status(input.count);
    BatchOutputView out;
    out.fx_n = fx, out.fz_n = fz, out.my_nm = my, out.status = status;
    for (auto _ : state) {
        benchmark::DoNotOptimize(evaluateBatch(soil, wheel, input, {}, out, control));
    }
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * input.count));
}
BENCHMARK(BatchForces)
    ->Args({4096, 1})
    ->Args({4096, 2})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// 10⁶ evaluations with θ_f given and every output written to caller-owned arrays: the C++ side
// of the Python module's figure (benchmarks/python_module_benchmark.py times terrastudio.forces
// on the same samples; docs/performance.md, "Python module"). Args: threads.
void BatchMillion(benchmark::State& state) {
    const Samples samples(1000000);
    const double entry = 25 * kDeg;
    const BatchInput input = samples.input(nullptr, &entry);
    const auto soil = sandyLoamPreset();
    const auto wheel = wheelAPreset();
    RunControl control;
    control.threads = static_cast<int>(state.range(0));
    std::vector<std::vector<double>> outputs(11, std::vector<double>(input.count));
    std::vector<SampleStatus> status(input.count);
    const BatchOutputView out{outputs[0], outputs[1], outputs[2],  outputs[3],
                              outputs[4], outputs[5], outputs[6],  outputs[7],
                              outputs[8], outputs[9], outputs[10], status};
    for (auto _ : state) {
        benchmark::DoNotOptimize(evaluateBatch(soil, wheel, input, {}, out, control));
    }
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * input.count));
}
BENCHMARK(BatchMillion)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

// The same with the load given: one cold entry-angle solve per sample.
void BatchEntryAngle(benchmark::State& state) {
    const Samples samples(static_cast<std::size_t>(state.range(0)));
    const double load = 58.86;
    const BatchInput input = samples.input(&load, nullptr);
    const auto soil = sandyLoamPreset();
    const auto wheel = wheelAPreset();
    RunControl control;
    control.threads = static_cast<int>(state.range(1));
    std::vector<double> fx(input.count), h(input.count);
    std::vector<SampleStatus> status(input.count);
    BatchOutputView out;
    out.fx_n = fx, out.sinkage_m = h, out.status = status;
    for (auto _ : state) {
        benchmark::DoNotOptimize(evaluateBatch(soil, wheel, input, {}, out, control));
    }
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * input.count));
}
BENCHMARK(BatchEntryAngle)
    ->Args({1024, 1})
    ->Args({1024, 2})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The first study of docs/sensitivity.md: F_x and sinkage of wheel A on sandy loam at 58.86 N,
// s = 0.1, 0.3, 0.6, over φ 20–35°, c 0–5 kPa, K 5–40 mm, n 0.5–1.1; N = 4096 (73,728 entry-angle
// solves); 1000 bootstrap resamples.
WheelStudy firstStudy() {
    WheelStudy study;
    study.soil = sandyLoamPreset();
    study.wheel = wheelAPreset();
    study.grid.slips = {0.1, 0.3, 0.6};
    study.grid.load_n = 58.86;
    study.outputs = {Output::kFx, Output::kSinkage};
    study.parameters.add("phi_deg", Uniform{20.0, 35.0});
    study.parameters.add("c_kPa", Uniform{0.0, 5.0});
    study.parameters.add("K_m", Uniform{0.005, 0.04});
    study.parameters.add("n", Uniform{0.5, 1.1});
    return study;
}

void printIndices(const SobolStudyResult& r) {
    std::fprintf(stderr, "Sobol' study: %zu base samples, %zu evaluations, status %d %s\n",
                 r.base_samples, r.evaluations, static_cast<int>(r.status), r.message.c_str());
    for (std::size_t o = 0; o < r.outputs.size(); ++o) {
        const Eigen::MatrixXd s1 = r.firstOrder(o), st = r.total(o);
        const Eigen::MatrixXd c1 = r.firstOrderConf(o), ct = r.totalConf(o);
        for (std::size_t p = 0; p < r.grid.size(); ++p) {
            std::fprintf(stderr, "%s s = %g (dropped %zu):", outputName(r.outputs[o]),
                         r.grid.slip(p), r.dropped_samples[p]);
            for (std::size_t i = 0; i < r.parameters.size(); ++i) {
                std::fprintf(stderr, "  %s S1 %.3f±%.3f ST %.3f±%.3f", r.parameters[i].c_str(),
                             s1(i, p), c1(i, p), st(i, p), ct(i, p));
            }
            std::fprintf(stderr, "\n");
        }
    }
}

void SobolStudy(benchmark::State& state) {
    const WheelStudy study = firstStudy();
    RunControl control;
    control.threads = static_cast<int>(state.range(0));
    static bool printed = false;
    for (auto _ : state) {
        const SobolStudyResult r = sobolStudy(study, {4096, 1, {}, 0.05, 0}, control);
        if (!printed) printIndices(r), printed = true;
        benchmark::DoNotOptimize(r);
    }
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * 4096 * 6 * 3));
}
BENCHMARK(SobolStudy)->Arg(1)->Arg(2)->Unit(benchmark::kSecond)->UseRealTime()->Iterations(1);

// Bands of F_x against slip for the same ranges: 1024 samples × 10 slips (10,240 solves); the
// figure of docs/sensitivity.md, printed once.
void UncertaintyBands(benchmark::State& state) {
    WheelStudy study = firstStudy();
    study.grid.slips = {0.0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9};
    study.outputs = {Output::kFx};
    RunControl control;
    control.threads = static_cast<int>(state.range(0));
    static bool printed = false;
    for (auto _ : state) {
        const BandResult r = uncertaintyBands(study, {1024, 1, {5.0, 50.0, 95.0}, 0.05}, control);
        if (!printed) {
            const terra::Table t = r.table();
            for (const std::string& c : t.columns) std::fprintf(stderr, "%s ", c.c_str());
            std::fprintf(stderr, "\n");
            for (const auto& row : t.rows) {
                for (double v : row) std::fprintf(stderr, "%.4g ", v);
                std::fprintf(stderr, "\n");
            }
            printed = true;
        }
        benchmark::DoNotOptimize(r);
    }
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * 1024 * 10));
}
BENCHMARK(UncertaintyBands)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
