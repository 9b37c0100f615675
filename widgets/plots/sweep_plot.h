#pragma once
/// @file sweep_plot.h
/// Draws a force-versus-slip table (core/analysis/sweep.h) on a QCustomPlot: one curve per slip
/// angle, axes labelled with units, and exports it to PNG at an explicit size.

#include <QColor>
#include <QString>
#include <string>

#include "core/common/table.h"

class QCustomPlot;

namespace terra::ui {

/// One quantity of a sweep table to plot against slip.
struct SweepQuantity {
    std::string column;  ///< table column ("Fx_N")
    QString label;       ///< axis label with unit ("Drawbar pull F_x [N]")
    double scale = 1.0;  ///< plotted value = table value × scale (m → mm: 1e3)
};

/// The quantities of the forces panel (Figs. 2.18–2.26): F_x, F_s, F_z, M_y, M_z, θ_f.
const std::vector<SweepQuantity>& sweepQuantities();

/// Sinkage h = r (1 − cos θ_f) against slip, in mm (the forces panel's tab; not in render's set).
const SweepQuantity& sinkageQuantity();

/// The pen colour of a sweep's `index`-th slip-angle curve (plotSweep; a reference soil's dashed
/// curves use the same colour for the same β).
QColor sweepColor(int index);

/// Replaces the plot's graphs by `quantity` against slip, one graph per slip angle, with a legend.
/// Non-finite values are skipped, never drawn. `replot` false: the caller adds graphs and replots
/// (fitSweepAxes), so the plot is drawn once.
void plotSweep(QCustomPlot& plot, const Table& table, const SweepQuantity& quantity,
               const QString& title, bool replot = true);

/// Fits the axes to the graphs (a quantity held constant is not zoomed into rounding noise), puts
/// the legend off the data (placeLegend) and replots (unless `replot` is false): after graphs
/// were added.
void fitSweepAxes(QCustomPlot& plot, bool replot = true);

/// Puts the legend off the data: under the axes, or where the user dragged it (layOutLegend of
/// plot_legend.h).
void placeLegend(QCustomPlot& plot);

/// Writes the plot as PNG of `width` × `height` pixels; false (and `error`) on failure.
bool exportPng(QCustomPlot& plot, const QString& path, int width, int height, QString* error);

}  // namespace terra::ui
