#pragma once
/// @file field_summary.h
/// What a field holds, before any wheel drives on it (docs/field.md, "Summary"): its extent,
/// height range and slopes, and the area of each soil class.

#include <array>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/field/field_map.h"

namespace terra::field {

/// One soil class of the legend with the area its cells cover.
struct ClassArea {
    int code = 0;
    std::string label;     ///< the legend's label, or the soil's name
    std::string soil;      ///< the soil's name
    std::string profile;   ///< the profile's name; empty without one
    double area_m2 = 0.0;  ///< cells of the class × cell area
    double share = 0.0;    ///< of the cells with a class [-]
};

struct FieldSummary {
    std::string name;
    /// The extent of the maps [m]: the union of the height and class rasters; all zero without
    /// either.
    double x_min_m = 0.0, y_min_m = 0.0, x_max_m = 0.0, y_max_m = 0.0;
    std::optional<double> height_min_m, height_max_m;  ///< without a height map: none
    double max_slope_rad = 0.0;   ///< steepest slope at the height map's cell centres
    double mean_slope_rad = 0.0;  ///< their mean
    double height_cell_m = 0.0, class_cell_m = 0.0;  ///< 0: no such map
    std::vector<ClassArea> classes;                  ///< by code
    std::vector<std::string> parameters;             ///< soil-file keys given as rasters
};

/// The extent [x_min, y_min, x_max, y_max] of a field's maps [m]: the union of its height,
/// class and parameter rasters; none without any map.
std::optional<std::array<double, 4>> extent(const FieldMap& field);

/// The summary of a field; `labels` are the legend's labels by code (io::FieldFile::labels).
FieldSummary summarize(const FieldMap& field, const std::map<int, std::string>& labels = {});

/// The steepest slope atan|∇z| [deg] at every cell centre of the height map (F2); none without
/// one.
std::optional<Raster> slopeRaster(const FieldMap& field);

}  // namespace terra::field
