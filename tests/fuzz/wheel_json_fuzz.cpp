// Fuzz harness: a wheel file (strict JSON, io::parseJson, then io::wheelFromJson, the reader of
// `--wheel FILE`).
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/io/json.h"
#include "core/io/json_reader.h"
#include "core/io/parameters_json.h"
#include "tests/fuzz/fuzz_support.h"

TERRA_FUZZ_HARNESS(wheel_json) {
    using namespace terra;
    const std::string text = fuzz::textOf(data, size);
    const Result<nlohmann::json> json = io::parseJson(text, "fuzz.json");
    fuzz::checkResult(json);
    if (json) fuzz::checkResult(io::wheelFromJson(*json, "fuzz.json"));
    // The loaders' path: numbers no double holds marked NaN, the reader run on them for the
    // ranges (io::readJsonTextWith).
    fuzz::checkResult(io::readJsonTextWith<wheel::WheelParameters>(
        text, "fuzz.json", [](const nlohmann::json& j, const std::string& source) {
            return io::wheelFromJson(j, source);
        }));
    return 0;
}
