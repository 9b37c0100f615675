// The main window's screenshots (`terrastudio gui --screenshots DIR`: the GUI smoke test and
// docs/images; main_window.h). Split from main_window.cpp to keep each file small.
#include <QDir>
#include <QEventLoop>
#include <QFile>
#include <QSlider>
#include <QTimer>
#include <QUndoStack>
#include <cstdio>
#include <filesystem>
#include <utility>

#include "app/main_window.h"
#include "core/io/experiment.h"
#include "widgets/document/project_document.h"
#include "widgets/panels/analysis_panel.h"
#include "widgets/panels/calibration_dialog.h"
#include "widgets/panels/experiment_actions.h"
#include "widgets/panels/forces_panel.h"
#include "widgets/panels/identification_panel.h"
#include "widgets/panels/plot_docking.h"
#include "widgets/panels/rover_panel.h"

namespace terra::app {

int MainWindow::takeScreenshots(const QString& dir) {
    QDir().mkpath(dir);
    QFile::remove(autosavePath());
    if (readingSavedResults()) {  // a project opened on the command line: its results first
        QEventLoop loop;
        QTimer::singleShot(60000, &loop, &QEventLoop::quit);
        connect(this, &MainWindow::savedResultsShown, &loop, &QEventLoop::quit);
        loop.exec();
    }
    int failures = 0;
    for (std::size_t i = 0; i < panels_.size(); ++i) {
        ui::AnalysisPanel* panel = panels_[i];
        showPanel(panel->name());
        if (panel) {
            QEventLoop loop;
            QTimer::singleShot(60000, &loop, &QEventLoop::quit);
            connect(panel, &ui::AnalysisPanel::resultShown, &loop, &QEventLoop::quit);
            connect(panel, &ui::AnalysisPanel::failed, &loop, &QEventLoop::quit);
            // A result saved with the project is shown as it is (a reopened project's screenshots).
            const bool on_request =
                (panel->name() == "identification" || panel->name() == "rover") &&
                !panel->showsSavedResult();
            if (on_request || panel->isBusy() ||
                (panel->lastLatencyMs() == 0.0 && !panel->showsSavedResult())) {
                if (on_request) panel->recompute();
                loop.exec();
            }
        }
        QEventLoop settle;
        QTimer::singleShot(300, &settle, &QEventLoop::quit);
        settle.exec();
        const QString name = panel->name();
        const QString path = dir + "/studio-" + name + ".png";
        if (!grab().save(path)) ++failures;
        std::printf("wrote %s\n", qPrintable(path));
    }
    // "Compare with…" (docs/images/studio-compare.png): the soil pinned, φ edited to 35°, then
    // the edit undone and the comparison cleared, so the project ends as it began.
    if (auto* forces = dynamic_cast<ui::ForcesPanel*>(panels_.front())) {
        showPanel(forces->name());
        auto waitForResult = [forces] {
            QEventLoop loop;
            QTimer::singleShot(60000, &loop, &QEventLoop::quit);
            connect(forces, &ui::AnalysisPanel::resultShown, &loop, &QEventLoop::quit);
            connect(forces, &ui::AnalysisPanel::failed, &loop, &QEventLoop::quit);
            loop.exec();
        };
        forces->pinReference();
        waitForResult();
        const int steps = document_->undoStack()->index();
        document_->setSoilValue("phi_deg", 35.0);
        waitForResult();
        QEventLoop settle;
        QTimer::singleShot(300, &settle, &QEventLoop::quit);
        settle.exec();
        const QString path = dir + "/studio-compare.png";
        if (!grab().save(path)) ++failures;
        std::printf("wrote %s\n", qPrintable(path));
        document_->undoStack()->setIndex(steps);
        forces->clearComparison();
    }
    // Traction control (docs/traction.md §7): the controllers compared on traction-border (cut
    // to 20 s), the optimal controller's run in the slip-control, efficiency and energy figures,
    // and the comparison table; then the edit reverted and the scenario shown before restored.
    for (ui::AnalysisPanel* panel : panels_) {
        auto* rover = dynamic_cast<ui::RoverPanel*>(panel);
        if (!rover) continue;
        showPanel(rover->name());
        const nlohmann::json before = rover->settings();
        rover->applySettings({{"scenario", "traction-border"}});
        auto json = nlohmann::json::parse(rover->scenarioText().toStdString());
        json["duration_s"] = 20.0;
        QString error;
        if (!rover->setScenarioText(QString::fromStdString(json.dump(2)), &error)) {
            ++failures;
            break;
        }
        // Starts the rover's computation with `start` and waits for its result (2 min at most).
        auto runAndWait = [rover](void (ui::RoverPanel::*start)()) {
            QEventLoop loop;
            QTimer::singleShot(120000, &loop, &QEventLoop::quit);
            QObject::connect(rover, &ui::AnalysisPanel::resultShown, &loop, &QEventLoop::quit);
            QObject::connect(rover, &ui::AnalysisPanel::failed, &loop, &QEventLoop::quit);
            (rover->*start)();
            loop.exec();
        };
        // The window as it settled, into dir/name.
        auto grabAs = [&](const QString& name) {
            QEventLoop settle;
            QTimer::singleShot(300, &settle, &QEventLoop::quit);
            settle.exec();
            const QString path = dir + "/" + name;
            if (!grab().save(path)) ++failures;
            std::printf("wrote %s\n", qPrintable(path));
        };
        runAndWait(&ui::RoverPanel::requestComparison);
        for (const char* tab : {"Slip control", "Efficiency", "Energy", "Comparison"}) {
            rover->showTab(tab);
            grabAs("studio-rover-" + QString(tab).toLower().replace(' ', '-') + ".png");
        }
        rover->showTab("Top view");
        rover->revertScenario();
        // A field run with its layers (docs/user-guide.md, "Field layers"): the shipped sloped
        // field, the ruts at the end and a third of the way, the soil classes, the compaction risk.
        rover->applySettings({{"scenario", "field-slope-wet"}});
        runAndWait(&ui::RoverPanel::requestRun);
        const int last = rover->scrubber()->maximum();
        const std::pair<const char*, int> shots[] = {{"rut_depth_m", last},
                                                     {"rut_depth_m", last / 3},
                                                     {"soil_classes", last},
                                                     {"compaction_risk", last}};
        for (const auto& [layer, row] : shots) {
            rover->chooseLayer(layer);
            rover->scrubber()->setValue(row);
            grabAs("studio-rover-field-" + QString(layer).replace('_', '-') +
                   (row == last ? QString() : QString("-scrubbed")) + ".png");
        }
        rover->chooseLayer("rut_depth_m");
        rover->applySettings(before);
        break;
    }
    // The window as it settled, into dir/name (the dialogs below grab themselves).
    auto grabWidget = [&](QWidget& widget, const QString& name) {
        QEventLoop settle;
        QTimer::singleShot(300, &settle, &QEventLoop::quit);
        settle.exec();
        const QString path = dir + "/" + name;
        if (!widget.grab().save(path)) ++failures;
        std::printf("wrote %s\n", qPrintable(path));
    };
    // The streaming playback (docs/images/studio-streaming.png): the synthetic drive over the soil
    // border played to its end at full speed, then back to the batch fit's page.
    if (identification_) {
        showPanel(identification_->name());
        identification_->showPage(1);
        identification_->setStreamSpeed(0.0);
        QEventLoop loop;
        QTimer::singleShot(120000, &loop, &QEventLoop::quit);
        connect(identification_, &ui::IdentificationPanel::playbackEnded, &loop, &QEventLoop::quit);
        identification_->play();
        loop.exec();
        grabWidget(*this, "studio-streaming.png");
        identification_->showPage(0);
    }
    // A measured test (docs/images/studio-experiment.png): the Ding et al. 2011 smooth wheel with
    // its setup, the metrics under the plots; calibrated on every point and on three slips with
    // the others held out (studio-calibration.png, -calibration-held-out.png), applied
    // (studio-calibrated.png); then undone, the project as it began.
    QString test;
    for (const std::filesystem::path& d : locations_.directories) {
        const QString candidate = QString::fromStdString(
            (d / "experiments" / "ding2011-smooth-hit-lss1-80N.csv").string());
        if (QFile::exists(candidate)) test = candidate;
    }
    auto* forces = dynamic_cast<ui::ForcesPanel*>(panels_.front());
    const Result<io::Experiment> read =
        test.isEmpty() ? Result<io::Experiment>(std::vector<Issue>{{"experiments", "not found"}})
                       : io::readExperiment(test.toStdString());
    if (forces && read) {
        const int steps = document_->undoStack()->index();
        const ui::ExperimentSetup setup = ui::experimentSetup(*read, locations_);
        showPanel(forces->name());
        QEventLoop shown;
        QTimer::singleShot(60000, &shown, &QEventLoop::quit);
        connect(forces, &ui::AnalysisPanel::resultShown, &shown, &QEventLoop::quit);
        if (ui::loadExperiment(*document_, test, &setup)) shown.exec();
        grabWidget(*this, "studio-experiment.png");
        if (ui::CalibrationDialog* dialog = forces->openCalibration()) {
            dialog->show();
            auto calibrate = [&](const QString& slips, const QString& file) {
                dialog->setOptions(1.0, 0.0, 1.0, false);  // the readings' ±1 N, ±1 mm
                dialog->setFitSlips(slips);
                QEventLoop fitted;
                QTimer::singleShot(120000, &fitted, &QEventLoop::quit);
                connect(dialog, &ui::CalibrationDialog::calibrationFinished, &fitted,
                        &QEventLoop::quit);
                if (dialog->start()) fitted.exec();
                grabWidget(*dialog, file);
            };
            calibrate("0, 0.2, 0.6", "studio-calibration-held-out.png");
            calibrate("", "studio-calibration.png");
            QEventLoop applied;
            QTimer::singleShot(60000, &applied, &QEventLoop::quit);
            connect(forces, &ui::AnalysisPanel::resultShown, &applied, &QEventLoop::quit);
            if (dialog->apply()) applied.exec();
            dialog->hide();
            grabWidget(*this, "studio-calibrated.png");
        }
        document_->undoStack()->setIndex(steps);
    }
    // The docks (docs/images/studio-side-by-side.png): forces and stresses side by side, then
    // every panel tiled; the layout for the screen afterwards.
    auto grabLayout = [&](Layout layout, const QString& file) {
        showPanel("forces");
        applyLayout(layout);
        QEventLoop settle;
        QTimer::singleShot(1500, &settle, &QEventLoop::quit);  // the panels shown compute
        settle.exec();
        const QString path = dir + "/" + file;
        if (!grab().save(path)) ++failures;
        std::printf("wrote %s\n", qPrintable(path));
    };
    grabLayout(Layout::kSideBySide, "studio-side-by-side.png");
    grabLayout(Layout::kTiled, "studio-tiled.png");
    applyLayout(layoutForScreen());
    // Two plots of one analysis side by side (docs/images/studio-plots-side-by-side.png): the
    // forces panel on its static sinkage, its drawbar pull in a dock of its own beside it (Side
    // by side); then put back, the panel on the plot it showed, the layout for the screen.
    if (forces) {
        const nlohmann::json before = forces->settings();
        showPanel(forces->name());
        forces->applySettings({{"plot", "static-sinkage-vs-load"}});
        for (const auto& [name, plot] : forces->plots()) {
            if (name == "Fx_N-vs-slip") plot_docking_->tearOff(plot);
        }
        applyLayout(Layout::kSideBySide);
        grabWidget(*this, "studio-plots-side-by-side.png");
        forces->applySettings(before);
        applyLayout(layoutForScreen());
    }
    document_->undoStack()->setClean();
    return failures == 0 ? 0 : 1;
}

}  // namespace terra::app
