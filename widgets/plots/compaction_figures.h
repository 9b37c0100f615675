#pragma once
/// @file compaction_figures.h
/// Draws a compaction result (core/analysis/compaction.h, docs/compaction.md) on a QCustomPlot:
/// the largest stresses against depth with the profile's precompression stress and Terranimo's
/// risk bands, the x–z map of σ_z under the wheel, and sinkage, rut and drawbar pull per pass. The
/// same drawing for the compaction panel and for `terrastudio run`. Each function replaces what
/// the plot showed.

#include <QColor>
#include <QString>

#include "core/analysis/compaction.h"
#include "widgets/plots/completion.h"

class QCustomPlot;

namespace terra::ui {

/// Translucent fills of the risk bands (green ≤ 0.5 σ_pc, yellow ≤ 1.1 σ_pc, red above), behind
/// the curves.
QColor riskBandColor(analysis::Risk risk);

/// How complete a run is: cancelled, or failed part way (the passes before the stop are kept).
Completion compactionCompletion(const analysis::CompactionResult& result);

/// "" for a completed run; "CANCELLED (partial)" or "FAILED (partial)" otherwise (the passes
/// before the stop are kept and drawn).
QString compactionStatus(const analysis::CompactionResult& result);

/// `title` with " — " and compactionStatus() appended when the run did not complete.
QString compactionTitle(const QString& title, const analysis::CompactionResult& result);

/// The largest σ_z, p and σ₁ (dashed) [kPa] against depth z [m] (downward) of pass `pass` (1 …
/// passes computed), or of the envelope over all passes (`pass` 0). With a profile: σ_pc before
/// that pass (the untouched profile's for the envelope) as a step line over the layers, the risk
/// bands of each layer as filled areas, and a dashed line where the red zone ends (when > 0). The
/// legend sits under the axes. Graph keys are depths, values stresses (the graphs are on
/// yAxis/xAxis). Throws std::out_of_range for a pass that was not computed.
void plotCompactionProfile(QCustomPlot& plot, const analysis::CompactionResult& result, int pass,
                           const QString& title);

/// The heat map of σ_z [kPa] from result.map (rows z-major, then x): x along travel, depth z
/// downward, a colour scale "σ_z [kPa]" on the right (logarithmic over three decades below the
/// largest σ_z: the stress falls off as 1/z²; smaller and tensile values get its lowest colour).
/// An empty map draws empty axes with a note.
void plotCompactionMap(QCustomPlot& plot, const analysis::CompactionResult& result,
                       const QString& title);

/// Sinkage and rut depth [mm] per pass (points and lines, left axis) and the drawbar pull F_x [N]
/// (right axis), the legend under the axes.
void plotCompactionPasses(QCustomPlot& plot, const analysis::CompactionResult& result,
                          const QString& title);

}  // namespace terra::ui
