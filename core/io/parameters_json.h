#pragma once
/// @file parameters_json.h
/// Soil and wheel parameter files (JSON, thesis units with unit-suffixed keys, see docs/soils.md)
/// and the presets in resources/. Every problem is reported with the file, the field, the value
/// and the allowed range; nothing throws.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/common/issue.h"
#include "core/io/json_reader.h"
#include "core/soil/soil_parameters.h"
#include "core/soil/soil_profile.h"
#include "core/wheel/wheel_parameters.h"

namespace terra::io {

/// The soil of the object `r` reads: every field of the table (soil_parameters.h), the rule
/// across them and an optional "profile" object (readProfile); problems go to the reader's
/// issues. A "posterior" key (an identification's, `identify --save-soil`) is allowed and left
/// to its readers. The caller calls r.finish().
soil::SoilParameters readSoil(ObjectReader& r);
/// The wheel of the object `r` reads ({"name", "source", "r_m", "b_m"}, optional
/// "grouser_height_m", "grouser_count", "grouser_thickness_m") and the rules across them.
wheel::WheelParameters readWheel(ObjectReader& r);

/// A soil profile ({"name", "source", "layers": [{"top_m", "bottom_m", "clay_kg_kg",
/// "bulk_density_Mg_m3", "matric_suction_hPa", "sigma_pc_kPa", "nu", "particle_density_Mg_m3",
/// "compression": {"N", "lambda", "kappa", "kappa2", "m"}}, …]}; docs/compaction.md) and its
/// rules (soil::validate); problems go to the reader's issues.
soil::SoilProfile readProfile(ObjectReader& r);
/// The JSON form of a profile (the keys readProfile reads; optional ones only when set).
nlohmann::json toJson(const soil::SoilProfile& profile);
/// Profile from a JSON object, or from a file, or a preset name ("loam-moist") or path.
Result<soil::SoilProfile> profileFromJson(const nlohmann::json& json, const std::string& where);
Result<soil::SoilProfile> loadProfile(const std::filesystem::path& path);

/// Soil from a JSON object; `where` prefixes every issue ("soils/x.json").
Result<soil::SoilParameters> soilFromJson(const nlohmann::json& json, const std::string& where);
/// Wheel from a JSON object ({"name", "r_m", "b_m"}).
Result<wheel::WheelParameters> wheelFromJson(const nlohmann::json& json, const std::string& where);

/// The JSON form of a soil or wheel (thesis units; optional keys only when set).
nlohmann::json toJson(const soil::SoilParameters& soil);
nlohmann::json toJson(const wheel::WheelParameters& wheel);

/// Loads a file (core/io/json.h: strict JSON, problems with line and column).
Result<soil::SoilParameters> loadSoil(const std::filesystem::path& path);
Result<wheel::WheelParameters> loadWheel(const std::filesystem::path& path);

/// Where presets are looked up: each directory holds soils/ and wheels/.
struct PresetLocations {
    std::vector<std::filesystem::path> directories;
    /// The directories to search: $TERRASTUDIO_RESOURCES, `<exe dir>/../share/terrastudio` (the
    /// install layout, which the build tree mirrors; build_info.h) and `<exe dir>/resources`.
    static PresetLocations standard(const std::filesystem::path& executable_dir);
};

/// The names of the presets of one kind ("soils" or "wheels"), sorted.
std::vector<std::string> presetNames(const PresetLocations& locations, const std::string& kind);

/// A preset name ("sandy-loam", "A") or a path to a JSON file.
Result<soil::SoilParameters> resolveSoil(const PresetLocations& locations,
                                         const std::string& name_or_path);
Result<wheel::WheelParameters> resolveWheel(const PresetLocations& locations,
                                            const std::string& name_or_path);
/// A profile preset (resources/profiles: "sandy-loam-moist") or a path to a JSON file.
Result<soil::SoilProfile> resolveProfile(const PresetLocations& locations,
                                         const std::string& name_or_path);

}  // namespace terra::io
