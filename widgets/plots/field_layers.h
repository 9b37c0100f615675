#pragma once
/// @file field_layers.h
/// A field's maps under the rover's top view (docs/user-guide.md, "Field layers"): one layer of
/// core/scenario/map_layers.h drawn as a colour map beneath the path and the robot, with a colour
/// scale and its unit (for the soil classes, a legend entry per class instead). The layer's
/// values come in as a raster (scenario::layerView: cropped and coarsened in core); this file
/// only chooses colours and draws.

#include <QColor>
#include <QString>

#include "core/field/raster.h"
#include "core/scenario/map_layers.h"

class QCustomPlot;
class QCPColorMap;

namespace terra::ui {

/// The colour map's name (QCPColorMap::name) and the object name of its scale and class entries.
inline const char* kFieldLayerName = "field layer";

/// How a layer is shown: its values times `factor` on a scale titled `title` over
/// [lower, upper] (the final map's range, so the colours hold while the time is scrubbed).
struct LayerDisplay {
    double factor = 1.0;  ///< SI → the scale's unit (1000 for a rut depth in mm)
    QString unit;         ///< "mm", "m", "-"
    QString title;        ///< "rut depth [mm]"
    double lower = 0.0, upper = 1.0;
    /// A map of the drive: cells at 0 (untouched soil) are left clear, so the ground shows.
    bool clear_zero = false;
};

/// The display of `layer` given its final view (layerView at t = ∞): scenario::layerScale (rut
/// depths below 0.1 m in mm, the range of the view's values, the compaction risk on at least
/// [0, 1.5]), the one scale the maps' PNGs use too. Its colours are scenario::layerColors.
LayerDisplay layerDisplay(const scenario::MapLayer& layer, const field::Raster& final_view);

/// The colour of soil class `index` (0-based in the legend's order) on the soil layer.
QColor classColor(int index);

/// The top view's layer colour map, or nullptr when none is drawn.
QCPColorMap* topViewLayer(QCustomPlot& plot);

/// Draws `view` as `layer` under the top view's path and robot, replacing any earlier layer (its
/// colour map, colour scale and class entries). An empty view draws nothing. No replot.
void drawTopViewLayer(QCustomPlot& plot, const scenario::MapLayer& layer,
                      const LayerDisplay& display, const field::Raster& view);

/// Replaces the cells of the drawn layer by `view` (the time scrub: the same window at another
/// time), keeping its colours and scale. No-op without a layer or for a view of another size.
/// No replot.
void updateTopViewLayer(QCustomPlot& plot, const LayerDisplay& display, const field::Raster& view);

/// Removes the layer, its scale and its class entries. No replot.
void removeTopViewLayer(QCustomPlot& plot);

}  // namespace terra::ui
