#pragma once
/// @file summary_html.h
/// A result's core summary (analysis::Summary: label, value, unit, detail, emphasis) as the
/// panels show it: the rows the command line prints, in the same words and digits, as HTML
/// lines; only the notation is a person's (channel symbols F_x, χ², σ).

#include <QString>
#include <span>

#include "core/analysis/analysis.h"

namespace terra::ui {

/// One row: "label: value unit (detail)"; a heading's label bold, a warning's row bold. The text
/// is escaped; channel names ("Fx_N"), "chi2" and "std" are shown as F_x, χ², σ, and the
/// Greek names the command line spells out (theta_f, sigma_pc, sigma, tau_l, beta, nu) as θ_f,
/// σ_pc, σ, τ_l, β, ν.
QString summaryRowHtml(const analysis::SummaryRow& row);
/// The rows, joined by <br>.
QString summaryHtml(std::span<const analysis::SummaryRow> rows);
/// The rows as a short paragraph, for a results line under a plot (a line a row would take the
/// plot's height at 1024×700): a heading starts a new line, the other rows follow on it, joined
/// by "; ".
QString summaryParagraphHtml(std::span<const analysis::SummaryRow> rows);
/// The row's value split at " ± ": the value and its std ("" when the row has none).
std::pair<QString, QString> valueAndStd(const analysis::SummaryRow& row);

}  // namespace terra::ui
