#pragma once
/// @file saved_rover.h
/// A rover run in a project's results file (core/project/results.h): the time series the rover
/// panel plots (every column, every row), the summary, the traction metrics, the streaming
/// table, the status and message of the run, and the scenario it ran (its name as shown and its
/// JSON, from which the top view draws the robot and its soils); a field run's maps and their
/// history as the run holds them (the rover panel crops them to the driven area first,
/// scenario::cropMaps). Read back to the same numbers.

#include <nlohmann/json.hpp>
#include <string>

#include "core/common/issue.h"
#include "core/scenario/runner.h"

namespace terra::project {

/// Version of the section's form (SavedResult::version).
inline constexpr int kRoverVersion = 1;

struct SavedRoverRun {
    scenario::RunResult run;
    std::string scenario_name;  ///< as the panel shows it ("straight (edited)")
    nlohmann::json scenario;    ///< the scenario's JSON as run (a preset's, or the edit)
};

nlohmann::json savedJson(const SavedRoverRun& run);
/// The run savedJson wrote; every problem with its field path under `where`.
Result<SavedRoverRun> savedRoverRunFromJson(const nlohmann::json& json, const std::string& where);

}  // namespace terra::project
