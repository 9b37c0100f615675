#pragma once
/// @file forces_panel.h
/// The forces-versus-slip panel (Figs. 2.18–2.26): F_x, F_s, F_z, M_y, M_z and θ_f against slip
/// for the project's slip angles, one plot per quantity in tabs, plus bulldozing resistance
/// against sinkage (Fig. 2.15) and static sinkage against load (Fig. 2.6); all recomputed live off
/// the GUI thread whenever the soil, wheel or conditions change (AnalysisPanel).

#include "core/analysis/forces.h"
#include "core/analysis/soil_curves.h"
#include "widgets/panels/analysis_panel.h"

class QComboBox;
class QLabel;
class QTabWidget;

namespace terra::ui {

class ForcesPanel : public AnalysisPanel {
    Q_OBJECT
public:
    explicit ForcesPanel(ProjectDocument* document, QWidget* parent = nullptr);

    /// The last sweep on screen (empty before the first one finishes).
    const analysis::ForcesResult& result() const { return result_; }
    /// The last bulldozing and static-sinkage curves on screen.
    const analysis::SoilCurves& soilCurves() const { return soil_curves_; }

    std::vector<std::pair<QString, QCustomPlot*>> plots() const override;
    QCustomPlot* currentPlot() const override;
    Table currentTable() const override;
    /// {"plot": name of the shown plot (plots())}: a project reopens on the same tab.
    nlohmann::json settings() const override;
    void applySettings(const nlohmann::json& settings) override;

protected:
    Job makeJob() override;
    void present(const std::any& result) override;

private:
    QComboBox* model_;
    QLabel* status_;
    QLabel* readout_;
    QTabWidget* tabs_;
    std::vector<QCustomPlot*>
        plots_;  ///< one per sweep quantity, then bulldozing_, static_sinkage_
    QCustomPlot* bulldozing_;
    QCustomPlot* static_sinkage_;
    analysis::ForcesResult result_;
    analysis::SoilCurves soil_curves_;
};

}  // namespace terra::ui
