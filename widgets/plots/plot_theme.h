#pragma once
/// @file plot_theme.h
/// The colours of a plot's frame (background, axes, tick labels, grid, legend, title): on screen
/// they follow the widget's palette, so a dark desktop gets dark plots; exports for reports use
/// the light theme unless asked otherwise (plot_export.h). Data colours are left alone.

#include <QColor>

class QCustomPlot;
class QPalette;

namespace terra::ui {

struct PlotTheme {
    QColor background;         ///< outside and inside the axis rect
    QColor foreground;         ///< axes, ticks, tick labels, axis labels, title, legend text
    QColor grid;               ///< major grid lines
    QColor sub_grid;           ///< minor grid lines
    QColor zero_line;          ///< the grid line at 0
    QColor legend_background;  ///< legend box (slightly translucent)

    /// White background, black text: QCustomPlot's own look, used for exports.
    static PlotTheme light();
    /// From a palette: Base for the background, Text for the foreground, grid between the two.
    static PlotTheme fromPalette(const QPalette& palette);
    bool isDark() const { return background.lightnessF() < 0.5; }
};

/// Paints the plot's frame in `theme` (no replot).
void applyPlotTheme(QCustomPlot& plot, const PlotTheme& theme);

/// Applies the theme of the plot's palette now and again whenever the palette changes (the
/// application's palette or the desktop's colour scheme). Idempotent.
void followPalette(QCustomPlot& plot);

/// Whether followPalette() was called on the plot.
bool followsPalette(const QCustomPlot& plot);

}  // namespace terra::ui
