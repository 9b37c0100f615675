#include "widgets/panels/experiment_actions.h"

#include <QDir>
#include <QFileDialog>
#include <QFileInfo>
#include <QLabel>
#include <QMessageBox>
#include <QPushButton>
#include <QUndoStack>
#include <QVBoxLayout>
#include <algorithm>

#include "widgets/document/project_document.h"

namespace terra::ui {

bool ExperimentSetup::differsFrom(const project::Project& project) const {
    const bool wheel_differs = wheel && io::toJson(*wheel) != io::toJson(project.wheel);
    const bool soil_differs = soil && (soil_preset != project.soil_preset ||
                                       io::toJson(*soil) != io::toJson(project.soil));
    const bool load_differs = load_n && *load_n != project.conditions.load_n;
    return wheel_differs || soil_differs || load_differs;
}

QString ExperimentSetup::describe() const {
    QStringList parts;
    if (wheel) {
        parts << QString("wheel %1 (r = %2 mm, b = %3 mm)")
                     .arg(QString::fromStdString(wheel->name))
                     .arg(wheel->radius_m * 1e3)
                     .arg(wheel->width_m * 1e3);
    }
    if (soil) parts << QString("soil %1").arg(QString::fromStdString(soil_preset));
    if (load_n) parts << QString("W = %1 N").arg(*load_n);
    return parts.join(", ");
}

ExperimentSetup experimentSetup(const io::Experiment& experiment,
                                const io::PresetLocations& locations) {
    ExperimentSetup out;
    if (experiment.metadata) {
        out.wheel = experiment.metadata->wheel;
        if (!experiment.metadata->soil_preset.empty()) {
            if (auto soil = io::resolveSoil(locations, experiment.metadata->soil_preset)) {
                out.soil = *soil;
                out.soil_preset = experiment.metadata->soil_preset;
            }
        }
    }
    const auto& points = experiment.points;
    if (!points.empty() && std::all_of(points.begin(), points.end(), [&](const auto& p) {
            return p.load_n == points.front().load_n;
        })) {
        out.load_n = points.front().load_n;
    }
    return out;
}

bool loadExperiment(ProjectDocument& document, const QString& path, const ExperimentSetup* setup,
                    QString* error) {
    if (!setup) return document.setExperiment(path, error);
    // Read first: a test that cannot be read must not leave an empty step on the stack.
    const Result<io::Experiment> read = io::readExperiment(path.toStdString());
    if (!read) {
        if (error) *error = QString::fromStdString(read.message());
        return false;
    }
    QUndoStack* undo = document.undoStack();
    undo->beginMacro(QString("Load experiment %1 with its setup").arg(QFileInfo(path).fileName()));
    const bool loaded = document.setExperiment(path, error);
    if (loaded) {
        if (setup->wheel) document.setWheel(*setup->wheel, "");
        if (setup->soil) document.setSoil(*setup->soil, setup->soil_preset);
        if (setup->load_n) document.setLoad(*setup->load_n);
    }
    undo->endMacro();
    return loaded;
}

bool promptLoadExperiment(QWidget* parent, ProjectDocument& document,
                          const io::PresetLocations& locations) {
    // Start in the shipped tests (resources/experiments/README.md).
    QString start;
    for (const auto& dir : locations.directories) {
        const QString candidate = QString::fromStdString((dir / "experiments").string());
        if (QFileInfo(candidate).isDir()) {
            start = candidate;
            break;
        }
    }
    const QString path = QFileDialog::getOpenFileName(
        parent, "Load experiment", start,
        "Measured tests (*.csv *.json);;CSV (*.csv);;Sidecar JSON (*.json)");
    if (path.isEmpty()) return false;
    return loadExperimentAsking(parent, document, locations, path);
}

QWidget* experimentPage(QWidget* parent, ProjectDocument& document,
                        const io::PresetLocations& locations, std::function<void()> loaded) {
    auto* page = new QWidget(parent);
    auto* text = new QLabel(
        "A measured single-wheel test (docs/validation.md): the Forces vs slip panel draws its "
        "points over the model, gives the errors and calibrates the soil to it.",
        page);
    text->setWordWrap(true);
    auto* load = new QPushButton("Load experiment…", page);
    auto* layout = new QVBoxLayout(page);
    layout->addWidget(text);
    layout->addWidget(load);
    layout->addStretch(1);
    QObject::connect(load, &QPushButton::clicked, page,
                     [page, &document, locations, loaded = std::move(loaded)] {
                         if (promptLoadExperiment(page->window(), document, locations) && loaded)
                             loaded();
                     });
    return page;
}

bool loadExperimentAsking(QWidget* parent, ProjectDocument& document,
                          const io::PresetLocations& locations, const QString& path) {
    const Result<io::Experiment> read = io::readExperiment(path.toStdString());
    if (!read) {
        QMessageBox::warning(parent, "Cannot load experiment",
                             QString::fromStdString(read.message()));
        return false;
    }
    const ExperimentSetup setup = experimentSetup(*read, locations);
    bool adopt = false;
    if (setup.differsFrom(document.project())) {
        const auto answer = QMessageBox::question(
            parent, "Use the test's setup?",
            QString("The test was measured with %1. Use them in the project (one undo step)?\n\n"
                    "No keeps the project's wheel, soil and load; the model is then also drawn "
                    "at the test's load.")
                .arg(setup.describe()),
            QMessageBox::Yes | QMessageBox::No | QMessageBox::Cancel, QMessageBox::Yes);
        if (answer == QMessageBox::Cancel) return false;
        adopt = answer == QMessageBox::Yes;
    }
    QString error;
    if (!loadExperiment(document, path, adopt ? &setup : nullptr, &error)) {
        QMessageBox::warning(parent, "Cannot load experiment", error);
        return false;
    }
    return true;
}

}  // namespace terra::ui
