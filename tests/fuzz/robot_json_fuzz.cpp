// Fuzz harness: a robot file (strict JSON, io::parseJson, then scenario::robotFromJson; its wheel
// may name a preset).
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/io/json.h"
#include "core/io/json_reader.h"
#include "core/scenario/scenario_json.h"
#include "tests/fuzz/fuzz_support.h"

TERRA_FUZZ_HARNESS(robot_json) {
    using namespace terra;
    const std::string text = fuzz::textOf(data, size);
    const Result<nlohmann::json> json = io::parseJson(text, "fuzz.json");
    fuzz::checkResult(json);
    if (json) fuzz::checkResult(scenario::robotFromJson(*json, "fuzz.json", fuzz::presets()));
    // The loaders' path: numbers no double holds marked NaN, the reader run on them for the
    // ranges (io::readJsonTextWith).
    fuzz::checkResult(io::readJsonTextWith<dynamics::RobotParameters>(
        text, "fuzz.json", [](const nlohmann::json& j, const std::string& source) {
            return scenario::robotFromJson(j, source, fuzz::presets());
        }));
    return 0;
}
