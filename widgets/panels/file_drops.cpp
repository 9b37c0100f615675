#include "widgets/panels/file_drops.h"

#include <QDragEnterEvent>
#include <QDropEvent>
#include <QFile>
#include <QFileInfo>
#include <QMimeData>
#include <QUrl>
#include <QWidget>
#include <algorithm>

#include "core/io/json.h"
#include "core/scenario/scenario_json.h"
#include "widgets/document/project_document.h"
#include "widgets/panels/experiment_actions.h"

namespace terra::ui {
namespace {

QStringList localFiles(const QMimeData* mime) {
    QStringList files;
    if (!mime || !mime->hasUrls()) return files;
    for (const QUrl& url : mime->urls()) {
        if (url.isLocalFile()) files << url.toLocalFile();
    }
    return files;
}

class FileDrops : public QObject {
public:
    FileDrops(QWidget* window, ProjectDocument& document, io::PresetLocations locations,
              DropActions actions)
        : QObject(window),
          window_(window),
          document_(document),
          locations_(std::move(locations)),
          actions_(std::move(actions)) {}

    bool eventFilter(QObject* watched, QEvent* event) override {
        if (watched != window_) return false;
        if (event->type() == QEvent::DragEnter || event->type() == QEvent::DragMove) {
            auto* drag = static_cast<QDropEvent*>(event);
            const QStringList files = localFiles(drag->mimeData());
            const bool known =
                !files.isEmpty() && std::all_of(files.begin(), files.end(), [](const QString& f) {
                    return classifyDroppedFile(f) != DroppedFile::kUnknown;
                });
            known ? drag->acceptProposedAction() : drag->ignore();
            return true;
        }
        if (event->type() == QEvent::Drop) {
            auto* drop = static_cast<QDropEvent*>(event);
            drop->acceptProposedAction();
            for (const QString& file : localFiles(drop->mimeData()))
                dropFile(window_, document_, locations_, actions_, file);
            return true;
        }
        return false;
    }

private:
    QWidget* window_;
    ProjectDocument& document_;
    io::PresetLocations locations_;
    DropActions actions_;
};

}  // namespace

DroppedFile classifyDroppedFile(const QString& path) {
    const QFileInfo info(path);
    if (!info.isFile()) return DroppedFile::kUnknown;
    const QString suffix = info.suffix().toLower();
    if (suffix == "terra") return DroppedFile::kProject;
    if (suffix == "csv") {
        // A measured test has a load_N column (core/io/experiment.h); identification data does
        // not (slip, entry_angle_deg, Fx_N, …).
        QFile file(path);
        if (!file.open(QIODevice::ReadOnly | QIODevice::Text)) return DroppedFile::kUnknown;
        const QStringList header = QString::fromUtf8(file.readLine()).trimmed().split(',');
        for (const QString& column : header) {
            if (column.trimmed() == "load_N") return DroppedFile::kExperiment;
        }
        return DroppedFile::kData;
    }
    if (suffix == "json") {
        const Result<nlohmann::json> json = io::readJsonFile(path.toStdString());
        if (!json || !json->is_object()) return DroppedFile::kUnknown;
        if (json->contains("data_file")) return DroppedFile::kExperiment;  // a test's sidecar
        if (json->contains("phi_deg") || json->contains("c_kPa")) return DroppedFile::kSoil;
        if (json->contains("r_m")) return DroppedFile::kWheel;
        // A scenario has its duration and a terrain or robot (docs/dynamics.md, "Scenario"); a
        // robot its wheelbase and track.
        if (json->contains("duration_s") && (json->contains("terrain") || json->contains("robot")))
            return DroppedFile::kScenario;
        if (json->contains("wheelbase_m") && json->contains("track_m")) return DroppedFile::kRobot;
    }
    return DroppedFile::kUnknown;
}

bool dropFile(QWidget* window, ProjectDocument& document, const io::PresetLocations& locations,
              const DropActions& actions, const QString& path) {
    const QString name = QFileInfo(path).fileName();
    auto report = [&actions](const QString& message) {
        if (actions.report) actions.report(message);
    };
    switch (classifyDroppedFile(path)) {
        case DroppedFile::kProject:
            return actions.open_project && actions.open_project(path);
        case DroppedFile::kExperiment:
            if (!loadExperimentAsking(window, document, locations, path)) return false;
            if (actions.show_panel) actions.show_panel("forces");
            report("Loaded the test " + name);
            return true;
        case DroppedFile::kData:
            if (actions.use_data) actions.use_data(path);
            report("Identification data: " + name + " (press Fit)");
            return true;
        case DroppedFile::kSoil: {
            const auto soil = io::resolveSoil(locations, path.toStdString());
            if (!soil || !document.setSoil(*soil, "", "Soil from " + name)) {
                report("Cannot use " + name + ": " +
                       QString::fromStdString(soil ? "not a valid soil" : soil.message()));
                return false;
            }
            report("Soil " + QString::fromStdString(soil->name) + " from " + name);
            return true;
        }
        case DroppedFile::kWheel: {
            const auto wheel = io::resolveWheel(locations, path.toStdString());
            if (!wheel || !document.setWheel(*wheel, "")) {
                report("Cannot use " + name + ": " +
                       QString::fromStdString(wheel ? "not a valid wheel" : wheel.message()));
                return false;
            }
            report("Wheel " + QString::fromStdString(wheel->name) + " from " + name);
            return true;
        }
        case DroppedFile::kScenario: {
            const std::string absolute = QFileInfo(path).absoluteFilePath().toStdString();
            const auto scenario = scenario::loadScenario(absolute, locations);
            if (!scenario) {
                report("Cannot use " + name + ": " + QString::fromStdString(scenario.message()));
                return false;
            }
            document.addScenario(absolute);
            if (actions.show_scenario) actions.show_scenario(QString::fromStdString(absolute));
            report("Scenario " + name + " added to the project (press Run)");
            return true;
        }
        case DroppedFile::kRobot: {
            const auto robot = scenario::resolveRobot(locations, path.toStdString());
            QString error = robot ? QString() : QString::fromStdString(robot.message());
            if (!robot || !actions.use_robot || !actions.use_robot(path, &error)) {
                report("Cannot use " + name + ": " + error);
                return false;
            }
            report("Robot " + QString::fromStdString(robot->name) + " from " + name +
                   " in the scenario (an edit: Revert drops it)");
            return true;
        }
        case DroppedFile::kUnknown:
            break;
    }
    report("Not a file the studio takes: " + name);
    return false;
}

void acceptFileDrops(QWidget* window, ProjectDocument& document, io::PresetLocations locations,
                     DropActions actions) {
    window->setAcceptDrops(true);
    window->installEventFilter(
        new FileDrops(window, document, std::move(locations), std::move(actions)));
}

}  // namespace terra::ui
