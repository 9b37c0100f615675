#pragma once
/// @file reference_overlay.h
/// A reference soil ("Compare with…" of the forces panel: the project's curves pinned before an
/// edit, or another soil preset) drawn over the forces panel's plots, and the data behind such a
/// plot. The reference is swept with the project's wheel and conditions, so that the plots compare
/// two soils and nothing else.

#include <QString>
#include <string>

#include "core/analysis/soil_curves.h"
#include "core/common/table.h"
#include "widgets/plots/sweep_plot.h"

class QCustomPlot;

namespace terra::ui {

/// Adds the reference sweep `sweep` (sweepColumns(), core/analysis/sweep.h) of `quantity` to a
/// plot drawn by plotSweep: one dashed curve per slip angle, in the colour of the project's curve
/// of the same β (sweepColor), object name "reference", named "<name>, β = 5°". One legend entry
/// stands for them all: with one slip angle the curve's own, with several the first curve's,
/// renamed "<name>, dashed". Refits the axes (fitSweepAxes); an empty sweep adds nothing.
void overlayReferenceSweep(QCustomPlot& plot, const SweepQuantity& quantity, const Table& sweep,
                           const QString& name);

/// Adds the reference's bulldozing resistance (Bekker coefficients, the one F_s uses) to a plot
/// drawn by plotBulldozing, grey and dashed, named "<name>, Bekker", object name "reference".
void overlayReferenceBulldozing(QCustomPlot& plot, const analysis::SoilCurves& curves,
                                const QString& name);

/// Adds the reference's static sinkage (Bekker, Eq. 2.8) to a plot drawn by plotStaticSinkage,
/// grey and dashed, named "<name>, Bekker Eq. 2.8", object name "reference".
void overlayReferenceStaticSinkage(QCustomPlot& plot, const analysis::SoilCurves& curves,
                                   const QString& name);

/// The data behind a plot with a reference (its CSV export and "Copy data"): the rows of `shown`
/// (the project's, possibly with a measured test: tableWithTest), then the reference's rows, under
/// the columns of `shown` matched by name. A text column "soil" names each row's soil
/// (`shown_name` or `reference_name`). Columns of `shown` the reference lacks are NaN, except
/// "measured" (0: the reference is a model) and "load_N" (`load_n`, the load it was swept at).
Table tableWithReference(const Table& shown, const std::string& shown_name, const Table& reference,
                         const std::string& reference_name, double load_n);

}  // namespace terra::ui
