#pragma once
/// @file identification_fit_page.h
/// The identification panel's "Batch fit" page (identification_panel.h): the data (synthesised
/// from the project's soil, or a CSV previewed before Fit by DataPreviewWidget), the fit's options
/// (full model or decoupled fit, prior, held-out validation, loss, wheel, j_max), the data against
/// the fitted curves for F_x, F_z and M_y, the parameters ± std with prior and truth, and the
/// report (held-out error, ambiguity, adequacy). The computation itself runs in the panel
/// (AnalysisPanel::makeJob): this page gives its job and shows its result.

#include <QWidget>
#include <any>
#include <atomic>
#include <functional>
#include <optional>

#include "core/analysis/identification.h"
#include "core/project/panels.h"
#include "core/wheel/wheel_parameters.h"

class QCheckBox;
class QCustomPlot;
class QDoubleSpinBox;
class QLabel;
class QLineEdit;
class QPushButton;
class QTabWidget;
class QTableWidget;

namespace terra::ui {

class DataPreviewWidget;
class IdentificationFitOptions;
class ProjectDocument;

class IdentificationFitPage : public QWidget {
    Q_OBJECT
public:
    explicit IdentificationFitPage(ProjectDocument* document, QWidget* parent = nullptr);

    const analysis::IdentificationResult& result() const { return result_; }
    /// The batch fit's settings as the controls show them (identification_panel.h).
    analysis::IdentificationSettings fitSettings() const;
    /// The controls' part of the panel's saved settings, and setting them from it.
    void writeSettings(project::IdentificationPanelSettings& s) const;
    void applySettings(const project::IdentificationPanelSettings& s);
    /// The CSV's path as typed (empty: synthetic data).
    QString dataFile() const;
    void setDataFile(const QString& path);
    DataPreviewWidget& preview() const { return *preview_; }
    /// The preview's text while its tab is shown (a CSV), else empty.
    QString dataPreview() const;
    /// The fit's options (method, validation, loss, prior, wheel, j_max).
    IdentificationFitOptions& options() const { return *options_; }
    QString fitStatus() const;
    QString fitReport() const;
    void setStatus(const QString& html);
    const wheel::WheelParameters& fitWheel() const { return fit_wheel_; }
    QString parameterCell(int row, int column) const;
    QString parameterHeader(int column) const;
    std::optional<soil::SoilParameters> identifiedSoil() const;
    bool applyIdentifiedSoil();

    /// The three plots (F_x, F_z, M_y) and the label their read-out goes to.
    const std::vector<QCustomPlot*>& plots() const { return plots_; }
    QLabel* readout() const { return readout_; }
    QCustomPlot* currentPlot() const;

    /// The fit's computation on a worker (AnalysisPanel::Job), with the wheel and j_max mode it
    /// runs with remembered for the result.
    std::function<std::any(const std::atomic<bool>&)> makeJob();
    /// Shows a result of makeJob's job; `marked` writes a status line led by the mark of a
    /// partial result (AnalysisPanel::markedStatus).
    void present(const std::any& value, const std::function<QString(const QString&)>& marked);
    /// A saved result is about to be shown: it was fitted with the controls' wheel and j_max.
    void prepareSaved();
    /// Clicks Fit when it is enabled (the studio's Ctrl+R).
    void requestFit();
    /// The running fit's state: Fit and Cancel follow it.
    void setBusy(bool busy);
    void showFailure(const QString& message);
    /// No fit on screen (another project was opened): curves, table and report cleared.
    void clearResult();

signals:
    /// Fit was pressed and the prior items are valid.
    void fitRequested();
    /// Cancel was pressed.
    void cancelRequested();

private:
    void updateDataControls();
    void updateDataPreview();
    /// The parameters' table as tall as its rows (none: no minimum), so that the layout gives it
    /// their height before the report's: at 1024×700 it showed 3 of 9 rows (issue 27).
    void fitTableToRows();
    /// Empties the report, the parameters' table and the plots (no fit of these inputs shown).
    void clearShown();

    ProjectDocument* document_;
    QLineEdit* file_;
    QDoubleSpinBox* noise_;
    QCheckBox* refine_;
    QCheckBox* three_loads_;
    QPushButton* fit_;
    QPushButton* cancel_fit_;  ///< stops the running fit (it then says so, nothing to apply)
    QLabel* status_;
    QLabel* readout_;
    QTabWidget* tabs_;
    std::vector<QCustomPlot*> plots_;
    QTableWidget* parameters_;
    QPushButton* apply_;
    wheel::WheelParameters pending_wheel_;  // of the job last started
    wheel::WheelParameters fit_wheel_;      // of the result on screen
    QString pending_jmax_mode_ = "auto";    // of the job last started
    QString fit_jmax_mode_ = "auto";        // of the result on screen
    QString fit_source_;                    // "synthetic" or the CSV's file name
    IdentificationFitOptions* options_;
    QTabWidget* side_tabs_;  ///< "Parameters", "Data preview" (shown for a CSV)
    DataPreviewWidget* preview_;
    QLabel* report_;
    analysis::IdentificationResult result_;
};

}  // namespace terra::ui
