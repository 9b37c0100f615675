// Fuzz harness: a .terra project (strict JSON, io::parseJson, then project::projectFromJson with
// the panels' settings and the rover panel's scenarios).
#include <cstddef>
#include <cstdint>

#include "core/io/json.h"
#include "core/project/project.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace terra;
    const Result<nlohmann::json> json = io::parseJson(fuzz::textOf(data, size), "fuzz.json");
    fuzz::checkResult(json);
    if (json) fuzz::checkResult(project::projectFromJson(*json, "fuzz.terra", &fuzz::presets()));
    return 0;
}
