#pragma once
/// @file figures.h
/// Draws the analyses' results (core/analysis) on a QCustomPlot: the same drawing
/// for the panels and for headless exports. Each function replaces what the plot showed.

#include <QString>
#include <string>

#include "core/analysis/identification.h"
#include "core/analysis/sensitivity.h"
#include "core/analysis/soil_curves.h"
#include "core/analysis/stresses.h"
#include "core/analysis/validation.h"

class QCustomPlot;

namespace terra::ui {

/// Clears graphs, items and the title row, then sets a new title.
void resetPlot(QCustomPlot& plot, const QString& title);

/// Removes the colour scales a figure added beside its axes (layout elements resetPlot() does not
/// clear).
void removeColorScales(QCustomPlot& plot);

/// Changes the title resetPlot() set, keeping what the plot shows (replots); no-op without one.
void setPlotTitle(QCustomPlot& plot, const QString& title);

/// The title resetPlot() set ("" without one).
QString plotTitle(const QCustomPlot& plot);

/// Puts the legend under the axes (where layOutLegend() of plot_legend.h puts every legend),
/// at most `columns` entries a row, fewer when the width takes fewer. resetPlot() forgets the
/// column count.
void legendBelow(QCustomPlot& plot, int columns);

/// One stress ("sigma", "tau", "tau_t", "tau_l") over θ: exact solid, quadratic dashed, with the
/// RMSE/MAE in the legend. "all" draws the four exact and approximated pairs together.
void plotStresses(QCustomPlot& plot, const analysis::StressResult& result,
                  const std::string& stress, const QString& title);

/// One curve per value of the varied parameter: `column` (Fx_N or Fs_N) against slip.
void plotSensitivityFamily(QCustomPlot& plot, const analysis::SensitivityResult& result,
                           const std::string& key, const std::string& column, const QString& title);

/// Horizontal bars: the change of F_x from the base soil at the lowest and highest variation of
/// each parameter, sorted by the largest change either makes (the most influential on top). In
/// the row of parameter k (y = k, 1-based) the low bar is centred at k − kTornadoBarOffset and the
/// high bar at k + kTornadoBarOffset, each kTornadoBarWidth tall: side by side, never overlapping.
constexpr double kTornadoBarOffset = 0.19;
constexpr double kTornadoBarWidth = 0.36;
void plotTornado(QCustomPlot& plot, const analysis::SensitivityResult& result, double slip,
                 const QString& title);

/// Bulldozing resistance F_b of one side wall against sinkage h (Fig. 2.15): Bekker's coefficients
/// solid (the ones the forces use), Hegedus's dashed.
void plotBulldozing(QCustomPlot& plot, const analysis::SoilCurves& curves, const QString& title);

/// Static sinkage h against load W (Fig. 2.6): Bekker's Eq. 2.8 (E2), Eq. 2.7 over the whole
/// contact and over its front half; a vertical line marks the project's load.
void plotStaticSinkage(QCustomPlot& plot, const analysis::SoilCurves& curves, const QString& title);

/// Data (points) and fitted curve (line) of one channel ("Fx_N", "Fz_N", "My_Nm") against slip.
void plotIdentification(QCustomPlot& plot, const analysis::IdentificationResult& result,
                        const std::string& channel, const QString& title);

/// A measured test against the model: channel `channel` ("Fx_N", "My_Nm", "sinkage_m" in mm,
/// "Fy_N", "Fz_N") against slip, per (load, slip angle) of the test one colour: the measured
/// points (discs), the given soil's curve (solid) and, after a usable calibration, the calibrated
/// soil's (dashed), each curve's legend entry with its RMSE over the measured points.
void plotValidation(QCustomPlot& plot, const analysis::ValidationResult& result,
                    const std::string& channel, const QString& title);

}  // namespace terra::ui
