#pragma once
/// @file analysis_figures.h
/// The figures of every analysis type of the registry (core/analysis/registry.h), by type and
/// figure key, from the analysis's Outcome: the same drawings as the studio's panels (figures.h,
/// sweep_plot.h, identification_figures.h, rover_figures.h, compaction_figures.h), for
/// `terrastudio run`.

#include <QString>
#include <any>
#include <optional>
#include <string>

#include "core/analysis/analysis.h"

class QCustomPlot;

namespace terra::ui {

/// Draws figure `key` of an analysis of `type` (whose settings and outcome these are) on `plot`,
/// replacing what it showed; the plot should be fresh (the streaming figures replace its
/// layout). Throws std::invalid_argument for a type or key the registry does not list.
void drawAnalysisFigure(QCustomPlot& plot, const std::string& type, const std::string& key,
                        const std::any& settings, const analysis::Outcome& outcome,
                        const QString& title);

/// The title of an analysis's figures: `title` when given, else the soil and wheel with the
/// load and what the analysis varies ("sandy loam, wheel A, W = 58.86 N, s = 0.3, β = 12°"); a
/// rover run's is its scenario and status.
QString analysisTitle(const std::string& type, const std::optional<std::string>& title,
                      const analysis::Inputs& inputs, const std::any& settings,
                      const analysis::Outcome& outcome);

}  // namespace terra::ui
