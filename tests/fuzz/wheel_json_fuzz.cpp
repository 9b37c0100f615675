// Fuzz harness: a wheel file (strict JSON, io::parseJson, then io::wheelFromJson, the reader of
// `--wheel FILE`).
#include <cstddef>
#include <cstdint>

#include "core/io/json.h"
#include "core/io/parameters_json.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace terra;
    const Result<nlohmann::json> json = io::parseJson(fuzz::textOf(data, size), "fuzz.json");
    fuzz::checkResult(json);
    if (json) fuzz::checkResult(io::wheelFromJson(*json, "fuzz.json"));
    return 0;
}
