#pragma once
/// @file plot_export.h
/// Writing a QCustomPlot as PNG, SVG or PDF at an explicit size and resolution, and a table as
/// CSV beside it. Used by the GUI's export dialog (which only gathers the options) and by the
/// headless runner; every file is written to a temporary name and renamed.

#include <QString>

#include "core/common/table.h"

class QCustomPlot;

namespace terra::ui {

struct ExportOptions {
    int width = 1200;  ///< [px] (PNG, SVG) or [pt] (PDF)
    int height = 800;
    int dpi = 96;        ///< resolution recorded in PNG/SVG
    double scale = 1.0;  ///< PNG pixel multiplier (2: a 2400 × 1600 image of the same layout)
    /// Keep the on-screen colours (a dark palette gives a dark image); by default plots that
    /// follow the palette (plot_theme.h) export light (white background) whatever the desktop.
    bool screen_colours = false;
};

/// Format from the suffix (.png, .svg, .pdf); false and `error` when unknown or not written. The
/// legend is where the screen shows it (plot_legend.h): under the axes with its columns fitted to
/// the export's width, or at the same place in the axes after a drag, or hidden.
bool exportPlot(QCustomPlot& plot, const QString& path, const ExportOptions& options,
                QString* error);

/// Table as CSV (core/io/csv.h), atomically.
bool exportTable(const Table& table, const QString& path, QString* error);

}  // namespace terra::ui
