// Fuzz harness: a soil file (strict JSON, io::parseJson, then io::soilFromJson, the reader of
// `--soil FILE` and of every soil a scenario, script or project names).
#include <cstddef>
#include <cstdint>

#include "core/io/json.h"
#include "core/io/parameters_json.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace terra;
    const Result<nlohmann::json> json = io::parseJson(fuzz::textOf(data, size), "fuzz.json");
    fuzz::checkResult(json);
    if (json) fuzz::checkResult(io::soilFromJson(*json, "fuzz.json"));
    return 0;
}
