#pragma once
/// @file data_preview.h
/// The identification's "Data preview" of a CSV before Fit: its first rows as the file has them
/// (line numbers at left), the columns found and ignored, the rows read and every bad row by line,
/// and the channels the fit will compare, or why it cannot fit the file. What it shows is
/// core/analysis/data_preview.h's previewDataFile, the same reading as the fit's, computed on a
/// worker (AnalysisRunner): the GUI thread only draws it, and a newer file or fit method
/// supersedes a preview still being read.

#include <QGroupBox>
#include <QString>

#include "core/analysis/data_preview.h"
#include "widgets/panels/analysis_runner.h"

class QLabel;
class QTableWidget;

namespace terra::ui {

/// Channel names of the data files ("Fx_N") in a text for a person: their symbols (F_x, F_z,
/// M_y, h), as the tabs and the other panels show them.
QString withChannelSymbols(QString text);

class DataPreviewWidget : public QGroupBox {
    Q_OBJECT
public:
    /// Data rows of the file shown as typed.
    static constexpr int kRows = 5;

    explicit DataPreviewWidget(QWidget* parent = nullptr);

    /// Previews the CSV at `path` as the fit with the full model (`full_model`) or the decoupled
    /// fit would read it; computed on a worker, shown when ready (previewShown()).
    void preview(const QString& path, bool full_model);
    /// Drops what is shown and any preview still being read.
    void clear();
    /// Whether a preview is being read on the worker.
    bool isReading() const { return runner_.isBusy() && !path_.isEmpty(); }

    /// The summary as shown (rows, columns, bad rows by line, channels fitted), or the reason
    /// there is none ("No such file: …").
    QString text() const;
    QString cell(int row, int column) const;
    QString header(int column) const;

signals:
    /// The preview of the newest file is on screen.
    void previewShown();

private:
    void display(const analysis::DataPreview& preview);

    QLabel* summary_;
    QTableWidget* rows_;
    AnalysisRunner runner_;
    QString path_;            // of the preview being read or shown
    bool full_model_ = true;  // of the preview being read or shown
};

}  // namespace terra::ui
