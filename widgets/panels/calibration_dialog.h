#pragma once
/// @file calibration_dialog.h
/// "Calibrate to this test" (forces panel): fits the project's soil to its measured test with the
/// validation analysis's calibration (core/analysis/validation.h — the global identification from
/// the load with the project's soil as the Gaussian prior and first start, the same as
/// `terrastudio validate --calibrate`), on a worker thread with a progress bar and Cancel. Shows
/// the metrics before and after and the fitted parameters with their std and prior; with "Fit on
/// slips" it calibrates on those slips only and shows the errors on the held-out points too (the
/// others, predicted, as `validate --fit-slips`); "Apply" puts
/// the calibrated soil, named "<soil> (calibrated)", into the project as one undo step. A result
/// whose project has changed since the fit started (another soil, wheel or test) is not applied.

#include <QDialog>
#include <optional>

#include "core/analysis/validation.h"
#include "core/project/results.h"
#include "widgets/panels/analysis_panel.h"
#include "widgets/panels/analysis_runner.h"

class QCheckBox;
class QDoubleSpinBox;
class QLabel;
class QLineEdit;
class QProgressBar;
class QPushButton;
class QTableWidget;

namespace terra::ui {

class ProjectDocument;

class CalibrationDialog : public QDialog {
    Q_OBJECT
public:
    explicit CalibrationDialog(ProjectDocument* document, QWidget* parent = nullptr);
    ~CalibrationDialog() override;  ///< cancels a running fit and waits for its worker

    /// The settings the controls show: the project's test, calibrate, the noise levels
    /// (0: estimated from the residuals), whether n₁ is fitted too and the fit slips; nothing
    /// (and fitSlipsProblem() says why) while the fit slips are not a list of numbers.
    std::optional<analysis::ValidationSettings> settings() const;
    /// The slips to calibrate on, comma separated ("" or blank: every point).
    void setFitSlips(const QString& slips);
    /// What is wrong with the typed fit slips, or "".
    QString fitSlipsProblem() const;
    /// The noise std of F_x [N], M_y [N·m] and the sinkage [mm] (0: estimated), and n₁.
    void setOptions(double fx_noise_n, double my_noise_nm, double sinkage_noise_mm, bool fit_n1);

    /// Starts the calibration of the project's soil to its test (false: no test, or running).
    bool start();
    /// Asks the running fit to stop; the dialog then says it was cancelled (nothing to apply).
    void cancel();
    bool isRunning() const { return runner_.isRunning(); }
    /// The last finished calibration (before/after), if any.
    const std::optional<analysis::ValidationResult>& result() const { return result_; }
    /// Whether the result can be applied: usable, and the project is still the one it was fitted
    /// for.
    bool canApply() const;
    /// Puts the calibrated soil into the project (one undo step "Calibrate soil to <test>").
    bool apply();

    /// The last finished calibration for the project's results file (core/project/results.h,
    /// section "forces.calibration"): the result, the settings it ran with, and the hash of its
    /// inputs (the given soil, the wheel, the test's content, those settings). Empty without one.
    std::optional<project::SavedResult> savedResult() const;
    /// Shows a saved calibration without fitting again, its settings in the controls, when the
    /// project's wheel and test are those it was fitted to and the project's soil is its given
    /// soil (it can be applied) or its calibrated soil (it was applied); else changes nothing
    /// and says why (the forces panel's answer to AnalysisPanel::restoreResult).
    AnalysisPanel::Restored restore(const project::SavedResult& saved);

    QString statusText() const;
    /// The metrics table, the core's analysis::validationMetricsTable with its cells' texts (rows:
    /// channel × RMSE, MAE, largest relative error; columns: metric, given soil, calibrated, and
    /// with held-out points: held out with the given soil, held out calibrated) and the parameter
    /// table (symbol [unit], calibrated, ± std, prior), for tests.
    QTableWidget* metricsTable() const { return metrics_; }
    QTableWidget* parameterTable() const { return parameters_; }

signals:
    /// A calibration ended (finished, failed or cancelled); result() holds it when it finished.
    void calibrationFinished();

private:
    void finished(const AnalysisRunner::Outcome& outcome);
    void showResult();
    /// The controls' settings (noise levels, n₁, fit slips) as saved with a result.
    nlohmann::json controlSettings() const;
    /// What a calibration's result depends on: the given soil, the wheel, the test's content,
    /// the settings.
    nlohmann::json calibrationInputs(const soil::SoilParameters& given,
                                     const nlohmann::json& settings) const;
    void updateButtons();

    ProjectDocument* document_;
    QLabel* intro_;
    QDoubleSpinBox* fx_noise_;
    QDoubleSpinBox* my_noise_;
    QDoubleSpinBox* sinkage_noise_;
    QCheckBox* fit_n1_;
    QLineEdit* fit_slips_;
    QPushButton* run_;
    QPushButton* cancel_;
    QProgressBar* progress_;
    QLabel* status_;
    QTableWidget* metrics_;
    QTableWidget* parameters_;
    QPushButton* apply_;
    AnalysisRunner runner_;  ///< the fit's worker, cancel flag and progress
    std::optional<analysis::ValidationResult> result_;
    /// The settings the running or last calibration started with (savedResult's inputs).
    nlohmann::json started_settings_, result_settings_;
    int started_revision_ = -1;  ///< the document's revision the running or last fit is of
    int result_revision_ = -1;
    bool applied_ = false;
    bool status_shows_result_ = false;  ///< the status line describes result_  ///< the result was
                                        ///< applied (the change that follows is ours)
};

}  // namespace terra::ui
