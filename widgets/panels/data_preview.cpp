#include "widgets/panels/data_preview.h"

#include <QFileInfo>
#include <QHeaderView>
#include <QLabel>
#include <QTableWidget>
#include <QVBoxLayout>

namespace terra::ui {
namespace {

QStringList qStrings(const std::vector<std::string>& strings) {
    QStringList out;
    for (const std::string& s : strings) out << QString::fromStdString(s);
    return out;
}

}  // namespace

QString withChannelSymbols(QString text) {
    const std::pair<const char*, const char*> symbols[] = {
        {"Fx_N", "F_x"}, {"Fz_N", "F_z"}, {"My_Nm", "M_y"}, {"sinkage_m", "h"}};
    for (const auto& [name, symbol] : symbols)
        text.replace(QString::fromUtf8(name), QString::fromUtf8(symbol));
    return text;
}

DataPreviewWidget::DataPreviewWidget(QWidget* parent) : QGroupBox(parent) {
    setFlat(true);
    summary_ = new QLabel(this);
    summary_->setWordWrap(true);
    summary_->setTextInteractionFlags(Qt::TextSelectableByMouse);
    rows_ = new QTableWidget(0, 0, this);
    rows_->verticalHeader()->setDefaultSectionSize(20);
    rows_->setEditTriggers(QAbstractItemView::NoEditTriggers);
    rows_->setWordWrap(false);
    rows_->horizontalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
    // The header, five rows and a horizontal scroll bar.
    rows_->setMaximumHeight(26 + 20 * kRows + 22);
    rows_->setToolTip("The first rows of the file as it has them (line numbers at left)");
    auto* layout = new QVBoxLayout(this);
    layout->addWidget(summary_);
    layout->addWidget(rows_);
    // A superseded preview (another file or fit method since) is dropped.
    connect(&runner_, &AnalysisRunner::finished, this,
            [this](const AnalysisRunner::Outcome& outcome) {
                if (!outcome.error.isEmpty()) {
                    summary_->setText("Cannot be previewed: " + outcome.error);
                    emit previewShown();
                    return;
                }
                display(std::any_cast<analysis::DataPreview>(outcome.value));
            });
}

void DataPreviewWidget::clear() {
    runner_.dropPending();
    runner_.supersede();
    path_.clear();
    rows_->clear();
    rows_->setRowCount(0);
    rows_->setColumnCount(0);
}

void DataPreviewWidget::preview(const QString& path, bool full_model) {
    clear();
    path_ = path;
    full_model_ = full_model;
    setTitle(QFileInfo(path).fileName());
    summary_->setText("Reading the file…");
    const auto needs = full_model ? identification::ColumnNeeds::kFullModel
                                  : identification::ColumnNeeds::kDecoupled;
    runner_.submit([file = path.toStdString(), needs](const analysis::Control&) -> std::any {
        return analysis::previewDataFile(file, needs, static_cast<std::size_t>(kRows));
    });
}

void DataPreviewWidget::display(const analysis::DataPreview& p) {
    if (!p.readable) {
        summary_->setText("No such file: " + path_);
        emit previewShown();
        return;
    }
    // The first rows as the file has them, with their line numbers.
    const QStringList header = qStrings(p.header);
    rows_->setColumnCount(static_cast<int>(header.size()));
    rows_->setHorizontalHeaderLabels(header);
    for (const analysis::PreviewRow& typed : p.rows) {
        const int row = rows_->rowCount();
        rows_->insertRow(row);
        rows_->setVerticalHeaderItem(row, new QTableWidgetItem(QString::number(typed.line)));
        const int count = std::min<int>(static_cast<int>(typed.cells.size()), header.size());
        for (int c = 0; c < count; ++c)
            rows_->setItem(row, c, new QTableWidgetItem(QString::fromStdString(typed.cells[c])));
    }
    const QStringList known = qStrings(p.known_columns), ignored = qStrings(p.ignored_columns);
    QStringList lines;
    lines << "Columns: " +
                 (known.isEmpty() ? QString("none of the data columns") : known.join(", ")) +
                 (ignored.isEmpty() ? QString() : " (ignored: " + ignored.join(", ") + ")");
    if (!p.read_error.empty()) {
        lines << "Cannot be fitted: " + withChannelSymbols(QString::fromStdString(p.read_error));
        summary_->setText(lines.join("\n"));
        emit previewShown();
        return;
    }
    const std::size_t bad = p.bad_rows.size();
    lines << QString("Rows: %1 read%2").arg(p.samples).arg(bad ? QString(", %1 bad").arg(bad) : "");
    for (const Issue& issue : p.bad_rows) {
        const QString where = QString::fromStdString(issue.where);
        const QString line = where.section(':', -1);  // "data.csv:6" → "6"
        lines << QString("  line %1: %2").arg(line, QString::fromStdString(issue.message));
    }
    if (bad > 0) lines << "Fit refuses the file until the bad rows are fixed or removed.";
    if (!full_model_) {
        lines << "Fits: " + withChannelSymbols("Fx_N, Fz_N, My_Nm") +
                     " (decoupled fit: entry angle measured)";
    } else if (!p.setup) {
        lines << "Cannot be fitted: " + withChannelSymbols(QString::fromStdString(p.setup_error));
    } else {
        QStringList fitted;
        for (int c = 0; c < identification::kChannelCount; ++c) {
            if (p.setup->channels[static_cast<std::size_t>(c)])
                fitted << withChannelSymbols(QString::fromUtf8(identification::channelNames()[c]));
        }
        lines << QString("Fits: %1 (%2)")
                     .arg(fitted.join(", "),
                          p.setup->source == identification::DataSource::kEntryAngle
                              ? "entry angle measured"
                              : "entry angle solved from the load");
    }
    summary_->setText(lines.join("\n"));
    emit previewShown();
}

QString DataPreviewWidget::text() const { return summary_->text(); }

QString DataPreviewWidget::cell(int row, int column) const {
    const QTableWidgetItem* item = rows_->item(row, column);
    return item != nullptr ? item->text() : QString();
}

QString DataPreviewWidget::header(int column) const {
    const QTableWidgetItem* item = rows_->horizontalHeaderItem(column);
    return item != nullptr ? item->text() : QString();
}

}  // namespace terra::ui
