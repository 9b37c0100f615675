#pragma once
/// @file scenario_json.h
/// Robot and scenario files (JSON; format in docs/dynamics.md). Every problem comes back with the
/// file, the field path, the value and what is allowed; nothing throws.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "core/common/issue.h"
#include "core/dynamics/robot.h"
#include "core/io/parameters_json.h"
#include "core/scenario/scenario.h"

namespace terra::scenario {

/// A robot from a JSON object; the wheel is a preset name, a file or an inline object.
Result<dynamics::RobotParameters> robotFromJson(const nlohmann::json& json,
                                                const std::string& where,
                                                const io::PresetLocations& locations);
/// A robot preset name (resources/robots/NAME.json) or a path.
Result<dynamics::RobotParameters> resolveRobot(const io::PresetLocations& locations,
                                               const std::string& name_or_path);

/// A scenario from a JSON object. Soils, wheel and robot are presets or files (relative paths are
/// tried against `base_dir`, the scenario file's directory, then the working directory).
Result<Scenario> scenarioFromJson(const nlohmann::json& json, const std::string& where,
                                  const io::PresetLocations& locations,
                                  const std::filesystem::path& base_dir = {});
/// A scenario file.
Result<Scenario> loadScenario(const std::filesystem::path& path,
                              const io::PresetLocations& locations);
/// A scenario preset name (resources/scenarios/NAME.json, e.g. "straight") or a path.
Result<Scenario> resolveScenario(const io::PresetLocations& locations,
                                 const std::string& name_or_path);

}  // namespace terra::scenario
