#pragma once
/// @file identification_panel.h
/// Identification panel (chapter 5, Figs. 5.1–5.6): synthesise data from the project's soil or
/// load a CSV, run the three-step decoupled fit (and the full-model refinement with standard
/// deviations), and see data against fitted curves for F_x, F_z and M_y with the parameters,
/// residual norms and timing. Runs on "Fit", not on every edit (a fit takes seconds).

#include "widgets/analyses/analyses.h"
#include "widgets/panels/analysis_panel.h"

class QCheckBox;
class QDoubleSpinBox;
class QLabel;
class QLineEdit;
class QPushButton;
class QTabWidget;
class QTableWidget;

namespace terra::ui {

class IdentificationPanel : public AnalysisPanel {
    Q_OBJECT
public:
    explicit IdentificationPanel(ProjectDocument* document, QWidget* parent = nullptr);

    const IdentificationResult& result() const { return result_; }
    /// Uses this CSV as data (empty: synthesise from the project's soil).
    void setDataFile(const QString& path);
    std::vector<std::pair<QString, QCustomPlot*>> plots() const override;
    QCustomPlot* currentPlot() const override;
    Table currentTable() const override { return result_.curves; }
    nlohmann::json settings() const override;
    void applySettings(const nlohmann::json& settings) override;

protected:
    Job makeJob() override;
    void present(const std::any& result) override;

private:
    QLineEdit* file_;
    QDoubleSpinBox* noise_;
    QCheckBox* refine_;
    QCheckBox* three_loads_;
    QPushButton* fit_;
    QLabel* status_;
    QLabel* readout_;
    QTabWidget* tabs_;
    std::vector<QCustomPlot*> plots_;
    QTableWidget* parameters_;
    IdentificationResult result_;
};

}  // namespace terra::ui
