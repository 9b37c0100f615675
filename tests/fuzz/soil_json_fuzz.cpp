// Fuzz harness: a soil file (strict JSON, io::parseJson, then io::soilFromJson, the reader of
// `--soil FILE` and of every soil a scenario, script or project names).
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/io/json.h"
#include "core/io/json_reader.h"
#include "core/io/parameters_json.h"
#include "tests/fuzz/fuzz_support.h"

TERRA_FUZZ_HARNESS(soil_json) {
    using namespace terra;
    const std::string text = fuzz::textOf(data, size);
    const Result<nlohmann::json> json = io::parseJson(text, "fuzz.json");
    fuzz::checkResult(json);
    if (json) fuzz::checkResult(io::soilFromJson(*json, "fuzz.json"));
    // The loaders' path: numbers no double holds marked NaN, the reader run on them for the
    // ranges (io::readJsonTextWith).
    fuzz::checkResult(io::readJsonTextWith<soil::SoilParameters>(
        text, "fuzz.json", [](const nlohmann::json& j, const std::string& source) {
            return io::soilFromJson(j, source);
        }));
    return 0;
}
