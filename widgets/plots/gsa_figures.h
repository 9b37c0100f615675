#pragma once
/// @file gsa_figures.h
/// The figures of the global studies (core/analysis/global_sensitivity.h), the same for the
/// studio's global sensitivity panel and `terrastudio run`: Sobol' indices (or Morris μ*/σ)
/// against slip as bars with confidence whiskers, and percentile bands of an output against slip
/// around the nominal curve.

#include <QColor>
#include <QString>
#include <cstddef>

#include "core/analysis/global_sensitivity.h"

class QCustomPlot;

namespace terra::ui {

/// The colour of parameter k of a study (the same in the bars and the legend).
QColor parameterColor(std::size_t k);

/// Bars of one output's indices at every slip of one slip angle (index into the grid's slip
/// angles): for each slip a group with, per parameter, S1 (solid) and ST (light) side by side,
/// each with its confidence interval as a whisker; Morris: μ* with its whisker and σ. A refused
/// study draws an empty plot with its message in the title. Throws std::out_of_range for an
/// output or slip angle the study does not have.
void plotGlobalIndices(QCustomPlot& plot, const analysis::GlobalSensitivityResult& result,
                       std::size_t output, std::size_t slip_angle, const QString& title);

/// One output against slip at one slip angle: the band between the lowest and the highest
/// percentile filled, the other percentiles as thin lines, the nominal curve (the soil itself)
/// solid on top. Throws std::out_of_range as above.
void plotUncertaintyBands(QCustomPlot& plot, const analysis::UncertaintyBandResult& result,
                          std::size_t output, std::size_t slip_angle, const QString& title);

}  // namespace terra::ui
