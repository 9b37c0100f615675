// Fuzz harness: a .terra project (strict JSON, io::parseJson, then project::projectFromJson with
// the panels' settings and the rover panel's scenarios).
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/io/json.h"
#include "core/io/json_reader.h"
#include "core/project/project.h"
#include "tests/fuzz/fuzz_support.h"

TERRA_FUZZ_HARNESS(project_terra) {
    using namespace terra;
    const std::string text = fuzz::textOf(data, size);
    const Result<nlohmann::json> json = io::parseJson(text, "fuzz.json");
    fuzz::checkResult(json);
    if (json) fuzz::checkResult(project::projectFromJson(*json, "fuzz.terra", &fuzz::presets()));
    // The loaders' path: numbers no double holds marked NaN, the reader run on them for the
    // ranges (io::readJsonTextWith).
    fuzz::checkResult(io::readJsonTextWith<project::Project>(
        text, "fuzz.json", [](const nlohmann::json& j, const std::string& source) {
            return project::projectFromJson(j, source, &fuzz::presets());
        }));
    return 0;
}
