#pragma once
// Reading a settings struct as a script's analysis object ("script.json: analyses[0]"), for the
// tests of the declared field lists.
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "core/common/issue.h"
#include "core/io/json_reader.h"

namespace terra::testing {

/// The settings `read(reader, settings)` makes of `json`, and the issues of reading them.
template <typename Settings, typename Read>
std::pair<Settings, std::vector<Issue>> readSettingsOf(const nlohmann::json& json, Read read) {
    std::vector<Issue> issues;
    io::ObjectReader r(json, issues, "script.json", "analyses[0]");
    Settings s;
    read(r, s);
    r.finish();
    return {s, issues};
}

/// The message of the issue at "script.json: analyses[0].KEY", or "(none)".
inline std::string settingsIssueAt(const std::vector<Issue>& issues, const std::string& key) {
    for (const Issue& issue : issues) {
        if (issue.where == "script.json: analyses[0]." + key) return issue.message;
    }
    return "(none)";
}

}  // namespace terra::testing
