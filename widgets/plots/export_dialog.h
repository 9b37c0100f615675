#pragma once
/// @file export_dialog.h
/// The GUI's plot export dialog: it only gathers the file, size and resolution, then calls
/// exportPlot() and exportTable() — the same writers as the headless runner.

#include <QDialog>
#include <QStringList>

#include "widgets/plots/plot_export.h"

class QCheckBox;
class QLineEdit;
class QSpinBox;

namespace terra::ui {

/// The folder of `file_path`, made when it is missing and the user agrees ("The folder … does not
/// exist. Create it?"). True when the folder exists (or was made); false when the user declined
/// (`error` left empty) or it could not be made (`error` says so).
bool offerMissingFolder(QWidget* parent, const QString& file_path, QString* error = nullptr);

class ExportDialog : public QDialog {
    Q_OBJECT
public:
    ExportDialog(const QString& suggested_path, QWidget* parent = nullptr);

    QString path() const;
    ExportOptions options() const;
    bool writeCsv() const;

    /// Asks, then writes the plot (and its data as CSV beside it). A folder that does not exist is
    /// offered to be created; declined, the dialog comes back to change the path. Returns false
    /// when cancelled or failed (the failure is shown to the user); `written` gets the files
    /// written.
    static bool exportWithDialog(QWidget* parent, QCustomPlot& plot, const Table& table,
                                 const QString& suggested_path, QStringList* written = nullptr);

private:
    QLineEdit* path_;
    QSpinBox* width_;
    QSpinBox* height_;
    QSpinBox* dpi_;
    QCheckBox* csv_;
};

}  // namespace terra::ui
