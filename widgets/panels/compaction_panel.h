#pragma once
/// @file compaction_panel.h
/// Compaction panel (docs/compaction.md): what the wheel does to the soil below it at one slip and
/// slip angle, over one or more passes on the same track — the largest stresses against depth
/// with the profile's precompression stress and Terranimo's risk bands (the envelope or one
/// pass), the x–z map of σ_z during one pass, and sinkage, rut and drawbar pull per pass
/// (core/analysis/compaction.h, as `terrastudio compaction`). A cancelled or failed run shows the
/// passes it computed, marked as such.

#include <optional>
#include <vector>

#include "core/analysis/compaction.h"
#include "core/io/parameters_json.h"
#include "widgets/panels/analysis_panel.h"

class QComboBox;
class QDoubleSpinBox;
class QLabel;
class QPushButton;
class QSpinBox;
class QTabWidget;

namespace terra::ui {

class CompactionPanel : public AnalysisPanel {
    Q_OBJECT
public:
    /// The map's points along x and z (the panel always computes one).
    static constexpr int kMapXPoints = 120;
    static constexpr int kMapZPoints = 60;
    static constexpr int kMaxPasses = 50;  ///< the passes box's range (a project may give more)
    /// The largest run that starts by itself, in passes × depths (a pass's cost grows with the
    /// depths): the most the panel's own controls give, 50 passes at the default 19 depths, with
    /// a margin. A project may ask for up to 1000 passes at 2000 depths (minutes): that run waits
    /// for Compute (Ctrl+R), as the global sensitivity's large studies do.
    static constexpr int kAutomaticPassDepths = 1000;

    CompactionPanel(ProjectDocument* document, io::PresetLocations locations,
                    QWidget* parent = nullptr);

    const analysis::CompactionResult& result() const { return shown_.result; }
    /// The settings the shown result was computed with.
    const analysis::CompactionSettings& resultSettings() const { return shown_.settings; }
    std::vector<std::pair<QString, QCustomPlot*>> plots() const override {
        return {{"profile", profile_plot_}, {"map", map_plot_}, {"passes", passes_plot_}};
    }
    QCustomPlot* currentPlot() const override;
    /// The data of the tab on screen: the profile shown (compactionOutcome's "profile" columns),
    /// the map, or the passes.
    Table currentTable() const override;
    nlohmann::json settings() const override;
    /// A whole settings object (toJson's: it always has "depths_m") also clears ν and the profile
    /// when it leaves them out (per layer, none); an object of other keys changes only those.
    void applySettings(const nlohmann::json& settings) override;

    /// The pass the depth profile shows: 0 for the envelope over all passes.
    int shownPass() const;
    void showPass(int pass);
    /// The results under the plots: the core summary (analysis::compactionSummary, what
    /// `terrastudio compaction` prints) but its heading, through summaryHtml: the rut, the red
    /// zone, the bulk density per layer, the notes.
    QString summary() const;
    /// Shown with the "Not computed" line when a run is too large to start by itself.
    QPushButton* computeButton() const { return compute_; }
    /// The study on screen ("compaction"; a cancelled one too, marked partial), for the
    /// project's results file; restoreResult shows it again, without computing, while the soil,
    /// wheel, conditions and the panel's settings are those it was computed from.
    std::map<std::string, project::SavedResult> savedResults() const override;
    Restored restoreResult(const std::string& section, const project::SavedResult& saved) override;

protected:
    Job makeJob() override;
    void present(const std::any& result) override;
    /// Only a run of at most kAutomaticPassDepths; a larger one shows "Not computed".
    bool startsByItself() override;

private:
    struct Shown {
        analysis::CompactionSettings settings;
        analysis::CompactionResult result;
    };
    analysis::CompactionSettings current() const;
    void selectProfile(const std::optional<soil::SoilProfile>& profile);
    void selectConcentration(const std::optional<double>& nu);
    void edited();
    void drawProfile();
    void redraw();
    /// "sandy loam, wheel A, W = 58.86 N, s = 0.1, β = 0°" of the shown result.
    QString baseTitle() const;
    QString summaryText() const;

    io::PresetLocations locations_;
    QDoubleSpinBox* slip_;
    QDoubleSpinBox* slip_angle_;
    QSpinBox* passes_;
    QComboBox* profile_;
    std::vector<std::optional<soil::SoilProfile>> profiles_;  // one per profile_ item
    QComboBox* concentration_;
    QComboBox* width_;
    QTabWidget* tabs_;
    QComboBox* shown_pass_;
    QSpinBox* map_pass_;
    QCustomPlot* profile_plot_;
    QCustomPlot* map_plot_;
    QCustomPlot* passes_plot_;
    QLabel* readout_;
    QLabel* summary_;
    QPushButton* compute_;
    analysis::CompactionSettings applied_;  // what the project gave beyond the controls (depths, …)
    Shown shown_;
};

}  // namespace terra::ui
