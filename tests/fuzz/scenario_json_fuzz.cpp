// Fuzz harness: a scenario file (strict JSON, io::parseJson, then scenario::scenarioFromJson:
// robot, soils, signals; presets resolve).
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/io/json.h"
#include "core/io/json_reader.h"
#include "core/scenario/scenario_json.h"
#include "tests/fuzz/fuzz_support.h"

TERRA_FUZZ_HARNESS(scenario_json) {
    using namespace terra;
    const std::string text = fuzz::textOf(data, size);
    const Result<nlohmann::json> json = io::parseJson(text, "fuzz.json");
    fuzz::checkResult(json);
    if (json) fuzz::checkResult(scenario::scenarioFromJson(*json, "fuzz.json", fuzz::presets()));
    // The loaders' path: numbers no double holds marked NaN, the reader run on them for the
    // ranges (io::readJsonTextWith).
    fuzz::checkResult(io::readJsonTextWith<scenario::Scenario>(
        text, "fuzz.json", [](const nlohmann::json& j, const std::string& source) {
            return scenario::scenarioFromJson(j, source, fuzz::presets());
        }));
    return 0;
}
