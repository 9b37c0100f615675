// Saving a project's results (docs/performance.md, "Saved results"): what Save costs on the GUI
// thread for the largest section, a 60 s rover run with its 6,001-row time series.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <stdexcept>

#include "core/project/results.h"
#include "core/project/saved_rover.h"
#include "core/scenario/runner.h"
#include "core/scenario/scenario_json.h"

namespace {

using namespace terra;

// The shipped pulse-steering scenario, 60 s, a row every 10 ms (6,001 rows).
const project::SavedRoverRun& pulseSteeringRun() {
    static const project::SavedRoverRun run = [] {
        auto loaded =
            scenario::resolveScenario(io::PresetLocations{{TERRA_RESOURCE_DIR}}, "pulse-steering");
        if (!loaded) throw std::runtime_error(loaded.message());
        scenario::Scenario s = loaded.value();
        s.duration_s = 60.0;
        s.output_interval_s = 0.01;
        return project::SavedRoverRun{scenario::runScenario(s), s.name, nlohmann::json::object()};
    }();
    return run;
}

// The section as the rover panel builds it (savedJson): the series into JSON.
void BM_SavedRoverJson(benchmark::State& state) {
    const project::SavedRoverRun& run = pulseSteeringRun();
    for (auto _ : state) {
        nlohmann::json json = project::savedJson(run);
        benchmark::DoNotOptimize(json);
    }
    state.counters["rows"] = static_cast<double>(run.run.series.rows.size());
}
BENCHMARK(BM_SavedRoverJson)->Unit(benchmark::kMillisecond);

// The whole write: the section built, the file's JSON dumped and written atomically.
void BM_SaveResultsWithRoverRun(benchmark::State& state) {
    const project::SavedRoverRun& run = pulseSteeringRun();
    const std::filesystem::path path =
        std::filesystem::temp_directory_path() / "terra_results_benchmark.terra.results";
    for (auto _ : state) {
        project::SavedResults results;
        project::SavedResult& section = results.panels["rover"];
        section.version = project::kRoverVersion;
        section.result = project::savedJson(run);
        if (const auto error = project::saveResults(path, results)) {
            state.SkipWithError(error->c_str());
            break;
        }
    }
    state.counters["bytes"] = static_cast<double>(std::filesystem::file_size(path));
    std::filesystem::remove(path);
}
BENCHMARK(BM_SaveResultsWithRoverRun)->Unit(benchmark::kMillisecond);

}  // namespace
