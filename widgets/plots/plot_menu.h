#pragma once
/// @file plot_menu.h
/// The right-click menu of the studio's plots: export, copy the image, copy the data (CSV text),
/// show or hide the legend and put it back under the axes after a drag (plot_legend.h), reset
/// the view (the whole data, as a double-click does), and show the plot in a dock of its own or
/// put it back (when the caller docks plots: widgets/panels/plot_docking.h).

#include <QString>
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

/// Whether the plot is in a dock of its own, and what moves it there (true) or back into its
/// panel `home` (false) — widgets/panels/plot_docking.h. No menu entry when not set.
struct PlotDockHooks {
    std::function<bool()> in_own_dock;
    std::function<void(bool)> set_own_dock;
    QString home;
};

/// Builds the menu (actions named "plot.export", "plot.copy_image", "plot.copy_data",
/// "plot.legend" (checkable), "plot.legend_below", "plot.reset_view", and with the docking hooks
/// "plot.own_dock": "Show in its own dock" or "Put back into <home>"); the caller shows or
/// inspects it.
QMenu* makePlotMenu(QCustomPlot& plot, const PlotMenuHooks& hooks, QWidget* parent,
                    const PlotDockHooks& dock = {});

/// Shows makePlotMenu() on a right click of the plot.
void installPlotMenu(QCustomPlot& plot, PlotMenuHooks hooks, PlotDockHooks dock = {});

}  // namespace terra::ui
