#pragma once
/// @file plot_menu.h
/// The right-click menu of the studio's plots: export, copy the image, copy the data (CSV text),
/// show or hide the legend and put it back under the axes after a drag (plot_legend.h), and reset
/// the view (the whole data, as a double-click does).

#include <functional>

#include "core/common/table.h"

class QCustomPlot;
class QMenu;
class QWidget;

namespace terra::ui {

/// The data behind the plot and what "Export plot…" does, asked for when the menu is used.
struct PlotMenuHooks {
    std::function<Table()> table;
    std::function<void()> export_plot;
};

/// Builds the menu (actions named "plot.export", "plot.copy_image", "plot.copy_data",
/// "plot.legend" (checkable), "plot.legend_below", "plot.reset_view"); the caller shows or
/// inspects it.
QMenu* makePlotMenu(QCustomPlot& plot, const PlotMenuHooks& hooks, QWidget* parent);

/// Shows makePlotMenu() on a right click of the plot.
void installPlotMenu(QCustomPlot& plot, PlotMenuHooks hooks);

}  // namespace terra::ui
