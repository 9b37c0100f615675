#include "widgets/plots/export_dialog.h"

#include <QCheckBox>
#include <QDialogButtonBox>
#include <QDir>
#include <QFileDialog>
#include <QFileInfo>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLineEdit>
#include <QMessageBox>
#include <QPushButton>
#include <QSpinBox>
#include <algorithm>

namespace terra::ui {

ExportDialog::ExportDialog(const QString& suggested_path, QWidget* parent) : QDialog(parent) {
    setWindowTitle("Export plot");
    path_ = new QLineEdit(suggested_path, this);
    path_->setObjectName("export.path");
    // The whole path on screen (it was clipped to the form's default width); long paths scroll.
    path_->setMinimumWidth(
        std::min(path_->fontMetrics().horizontalAdvance(suggested_path) + 24, 720));
    path_->setToolTip(suggested_path);
    connect(path_, &QLineEdit::textChanged, path_, &QLineEdit::setToolTip);
    auto* browse = new QPushButton("…", this);
    width_ = new QSpinBox(this);
    width_->setRange(16, 20000);
    width_->setValue(1200);
    width_->setSuffix(" px");
    height_ = new QSpinBox(this);
    height_->setRange(16, 20000);
    height_->setValue(800);
    height_->setSuffix(" px");
    dpi_ = new QSpinBox(this);
    dpi_->setRange(10, 2400);
    dpi_->setValue(96);
    csv_ = new QCheckBox("Also write the data as CSV beside it", this);
    csv_->setChecked(true);
    auto* file_row = new QHBoxLayout;
    file_row->addWidget(path_, 1);
    file_row->addWidget(browse);
    auto* buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel, this);
    auto* form = new QFormLayout(this);
    form->addRow("File (.png, .svg, .pdf)", file_row);
    form->addRow("Width", width_);
    form->addRow("Height", height_);
    form->addRow("Resolution [dpi]", dpi_);
    form->addRow(csv_);
    form->addRow(buttons);
    connect(buttons, &QDialogButtonBox::accepted, this, &QDialog::accept);
    connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::reject);
    connect(browse, &QPushButton::clicked, this, [this] {
        const QString path =
            QFileDialog::getSaveFileName(this, "Export plot", path_->text(),
                                         "PNG image (*.png);;SVG drawing (*.svg);;PDF (*.pdf)");
        if (!path.isEmpty()) path_->setText(path);
    });
}

QString ExportDialog::path() const { return path_->text().trimmed(); }

ExportOptions ExportDialog::options() const {
    ExportOptions o;
    o.width = width_->value();
    o.height = height_->value();
    o.dpi = dpi_->value();
    return o;
}

bool ExportDialog::writeCsv() const { return csv_->isChecked(); }

bool offerMissingFolder(QWidget* parent, const QString& file_path, QString* error) {
    const QString folder = QFileInfo(file_path).absolutePath();
    if (QFileInfo(folder).isDir()) return true;
    const auto answer = QMessageBox::question(
        parent, "Create the folder?",
        QString("The folder %1 does not exist. Create it?").arg(QDir::toNativeSeparators(folder)),
        QMessageBox::Yes | QMessageBox::No, QMessageBox::Yes);
    if (answer != QMessageBox::Yes) return false;
    if (!QDir().mkpath(folder)) {
        if (error) *error = "cannot create the folder " + folder;
        return false;
    }
    return true;
}

bool ExportDialog::exportWithDialog(QWidget* parent, QCustomPlot& plot, const Table& table,
                                    const QString& suggested_path, QStringList* written) {
    ExportDialog dialog(suggested_path, parent);
    for (;;) {
        if (dialog.exec() != QDialog::Accepted) return false;
        QString error;
        if (offerMissingFolder(parent, dialog.path(), &error)) break;
        if (!error.isEmpty()) {
            QMessageBox::warning(parent, "Export failed", error);
            return false;
        }
        // Declined: back to the dialog, its path kept, to choose another folder.
    }
    QString error;
    bool ok = exportPlot(plot, dialog.path(), dialog.options(), &error);
    if (ok && written) written->append(dialog.path());
    if (ok && dialog.writeCsv()) {
        const QFileInfo info(dialog.path());
        const QString csv = info.path() + "/" + info.completeBaseName() + ".csv";
        ok = exportTable(table, csv, &error);
        if (ok && written) written->append(csv);
    }
    if (!ok) QMessageBox::warning(parent, "Export failed", error);
    return ok;
}

}  // namespace terra::ui
