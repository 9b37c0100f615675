#pragma once
/// @file experiment_actions.h
/// Putting a measured single-wheel test (core/io/experiment.h) into the project: File ▸ Load
/// Experiment… reads the test and offers to take over the setup it was measured with — the wheel
/// of its sidecar, its soil preset and its load — so that the forces panel compares the model with
/// the rig on the rig's wheel. The test and the setup are one undo step.

#include <QString>
#include <functional>
#include <optional>
#include <string>

#include "core/io/experiment.h"
#include "core/io/parameters_json.h"
#include "core/project/project.h"

class QWidget;

namespace terra::ui {

class ProjectDocument;

/// The setup a test was measured with, as far as its files say.
struct ExperimentSetup {
    std::optional<wheel::WheelParameters> wheel;  ///< the sidecar's wheel
    std::optional<soil::SoilParameters> soil;     ///< the sidecar's soil preset, resolved
    std::string soil_preset;
    std::optional<double> load_n;  ///< W [N] when every point of the test has the same load

    /// Whether taking it over would change the project (wheel, soil or load differ).
    bool differsFrom(const project::Project& project) const;
    /// "wheel Ding 2011 smooth wheel (r = 157.35 mm, b = 165 mm), soil hit-lss1, W = 80 N".
    QString describe() const;
};

/// The setup of `experiment`; a soil preset that `locations` cannot resolve is left out.
ExperimentSetup experimentSetup(const io::Experiment& experiment,
                                const io::PresetLocations& locations);

/// Makes the test at `path` the project's and, with `setup`, takes its wheel, soil and load over,
/// all in one undo step ("Load experiment <file> with its setup"). False (nothing changed) and
/// `error` when the test cannot be read.
bool loadExperiment(ProjectDocument& document, const QString& path,
                    const ExperimentSetup* setup = nullptr, QString* error = nullptr);

/// File ▸ Load Experiment…: asks for the file, reads it, asks whether to take its setup over when
/// that differs from the project's, and loads it; an unreadable test is shown with its problems.
/// True when a test was loaded.
bool promptLoadExperiment(QWidget* parent, ProjectDocument& document,
                          const io::PresetLocations& locations);

/// The project tree's "Measured test" page: what a test is for, and Load experiment…
/// (promptLoadExperiment), then `loaded`.
QWidget* experimentPage(QWidget* parent, ProjectDocument& document,
                        const io::PresetLocations& locations, std::function<void()> loaded);

/// The same for the test at `path` (a file dropped on the window): reads it, asks about its
/// setup, loads it. True when a test was loaded.
bool loadExperimentAsking(QWidget* parent, ProjectDocument& document,
                          const io::PresetLocations& locations, const QString& path);

}  // namespace terra::ui
