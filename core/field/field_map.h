#pragma once
/// @file field_map.h
/// A field as the rover meets it (docs/field.md): a height map (the surface z(x, y); flat z = 0
/// without one), a soil-class map whose codes a legend turns into soils (each with its profile
/// for compaction), and rasters of single soil parameters that override the class's value where
/// they hold data (a moisture-driven cohesion, a measured K). SI inside; a parameter raster
/// holds the soil file's unit (phi_deg in degrees, c_kPa in kPa), converted by the soil's field
/// table.

#include <Eigen/Core>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/field/raster.h"
#include "core/soil/soil_parameters.h"

namespace terra::field {

/// One soil parameter given as a raster in the soil file's unit.
struct ParameterRaster {
    const soil::SoilField* field = nullptr;  ///< which parameter (soil::soilFields())
    Raster raster;
};

/// The slope under a heading (docs/field.md, F3).
struct LocalSlope {
    double grade_rad = 0.0;  ///< pitch: atan(∇z · d), positive uphill along the heading d
    double cross_rad = 0.0;  ///< roll: atan(∇z · d⊥), positive when the ground rises to the left
};

struct FieldMap {
    std::string name;
    std::optional<Raster> height;      ///< z [m]; empty: the plane z = 0
    std::optional<Raster> soil_class;  ///< whole-number class codes; empty: `base` everywhere
    std::map<int, soil::SoilParameters> legend;  ///< class code → soil (with its profile)
    soil::SoilParameters base;  ///< outside the class raster and on its cells without data
    std::vector<ParameterRaster> parameters;  ///< later rasters override earlier ones

    /// z [m] at (x, y): the height raster's bilinear surface (F1); 0 without a height map, and
    /// the nearest edge value outside it (the field continues flat beyond its map).
    double heightAt(double x_m, double y_m) const;
    /// ∇z = (∂z/∂x, ∂z/∂y) [-] (F2); zero without a height map and outside it.
    Eigen::Vector2d gradientAt(double x_m, double y_m) const;
    /// The upward unit normal (−∂z/∂x, −∂z/∂y, 1)/√(1 + |∇z|²).
    Eigen::Vector3d normalAt(double x_m, double y_m) const;
    /// The steepest slope atan|∇z| [rad].
    double slopeAt(double x_m, double y_m) const;
    /// Grade and cross slope under the heading ψ [rad] (from +x, counter-clockwise).
    LocalSlope slopeUnder(double x_m, double y_m, double heading_rad) const;

    /// The class code at (x, y), or none (outside the class raster or no data there).
    std::optional<int> classAt(double x_m, double y_m) const;
    /// The soil at (x, y): the class's soil (or `base`) with every parameter raster that holds
    /// data at (x, y) applied (nearest cell).
    soil::SoilParameters soilAt(double x_m, double y_m) const;
};

/// The class code a class raster's value stands for: the nearest whole number, none for no data.
std::optional<int> classCode(double value);

/// The EPSG code of the field's coordinate system: the first of its rasters (height, soil
/// classes, parameters) that names one (a GeoTIFF's; the field reader refuses rasters that name
/// different ones, core/io/field_json.h), or none.
std::optional<int> epsgCode(const FieldMap& field);

/// Every problem of a field, each naming the raster ("soil_classes", "parameters.phi_deg"), the
/// cell (col, row) and the value with the allowed range: a class code that is not a whole
/// number or has no legend entry (with its cell count), a parameter value outside its field's
/// range, a height not finite where it has data or steeper than 60° between neighbours, and
/// layout problems (validate(Raster)).
std::vector<Issue> validate(const FieldMap& field);

}  // namespace terra::field
