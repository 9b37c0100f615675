#pragma once
/// @file forces_panel.h
/// The forces-versus-slip panel (Figs. 2.18–2.26): F_x, F_s, F_z, M_y, M_z and θ_f against slip
/// for the project's slip angles, one plot per quantity in tabs, plus bulldozing resistance
/// against sinkage (Fig. 2.15) and static sinkage against load (Fig. 2.6); all recomputed live off
/// the GUI thread whenever the soil, wheel or conditions change (AnalysisPanel).
///
/// With a measured test in the project (File ▸ Load Experiment…, core/io/experiment.h), the same
/// job predicts every measured point (core/analysis/validation.h, θ_f solved from the measured
/// load) and sweeps the model at the test's loads and slip angles: the drawbar pull, torque,
/// sinkage and side-force plots show the measured points over the model curves at the measured
/// load (experiment_overlay.h), and a box under the plots gives RMSE, MAE and the largest relative
/// error per measured channel, with "Calibrate to this test…" (calibration_dialog.h).
///
/// "Compare with…" overlays a reference soil on every plot (reference_overlay.h): the project's
/// soil pinned as it is now ("sandy loam (before edit)"), kept while the project's soil is edited,
/// or a soil preset. The same job sweeps it with the project's wheel and conditions (two soils, one
/// wheel); "Clear comparison" removes it. The reference is session state, not saved in the project.

#include <memory>
#include <optional>

#include "core/analysis/forces.h"
#include "core/analysis/soil_curves.h"
#include "core/analysis/validation.h"
#include "core/io/parameters_json.h"
#include "widgets/panels/analysis_panel.h"
#include "widgets/plots/experiment_overlay.h"

class QComboBox;
class QToolButton;
class QGroupBox;
class QLabel;
class QPushButton;
class QTabWidget;
class QTableWidget;

namespace terra::ui {

class CalibrationDialog;

class ForcesPanel : public AnalysisPanel {
    Q_OBJECT
public:
    explicit ForcesPanel(ProjectDocument* document, QWidget* parent = nullptr);

    /// The last sweep on screen (empty before the first one finishes).
    const analysis::ForcesResult& result() const { return result_; }
    /// The last bulldozing and static-sinkage curves on screen.
    const analysis::SoilCurves& soilCurves() const { return soil_curves_; }
    /// The project's test predicted with the soil on screen (empty without a test).
    const std::optional<analysis::ValidationResult>& validation() const { return validation_; }
    /// The metrics table under the plots (rows: measured channels; columns: channel, points,
    /// RMSE, MAE, max rel. error), for tests.
    QTableWidget* metricsTable() const { return metrics_; }
    /// Opens "Calibrate to this test" (created on first use; nullptr before).
    CalibrationDialog* openCalibration();
    CalibrationDialog* calibrationDialog() const { return calibration_; }

    /// Where "Compare with…" lists soil presets (none until set; the main window sets it).
    void setPresetLocations(const io::PresetLocations& locations);
    /// Pins the project's soil as it is now as the reference, named "<soil's name> (before
    /// edit)", and recomputes.
    void pinReference();
    /// Makes `soil` the reference under `name` and recomputes.
    void compareWith(const std::string& name, const soil::SoilParameters& soil);
    /// A soil preset ("clayey-soil") as the reference, under its soil's name; false (and
    /// `error`) when it cannot be read.
    bool compareWithPreset(const std::string& preset, QString* error = nullptr);
    /// Removes the reference and recomputes.
    void clearComparison();
    /// The reference asked for (its name; empty: none).
    QString referenceName() const;
    /// The reference's curves on screen: swept with the project's wheel and conditions of that
    /// result (empty tables without a reference or when it cannot be computed).
    const Table& referenceSweep() const { return shown_reference_.sweep; }
    const analysis::SoilCurves& referenceSoilCurves() const { return shown_reference_.soil; }
    QToolButton* compareButton() const { return compare_; }
    QPushButton* clearComparisonButton() const { return clear_compare_; }

    std::vector<std::pair<QString, QCustomPlot*>> plots() const override;
    QCustomPlot* currentPlot() const override;
    Table currentTable() const override;
    /// {"plot": name of the shown plot (plots())}: a project reopens on the same tab.
    nlohmann::json settings() const override;
    void applySettings(const nlohmann::json& settings) override;
    /// The sweep, soil curves and comparison with the project's test on screen ("forces"; not
    /// the comparison soil, which is session state) and the calibration dialog's last result
    /// ("forces.calibration"), for the project's results file. restoreResult shows the sweep
    /// again, without computing, while the soil, wheel, conditions and test are those it was
    /// computed from and no comparison soil is asked for.
    std::map<std::string, project::SavedResult> savedResults() const override;
    Restored restoreResult(const std::string& section, const project::SavedResult& saved) override;

protected:
    /// The project's soil, wheel and conditions and its measured test's content (not the tab
    /// shown, nor the comparison soil).
    nlohmann::json resultInputs() const override;
    Job makeJob() override;
    void present(const std::any& result) override;

public:
    /// A reference soil and what the panel computed of it.
    struct Reference {
        std::string name;
        soil::SoilParameters soil;
    };
    struct ReferenceCurves {
        std::string name;  ///< empty: no reference
        Table sweep;
        analysis::SoilCurves soil;
        std::string error;      ///< why it could not be computed ("" when it could)
        nlohmann::json key;     ///< what it was computed of: soil, wheel, conditions, name
        bool complete = false;  ///< not cancelled: reusable while `key` does not change
    };

private:
    void updateTestBox();
    void updateCompareControls();
    void fillCompareMenu();
    void showMetrics();

    QComboBox* model_;
    QToolButton* compare_;
    QPushButton* clear_compare_;
    QLabel* compare_label_;
    std::optional<io::PresetLocations> locations_;
    std::optional<Reference> reference_;  ///< the reference asked for
    ReferenceCurves shown_reference_;     ///< the reference of the result on screen
    /// The last complete reference, reused by the next job while its key is the same (editing the
    /// project's soil leaves a pinned reference's inputs as they are: it is not swept again).
    ReferenceCurves cached_reference_;
    QLabel* status_;
    QLabel* readout_;
    QTabWidget* tabs_;
    std::vector<QCustomPlot*>
        plots_;  ///< one per sweep quantity, then bulldozing_, static_sinkage_
    QCustomPlot* bulldozing_;
    QCustomPlot* static_sinkage_;
    QGroupBox* test_box_;
    QLabel* test_label_;
    QTableWidget* metrics_;
    QPushButton* calibrate_;
    CalibrationDialog* calibration_ = nullptr;
    analysis::ForcesResult result_;
    analysis::SoilCurves soil_curves_;
    std::optional<analysis::ValidationResult> validation_;
    std::vector<TestSweep> test_sweeps_;
    std::shared_ptr<const io::Experiment> shown_test_;  ///< the test validation_ is of
};

}  // namespace terra::ui
