#include "widgets/panels/summary_html.h"

#include <QRegularExpression>
#include <QStringList>

#include "widgets/panels/data_preview.h"

namespace terra::ui {
namespace {

// The summary's plain-text notation in a person's symbols.
QString symbols(const std::string& text) {
    static const QRegularExpression chi2("\\bchi2\\b"), std_word("\\bstd\\b");
    QString out = withChannelSymbols(QString::fromStdString(text)).toHtmlEscaped();
    out.replace(chi2, "χ²");
    out.replace(std_word, "σ");
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

std::pair<QString, QString> valueAndStd(const analysis::SummaryRow& row) {
    const QString value = QString::fromStdString(row.value);
    const qsizetype at = value.indexOf(" ± ");
    if (at < 0) return {value, QString()};
    return {value.left(at), value.mid(at + 3)};
}

}  // namespace terra::ui
