#pragma once
/// @file settings_flags.h
/// A command's flags as its analysis's settings object (issue 26): the flags that map onto a
/// settings struct are put in the JSON object its own reader reads, so that the ranges, the
/// kinds and their words are the reader's (one wording, one exit 2), the keys named by the flags
/// (nameFlags: "--slips[11]: 1.1 is outside the allowed range [-1, 1]").

#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "app/cli/cli_support.h"
#include "core/io/json_reader.h"

namespace terra::app {

using FlagNames = std::vector<std::pair<std::string, std::string>>;

/// The model flags given (--exit-angle or --rut-ratio, --max-stress-angle, --bulldozing) as the
/// keys of analysis::ModelChoices, added to `settings`.
inline void addModelChoices(const ModelOptions& o, nlohmann::json& settings) {
    if (o.exit_angle_deg) settings["exit_angle_deg"] = *o.exit_angle_deg;
    if (o.rut_ratio) settings["rut_ratio"] = *o.rut_ratio;
    if (o.max_stress_angle_deg) settings["max_stress_angle_deg"] = *o.max_stress_angle_deg;
    settings["bulldozing"] = o.bulldozing;
}

/// The keys of analysis::ModelChoices and their flags.
inline FlagNames modelChoiceFlags() {
    return {{"exit_angle_deg", "--exit-angle"},
            {"rut_ratio", "--rut-ratio"},
            {"max_stress_angle_deg", "--max-stress-angle"},
            {"bulldozing", "--bulldozing"}};
}

/// `settings` read from `object` by the analysis's reader `read(reader, settings)`; every
/// problem named by its flag (`keys_to_flags`, the model flags added) and thrown as InputError
/// (exit 2).
template <typename Settings, typename Read>
Settings readFlagSettings(const nlohmann::json& object, Read read, FlagNames keys_to_flags,
                          Settings settings = {}) {
    std::vector<Issue> issues;
    io::ObjectReader reader(object, issues);
    read(reader, settings);
    reader.finish();
    if (!issues.empty()) {
        for (auto& pair : modelChoiceFlags()) keys_to_flags.push_back(std::move(pair));
        nameFlags(issues, keys_to_flags);
        throw InputError(formatIssues(issues));
    }
    return settings;
}

}  // namespace terra::app
