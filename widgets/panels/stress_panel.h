#pragma once
/// @file stress_panel.h
/// Stress distribution panel (Figs. 2.11, 2.16; Tables 2.4–2.5): σ, τ, τ_t, τ_l over the contact
/// angle at one slip and slip angle (θ_f solved from the load), exact and quadratic overlaid, with
/// the approximation's RMSE and MAE.

#include "widgets/analyses/analyses.h"
#include "widgets/panels/analysis_panel.h"

class QComboBox;
class QDoubleSpinBox;
class QLabel;

namespace terra::ui {

class StressPanel : public AnalysisPanel {
    Q_OBJECT
public:
    explicit StressPanel(ProjectDocument* document, QWidget* parent = nullptr);

    const StressResult& result() const { return result_; }
    std::vector<std::pair<QString, QCustomPlot*>> plots() const override {
        return {{"stresses", plot_}};
    }
    QCustomPlot* currentPlot() const override { return plot_; }
    Table currentTable() const override { return result_.table; }
    nlohmann::json settings() const override;
    void applySettings(const nlohmann::json& settings) override;

protected:
    Job makeJob() override;
    void present(const std::any& result) override;

private:
    void redraw();
    QDoubleSpinBox* slip_;
    QDoubleSpinBox* slip_angle_;
    QComboBox* stress_;
    QLabel* info_;
    QLabel* readout_;
    QCustomPlot* plot_;
    StressResult result_;
};

}  // namespace terra::ui
