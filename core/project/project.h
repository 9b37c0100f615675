#pragma once
/// @file project.h
/// The studio's session as plain data — soil, wheel, operating conditions, data set and scenario
/// references, panel settings — and its readable JSON form, the `.terra` file (format
/// "terrastudio-project", version 1; docs/user-guide.md). The studio (widgets/document) and the
/// scripts share it; reading is strict (core/io/json_reader.h): every problem is reported with
/// its field path, unknown and duplicated keys included.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "core/analysis/analysis.h"
#include "core/analysis/conditions.h"
#include "core/common/issue.h"
#include "core/io/json_reader.h"
#include "core/io/parameters_json.h"
#include "core/soil/soil_parameters.h"
#include "core/wheel/wheel_parameters.h"

namespace terra::project {

/// The "format" of a .terra file and the version this program writes and reads.
inline constexpr const char* kFormat = "terrastudio-project";
inline constexpr int kVersion = 1;

struct Project {
    std::string soil_preset = "sandy-loam";  ///< preset the soil started from ("" = custom)
    soil::SoilParameters soil;
    std::string wheel_preset = "A";
    wheel::WheelParameters wheel;
    analysis::OperatingConditions conditions;
    std::vector<std::string> data_sets;  ///< CSV paths (identification)
    std::vector<std::string> scenarios;  ///< scenario file paths (rover)
    /// A measured single-wheel test (core/io/experiment.h: its CSV or its sidecar JSON) that the
    /// forces panel overlays on the model and calibrates to; relative paths are relative to the
    /// .terra file. "" = none. Written only when set ("experiment"), so that a project without a
    /// test is the version-1 file older studios read.
    std::string experiment;
    nlohmann::json panels = nlohmann::json::object();  ///< per-panel settings, by panel name

    bool operator==(const Project& other) const;
};

/// The project as JSON.
nlohmann::json toJson(const Project& project);

/// A project from JSON; every problem is listed with its field path under `where` (the file).
/// The panels' settings are checked too (panels.h); with `locations`, the scenarios edited in the
/// rover panel are checked as scenarios, their relative file names (a dropped robot's, written
/// relative by withRelativePaths) read against `project_dir`, the project file's folder.
Result<Project> projectFromJson(const nlohmann::json& json, const std::string& where,
                                const io::PresetLocations* locations = nullptr,
                                const std::filesystem::path& project_dir = {});

/// Reads a .terra file (strict JSON, then projectFromJson).
Result<Project> loadProject(const std::filesystem::path& path,
                            const io::PresetLocations* locations = nullptr);

/// The project with every file it names (data sets, scenarios, the experiment, the
/// identification panel's "csv" and "stream_csv", the rover panel's scenario file and the keys of
/// its edits of scenario files) that lies inside `project_dir` written relative to it
/// ("data/run1.csv"), so that the project's folder can be moved or shared as a whole. Files
/// elsewhere (installed presets, another disk) stay absolute. For writing a .terra file.
Project withRelativePaths(const Project& project, const std::filesystem::path& project_dir);

/// Whether a rover scenario the project names is a file (its name ends in ".json", in any case)
/// rather than a preset's name ("straight").
bool isScenarioFileName(std::string_view name);

/// The project with every relative file name (above) resolved against `project_dir`; absolute
/// names, as older studios wrote them, are kept. For reading a .terra file.
Project withAbsolutePaths(const Project& project, const std::filesystem::path& project_dir);

/// What the project's analyses read: its soil, wheel and conditions.
analysis::Inputs inputsOf(const Project& project);

}  // namespace terra::project
