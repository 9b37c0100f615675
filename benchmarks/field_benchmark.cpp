// Speed of the field's lookups (core/field/; docs/performance.md, "Field"): what a wheel asks of
// the terrain every step — the height and its gradient, the soil under it, its cell's state — on
// the shipped sloped field. The ≥ 1000× real-time rover of issue 23 has ~1 µs per wheel and step
// for all of its terrain work at a 1 ms step.
//   terra_benchmarks --benchmark_filter=Field
#include <benchmark/benchmark.h>

#include <random>

#include "core/field/cell_grid.h"
#include "core/io/field_json.h"

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
