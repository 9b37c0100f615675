#pragma once
/// @file project_document.h
/// The open project: owns a Project and a QUndoStack and changes the project only through undo
/// commands — one command per setter, none when the value did not change, repeated edits of one
/// field merged (LabPlot/Tiled pattern). Views listen to the signals; every change bumps
/// `revision()` so that results computed from an older state can be recognised and dropped.

#include <QObject>
#include <QString>
#include <memory>

#include "core/io/experiment.h"
#include "core/io/parameters_json.h"
#include "core/project/project.h"

class QUndoStack;

namespace terra::ui {

using project::Project;

class ProjectDocument : public QObject {
    Q_OBJECT
public:
    explicit ProjectDocument(QObject* parent = nullptr);

    const Project& project() const { return project_; }
    QUndoStack* undoStack() const { return undo_; }
    int revision() const { return revision_; }
    bool isModified() const;
    QString filePath() const { return file_path_; }

    /// A soil field (soil_parameters.h field table) in its user unit. Out-of-range or non-finite
    /// values are refused (false, nothing pushed); an unchanged value pushes nothing (true).
    /// Editing a soil that is a preset leaves the preset: the soil becomes custom and is named
    /// "<preset's name> (edited)" (editedSoilName()), in the editor, plot titles, exports and the
    /// .terra file alike. "jmax_m" also takes +inf (no limit).
    bool setSoilValue(const std::string& key, double user_value);
    /// The soil's name (a custom soil of that name; empty is refused).
    bool setSoilName(const std::string& name);
    /// The name an edit gives the project's soil: "<name> (edited)" while it is a preset.
    static std::string editedSoilName(const Project& project);
    /// A wheel field ("r_m", "b_m", "grouser_height_m", "grouser_count", "grouser_thickness_m",
    /// "lug_effect_coefficient") in the field's unit, same rules, and the whole wheel must stay
    /// valid (grousers below the radius, a whole count); editing a preset wheel names it
    /// "<name> (edited)".
    bool setWheelValue(const std::string& key, double value);
    /// Why setWheelValue(key, value) is refused ("grouser_height_m: 0.2 m is not below the
    /// radius r_m = 0.15 m"), or "" when it is not.
    std::string wheelValueProblem(const std::string& key, double value) const;
    /// W [N], same rules.
    bool setLoad(double load_n);
    bool setSlipAngles(const std::vector<double>& slip_angles_deg);
    bool setQuadraticModel(bool quadratic);
    /// Replace the whole soil or wheel (a preset was chosen); refused when invalid.
    /// `text` names the undo step (default "Soil preset <preset>").
    bool setSoil(const soil::SoilParameters& soil, const std::string& preset,
                 const QString& text = {});
    bool setWheel(const wheel::WheelParameters& wheel, const std::string& preset);
    bool addDataSet(const std::string& path);
    /// Adds a scenario file (its absolute path) to the project's scenarios, which the rover panel
    /// lists beside the presets: one undo step "Add scenario <file>"; a path already there pushes
    /// nothing. The file is not read here (the rover panel reads it when it is chosen).
    bool addScenario(const std::string& path);
    /// Reads a measured test (core/io/experiment.h: its CSV or its sidecar JSON) and makes it the
    /// project's, stored by its absolute path: one undo step "Load experiment <file>"; an empty
    /// path removes the test ("Remove experiment"). A test that cannot be read pushes nothing:
    /// false, and `error` lists every problem with its file:line.
    bool setExperiment(const QString& path, QString* error = nullptr);
    /// The project's test as read when it was set or the project was opened (its path relative
    /// to the .terra file when not absolute); nullptr when there is none or it cannot be read.
    const io::Experiment* experiment() const { return experiment_.data.get(); }
    /// Why the project's test could not be read ("" when it could, or there is none).
    QString experimentError() const { return QString::fromStdString(experiment_.error); }
    /// Panel settings are session state but not undoable edits of the model; a change marks the
    /// project modified (they are saved with it) until the next save or reset.
    void setPanelSettings(const std::string& panel, const nlohmann::json& settings);

    /// Ends the current undo step: the next edit, even of the same field, is a step of its own
    /// (editors call it when a slider is released or typing in a field ends).
    void endMerge() { ++gesture_; }
    /// The state on disk is what is shown (an opened project after its panels took their
    /// settings): not modified, Undo stays as it is.
    void markUnmodified();

    /// Replaces everything (new/open): clears the undo stack and marks the document clean.
    void reset(const Project& project, const QString& file_path = {});

    /// Writes the project atomically (QSaveFile); on failure the document stays modified.
    bool save(const QString& path, QString* error);
    /// Reads a project file (core/project/project.h: strict, every problem listed); with
    /// `locations` the scenarios edited in the rover panel are checked too. The open document is
    /// untouched (the caller calls reset()).
    static Result<Project> load(const QString& path,
                                const io::PresetLocations* locations = nullptr);
    /// A new project on presets "sandy-loam" and "A" (the studio's default).
    static Project defaultProject(const io::PresetLocations& locations);

signals:
    void soilChanged();
    void wheelChanged();
    void conditionsChanged();
    void dataSetsChanged();
    void scenariosChanged();      ///< the project's scenario files (addScenario, undo, open)
    void experimentChanged();     ///< the test was loaded, removed, or undone (see experiment())
    void changed();               ///< after any change of the model (revision bumped)
    void panelSettingsChanged();  ///< a panel's settings changed (not a model change)
    void modifiedChanged(bool modified);
    void filePathChanged(const QString& path);

private:
    enum class Part { kSoil, kWheel, kConditions, kDataSets, kScenarios, kExperiment };
    /// The project's test path and what reading it gave (undo keeps the read test).
    struct ExperimentState {
        std::string path;
        std::shared_ptr<const io::Experiment> data;
        std::string error;
    };
    ExperimentState readExperiment(const std::string& path) const;
    template <typename T>
    bool push(const QString& text, int merge_id, Part part, T Project::*member, const T& value);
    template <typename T>
    bool pushField(const QString& text, int merge_id, Part part, T* field, const T& value);
    void notify(Part part);
    bool pushSoil(const QString& text, int merge_id, soil::SoilParameters soil,
                  const std::string& preset);
    bool pushWheel(const QString& text, int merge_id, wheel::WheelParameters wheel,
                   const std::string& preset);

    Project project_;
    ExperimentState experiment_;
    QUndoStack* undo_;
    int revision_ = 0;
    int gesture_ = 0;                 // commands of different gestures never merge
    bool settings_modified_ = false;  // panel settings differ from saved_panels_
    nlohmann::json saved_panels_;  // the panel settings at the last save, reset or markUnmodified
    QString file_path_;
};

}  // namespace terra::ui
