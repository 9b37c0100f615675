#include "widgets/panels/summary_html.h"

#include <QRegularExpression>
#include <QStringList>
#include <utility>

#include "widgets/panels/data_preview.h"

namespace terra::ui {
namespace {

// The summary's plain-text notation in a person's symbols.
QString symbols(const std::string& text) {
    static const QRegularExpression chi2("\\bchi2\\b"), std_word("\\bstd\\b");
    // The plain-text spelling of the Greek symbols the command line prints (θ_f, σ_pc, τ_l, β).
    static const std::pair<QRegularExpression, QString> greek[] = {
        {QRegularExpression("\\btheta_(f|m|r)\\b"), "θ_\\1"},
        {QRegularExpression("\\bsigma_(pc|z|1)\\b"), "σ_\\1"},
        {QRegularExpression("\\bsigma\\b"), "σ"},
        {QRegularExpression("\\btau_(t|l)\\b"), "τ_\\1"},
        {QRegularExpression("\\btau\\b"), "τ"},
        {QRegularExpression("\\bbeta\\b"), "β"},
        {QRegularExpression("\\bnu\\b"), "ν"}};
    QString out = withChannelSymbols(QString::fromStdString(text)).toHtmlEscaped();
    out.replace(chi2, "χ²");
    out.replace(std_word, "σ");
    for (const auto& [pattern, symbol] : greek) out.replace(pattern, symbol);
    return out;
}

}  // namespace

QString summaryRowHtml(const analysis::SummaryRow& row) {
    using Emphasis = analysis::SummaryRow::Emphasis;
    QString line = symbols(row.label);
    if (row.emphasis == Emphasis::kHeading) line = "<b>" + line + "</b>";
    if (!row.value.empty()) line += ": " + symbols(row.value);
    if (!row.unit.empty()) line += " " + QString::fromStdString(row.unit).toHtmlEscaped();
    if (!row.detail.empty()) line += " (" + symbols(row.detail) + ")";
    if (row.emphasis == Emphasis::kWarning) line = "<b>" + line + "</b>";
    return line;
}

QString summaryHtml(std::span<const analysis::SummaryRow> rows) {
    QStringList lines;
    for (const analysis::SummaryRow& row : rows) lines << summaryRowHtml(row);
    return lines.join("<br>");
}

QString summaryParagraphHtml(std::span<const analysis::SummaryRow> rows) {
    QString out;
    for (const analysis::SummaryRow& row : rows) {
        if (!out.isEmpty())
            out += row.emphasis == analysis::SummaryRow::Emphasis::kHeading ? "<br>" : "; ";
        out += summaryRowHtml(row);
    }
    return out;
}

std::pair<QString, QString> valueAndStd(const analysis::SummaryRow& row) {
    const QString value = QString::fromStdString(row.value);
    const qsizetype at = value.indexOf(" ± ");
    if (at < 0) return {value, QString()};
    return {value.left(at), value.mid(at + 3)};
}

}  // namespace terra::ui
