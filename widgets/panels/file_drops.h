#pragma once
/// @file file_drops.h
/// Files dropped onto the studio's window, each taken for what it is: a project (.terra) is
/// opened, a measured test (its CSV, with a load_N column, or its sidecar JSON) loaded into the
/// project with its setup offered as File ▸ Load Experiment does, any other CSV given to the
/// identification panel as data, and a soil or wheel file (JSON) made the project's soil or wheel
/// in one undo step, a rover scenario added to the project's scenarios and shown in the rover
/// panel, a robot file made the rover's current scenario's robot (an edit of the scenario). A
/// drag of anything else is refused before the drop; a file of a known kind that is not valid is
/// refused at the drop with its problems (naming the fields) in the status bar.

#include <QString>
#include <functional>

#include "core/io/parameters_json.h"

class QWidget;

namespace terra::ui {

class ProjectDocument;

enum class DroppedFile { kProject, kExperiment, kData, kSoil, kWheel, kScenario, kRobot, kUnknown };

/// What the file at `path` is, by its suffix and its first line or keys (not read whole).
DroppedFile classifyDroppedFile(const QString& path);

/// What the window does with the files that are not the document's to take.
struct DropActions {
    std::function<bool(const QString& path)> open_project;  ///< after asking to save
    std::function<void(const QString& path)> use_data;      ///< the identification panel's data
    std::function<void(const QString& panel)> show_panel;   ///< "forces" after a test
    /// Shows the scenario file at `path` (absolute, already in the project's scenarios).
    std::function<void(const QString& path)> show_scenario;
    /// Makes the robot file at `path` the current scenario's robot; false and why in `error`.
    std::function<bool(const QString& path, QString* error)> use_robot;
    std::function<void(const QString& message)> report;  ///< the status bar
};

/// Handles one dropped file; false (and `report` says why) when it was not taken.
bool dropFile(QWidget* window, ProjectDocument& document, const io::PresetLocations& locations,
              const DropActions& actions, const QString& path);

/// Accepts drags of local files that classifyDroppedFile() knows onto `window` and drops them
/// (dropFile), in the order given.
void acceptFileDrops(QWidget* window, ProjectDocument& document, io::PresetLocations locations,
                     DropActions actions);

}  // namespace terra::ui
