#pragma once
/// @file map_layers.h
/// The maps drawn under the studio's top view (docs/user-guide.md, "Field layers"): a field's own
/// maps (height, soil classes) and every map a field run left (mapRasters), each with its label
/// and unit; a run's map as it was at a time t (from MapHistory); and the view of a map: the
/// window of it that a box covers, merged into blocks when it would hold more cells per side
/// than a screen shows, so that a 2,500 × 1,000 raster is drawn in milliseconds.

#include <array>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "core/common/table.h"
#include "core/field/raster.h"
#include "core/scenario/runner.h"
#include "core/scenario/scenario.h"

namespace terra::scenario {

/// How a layer's values read.
enum class LayerKind {
    kContinuous,  ///< a quantity with a unit (height, rut depth, passes, risk)
    kClasses,     ///< whole-number codes with labels (the soil classes)
};

/// One map that can be drawn under the top view.
struct MapLayer {
    std::string key;    ///< "height", "soil_classes", or a run map's key ("rut_depth_m")
    std::string label;  ///< "rut depth"
    std::string unit;   ///< SI: "m", "-" (a ratio or a count); empty for classes
    LayerKind kind = LayerKind::kContinuous;
    /// A map of the drive: it grows as the wheels pass (mapAt); the field's maps do not.
    bool timed = false;
    /// kClasses: each code with its label (the legend's, else its soil's name), ascending.
    std::vector<std::pair<int, std::string>> classes;
};

/// How a continuous layer's values are shown, by the studio's colour scale and by a map's PNG
/// (core/scenario/map_image.h): its values times `factor` on a scale titled `title` over
/// [lower, upper] (the final map's range, so that the colours hold while the time is scrubbed).
struct LayerScale {
    double factor = 1.0;  ///< SI → the scale's unit (1000 for a rut depth in mm)
    std::string unit;     ///< "mm", "m", "-"
    std::string title;    ///< "rut depth [mm]"
    double lower = 0.0;   ///< the scale's start, in its unit
    double upper = 1.0;   ///< the scale's end, in its unit
    /// A map of the drive: the studio leaves cells at 0 (untouched soil) clear, so the ground
    /// shows.
    bool clear_zero = false;
};

/// The scale of `layer` given its final map (or view of it): rut depths below 0.1 m in mm, the
/// range of the values (a map that is 0 everywhere gets [0, 1]; a map of the drive starts at 0,
/// untouched soil), the compaction risk on at least [0, 1.5] (Terranimo's bands at 0.5 and 1.1
/// stay where they belong).
LayerScale layerScale(const MapLayer& layer, const field::Raster& final_view);

/// A colour, 0–255 per channel.
struct Rgb {
    std::uint8_t r = 0, g = 0, b = 0;
    bool operator==(const Rgb&) const = default;
};

/// The colour at `at` ∈ [0, 1] along a scale (0: its lower end).
struct ColorStop {
    double at = 0.0;
    Rgb color;
};

/// The colours of a continuous layer along `scale`, one palette for the studio and the PNG maps:
/// the height as the land (green low, light, brown high); the compaction risk in Terranimo's
/// bands (green ≤ 0.5, yellow to orange ≤ 1.1, red to dark red above; the band edges at 0.5 and
/// 1.1 of the scale's values, whatever its range); the other maps of a drive sequential from
/// light to dark, every channel falling along the scale so that lightness does too (not
/// perceptually uniform): a rut from an ochre that stands out of a light soil to a dark brown,
/// passes in blues, any other map (slip, energy per metre) light yellow to dark purple.
/// Interpolated linearly in RGB between the stops (colorAt).
std::vector<ColorStop> layerColors(const MapLayer& layer, const LayerScale& scale);

/// The colour at `fraction` ∈ [0, 1] of `stops` (ascending): linear in RGB between the two
/// stops around it, rounded to the nearest integer; clamped to the end stops outside [0, 1] and
/// beyond the first and last stop. Throws std::invalid_argument for no stops.
Rgb colorAt(const std::vector<ColorStop>& stops, double fraction);

/// The layers of a scenario and its run, data-driven: "height" when the field has a height map,
/// "soil_classes" when it has a class map, then every map of `maps` (mapRasters: whatever the run
/// left, in its order). None for a patch scenario without a run's maps.
std::vector<MapLayer> mapLayers(const Scenario& scenario, const FieldMaps* maps);

/// A run's map `key` as a layer (timed, kContinuous) with its label and unit: the maps known by
/// name ("rut_depth_m": rut depth, m; "passes": wheel passes, -; "compaction_risk": the risk at
/// `maps.risk_depth_m`, -; "energy_per_m_J": energy per metre, J/m), else the key's words with its
/// unit suffix read off ("energy_J_m": energy, J/m; "max_slip": max slip, -), so that a map added
/// to FieldMaps is listed at once.
MapLayer runMapLayer(const std::string& key, const FieldMaps& maps);

/// The raster of layer `key`, the field's or the run's; nullptr when there is none.
const field::Raster* layerRaster(const Scenario& scenario, const FieldMaps* maps,
                                 const std::string& key);

/// A rectangle of a raster's cells: columns [col, col + cols) and rows [row, row + rows) (row 0
/// the northern one, as field::Raster). Empty when cols or rows is 0.
struct CellWindow {
    int col = 0, row = 0, cols = 0, rows = 0;
    bool empty() const { return cols <= 0 || rows <= 0; }
};

/// The cells of `raster` that overlap [x_min, x_max] × [y_min, y_max] [m] (clipped to the
/// raster; empty when the box misses it or is not finite).
CellWindow windowOver(const field::Raster& raster, double x_min_m, double y_min_m, double x_max_m,
                      double y_max_m);

/// The window's cells as a raster of their own (same cells, same place).
field::Raster crop(const field::Raster& raster, const CellWindow& window);

/// The area a run drove over [x_min, y_min, x_max, y_max] (m): the bounding box of the scenario's
/// start and the centre of mass's path (the series' finite x_m, y_m) widened on every side by the
/// robot's reach, 0.6 (L + T) + 2 r (wheelbase L, track T, wheel radius r). The top view shows
/// it and draws a run's maps over it; a saved run keeps its maps over it.
std::array<double, 4> drivenArea(const Scenario& scenario, const Table& series);

/// The maps cut to the cells of `window` (of their rasters, which share one geometry), the
/// history kept for the passages inside it (its cells renumbered). mapAt on the result equals
/// mapAt on `maps` over the same cells.
FieldMaps cropMaps(const FieldMaps& maps, const CellWindow& window);

/// Map `key` of a run (mapRasters) inside `window` as it was at time t [s]: a cell that
/// passages wrote takes the value after the last one written at or before t; before its first
/// one, the value of untouched soil: 0, or no data (NaN) where the final map has none. A map
/// without values in the history is drawn with its final value from the cell's first passage
/// on. Every cell no passage wrote keeps the final map's value. At t ≥ the last passage's time
/// the window equals the final map's. Throws std::invalid_argument for an unknown key.
/// Cost: the window's cells plus the passages up to t.
field::Raster mapAt(const FieldMaps& maps, const std::string& key, double t_s,
                    const CellWindow& window);

/// `raster` merged into blocks of k × k cells, k the smallest that leaves at most `max_side`
/// cells along each side (k = 1: a copy). For kContinuous each block holds the largest value
/// with data among its cells (a rut one cell wide stays visible at any zoom), NaN when none has
/// data; for kClasses the value of the block's middle cell (no code is invented). Blocks at the
/// east and south edges may hold fewer cells. Throws std::invalid_argument for max_side < 1.
field::Raster coarsen(const field::Raster& raster, int max_side, LayerKind kind);

/// The most cells per side coarsen leaves for the top view (about a screen's width).
inline constexpr int kMaxViewCells = 800;

/// What the top view draws for `layer` over [x_min, x_max] × [y_min, y_max]: the window of its
/// raster over the box, at time t for a map of the drive (mapAt; +∞: the final map), coarsened
/// to kMaxViewCells (or `max_side`). An empty raster (0 × 0) when the layer has no raster or the
/// box misses it.
field::Raster layerView(const Scenario& scenario, const FieldMaps* maps, const MapLayer& layer,
                        const std::array<double, 4>& box_m,
                        double t_s = std::numeric_limits<double>::infinity(),
                        int max_side = kMaxViewCells);

}  // namespace terra::scenario
