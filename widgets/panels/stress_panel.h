#pragma once
/// @file stress_panel.h
/// Stress distribution panel (Figs. 2.11, 2.16; Tables 2.4–2.5): σ, τ, τ_t, τ_l over the contact
/// angle at one slip and slip angle (θ_f solved from the load), exact and quadratic overlaid, with
/// the approximation's RMSE and MAE (core/analysis/stresses.h, as `terrastudio stresses`).

#include "core/analysis/stresses.h"
#include "widgets/panels/analysis_panel.h"

class QComboBox;
class QDoubleSpinBox;
class QLabel;

namespace terra::ui {

class StressPanel : public AnalysisPanel {
    Q_OBJECT
public:
    explicit StressPanel(ProjectDocument* document, QWidget* parent = nullptr);

    const analysis::StressResult& result() const { return result_; }
    std::vector<std::pair<QString, QCustomPlot*>> plots() const override {
        return {{"stresses", plot_}};
    }
    QCustomPlot* currentPlot() const override { return plot_; }
    Table currentTable() const override { return result_.table; }
    nlohmann::json settings() const override;
    void applySettings(const nlohmann::json& settings) override;
    /// The stresses on screen ("stresses"), for the project's results file; restoreResult shows
    /// them again, without computing, while the soil, wheel, conditions, slip and slip angle are
    /// those they were computed from.
    std::map<std::string, project::SavedResult> savedResults() const override;
    Restored restoreResult(const std::string& section, const project::SavedResult& saved) override;

protected:
    /// The default inputs without the stress shown (drawing another one computes nothing).
    nlohmann::json resultInputs() const override;
    Job makeJob() override;
    void present(const std::any& result) override;

private:
    void redraw();
    analysis::StressSettings current() const;
    QDoubleSpinBox* slip_;
    QDoubleSpinBox* slip_angle_;
    QComboBox* stress_;
    QLabel* info_;
    QLabel* readout_;
    QCustomPlot* plot_;
    analysis::StressResult result_;
    analysis::StressSettings applied_;  // what the project gave beyond the controls (θ_f, step, …)
};

}  // namespace terra::ui
