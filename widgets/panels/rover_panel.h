#pragma once
/// @file rover_panel.h
/// Rover scenario panel (Figs. 3.7–3.15): pick a scenario (resources/scenarios), edit it as JSON
/// (checked by the core scenario parser) or just its duration, run it off the GUI thread with a
/// progress bar and cancel, and see the path, yaw, velocities, per-wheel slip, steering and forces
/// (widgets/plots/rover_figures.h), and a top-down view of the robot on its soil patches with a
/// time scrubber that only redraws. On a field (docs/field.md) the top view draws a layer under the
/// track, chosen from the field's maps and the run's (height, soil classes, rut depth, passes,
/// compaction risk, ...: scenario::mapLayers), the run's maps as they were at the scrubbed time. A
/// cancelled run keeps and shows what it computed, marked as such. Edited scenarios are kept in the
/// project (the panel's settings, "edited": {name: JSON}).

#include <QDialog>
#include <optional>

#include "core/io/parameters_json.h"
#include "core/scenario/map_layers.h"
#include "core/scenario/runner.h"
#include "widgets/panels/analysis_panel.h"
#include "widgets/plots/field_layers.h"

class QCheckBox;
class QComboBox;
class QDialogButtonBox;
class QDoubleSpinBox;
class QLabel;
class QPlainTextEdit;
class QProgressBar;
class QPushButton;
class QSlider;
class QTabWidget;
class QTableWidget;
class QTimer;

namespace terra::ui {

/// A scenario as JSON text, parsed by the core reader (scenario_json.h): the scenario, or every
/// problem with its field path ("edited straight: duration_s: -1 is outside ...").
Result<scenario::Scenario> parseScenarioText(const QString& text, const std::string& name,
                                             const io::PresetLocations& locations);

/// Edits a scenario's JSON; OK stays disabled and the error (naming the field) is shown until the
/// text parses as a valid scenario.
class ScenarioDialog : public QDialog {
    Q_OBJECT
public:
    ScenarioDialog(const QString& name, const QString& text, io::PresetLocations locations,
                   QWidget* parent = nullptr);
    QString text() const;
    void setText(const QString& text);
    bool isValid() const { return valid_; }
    QString errorText() const;
    bool okEnabled() const;

private:
    void validate();
    std::string name_;
    io::PresetLocations locations_;
    QPlainTextEdit* edit_;
    QLabel* error_;
    QDialogButtonBox* buttons_;
    bool valid_ = false;
};

class RoverPanel : public AnalysisPanel {
    Q_OBJECT
public:
    RoverPanel(ProjectDocument* document, io::PresetLocations locations, QWidget* parent = nullptr);

    const scenario::RunResult& result() const { return result_; }
    /// The scenario of the shown result (robot geometry and soils of the top view).
    const scenario::Scenario& shownScenario() const { return shown_; }
    std::vector<std::pair<QString, QCustomPlot*>> plots() const override;
    /// Run (when no run goes on).
    void requestRun() override;
    QCustomPlot* currentPlot() const override;
    /// A figure in a dock of its own is drawn when shown (the others when their tab is).
    void plotShownOutside(QCustomPlot* plot) override;
    /// The time series; on the comparison's tab the comparison table.
    Table currentTable() const override;
    nlohmann::json settings() const override;
    void applySettings(const nlohmann::json& settings) override;

    /// The current scenario's JSON text: the edited one when there is one, else the file's.
    QString scenarioText() const;
    /// Replaces the current scenario by `text` when it parses (stored in the project); false and
    /// the problems (naming the fields) in `error` otherwise, nothing changed.
    bool setScenarioText(const QString& text, QString* error);
    /// Drops the current scenario's edit (back to the file).
    void revertScenario();
    /// Shows the scenario `name`: a preset's name, or the path of one of the project's scenario
    /// files (ProjectDocument::addScenario), which the chooser lists after the presets by file
    /// name; false when the chooser has no such scenario.
    bool chooseScenario(const QString& name);
    /// Makes the robot file at `path` the current scenario's robot: an edit of the scenario
    /// ("robot": its absolute path), kept in the project and undone by Revert; false and the
    /// problems in `error` when the scenario would not be valid with it, nothing changed.
    bool useRobotFile(const QString& path, QString* error);
    bool isEdited() const;

    /// The top view and its scrubber: row of the series shown, time label.
    QCustomPlot* topView() const { return top_view_; }
    QSlider* scrubber() const { return scrubber_; }
    QString timeLabel() const;
    /// The layer under the top view: "none", then scenario::mapLayers of the scenario shown (a
    /// run's, or the chosen scenario's before a run); the item data holds the layer's key.
    QComboBox* layerChooser() const { return layer_; }
    /// Chooses the layer `key` ("" or "none": no layer); false when the chooser has no such layer.
    bool chooseLayer(const QString& key);
    /// The key of the layer drawn ("" for none).
    QString layerKey() const;
    /// Runs the scenario under every controller (docs/traction.md §6) off the GUI thread, then
    /// shows the run of the chosen controller and the comparison table (when no run goes on).
    void requestComparison();
    QPushButton* compareButton() const { return compare_; }
    /// The comparison of the last "Compare controllers" (rows of controllerComparison; an
    /// empty array before one), and its tab.
    const nlohmann::json& comparison() const { return comparison_; }
    QTableWidget* comparisonTable() const { return comparison_table_; }
    /// Shows the tab labelled `label` ("Top view", a figure's tab, "Comparison"); false when
    /// there is none.
    bool showTab(const QString& label);
    /// The comparison as a table: the controller as the label, one column per figure.
    Table comparisonAsTable() const;
    /// Shows row `row` of the series in the top view (redraw only).
    void scrubTo(int row);

    /// The run on screen ("rover": its series, summary and scenario) for the project's results
    /// file; restoreResult shows it again, without running, when the current scenario's JSON is
    /// the one it ran.
    std::map<std::string, project::SavedResult> savedResults() const override;
    Restored restoreResult(const std::string& section, const project::SavedResult& saved) override;

protected:
    Job makeJob() override;
    void present(const std::any& result) override;
    /// The scenario's JSON (edited or the file's): all a run depends on.
    nlohmann::json resultInputs() const override;
    void projectReplaced() override;

private slots:
    void editScenario();

private:
    /// The scenario of the chooser's item `index`: a preset's name or a scenario file's path.
    std::string nameAt(int index) const;
    std::string currentName() const;
    /// The chooser's index of the scenario `name` (a preset's name or a file's path), or -1.
    int scenarioIndex(const std::string& name) const;
    /// Lists the project's scenario files after the presets (keeps the choice when it stays).
    void listScenarioFiles();
    nlohmann::json currentJson() const;  // edited or file JSON (null when unreadable)
    void showScenarioState();
    /// Before a run (or after choosing another scenario): the top view of its soils and start,
    /// and which soils it runs on (a scenario brings its own; the project's soil is not used).
    void previewScenario();
    void storeEdit(const nlohmann::json& json);
    /// Sets `key` of the scenario's "controller" object to `value` (an edit, as the duration).
    void setControllerValue(const std::string& key, const nlohmann::json& value);
    /// Draws figure i of roverFigures() if the shown run has not been drawn on it yet. Figures are
    /// drawn when their tab is first shown (or exported), not all in present(): drawing the eleven
    /// plots of a 6001-row run at once held the GUI thread 63–203 ms (docs/performance.md).
    void drawFigure(std::size_t i) const;
    /// The status line of the run on screen ("Completed on …" or "CANCELLED (partial) — on …").
    QString summaryText() const;
    /// Retitles every tab (figures and top view) with `title`: they show the same run.
    void retitle(const QString& title);
    /// Fills the comparison's tab from comparison_.
    void showComparison();
    /// Fills the layer chooser with the layers of `scenario` (and of `maps`, a run's), keeps the
    /// chosen layer when it is still there (else a run's rut depth, else the soil classes), and
    /// draws it.
    void listLayers(const scenario::Scenario& scenario, const scenario::FieldMaps* maps);
    /// Draws the chosen layer under the top view at the scrubbed time, or removes it.
    void drawLayer();
    /// The chosen layer at the scrubbed time (a map of the drive only), then the robot's pose.
    void scrubLayer();
    /// The scenario and maps the layers come from: the run's, or the previewed scenario's.
    const scenario::Scenario& layerScenario() const;
    const scenario::FieldMaps* layerMaps() const;
    /// Frames the driven area again when the axes' width changed from `width_before` [px] (a
    /// colour scale came or went); replots.
    void refitTopView(int width_before);
    /// t [s] of the scrubbed row; +∞ without a run.
    double scrubTime() const;

    io::PresetLocations locations_;
    QComboBox* scenario_;
    QPushButton* edit_;
    QPushButton* revert_;
    QLabel* edited_label_;
    QDoubleSpinBox* duration_;
    QComboBox* controller_;        // the scenario's "controller" type (docs/traction.md §5)
    QDoubleSpinBox* slip_set_;     // and its fixed set-point "slip"
    QCheckBox* traction_limited_;  // and its "traction_limited" mode
    QComboBox* robust_;            // optimal: its "robust" set-point (docs/traction.md §8)
    QDoubleSpinBox* quantile_;     // and that set-point's "quantile"
    QComboBox* identifier_;        // optimal: its soil estimator, "identifier"
    QPushButton* run_;
    QPushButton* compare_;
    QPushButton* cancel_;
    QProgressBar* progress_;
    QLabel* status_;
    QLabel* readout_;
    QTabWidget* tabs_;
    std::vector<QCustomPlot*> plots_;  // figures of roverFigures()
    mutable std::vector<bool> drawn_;  // plots_[i] shows the current result
    QString title_;
    QCustomPlot* top_view_;
    QSlider* scrubber_;
    QLabel* time_;
    QPushButton* play_;
    QTimer* player_;
    QLabel* layer_label_;
    QComboBox* layer_;
    std::vector<scenario::MapLayer> layers_;  // of the chooser's items after "none"
    std::string layer_choice_;                // the user's choice, kept across runs
    bool previewing_ = false;                 // layers from preview_ (no run on screen)
    scenario::Scenario preview_;
    LayerDisplay layer_display_;         // colours and scale of the layer drawn
    std::array<double, 4> layer_box_{};  // the area it is drawn over [m]
    QTableWidget* comparison_table_;
    nlohmann::json comparison_ = nlohmann::json::array();
    bool compare_next_ = false;                        // the next job compares the controllers
    nlohmann::json edits_ = nlohmann::json::object();  // scenario name → edited JSON
    scenario::RunResult result_;
    scenario::Scenario shown_;
    std::string shown_name_;     // "straight (edited)": the scenario of the run on screen
    nlohmann::json shown_json_;  // and its JSON, to tell whether the current one is another
    std::string pending_name_;   // of the run going on (makeJob)
    nlohmann::json pending_json_;
};

}  // namespace terra::ui
