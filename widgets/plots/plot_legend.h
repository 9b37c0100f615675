#pragma once
/// @file plot_legend.h
/// Where a plot's legend goes, for the studio's plots and their exports alike. By default it sits
/// under the axes, off the data, with as many entries a row as the width takes (so it never
/// widens the plot). The user may drag it anywhere inside the axes, where it stays through
/// redraws (kept as a fraction of the axes, so an export of another size puts it at the same
/// place), hide it and show it again (the plot menu, plot_menu.h), or put it back under the axes.
/// The choice belongs to the plot widget: every figure drawn on it keeps it.

#include <QPointF>

class QCustomPlot;

namespace terra::ui {

/// Puts the legend where the user left it, or by default under the axes with its entries in as
/// many columns as fit `width_px` (the plot's width when 0). Called before every replot of a plot
/// with installLegendControls() and by exportPlot() for the export's width. No-op for a plot
/// without a legend or axes.
void layOutLegend(QCustomPlot& plot, int width_px = 0);

/// At most `columns` entries a row under the axes (0: as many as the width takes); a figure's
/// choice (figures.h legendBelow()), forgotten by resetPlot().
void setLegendColumns(QCustomPlot& plot, int columns);

/// Shows or hides the legend (the user's choice, kept through redraws); shown, it appears when
/// the figure has entries.
void setLegendShown(QCustomPlot& plot, bool shown);
bool legendShown(const QCustomPlot& plot);

/// Moves the legend's top-left corner to `top_left` [px of the plot widget], inside the axes (as
/// a drag drops it); kept through redraws until resetLegendPlacement().
void moveLegend(QCustomPlot& plot, const QPointF& top_left);
/// Whether the user has placed the legend (moveLegend), and back to the default place.
bool legendMoved(const QCustomPlot& plot);
void resetLegendPlacement(QCustomPlot& plot);

/// Lets the user drag the legend with the left button (it does not pan the axes then) and applies
/// layOutLegend() before every replot.
void installLegendControls(QCustomPlot& plot);

}  // namespace terra::ui
