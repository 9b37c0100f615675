#pragma once
/// @file traversability.h
/// The traversability map of a field, made before driving (docs/field.md, "Traversability";
/// issue 23, item 4): for every cell and heading, the slip a robot's wheels need to hold a steady
/// speed there, and where they cannot (a stall). The robot's weight is shared by its four wheels;
/// on the grade θ_g and cross slope θ_c under the heading (F3) each wheel carries
/// W = m g cos θ_g cos θ_c / 4 and must pull F_x = m g sin θ_g / 4 (T1); the slip is the
/// smallest s in [s_min, s_max] with F_x(s; soil, W) = that pull (T2).

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/analysis/analysis.h"
#include "core/common/declared_fields.h"
#include "core/dynamics/robot.h"
#include "core/field/field_map.h"
#include "core/field/raster.h"
#include "core/io/png.h"

namespace terra::analysis {

/// The slips a traversability map may search [-].
inline constexpr Range kTraversabilitySlipRange{0.0, 0.99};

struct TraversabilitySettings {
    int headings = 8;              ///< headings evenly from 0 (along +x), counter-clockwise
    std::optional<double> cell_m;  ///< the map's cell [m]; empty: the height map's (or 1 m)
    double slip_min = 0.01;        ///< the slips searched [-]
    double slip_max = 0.9;
    int curve_points = 200;  ///< slips of each F_x(s) curve the search interpolates
    bool quadratic = true;   ///< the quadratic closed form (the rover's), else full model
    ModelChoices model;

    /// Its file keys, one line each (core/common/declared_fields.h): the reader, toJson and
    /// compute's checks are made from them. The model choices are read and written beside it.
    template <typename Visitor>
    void visitFields(Visitor& v) {
        v(fields::integer("headings", headings, 1, 360,
                          "headings evenly from 0 (along +x), counter-clockwise"));
        v(fields::number("cell_m", cell_m, {0.0, 100.0, true, false}, "m",
                         "the map's cell; absent: the height map's (or 1 m)"));
        v(fields::number("slip_min", slip_min, kTraversabilitySlipRange, "",
                         "the smallest slip searched"));
        v(fields::number("slip_max", slip_max, kTraversabilitySlipRange, "",
                         "the largest slip searched (above slip_min)"));
        v(fields::integer("curve_points", curve_points, 10, 5000,
                          "slips of each F_x(s) curve the search interpolates"));
        v(fields::flag("quadratic", quadratic,
                       "the quadratic closed form (the rover's); false: the full model"));
        v(fields::members(model));
    }
};

/// The keys of TraversabilitySettings::visitFields read strictly (io::readFields), the model
/// choices among them, then traversabilityRuleIssues.
void readTraversabilitySettings(io::ObjectReader& r, TraversabilitySettings& out);
/// The rule between keys: slip_min below slip_max (when both are in their range).
std::vector<Issue> traversabilityRuleIssues(const TraversabilitySettings& settings);
/// The settings' file keys (io::fieldsToJson), the model choices among them.
nlohmann::json toJson(const TraversabilitySettings& settings);

/// What a wheel can do on a cell under a heading.
enum class TraverseStatus : std::uint8_t {
    kOk = 0,       ///< a slip in [s_min, s_max] gives the pull
    kStall = 1,    ///< no slip gives it: the robot stalls (or slides back)
    kBraking = 2,  ///< downhill: even s_min pulls more than needed; the wheels must brake
};
const char* statusName(TraverseStatus status);

/// One heading's maps on the cells of `TraversabilityResult::grid`.
struct HeadingMap {
    double heading_rad = 0.0;
    field::Raster slip;    ///< the slip needed; NaN where not kOk
    field::Raster status;  ///< TraverseStatus as a number
    std::size_t stalled = 0, braking = 0;
};

struct TraversabilityResult {
    field::Raster grid;  ///< the cells (values: the steepest slope [deg], F2)
    std::vector<HeadingMap> headings;
    /// Per cell over the headings: the largest slip needed (NaN: every heading stalls or brakes)
    /// and the share of headings that stall.
    field::Raster worst_slip, stall_share;
    double robot_mass_kg = 0.0;
    int curves = 0;  ///< F_x(s) curves computed (one per soil and load bin)
    bool cancelled = false;
};

/// Throws std::invalid_argument for invalid settings or a robot whose wheel is invalid.
TraversabilityResult computeTraversability(const field::FieldMap& field,
                                           const dynamics::RobotParameters& robot,
                                           const TraversabilitySettings& settings = {},
                                           const Control& control = {});

/// {"cells", "cell_m", "headings": [{"heading_deg", "stalled", "braking", "max_slip"}],
///  "stall_cells" (cells where some heading stalls), "max_slip", "robot_mass_kg", "curves",
///  "cancelled"}.
nlohmann::json toJson(const TraversabilityResult& result);
/// The map for a person, as `terrastudio field --traversability` prints it: a heading with the
/// robot's mass, the grid and the slip curves; the cells, the cells where some heading stalls,
/// the largest slip needed; then one row per heading: its stalled cells, with its braking cells
/// and largest slip; "cancelled" when it was. Each number's `json` points at it in toJson(result).
Summary traversabilitySummary(const TraversabilityResult& result);
/// One row per cell and heading: x_m, y_m, heading_deg, grade_deg, slip, status.
Table traversabilityTable(const TraversabilityResult& result, const field::FieldMap& field);

/// The map of the largest slip needed over the headings as a picture with its legend
/// (scenario::renderMap, the palette of the run's slip map) on the fixed scale [0, 1]: a cell
/// where every heading stalls or brakes takes slip 1 (the darkest colour; the title says so), a
/// cell outside the field's data stays transparent.
io::RgbaImage traversabilityImage(const TraversabilityResult& result);

}  // namespace terra::analysis
