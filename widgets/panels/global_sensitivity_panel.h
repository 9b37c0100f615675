#pragma once
/// @file global_sensitivity_panel.h
/// Global sensitivity panel: which soil parameters matter when all are uncertain together, and
/// how uncertain the predicted forces are. Its "Indices" page shows Sobol' S1 and ST (or Morris
/// μ*, σ) of a chosen output against slip as bars with confidence whiskers; its "Uncertainty
/// bands" page shows Monte Carlo percentile bands of an output against slip around the project
/// soil's curve. The uncertain parameters are the ranges the user ticks in the table, or the
/// identified soil's covariance (from the identification panel's last fit). Computed on "Compute"
/// off the GUI thread (core/analysis/global_sensitivity.h), with progress and cancel. A study of
/// at most kAutomaticEvaluations model evaluations (the example study's 18,432) also computes when
/// the panel is first shown; a larger one (a project saved with 100,000 samples: 1.8 M) waits for
/// Compute and says so, so opening a project never starts a long study by itself.

#include <atomic>
#include <memory>
#include <optional>

#include "core/analysis/global_sensitivity.h"
#include "widgets/panels/analysis_panel.h"

class QComboBox;
class QDoubleSpinBox;
class QLabel;
class QLineEdit;
class QProgressBar;
class QPushButton;
class QSpinBox;
class QTabWidget;
class QTableWidget;
class QTimer;

namespace terra::ui {

class GlobalSensitivityPanel : public AnalysisPanel {
    Q_OBJECT
public:
    /// The most model evaluations a study may take to start without Compute (about 1 s here).
    static constexpr std::size_t kAutomaticEvaluations = 50000;

    explicit GlobalSensitivityPanel(ProjectDocument* document, QWidget* parent = nullptr);

    /// What the last computation gave (empty before one finished).
    const std::optional<analysis::GlobalSensitivityResult>& indices() const { return indices_; }
    const std::optional<analysis::UncertaintyBandResult>& bands() const { return bands_; }

    /// The page computed by compute(): 0 indices, 1 bands.
    void showPage(int page);
    /// A parameter row of the table: ticked (varied) with this range in the field's unit.
    /// Returns false for a key the table does not list.
    bool setRange(const std::string& key, bool varied, double low, double high);
    void setSlips(const QString& slips);
    void setSamples(int samples);
    void setMethod(analysis::GsaMethod method);
    /// The identified soil and its uncertainty (the identification panel's refined fit): makes
    /// "identified soil's covariance" available as the source of the parameters.
    void setIdentification(const identification::DecoupledParameters& identified,
                           const identification::Uncertainty& uncertainty);
    /// 0: the ranges of the table; 1: the identified soil's covariance.
    void setSource(int source);
    /// Computes the current page.
    void compute();
    /// Compute (when no study runs).
    void requestRun() override;

    /// Model evaluations the shown page's study takes: Sobol' N (d + 2), Morris r (d + 1) or the
    /// bands' M samples, per slip and slip angle (throws as indexSettings()).
    std::size_t plannedEvaluations() const;
    /// The status line ("Not computed: … press Compute", the evaluations, an error).
    QString statusText() const;

    /// The settings the controls make (throws std::invalid_argument for unreadable slips).
    analysis::GlobalSensitivitySettings indexSettings() const;
    analysis::UncertaintyBandSettings bandSettings() const;

    std::vector<std::pair<QString, QCustomPlot*>> plots() const override;
    QCustomPlot* currentPlot() const override;
    Table currentTable() const override;
    nlohmann::json settings() const override;
    void applySettings(const nlohmann::json& settings) override;
    /// The indices ("global-sensitivity") and the bands ("global-sensitivity.bands") on screen,
    /// for the project's results file; restoreResult shows each again when its study's inputs
    /// are unchanged (the bands': the indices' without the method and samples, with the bands'
    /// samples).
    std::map<std::string, project::SavedResult> savedResults() const override;
    Restored restoreResult(const std::string& section, const project::SavedResult& saved) override;

protected:
    /// The inputs (soil, wheel, conditions, or the identified soil), the parameters varied with
    /// their ranges, the method, slips, slip angle, samples and seed: not the page or output shown.
    nlohmann::json resultInputs() const override;
    Job makeJob() override;
    void present(const std::any& result) override;
    /// Only a study of at most kAutomaticEvaluations; a larger one shows "not computed".
    bool startsByItself() override;
    void projectReplaced() override;

private:
    analysis::StudyDefinition definition() const;
    nlohmann::json bandInputs() const;
    analysis::Inputs inputs() const;
    void redraw();

    QTabWidget* pages_;
    QTableWidget* parameters_;
    QComboBox* source_;
    QComboBox* method_;
    QComboBox* output_;
    QLineEdit* slips_;
    QDoubleSpinBox* slip_angle_;
    QSpinBox* samples_;
    QSpinBox* band_samples_;
    QSpinBox* seed_;
    QPushButton* compute_;
    QPushButton* cancel_;
    QProgressBar* progress_;
    QLabel* status_;
    QLabel* readout_;
    QCustomPlot* indices_plot_;
    QCustomPlot* bands_plot_;
    QTimer* progress_timer_;
    std::shared_ptr<std::atomic<double>> fraction_;
    std::optional<analysis::GlobalSensitivityResult> indices_;
    std::string indices_hash_;  // of the inputs the indices were computed from
    std::optional<analysis::UncertaintyBandResult> bands_;
    std::string bands_hash_;          // of the inputs the bands were computed from
    std::string pending_bands_hash_;  // of the bands being computed (makeJob)
    // The identification's estimate and uncertainty (setIdentification), if any.
    std::optional<std::pair<identification::DecoupledParameters, identification::Uncertainty>>
        identification_;
};

}  // namespace terra::ui
