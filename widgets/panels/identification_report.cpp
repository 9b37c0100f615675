#include "widgets/panels/identification_report.h"

#include <QStringList>
#include <QTableWidget>
#include <cmath>

#include "core/identification/parameter_text.h"
#include "widgets/panels/summary_html.h"
#include "widgets/plots/number_format.h"

namespace terra::ui {
namespace {

using analysis::SummaryRow;

/// The size of a field's values: what rounding noise is measured against (formatNumber).
double scaleOf(const FieldInfo& field) {
    const double high = std::max(std::abs(field.range.low), std::abs(field.range.high));
    return std::isfinite(high) ? high : 1.0;
}

/// The summary's row of a parameter's estimate: the first row labelled with its symbol (the
/// prior and profile rows that follow use the symbol too); nullptr when the summary has none
/// (n₁ after the refinement, j_max of the decoupled fit).
const SummaryRow* estimateRow(const analysis::Summary& summary,
                              const analysis::IdentifiedField& field) {
    for (const SummaryRow& row : summary) {
        if (row.label == field.symbol) return &row;
    }
    return nullptr;
}

/// The summary's row of a parameter's prior against its posterior, or nullptr.
const SummaryRow* priorRow(const analysis::Summary& summary,
                           const analysis::IdentifiedField& field) {
    const std::string at = "/prior/" + std::string(field.key) + "/prior_mean";
    for (const SummaryRow& row : summary) {
        if (row.json == at) return &row;
    }
    return nullptr;
}

/// Whether a row is one of the parameter estimates the table shows.
bool isEstimateRow(const analysis::Summary& summary, const SummaryRow& row) {
    for (const analysis::IdentifiedField& field : analysis::identifiedFields()) {
        if (estimateRow(summary, field) == &row) return true;
    }
    return false;
}

}  // namespace

void fillParameterTable(QTableWidget& table, const analysis::IdentificationResult& result,
                        const std::optional<identification::DecoupledParameters>& truth) {
    const analysis::Summary summary = analysis::identificationSummary(result);
    const auto fields = analysis::identifiedFields();
    table.setRowCount(static_cast<int>(fields.size()));
    for (std::size_t i = 0; i < fields.size(); ++i) {
        const analysis::IdentifiedField& field = fields[i];
        const int row = static_cast<int>(i);
        auto* name = new QTableWidgetItem(QString::fromStdString(field.symbolWithUnit()));
        name->setToolTip(QString::fromUtf8(field.description));
        table.setItem(row, 0, name);
        // The estimate and its std as the summary (and the command line) gives them.
        QString value = "–", sd = "–";
        if (const SummaryRow* estimate = estimateRow(summary, field)) {
            const auto [shown, std_text] = valueAndStd(*estimate);
            value = shown;
            if (!std_text.isEmpty()) sd = std_text;
        }
        table.setItem(row, 1, new QTableWidgetItem(value));
        table.setItem(row, 2, new QTableWidgetItem(sd));
        // The summary's "prior ± std -> posterior ± std" and "shift, posterior/prior std".
        QString prior = "–", ratio = "–";
        if (const SummaryRow* p = priorRow(summary, field)) {
            const QString text = QString::fromStdString(p->value);
            prior = text.left(text.indexOf(" -> "));
            const QString detail = QString::fromStdString(p->detail);
            ratio = detail.mid(detail.indexOf(", ") + 2);
        }
        table.setItem(row, 3, new QTableWidgetItem(prior));
        table.setItem(row, 4, new QTableWidgetItem(ratio));
        // The truth is the panel's (the soil it synthesised the data from), not the result's.
        table.setItem(
            row, 5,
            new QTableWidgetItem(!truth ? QString("–")
                                 : std::isinf(field.userValue(*truth))
                                     ? QString("none")
                                     : formatNumber(field.userValue(*truth), scaleOf(field), 5)));
    }
}

QString identificationReport(const analysis::IdentificationResult& result) {
    // The core summary (what `identify` prints) but the estimates, which the table shows; the
    // steps last, under the rest.
    const analysis::Summary summary = analysis::identificationSummary(result);
    analysis::Summary rows;
    analysis::Summary steps;
    for (const SummaryRow& row : summary) {
        if (isEstimateRow(summary, row)) continue;
        (row.json.starts_with("/steps/") ? steps : rows).push_back(row);
    }
    rows.insert(rows.end(), steps.begin(), steps.end());
    return summaryHtml(rows);
}

QString identificationStatus(const analysis::IdentificationResult& result) {
    // One line: the time, and whether the solver's steps converged (the report lists each).
    QStringList unconverged;
    int solved = 0;
    for (const identification::StepReport& step : result.steps()) {
        const std::optional<bool> converged = identification::solverConverged(step.termination);
        if (!converged) continue;  // a step's own note, not a solver's end
        ++solved;
        if (*converged) continue;
        unconverged << QString::fromStdString(
                           step.name.worded(identification::ParameterNaming::kSymbol) + ": " +
                           identification::solverOutcome(step.termination))
                           .toHtmlEscaped();
    }
    QString line = QString("Fit in %1 ms").arg(result.fit_time_ms, 0, 'f', 0);
    if (solved > 0) {
        line += unconverged.isEmpty()
                    ? (solved == 1 ? QString(", converged") : QString(", every step converged"))
                    : QString("; not converged: ") + unconverged.join("; ");
    }
    return line + " (the steps are at the end of the report).";
}

}  // namespace terra::ui
