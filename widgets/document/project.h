#pragma once
/// @file project.h
/// The studio's session as plain data: soil, wheel, operating conditions, data set references,
/// scenarios and panel settings; and its readable JSON form (the `.terra` file,
/// docs/user-guide.md).

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/common/issue.h"
#include "core/soil/soil_parameters.h"
#include "core/wheel/wheel_parameters.h"

namespace terra::ui {

/// Operating conditions shared by the analyses (Table 2.6 defaults).
struct OperatingConditions {
    double load_n = 58.86;                                       ///< W [N] (6 kg)
    std::vector<double> slip_angles_deg{5, 10, 15, 20, 25, 30};  ///< β values of sweeps [deg]
    int slip_count = 100;                                        ///< slips 0 … slip_max
    double slip_max = 0.99;                                      ///< [-]
    bool quadratic = false;  ///< closed-form model instead of full
};

/// Allowed range of the load [N] in the editors and the file.
inline const Range kLoadRange{0.0, 1e5, true, false};

struct Project {
    std::string soil_preset = "sandy-loam";  ///< preset the soil started from ("" = custom)
    soil::SoilParameters soil;
    std::string wheel_preset = "A";
    wheel::WheelParameters wheel;
    OperatingConditions conditions;
    std::vector<std::string> data_sets;                ///< CSV paths (identification)
    std::vector<std::string> scenarios;                ///< scenario file paths (rover, issue 4)
    nlohmann::json panels = nlohmann::json::object();  ///< per-panel settings, by panel name

    bool operator==(const Project& other) const;
};

/// The project as JSON (format "terrastudio-project", version 1).
nlohmann::json toJson(const Project& project);

/// A project from JSON; every problem is listed with its field path.
Result<Project> projectFromJson(const nlohmann::json& json, const std::string& where);

}  // namespace terra::ui
