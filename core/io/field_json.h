#pragma once
/// @file field_json.h
/// Field files (docs/field.md, "Field files"): a JSON object naming the rasters of a field and
/// the legend of its soil classes,
///
///     {"name": "...", "source": "...",
///      "height": "height.asc",                  (optional: flat without it)
///      "soil": "sandy-loam",                    (the soil outside the class map)
///      "soil_classes": "classes.asc",           (optional)
///      "legend": {"1": {"label": "field", "soil": "sandy-loam", "profile": "sandy-loam-moist"},
///                 "2": "clayey-soil"},
///      "parameters": {"c_kPa": "cohesion.asc"}} (optional: soil-file key → raster)
///
/// Raster and soil paths are relative to the field file. Soils and profiles are preset names,
/// files or inline objects (as in scenarios). Every problem comes back named; nothing throws.

#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "core/common/issue.h"
#include "core/field/field_map.h"
#include "core/field/field_summary.h"
#include "core/io/parameters_json.h"

namespace terra::io {

/// A field and what its file said besides the maps.
struct FieldFile {
    field::FieldMap map;
    std::string source;
    std::map<int, std::string> labels;  ///< class code → label ("wet patch"); the soil's name else
};

/// Reads a field from its JSON object; `base_dir` resolves relative raster and soil paths.
Result<FieldFile> fieldFromJson(const nlohmann::json& json, const std::string& where,
                                const std::filesystem::path& base_dir,
                                const PresetLocations& locations);
/// Reads a field file (core/io/json.h: strict JSON).
Result<FieldFile> loadField(const std::filesystem::path& path, const PresetLocations& locations);

/// The summary as JSON: {"name", "extent_m": [x_min, y_min, x_max, y_max], "height_m": [min,
/// max] or null, "max_slope_deg", "mean_slope_deg", "height_cell_m", "class_cell_m",
/// "classes": [{"code", "label", "soil", "profile", "area_m2", "share"}], "parameters": [keys]}.
nlohmann::json toJson(const field::FieldSummary& summary);

}  // namespace terra::io
