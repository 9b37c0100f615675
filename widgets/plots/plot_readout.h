#pragma once
/// @file plot_readout.h
/// The read-out of a plot under the mouse: the data point of any curve nearest to the mouse on
/// screen, with its coordinates in the axes' units and the curve's name ("Slip ratio s = 0.3,
/// Drawbar pull F_x = 120.4 N — β = 0°"), marked by a ring on the plot; not the mouse position,
/// which lies between the curves. On a colour map, the value of the cell under the mouse.

#include <QPointF>
#include <QString>
#include <optional>

class QCPAbstractPlottable;
class QCustomPlot;
class QLabel;

namespace terra::ui {

/// A data point of a plottable (graph, curve, bars) and where it is drawn [px].
struct PlotPoint {
    QCPAbstractPlottable* plottable = nullptr;
    double key = 0.0, value = 0.0;
    QPointF pixel;
};

/// The drawn data point nearest to `pixel` among the visible plottables, inside the axes' ranges;
/// none for a plot without data points.
std::optional<PlotPoint> nearestPoint(QCustomPlot& plot, const QPointF& pixel);

/// "Drawbar pull F_x = 120 N" from an axis label "Drawbar pull F_x [N]" and a value (4
/// significant digits; no unit for "[-]"); empty for an axis without a label.
QString readoutPart(const QString& label, double value);

/// The read-out's text at `pixel` of the plot: nearestPoint()'s coordinates and its curve's name,
/// or the cell under the mouse of a colour map; empty when there is nothing to read.
QString readoutText(QCustomPlot& plot, const QPointF& pixel);

/// Shows readoutText() in `label` while the mouse moves over the plot, with a ring on the point
/// read; both are cleared when the mouse leaves the plot or the plot is hidden (another tab), so
/// the read-out never describes a plot out of sight.
void installReadout(QCustomPlot& plot, QLabel* label);

}  // namespace terra::ui
