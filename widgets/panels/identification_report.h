#pragma once
/// @file identification_report.h
/// What the identification panel's batch fit shows of a result besides its curves, all rendered
/// from the core summary (analysis::identificationSummary, what `identify` prints; issue 26): the
/// parameter table (identified, std, prior, σ post/prior from the summary's rows; the truth, the
/// panel's own), the report under it (the summary's other rows: the data, whether the fit is at
/// a minimum, the held-out error, the ambiguity, the adequacy, the notes, then each step) and the
/// status line (the time, and whether the solver's steps converged: one line, so that the page
/// fits 1024×700 with every parameter row in view).

#include <QString>
#include <optional>

#include "core/analysis/identification.h"

class QTableWidget;

namespace terra::ui {

/// Fills the six columns of `table` with the parameters of `result`; `truth`: the soil the
/// synthetic data were made from (none for a CSV: "–").
void fillParameterTable(QTableWidget& table, const analysis::IdentificationResult& result,
                        const std::optional<identification::DecoupledParameters>& truth);
/// The report under the table: the summary's rows but the estimates, the steps last, as HTML.
QString identificationReport(const analysis::IdentificationResult& result);
/// The status line of a fit: its time and whether each solver step converged (those that did
/// not named, in a user's words: identification::solverOutcome).
QString identificationStatus(const analysis::IdentificationResult& result);

}  // namespace terra::ui
