// Fuzz harness: a run script (strict JSON, io::parseJson, then project::scriptFromJson, the reader
// of `terrastudio run`; every analysis's settings).
#include <cstddef>
#include <cstdint>

#include "core/io/json.h"
#include "core/project/script.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace terra;
    const Result<nlohmann::json> json = io::parseJson(fuzz::textOf(data, size), "fuzz.json");
    fuzz::checkResult(json);
    if (json)
        fuzz::checkResult(project::scriptFromJson(*json, "fuzz.json", fuzz::presets(),
                                                  TERRA_RESOURCE_DIR "/scripts"));
    return 0;
}
