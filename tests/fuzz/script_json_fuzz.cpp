// Fuzz harness: a run script (strict JSON, io::parseJson, then project::scriptFromJson, the reader
// of `terrastudio run`; every analysis's settings).
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/io/json.h"
#include "core/io/json_reader.h"
#include "core/project/script.h"
#include "tests/fuzz/fuzz_support.h"

TERRA_FUZZ_HARNESS(script_json) {
    using namespace terra;
    const std::string text = fuzz::textOf(data, size);
    const Result<nlohmann::json> json = io::parseJson(text, "fuzz.json");
    fuzz::checkResult(json);
    if (json)
        fuzz::checkResult(project::scriptFromJson(*json, "fuzz.json", fuzz::presets(),
                                                  TERRA_RESOURCE_DIR "/scripts"));
    // The loaders' path: numbers no double holds marked NaN, the reader run on them for the
    // ranges (io::readJsonTextWith).
    fuzz::checkResult(io::readJsonTextWith<project::Script>(
        text, "fuzz.json", [](const nlohmann::json& j, const std::string& source) {
            return project::scriptFromJson(j, source, fuzz::presets(),
                                           TERRA_RESOURCE_DIR "/scripts");
        }));
    return 0;
}
