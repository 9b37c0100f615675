#pragma once
/// @file sensitivity_panel.h
/// Sensitivity panel (section 4.2, Table 4.1, Figs. 4.1–4.6): pick a soil parameter, see the
/// family of F_x and F_s curves over its Table 4.1 variations, and a tornado chart of how far each
/// parameter moves F_x at a chosen slip.

#include "core/analysis/sensitivity.h"
#include "widgets/panels/analysis_panel.h"

class QComboBox;
class QDoubleSpinBox;
class QLabel;
class QTabWidget;

namespace terra::ui {

class SensitivityPanel : public AnalysisPanel {
    Q_OBJECT
public:
    explicit SensitivityPanel(ProjectDocument* document, QWidget* parent = nullptr);

    const analysis::SensitivityResult& result() const { return result_; }
    std::vector<std::pair<QString, QCustomPlot*>> plots() const override;
    QCustomPlot* currentPlot() const override;
    Table currentTable() const override;
    nlohmann::json settings() const override;
    void applySettings(const nlohmann::json& settings) override;
    /// The study on screen ("sensitivity"), for the project's results file; restoreResult shows
    /// it again, without computing, while its inputs (soil, wheel, conditions, parameter, slip
    /// angle, tornado slip) are those it was computed from.
    std::map<std::string, project::SavedResult> savedResults() const override;
    Restored restoreResult(const std::string& section, const project::SavedResult& saved) override;

protected:
    /// The default inputs without the tab shown.
    nlohmann::json resultInputs() const override;
    Job makeJob() override;
    void present(const std::any& result) override;

private:
    /// The study the controls make.
    analysis::SensitivitySettings current() const;

    QComboBox* parameter_;
    QDoubleSpinBox* slip_angle_;
    QDoubleSpinBox* tornado_slip_;
    QLabel* status_;
    QLabel* readout_;
    QTabWidget* tabs_;
    QCustomPlot* fx_;
    QCustomPlot* fs_;
    QCustomPlot* tornado_;
    analysis::SensitivityResult result_;
    analysis::SensitivitySettings shown_;
    analysis::SensitivitySettings applied_;  // what the project gave beyond the controls
};

}  // namespace terra::ui
