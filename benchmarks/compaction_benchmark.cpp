// Speed of the compaction analysis (docs/performance.md, "Compaction"; docs/compaction.md): the
// depth profile under one wheel (goal ≤ 5 ms), an x–z map of 200 × 100 points (≤ 50 ms), and a
// Sobol' study of 8 soil parameters × 4,096 base samples on the compaction outputs (≤ 60 s on 2
// cores).
//   terra_benchmarks --benchmark_filter=Compaction
#include <benchmark/benchmark.h>

#include "core/analysis/compaction.h"
#include "core/analysis/global_sensitivity.h"
#include "core/compaction/footprint.h"
#include "core/compaction/passes.h"
#include "core/io/parameters_json.h"

namespace {

using namespace terra;

const io::PresetLocations& locations() {
    static const io::PresetLocations l{{TERRA_RESOURCE_DIR}};
    return l;
}

analysis::Inputs inputs(const std::string& wheel, double load) {
    analysis::Inputs in;
    in.soil = io::resolveSoil(locations(), "sandy-loam").value();
    in.wheel = io::resolveWheel(locations(), wheel).value();
    in.conditions.load_n = load;
    return in;
}

// The default profile of `terrastudio compaction` (19 depths, 0.1–1 m) with a 3-layer profile:
// one pass, the contact solved from the load. Args: passes.
void CompactionDepthProfile(benchmark::State& state) {
    const analysis::Inputs in = inputs("B", 800.0);
    analysis::CompactionSettings settings;
    settings.slip = 0.2;
    settings.profile = io::resolveProfile(locations(), "clay-wet").value();
    settings.passes = static_cast<int>(state.range(0));
    for (auto _ : state) benchmark::DoNotOptimize(analysis::computeCompaction(in, settings));
}
BENCHMARK(CompactionDepthProfile)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);

// σ_z, p and σ₁ on an x–z grid of 200 × 100 points under one solved wheel.
void CompactionStressMap(benchmark::State& state) {
    const analysis::Inputs in = inputs("B", 800.0);
    compaction::PassConditions c;
    c.load_n = 800.0;
    c.slip = 0.2;
    const compaction::SolvedPass pass =
        compaction::solvePass(in.contact(), {}, compaction::ReloadLaw{}, c);
    const compaction::StressPropagation propagation(
        compaction::wheelFootprint(pass.params, pass.op), 5.0);
    for (auto _ : state) {
        double sum = 0.0;
        for (int iz = 0; iz < 100; ++iz) {
            const double z = 0.05 + 0.95 * iz / 99.0;
            for (int ix = 0; ix < 200; ++ix) {
                const double x = -1.0 + 2.0 * ix / 199.0;
                sum += propagation.measuresAt({x, 0.0, z}).major;
            }
        }
        benchmark::DoNotOptimize(sum);
    }
    state.SetItemsProcessed(state.iterations() * 20000);
}
BENCHMARK(CompactionStressMap)->Unit(benchmark::kMillisecond);

// Sobol' indices of 8 soil parameters on max_sigma_z_kPa (0.3 m), red_to_depth_m and
// rut_depth_m after 2 passes: 4,096 base samples, N (d + 2) = 40,960 model runs. Args: threads.
void CompactionSobolStudy(benchmark::State& state) {
    analysis::Inputs in = inputs("B", 800.0);
    analysis::GlobalSensitivitySettings s;
    s.samples = 4096;
    s.resamples = 200;
    s.study.slips = {0.2};
    s.study.outputs = {"max_sigma_z_kPa", "red_to_depth_m", "rut_depth_m"};
    s.study.parameters = {{"phi_deg", gsa::Uniform{25.0, 33.0}}, {"c_kPa", gsa::Uniform{0.0, 5.0}},
                          {"n", gsa::Uniform{0.5, 1.0}},         {"kphi", gsa::Uniform{800, 2000}},
                          {"kc", gsa::Uniform{0.0, 20.0}},       {"K_m", gsa::Uniform{0.01, 0.04}},
                          {"a0", gsa::Uniform{0.1, 0.4}},        {"a1", gsa::Uniform{0.1, 0.5}}};
    s.study.compaction.passes = 2;
    s.study.compaction.profile = io::resolveProfile(locations(), "clay-wet").value();
    s.study.threads = static_cast<int>(state.range(0));
    for (auto _ : state) {
        const analysis::GlobalSensitivityResult r = analysis::computeGlobalSensitivity(in, s);
        benchmark::DoNotOptimize(r);
        if (r.status() != gsa::StudyStatus::kCompleted) state.SkipWithError(r.message().c_str());
    }
}
BENCHMARK(CompactionSobolStudy)->Arg(2)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();

}  // namespace
