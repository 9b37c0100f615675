#pragma once
/// @file traction_figures.h
/// The best-slip figure (core/analysis/traction.h; docs/traction.md): the objective against
/// slip for the given soil, the posterior's 5–95 % band and its lower quantile when there is
/// one, and markers at s* and the robust s*.

#include <QString>

#include "core/analysis/traction.h"

class QCustomPlot;

namespace terra::ui {

void plotTraction(QCustomPlot& plot, const analysis::TractionResult& result, const QString& title);

}  // namespace terra::ui
