// Fuzz harness: a scenario file (strict JSON, io::parseJson, then scenario::scenarioFromJson:
// robot, soils, signals; presets resolve).
#include <cstddef>
#include <cstdint>

#include "core/io/json.h"
#include "core/scenario/scenario_json.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace terra;
    const Result<nlohmann::json> json = io::parseJson(fuzz::textOf(data, size), "fuzz.json");
    fuzz::checkResult(json);
    if (json) fuzz::checkResult(scenario::scenarioFromJson(*json, "fuzz.json", fuzz::presets()));
    return 0;
}
