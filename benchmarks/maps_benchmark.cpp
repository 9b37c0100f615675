// Writing a field run's maps as files (core/io/geotiff.h, core/scenario/map_image.h;
// docs/performance.md, "Maps as files"): the five maps of a 50 m × 20 m field on 2 cm cells
// (2,500 × 1,000 cells each), driven in ten lanes of two wheel tracks, as Float64 GeoTIFFs and
// as PNG pictures with their legend — encoding in memory, and the files written atomically.
//   terra_benchmarks --benchmark_filter=Maps
#include <benchmark/benchmark.h>

#include <cmath>
#include <filesystem>
#include <limits>

#include "core/io/geotiff.h"
#include "core/io/raster_io.h"
#include "core/scenario/map_image.h"
#include "core/scenario/runner.h"

namespace {

using namespace terra;

// Ten lanes 2 m apart along x, each two tracks of 10 cm (0.4 m track width) with values that vary
// along them; untouched soil elsewhere (0, or no data for slip and energy).
const scenario::FieldMaps& laneMaps() {
    static const scenario::FieldMaps maps = [] {
        constexpr int kCols = 2500, kRows = 1000;
        constexpr double kCell = 0.02;
        const double nan = std::numeric_limits<double>::quiet_NaN();
        scenario::FieldMaps m;
        m.risk_depth_m = 0.3;
        m.rut_depth_m = field::makeRaster(kCols, kRows, 0.0, 0.0, kCell, 0.0);
        m.passes = m.rut_depth_m;
        m.compaction_risk = m.rut_depth_m;
        m.slip = field::makeRaster(kCols, kRows, 0.0, 0.0, kCell, nan);
        m.energy_per_m_j = m.slip;
        for (int lane = 0; lane < 10; ++lane) {
            for (const double y_track : {1.0 + 2.0 * lane - 0.2, 1.0 + 2.0 * lane + 0.2}) {
                const int row0 = kRows - 1 - static_cast<int>((y_track + 0.05) / kCell);
                for (int row = row0; row < row0 + 5; ++row) {
                    for (int col = 0; col < kCols; ++col) {
                        const double s = std::sin(0.01 * col + lane);
                        m.rut_depth_m.value(col, row) = 4.5e-3 + 1.5e-3 * s;
                        m.passes.value(col, row) = 2.0;
                        m.compaction_risk.value(col, row) = 0.2 + 0.15 * s;
                        m.slip.value(col, row) = 0.2 + 0.1 * s;
                        m.energy_per_m_j.value(col, row) = 40.0 + 20.0 * s;
                    }
                }
            }
        }
        return m;
    }();
    return maps;
}

void MapsGeoTiffEncode(benchmark::State& state) {
    std::size_t bytes = 0;
    for (auto _ : state) {
        bytes = 0;
        for (const auto& entry : scenario::mapRasters(laneMaps()))
            bytes += io::toGeoTiff(*entry.second).value().size();
    }
    state.counters["bytes"] = static_cast<double>(bytes);
}
BENCHMARK(MapsGeoTiffEncode)->Unit(benchmark::kMillisecond);

void MapsPngRender(benchmark::State& state) {
    const scenario::FieldMaps& maps = laneMaps();
    for (auto _ : state) {
        for (const auto& [key, raster] : scenario::mapRasters(maps)) {
            const scenario::MapLayer layer = scenario::runMapLayer(key, maps);
            const scenario::LayerScale scale = scenario::layerScale(layer, *raster);
            benchmark::DoNotOptimize(scenario::renderMap(layer, scale, *raster));
        }
    }
}
BENCHMARK(MapsPngRender)->Unit(benchmark::kMillisecond);

void MapsPngRenderAndEncode(benchmark::State& state) {
    std::size_t bytes = 0;
    const scenario::FieldMaps& maps = laneMaps();
    for (auto _ : state) {
        bytes = 0;
        for (const auto& [key, raster] : scenario::mapRasters(maps)) {
            const scenario::MapLayer layer = scenario::runMapLayer(key, maps);
            const scenario::LayerScale scale = scenario::layerScale(layer, *raster);
            bytes += io::toPng(scenario::renderMap(layer, scale, *raster)).value().size();
        }
    }
    state.counters["bytes"] = static_cast<double>(bytes);
}
BENCHMARK(MapsPngRenderAndEncode)->Unit(benchmark::kMillisecond);

// What `simulate --out` adds for a field run: the .tif and .png of every map, written atomically.
void MapsTifAndPngFiles(benchmark::State& state) {
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / "terra_maps_benchmark";
    std::filesystem::create_directories(dir);
    const scenario::FieldMaps& maps = laneMaps();
    for (auto _ : state) {
        for (const auto& [key, raster] : scenario::mapRasters(maps)) {
            if (auto error = io::writeRaster(dir / (key + ".tif"), *raster))
                state.SkipWithError(error->c_str());
        }
        if (auto error = scenario::writeMapPngs(maps, dir)) state.SkipWithError(error->c_str());
    }
    std::filesystem::remove_all(dir);
}
BENCHMARK(MapsTifAndPngFiles)->Unit(benchmark::kMillisecond);

}  // namespace
