#pragma once
/// @file identification_report.h
/// What the identification panel's batch fit shows of a result besides its curves: the parameter
/// table (identified ± std, prior, σ post/prior, truth), the report under it (the data, whether
/// the fit is at a minimum, the held-out error, the ambiguity, the adequacy) and the status line.

#include <QString>
#include <optional>

#include "core/analysis/identification.h"

class QTableWidget;

namespace terra::ui {

/// Fills the six columns of `table` with the parameters of `result`; `truth`: the soil the
/// synthetic data were made from (none for a CSV: "–").
void fillParameterTable(QTableWidget& table, const analysis::IdentificationResult& result,
                        const std::optional<identification::DecoupledParameters>& truth);
/// The report under the table, HTML lines joined by <br>.
QString identificationReport(const analysis::IdentificationResult& result);
/// The status line of a fit: its time and each step's Σr².
QString identificationSteps(const analysis::IdentificationResult& result);

}  // namespace terra::ui
