#pragma once
/// @file rover_panel.h
/// Rover scenario panel (Figs. 3.7–3.15): pick a scenario (resources/scenarios), run it off the GUI
/// thread with a progress bar and cancel, and see the path, yaw, velocities, per-wheel slip and
/// drawbar pull. A cancelled run keeps and shows what it computed, marked as such.

#include "core/io/parameters_json.h"
#include "core/scenario/runner.h"
#include "widgets/panels/analysis_panel.h"

class QComboBox;
class QLabel;
class QProgressBar;
class QPushButton;
class QTabWidget;

namespace terra::ui {

class RoverPanel : public AnalysisPanel {
    Q_OBJECT
public:
    RoverPanel(ProjectDocument* document, io::PresetLocations locations, QWidget* parent = nullptr);

    const scenario::RunResult& result() const { return result_; }
    std::vector<std::pair<QString, QCustomPlot*>> plots() const override;
    QCustomPlot* currentPlot() const override;
    Table currentTable() const override { return result_.series; }
    nlohmann::json settings() const override;
    void applySettings(const nlohmann::json& settings) override;

protected:
    Job makeJob() override;
    void present(const std::any& result) override;

private:
    io::PresetLocations locations_;
    QComboBox* scenario_;
    QPushButton* run_;
    QPushButton* cancel_;
    QProgressBar* progress_;
    QLabel* status_;
    QLabel* readout_;
    QTabWidget* tabs_;
    std::vector<QCustomPlot*> plots_;
    scenario::RunResult result_;
};

}  // namespace terra::ui
