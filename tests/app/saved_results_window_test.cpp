// Issue 27, item 2, on real widgets (QT_QPA_PLATFORM=offscreen): a project saved after a fit, a
// streaming playback, a rover run and uncertainty bands reopens in a fresh main window showing
// each of them (the same tables, the plots drawn) with no computation started; changed settings,
// a damaged section or a results file of a newer version cost those results only, never the
// project, and the status bar says why.
#include <gtest/gtest.h>
#include <qcustomplot.h>

#include <QComboBox>
#include <QDir>
#include <QElapsedTimer>
#include <QFile>
#include <QFileInfo>
#include <QLineEdit>
#include <QSignalSpy>
#include <QStandardItemModel>
#include <QStatusBar>
#include <QTableWidget>
#include <QTemporaryDir>
#include <QTest>
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "app/main_window.h"
#include "core/analysis/compaction.h"
#include "core/analysis/forces.h"
#include "core/analysis/sensitivity.h"
#include "core/analysis/soil_curves.h"
#include "core/analysis/stresses.h"
#include "core/identification/data_set.h"
#include "core/identification/synthetic.h"
#include "core/io/atomic_file.h"
#include "core/io/experiment.h"
#include "core/io/table_json.h"
#include "core/project/panels.h"
#include "widgets/document/project_document.h"
#include "widgets/panels/calibration_dialog.h"
#include "widgets/panels/compaction_panel.h"
#include "widgets/panels/experiment_actions.h"
#include "widgets/panels/forces_panel.h"
#include "widgets/panels/global_sensitivity_panel.h"
#include "widgets/panels/identification_panel.h"
#include "widgets/panels/rover_panel.h"
#include "widgets/panels/sensitivity_panel.h"
#include "widgets/panels/stress_panel.h"
#include "widgets/plots/figures.h"
#include "window_test_support.h"

namespace terra::app {
namespace {

using nlohmann::json;

using test::Studio;

bool waitForResult(ui::AnalysisPanel& panel, int timeout_ms = 120000) {
    QSignalSpy shown(&panel, &ui::AnalysisPanel::resultShown);
    if (!shown.wait(timeout_ms)) return false;
    while (panel.isBusy()) {
        if (!shown.wait(timeout_ms)) return false;
    }
    return true;
}

/// Opens `path` in `studio` and waits until its saved results are read and shown.
void openAndWait(Studio& studio, const QString& path) {
    QSignalSpy restored(&studio.window, &MainWindow::savedResultsShown);
    ASSERT_TRUE(studio.window.openProject(path, true));
    ASSERT_TRUE(restored.wait(30000)) << "the saved results were never shown";
}

/// Counts the computations a panel starts (busyChanged(true)).
struct StartCounter {
    explicit StartCounter(ui::AnalysisPanel* panel) : spy(panel, &ui::AnalysisPanel::busyChanged) {}
    int started() const {
        int n = 0;
        for (const QList<QVariant>& arguments : spy) n += arguments.at(0).toBool() ? 1 : 0;
        return n;
    }
    QSignalSpy spy;
};

/// The straight scenario cut to 1.5 s (a quick run with a few hundred rows).
QString shortStraight(ui::RoverPanel& rover) {
    json scenario = json::parse(rover.scenarioText().toStdString());
    scenario["duration_s"] = 1.5;
    return QString::fromStdString(scenario.dump(2));
}

/// The points drawn on a plot, over all its graphs.
int pointsOn(QCustomPlot& plot) {
    int n = 0;
    for (int i = 0; i < plot.graphCount(); ++i) n += plot.graph(i)->dataCount();
    return n;
}

/// What the first window computed, to compare the reopened one with.
struct Computed {
    Table fit_curves, fit_parameters, streamed, rover_series, bands;
    QString parameter_cell, time_label;
    std::size_t frames = 0;
    int fx_points = 0;  // data and fit points drawn on the F_x plot
    soil::SoilParameters identified_soil;
};

/// Fits, plays, runs and computes the bands in a fresh window, then saves the project to `path`
/// (results beside it).
Computed computeAndSave(const QString& path) {
    Computed out;
    Studio studio;
    MainWindow& w = studio.window;
    auto* identification = studio.panel<ui::IdentificationPanel>();
    w.showPanel("identification");
    identification->recompute();
    EXPECT_TRUE(waitForResult(*identification)) << identification->fitStatus().toStdString();
    EXPECT_TRUE(identification->result().usable());
    out.fit_curves = identification->result().curves;
    out.fit_parameters = identification->result().parameters;
    out.parameter_cell = identification->parameterCell(0, 1);
    out.fx_points = pointsOn(*identification->plots().front().second);
    out.identified_soil = identification->identifiedSoil().value_or(soil::SoilParameters{});
    // The streaming playback, at full speed.
    identification->showPage(1);
    identification->setStreamSource("", "clayey-soil");
    identification->setStreamSpeed(0.0);
    QSignalSpy ended(identification, &ui::IdentificationPanel::playbackEnded);
    identification->play();
    EXPECT_TRUE(ended.wait(120000)) << identification->streamStatus().toStdString();
    out.streamed = identification->currentTable();
    out.frames = identification->streamingFigures().frameCount();
    identification->showPage(0);

    auto* rover = studio.panel<ui::RoverPanel>();
    w.showPanel("rover");
    rover->applySettings({{"scenario", "straight"}});
    QString error;
    EXPECT_TRUE(rover->setScenarioText(shortStraight(*rover), &error)) << error.toStdString();
    rover->recompute();
    EXPECT_TRUE(waitForResult(*rover));
    out.rover_series = rover->result().series;
    out.time_label = rover->timeLabel();

    auto* global = studio.panel<ui::GlobalSensitivityPanel>();
    global->setSamples(48);
    global->showPage(1);
    w.showPanel("global-sensitivity");
    global->compute();
    EXPECT_TRUE(waitForResult(*global));
    EXPECT_TRUE(global->bands().has_value());
    out.bands = global->currentTable();
    w.showPanel("forces");

    EXPECT_TRUE(w.document()->save(path, &error)) << error.toStdString();
    EXPECT_EQ(studio.saveAndWaitForResults(),
              QString());  // to the project's path, results beside it
    EXPECT_TRUE(QFileInfo::exists(path + ".results"));
    return out;
}

TEST(SavedResultsWindow, AReopenedProjectShowsItsFitPlaybackRunAndBandsWithoutComputing) {
    QTemporaryDir dir;
    // TERRA_KEEP_SAVED_PROJECT=1 keeps the project and its results for screenshots of a reopened
    // project (scripts/screenshots --project DIR/field.terra).
    if (qEnvironmentVariableIsSet("TERRA_KEEP_SAVED_PROJECT")) {
        dir.setAutoRemove(false);
        std::printf("kept %s\n", qPrintable(dir.filePath("field.terra")));
    }
    const QString path = dir.filePath("field.terra");
    const Computed computed = computeAndSave(path);
    ASSERT_GT(computed.fit_curves.rows.size(), 10u);
    ASSERT_GT(computed.rover_series.rows.size(), 10u);
    ASSERT_GT(computed.frames, 100u);

    Studio studio;
    MainWindow& w = studio.window;
    auto* identification = studio.panel<ui::IdentificationPanel>();
    auto* rover = studio.panel<ui::RoverPanel>();
    auto* global = studio.panel<ui::GlobalSensitivityPanel>();
    StartCounter fits(identification), runs(rover), studies(global);
    openAndWait(studio, path);
    const QString message = w.statusBar()->currentMessage();
    for (const char* shown : {"Identification", "Identification (streaming)", "Rover scenario",
                              "Global sensitivity (bands)"})
        EXPECT_TRUE(message.contains(shown)) << message.toStdString();
    // The indices the panel showed were computed before the samples changed: not shown (they
    // are of other settings), and nothing else is refused.
    EXPECT_TRUE(message.endsWith(
        "not shown (computed again when asked): Global sensitivity: its inputs changed since it "
        "was computed"))
        << message.toStdString();
    for (const char* name : {"identification", "rover", "global-sensitivity"}) {
        w.showPanel(name);
        QTest::qWait(300);
    }

    // The fit: its data and curves in the plots, its parameters in the table, its soil to apply.
    EXPECT_TRUE(identification->showsSavedResult());
    EXPECT_EQ(io::toJson(identification->result().curves), io::toJson(computed.fit_curves));
    EXPECT_EQ(io::toJson(identification->result().parameters), io::toJson(computed.fit_parameters));
    EXPECT_EQ(identification->parameterCell(0, 1), computed.parameter_cell);
    EXPECT_TRUE(identification->fitStatus().contains("Saved with the project"))
        << identification->fitStatus().toStdString();
    QCustomPlot* fx = identification->plots().front().second;
    ASSERT_GE(fx->graphCount(), 2);
    EXPECT_GE(pointsOn(*fx), static_cast<int>(computed.fit_curves.rows.size()));
    EXPECT_EQ(pointsOn(*fx), computed.fx_points);
    const auto soil = identification->identifiedSoil();
    ASSERT_TRUE(soil.has_value());
    EXPECT_EQ(soil->friction_angle_rad, computed.identified_soil.friction_angle_rad);
    EXPECT_EQ(soil->cohesion_pa, computed.identified_soil.cohesion_pa);
    // The playback: every frame, as the table and the figures hold them.
    identification->showPage(1);
    EXPECT_EQ(io::toJson(identification->currentTable()), io::toJson(computed.streamed));
    EXPECT_EQ(identification->streamingFigures().frameCount(), computed.frames);
    EXPECT_TRUE(identification->streamStatus().contains("Saved with the project"))
        << identification->streamStatus().toStdString();
    EXPECT_TRUE(identification->streamStatus().contains("change of soil at sample"))
        << identification->streamStatus().toStdString();
    identification->showPage(0);

    // The rover run: its time series, top view and time label as before.
    EXPECT_TRUE(rover->showsSavedResult());
    EXPECT_EQ(io::toJson(rover->currentTable()), io::toJson(computed.rover_series));
    EXPECT_EQ(rover->timeLabel(), computed.time_label);
    EXPECT_GT(rover->topView()->plottableCount(), 0);
    EXPECT_EQ(rover->completion(), ui::Completion::kComplete);

    // The bands, on the page they were computed on.
    ASSERT_TRUE(global->bands().has_value());
    EXPECT_EQ(io::toJson(global->currentTable()), io::toJson(computed.bands));
    EXPECT_TRUE(global->statusText().contains("Saved with the project"))
        << global->statusText().toStdString();

    EXPECT_EQ(fits.started(), 0) << "a fit started on opening";
    EXPECT_EQ(runs.started(), 0) << "a rover run started on opening";
    EXPECT_EQ(studies.started(), 0) << "a global study started on opening";
}

// The results were computed from other settings than those the project now has: not shown.
TEST(SavedResultsWindow, ChangedSettingsAreNotShownWithOldResults) {
    QTemporaryDir dir;
    const QString path = dir.filePath("field.terra");
    computeAndSave(path);
    std::string text;
    ASSERT_FALSE(io::readFile(path.toStdString(), text));
    json project = json::parse(text);
    project["panels"]["identification"]["noise_percent"] = 3.5;
    project["panels"]["rover"]["edited"]["straight"]["duration_s"] = 1.25;
    ASSERT_FALSE(io::writeFileAtomically(path.toStdString(), project.dump(1)));

    Studio studio;
    auto* identification = studio.panel<ui::IdentificationPanel>();
    auto* rover = studio.panel<ui::RoverPanel>();
    StartCounter fits(identification), runs(rover);
    openAndWait(studio, path);
    EXPECT_FALSE(identification->showsSavedResult());
    EXPECT_FALSE(identification->hasResult());
    EXPECT_FALSE(rover->showsSavedResult());
    EXPECT_TRUE(rover->result().series.rows.empty());
    const QString message = studio.window.statusBar()->currentMessage();
    EXPECT_TRUE(message.contains("not shown")) << message.toStdString();
    EXPECT_TRUE(message.contains("Identification: its inputs changed")) << message.toStdString();
    EXPECT_TRUE(message.contains("Rover scenario: its inputs changed")) << message.toStdString();
    // The streaming playback's inputs (soil, source) did not change: it is still shown.
    EXPECT_TRUE(message.contains("Identification (streaming)")) << message.toStdString();
    EXPECT_GT(identification->streamingFigures().frameCount(), 0u);
    // Nothing heavy started by itself.
    QTest::qWait(300);
    EXPECT_EQ(fits.started(), 0);
    EXPECT_EQ(runs.started(), 0);
    EXPECT_EQ(studio.window.document()->project().panels["identification"]["noise_percent"], 3.5);
}

// Issue 27, item 3 (found by a new user's audit): a second project opened in the same window
// without a results file, and File ▸ New, showed the project before's fit, rover run and
// indices as their own ("Saved with the project", the seed of the new one beside them), and New
// kept its settings. Every panel now drops what it showed; nothing heavy starts by itself.
TEST(SavedResultsWindow, AnotherProjectOrANewOneShowsNoneOfTheResultsBefore) {
    QTemporaryDir dir;
    const QString first = dir.filePath("first.terra");
    Studio studio;
    MainWindow& w = studio.window;
    auto* identification = studio.panel<ui::IdentificationPanel>();
    auto* rover = studio.panel<ui::RoverPanel>();
    auto* global = studio.panel<ui::GlobalSensitivityPanel>();
    w.showPanel("identification");
    identification->recompute();
    ASSERT_TRUE(waitForResult(*identification));
    w.showPanel("rover");
    rover->applySettings({{"scenario", "straight"}});
    QString error;
    ASSERT_TRUE(rover->setScenarioText(shortStraight(*rover), &error)) << error.toStdString();
    rover->recompute();
    ASSERT_TRUE(waitForResult(*rover));
    global->setSamples(48);
    w.showPanel("global-sensitivity");
    global->compute();
    ASSERT_TRUE(waitForResult(*global));
    ASSERT_TRUE(global->indices().has_value());
    // The fit is offered to the global study as a source (its covariance).
    auto identifiedSource = [global]() -> const QStandardItem* {
        for (QComboBox* box : global->findChildren<QComboBox*>()) {
            const int i = box->findText("Identified soil's covariance");
            if (i >= 0) return static_cast<QStandardItemModel*>(box->model())->item(i);
        }
        return nullptr;
    };
    ASSERT_NE(identifiedSource(), nullptr);
    EXPECT_TRUE(identifiedSource()->isEnabled());
    ASSERT_TRUE(w.document()->save(first, &error)) << error.toStdString();
    ASSERT_EQ(studio.saveAndWaitForResults(), QString());

    // The same project with a heavy study and another seed, and no results file.
    std::string text;
    ASSERT_FALSE(io::readFile(first.toStdString(), text));
    json project = json::parse(text);
    project["panels"]["global-sensitivity"]["samples"] = 100000;
    project["panels"]["global-sensitivity"]["seed"] = 2;
    const QString second = dir.filePath("second.terra");
    ASSERT_FALSE(io::writeFileAtomically(second.toStdString(), project.dump(1)));
    StartCounter fits(identification), runs(rover), studies(global);
    ASSERT_TRUE(w.openProject(second, true));
    QTest::qWait(500);
    EXPECT_FALSE(identification->hasResult());
    EXPECT_TRUE(identification->result().curves.rows.empty());
    // The fit's plots no longer titled with the old fit's samples.
    for (const auto& [name, plot] : identification->plots())
        EXPECT_FALSE(ui::plotTitle(*plot).contains("samples")) << name.toStdString();
    EXPECT_FALSE(rover->hasResult());
    EXPECT_TRUE(rover->result().series.rows.empty());
    // The time scrubber of no run: the old run's range and time gone.
    EXPECT_EQ(rover->scrubber()->maximum(), 0);
    EXPECT_FALSE(rover->scrubber()->isEnabled());
    EXPECT_EQ(rover->timeLabel(), "t = – s");
    EXPECT_FALSE(global->hasResult());
    EXPECT_FALSE(global->indices().has_value());
    EXPECT_TRUE(global->statusText().contains("Not computed"))
        << global->statusText().toStdString();
    EXPECT_FALSE(identifiedSource()->isEnabled()) << "the project before's fit is no source";
    EXPECT_EQ(fits.started(), 0);
    EXPECT_EQ(runs.started(), 0);
    EXPECT_EQ(studies.started(), 0);
    // Saved now, the second project carries none of the first one's results.
    ASSERT_EQ(studio.saveAndWaitForResults(), QString());
    std::string saved;
    if (!io::readFile((second + ".results").toStdString(), saved)) {
        for (const char* section : {"\"identification\"", "\"rover\"", "\"global-sensitivity\""})
            EXPECT_EQ(saved.find(section), std::string::npos) << section;
    }

    // File ▸ New after a run: the defaults, and no run on screen.
    rover->recompute();
    ASSERT_TRUE(waitForResult(*rover));
    ASSERT_TRUE(w.document()->save(second, &error)) << error.toStdString();  // nothing to ask
    studio.action("action.new")->trigger();
    QTest::qWait(500);
    EXPECT_TRUE(rover->result().series.rows.empty());
    EXPECT_FALSE(rover->hasResult());
    EXPECT_EQ(global->settings().value("samples", 0),
              project::GlobalSensitivityPanelSettings{}.samples);
    EXPECT_EQ(global->settings().value("seed", 0), 1);
}

// Issue 27, item 5: a project folder moved as a whole keeps the fit of its data file (the saved
// result names the file by its content, not its path); an edited data file does not.
TEST(SavedResultsWindow, AMovedProjectFolderKeepsTheFitOfItsDataFile) {
    QTemporaryDir root;
    ASSERT_TRUE(QDir(root.path()).mkpath("before/data"));
    identification::SyntheticSpec spec;
    for (int i = 0; i <= 15; ++i) spec.slips.push_back(0.05 * i);
    const contact::ContactParameters<double> soil = analysis::Inputs{
        io::resolveSoil(test::resources(), "sandy-loam").value(),
        io::resolveWheel(test::resources(), "A").value(),
        {}}.contact();
    const std::string csv = identification::toCsv(identification::synthesize(soil, spec).data);
    const QString before = root.filePath("before/field.terra");
    ASSERT_FALSE(io::writeFileAtomically(root.filePath("before/data/run.csv").toStdString(), csv));
    std::vector<std::string> fitted_curves;
    {
        Studio studio;
        auto* identification = studio.panel<ui::IdentificationPanel>();
        studio.window.showPanel("identification");
        identification->setDataFile(root.filePath("before/data/run.csv"));
        identification->recompute();
        ASSERT_TRUE(waitForResult(*identification));
        ASSERT_TRUE(identification->result().usable()) << identification->fitStatus().toStdString();
        QString error;
        ASSERT_TRUE(studio.window.document()->save(before, &error)) << error.toStdString();
        EXPECT_EQ(studio.saveAndWaitForResults(), QString());
        ASSERT_TRUE(QFileInfo::exists(before + ".results"));
        fitted_curves.push_back(io::toJson(identification->result().curves).dump());
    }
    ASSERT_TRUE(QDir(root.path()).rename("before", "after"));
    const QString after = root.filePath("after/field.terra");
    {
        Studio studio;
        auto* identification = studio.panel<ui::IdentificationPanel>();
        StartCounter fits(identification);
        openAndWait(studio, after);
        studio.window.showPanel("identification");
        QTest::qWait(300);
        EXPECT_TRUE(identification->showsSavedResult())
            << studio.window.statusBar()->currentMessage().toStdString();
        EXPECT_EQ(io::toJson(identification->result().curves).dump(), fitted_curves.front());
        EXPECT_EQ(fits.started(), 0);
    }
    // The same name, other data (one value changed): the saved fit is not shown.
    std::string edited = csv;
    const std::size_t last_digit = edited.find_last_of("0123456789");
    edited[last_digit] = edited[last_digit] == '1' ? '2' : '1';
    ASSERT_FALSE(
        io::writeFileAtomically(root.filePath("after/data/run.csv").toStdString(), edited));
    Studio studio;
    auto* identification = studio.panel<ui::IdentificationPanel>();
    openAndWait(studio, after);
    EXPECT_FALSE(identification->showsSavedResult());
    const QString message = studio.window.statusBar()->currentMessage();
    EXPECT_TRUE(message.contains("Identification: its inputs changed")) << message.toStdString();
}

// Issue 27, item 2: a calibration to the project's measured test reopens in its dialog with the
// same tables and settings, fitted zero times and applicable; applied and saved, it reopens as
// applied; the test's data edited, it is not shown.
TEST(SavedResultsWindow, ACalibrationReopensWithoutFittingAgain) {
    QTemporaryDir dir;
    const QString source = TERRA_RESOURCE_DIR "/experiments/ding2011-smooth-hit-lss1-80N";
    const QString test = dir.filePath("ding2011-smooth-hit-lss1-80N.csv");
    ASSERT_TRUE(QFile::copy(source + ".csv", test));
    ASSERT_TRUE(QFile::copy(source + ".json", dir.filePath("ding2011-smooth-hit-lss1-80N.json")));
    const QString path = dir.filePath("calibrated.terra");
    auto texts = [](const QTableWidget& table) {
        QStringList out;
        for (int r = 0; r < table.rowCount(); ++r)
            for (int c = 0; c < table.columnCount(); ++c)
                out << (table.item(r, c) ? table.item(r, c)->text() : QString());
        return out;
    };
    QStringList metrics, parameters;
    {
        Studio studio;
        const Result<io::Experiment> read = io::readExperiment(test.toStdString());
        ASSERT_TRUE(read.ok()) << read.message();
        const ui::ExperimentSetup setup = ui::experimentSetup(*read, test::resources());
        ASSERT_TRUE(ui::loadExperiment(*studio.window.document(), test, &setup));
        auto* forces = studio.panel<ui::ForcesPanel>();
        ui::CalibrationDialog* dialog = forces->openCalibration();
        ASSERT_NE(dialog, nullptr);
        dialog->setOptions(1.0, 0.0, 1.0, false);
        dialog->setFitSlips("0, 0.2, 0.6");
        QSignalSpy done(dialog, &ui::CalibrationDialog::calibrationFinished);
        ASSERT_TRUE(dialog->start());
        ASSERT_TRUE(done.wait(120000));
        ASSERT_TRUE(dialog->canApply());
        metrics = texts(*dialog->metricsTable());
        parameters = texts(*dialog->parameterTable());
        ASSERT_EQ(dialog->metricsTable()->columnCount(), 5);  // with the held-out columns
        QString error;
        ASSERT_TRUE(studio.window.document()->save(path, &error)) << error.toStdString();
        EXPECT_EQ(studio.saveAndWaitForResults(), QString());
    }
    {
        Studio studio;
        openAndWait(studio, path);
        const QString message = studio.window.statusBar()->currentMessage();
        EXPECT_TRUE(message.contains("Forces vs slip (calibration)")) << message.toStdString();
        // (Another panel computed in the first window — the one in front at start-up — may be
        // listed as not shown: its inputs changed with the test's setup.)
        EXPECT_FALSE(message.contains("Forces vs slip (calibration):")) << message.toStdString();
        ui::CalibrationDialog* dialog = studio.panel<ui::ForcesPanel>()->calibrationDialog();
        ASSERT_NE(dialog, nullptr);
        ASSERT_TRUE(dialog->result().has_value());  // without a Calibrate: nothing ran
        EXPECT_FALSE(dialog->isRunning());
        EXPECT_EQ(texts(*dialog->metricsTable()), metrics);
        EXPECT_EQ(texts(*dialog->parameterTable()), parameters);
        EXPECT_EQ(dialog->findChild<QLineEdit*>("fit_slips")->text(), "0, 0.2, 0.6");
        EXPECT_TRUE(dialog->statusText().contains("Saved with the project"))
            << dialog->statusText().toStdString();
        // It applies the same calibrated soil as the fit did.
        ASSERT_TRUE(dialog->canApply());
        const soil::SoilParameters calibrated = dialog->result()->calibration->soil;
        ASSERT_TRUE(dialog->apply());
        EXPECT_EQ(studio.window.document()->project().soil.friction_angle_rad,
                  calibrated.friction_angle_rad);
        EXPECT_EQ(studio.saveAndWaitForResults(), QString());
    }
    {
        Studio studio;
        openAndWait(studio, path);
        ui::CalibrationDialog* dialog = studio.panel<ui::ForcesPanel>()->calibrationDialog();
        ASSERT_NE(dialog, nullptr);
        ASSERT_TRUE(dialog->result().has_value());
        EXPECT_FALSE(dialog->canApply());  // applied already: the project's soil is its result
        EXPECT_TRUE(dialog->statusText().contains("Applied")) << dialog->statusText().toStdString();
    }
    // Other data under the same name: the calibration is not one of this test.
    std::string csv;
    ASSERT_FALSE(io::readFile(test.toStdString(), csv));
    const std::size_t last_digit = csv.find_last_of("123456789");
    csv[last_digit] = csv[last_digit] == '1' ? '2' : '1';
    ASSERT_FALSE(io::writeFileAtomically(test.toStdString(), csv));
    Studio studio;
    openAndWait(studio, path);
    ui::CalibrationDialog* dialog = studio.panel<ui::ForcesPanel>()->calibrationDialog();
    EXPECT_TRUE(dialog == nullptr || !dialog->result().has_value());
    const QString message = studio.window.statusBar()->currentMessage();
    EXPECT_TRUE(
        message.contains("Forces vs slip (calibration): its wheel, test or settings changed"))
        << message.toStdString();
}

// A damaged section costs that section; a newer file costs the results, never the project.
TEST(SavedResultsWindow, ADamagedOrNewerResultsFileNeverLosesTheProject) {
    QTemporaryDir dir;
    const QString path = dir.filePath("field.terra");
    computeAndSave(path);
    const std::string results_path = (path + ".results").toStdString();
    std::string text;
    ASSERT_FALSE(io::readFile(results_path, text));
    json results = json::parse(text);
    results["panels"]["rover"]["result"]["series"]["rows"][3] = {1.0, "x"};
    ASSERT_FALSE(io::writeFileAtomically(results_path, results.dump()));
    {
        Studio studio;
        openAndWait(studio, path);
        EXPECT_TRUE(studio.panel<ui::IdentificationPanel>()->showsSavedResult());
        EXPECT_FALSE(studio.panel<ui::RoverPanel>()->showsSavedResult());
        const QString message = studio.window.statusBar()->currentMessage();
        EXPECT_TRUE(message.contains("Rover scenario: rover: series")) << message.toStdString();
        EXPECT_EQ(studio.window.document()->filePath(), QFileInfo(path).absoluteFilePath());
        EXPECT_FALSE(studio.window.document()->isModified());
    }
    results["version"] = 7;
    ASSERT_FALSE(io::writeFileAtomically(results_path, results.dump()));
    Studio studio;
    openAndWait(studio, path);
    EXPECT_FALSE(studio.panel<ui::IdentificationPanel>()->showsSavedResult());
    const QString message = studio.window.statusBar()->currentMessage();
    EXPECT_TRUE(message.contains("cannot be read")) << message.toStdString();
    EXPECT_TRUE(message.contains("version")) << message.toStdString();
    EXPECT_EQ(studio.window.document()->filePath(), QFileInfo(path).absoluteFilePath());
    // Saving again with nothing on screen removes the file: no result for these inputs is left.
    EXPECT_EQ(studio.saveAndWaitForResults(), QString());
    EXPECT_FALSE(QFileInfo::exists(QString::fromStdString(results_path)));
}

// The quick panels (forces, stresses, compaction, sensitivity): their results are saved too and
// reopen with zero computations; a changed input recomputes that panel once, a damaged section
// is said and computed again. Their numbers are compared with the analyses run here from the
// reopened project's own inputs and settings.

/// Equal to 1e-12 relative, NaN to NaN (the panels and the core run the same deterministic code).
bool sameTable(const Table& a, const Table& b) {
    if (a.columns != b.columns || a.rows.size() != b.rows.size()) return false;
    for (std::size_t r = 0; r < a.rows.size(); ++r) {
        if (a.rows[r].size() != b.rows[r].size()) return false;
        for (std::size_t c = 0; c < a.rows[r].size(); ++c) {
            const double x = a.rows[r][c], y = b.rows[r][c];
            if (std::isnan(x) || std::isnan(y)) {
                if (!(std::isnan(x) && std::isnan(y))) return false;
            } else if (std::abs(x - y) > 1e-12 * std::max({1.0, std::abs(x), std::abs(y)})) {
                return false;
            }
        }
    }
    return true;
}

/// Waits until `panel` shows the result of its inputs as they are now.
bool settled(ui::AnalysisPanel& panel, int timeout_ms = 60000) {
    QElapsedTimer timer;
    timer.start();
    while (timer.elapsed() < timeout_ms) {
        const auto saved = panel.savedResults();
        const auto it = saved.find(panel.name().toStdString());
        if (!panel.isBusy() && it != saved.end() && it->second.inputs_hash == panel.inputsHash())
            return true;
        QTest::qWait(20);
    }
    return false;
}

const char* const kQuickPanels[] = {"forces", "stresses", "compaction", "sensitivity"};

std::vector<ui::AnalysisPanel*> quickPanels(Studio& studio) {
    return {studio.panel<ui::ForcesPanel>(), studio.panel<ui::StressPanel>(),
            studio.panel<ui::CompactionPanel>(), studio.panel<ui::SensitivityPanel>()};
}

/// Shows each quick panel in turn until it shows the result of its inputs as they are now.
void showQuickPanels(Studio& studio) {
    for (ui::AnalysisPanel* panel : quickPanels(studio)) {
        studio.window.showPanel(panel->name());
        EXPECT_TRUE(settled(*panel)) << panel->name().toStdString();
    }
}

/// Each quick panel computed with settings of its own, then the project saved with its results.
void computeQuickAndSave(const QString& path) {
    Studio studio;
    MainWindow& w = studio.window;
    studio.panel<ui::StressPanel>()->applySettings({{"slip", 0.35}, {"slip_angle_deg", 5.0}});
    studio.panel<ui::CompactionPanel>()->applySettings({{"passes", 2}, {"slip", 0.2}});
    studio.panel<ui::SensitivityPanel>()->applySettings({{"parameter", "n"}});
    showQuickPanels(studio);
    QString error;
    EXPECT_TRUE(w.document()->save(path, &error)) << error.toStdString();
    EXPECT_EQ(studio.saveAndWaitForResults(), QString());
}

/// The four panels' results against the analyses run here on the window's project.
void expectQuickResultsOfTheProject(Studio& studio) {
    const project::Project& p = studio.window.document()->project();
    const analysis::Inputs inputs = project::inputsOf(p);
    const auto stress =
        project::panelSettingsFromJson<project::StressPanelSettings>(p.panels.at("stresses"));
    const auto compaction =
        project::panelSettingsFromJson<project::CompactionPanelSettings>(p.panels.at("compaction"));
    const auto sensitivity = project::panelSettingsFromJson<project::SensitivityPanelSettings>(
        p.panels.at("sensitivity"));
    ASSERT_TRUE(stress && compaction && sensitivity);
    EXPECT_EQ(stress->analysis.slip, 0.35);
    EXPECT_EQ(compaction->analysis.passes, 2);

    auto* forces = studio.panel<ui::ForcesPanel>();
    EXPECT_TRUE(sameTable(forces->result().table, analysis::computeForceSweep(inputs).table));
    const analysis::SoilCurves curves = analysis::computeSoilCurves(inputs);
    EXPECT_TRUE(sameTable(forces->soilCurves().static_sinkage, curves.static_sinkage));
    EXPECT_TRUE(sameTable(forces->soilCurves().bulldozing, curves.bulldozing));

    const analysis::StressResult stresses = analysis::computeStresses(inputs, stress->analysis);
    EXPECT_TRUE(sameTable(studio.panel<ui::StressPanel>()->result().table, stresses.table));
    EXPECT_EQ(studio.panel<ui::StressPanel>()->result().entry_angle_deg, stresses.entry_angle_deg);

    analysis::CompactionSettings c = compaction->analysis;
    c.map_x_points = ui::CompactionPanel::kMapXPoints;
    c.map_z_points = ui::CompactionPanel::kMapZPoints;
    const analysis::CompactionResult passes = analysis::computeCompaction(inputs, c);
    auto* panel = studio.panel<ui::CompactionPanel>();
    ASSERT_EQ(panel->result().passes.size(), 2u);
    EXPECT_TRUE(sameTable(panel->result().map, passes.map));
    EXPECT_TRUE(sameTable(*analysis::compactionOutcome(panel->result()).table("passes"),
                          *analysis::compactionOutcome(passes).table("passes")));
    EXPECT_TRUE(sameTable(*analysis::compactionOutcome(panel->result()).table("profile"),
                          *analysis::compactionOutcome(passes).table("profile")));

    const analysis::SensitivityResult family =
        analysis::computeSensitivity(inputs, sensitivity->analysis);
    EXPECT_TRUE(sameTable(studio.panel<ui::SensitivityPanel>()->result().family.table,
                          family.family.table));
    EXPECT_TRUE(sameTable(studio.panel<ui::SensitivityPanel>()->result().tornado, family.tornado));
}

TEST(SavedResultsWindow, TheQuickPanelsReopenWithTheirResultsAndComputeOnlyWhatChanged) {
    QTemporaryDir dir;
    const QString path = dir.filePath("quick.terra");
    computeQuickAndSave(path);
    std::string text;
    ASSERT_FALSE(io::readFile((path + ".results").toStdString(), text));
    const json saved = json::parse(text);
    for (const char* name : kQuickPanels) EXPECT_TRUE(saved["panels"].contains(name)) << name;

    Studio studio;
    MainWindow& w = studio.window;
    StartCounter forces(studio.panel<ui::ForcesPanel>()), stresses(studio.panel<ui::StressPanel>()),
        compaction(studio.panel<ui::CompactionPanel>()),
        sensitivity(studio.panel<ui::SensitivityPanel>());
    openAndWait(studio, path);
    const QString message = w.statusBar()->currentMessage();
    EXPECT_TRUE(message.contains("with its saved results")) << message.toStdString();
    for (const char* shown : {"Forces vs slip", "Stresses", "Compaction", "Sensitivity"})
        EXPECT_TRUE(message.contains(shown)) << message.toStdString();
    EXPECT_FALSE(message.contains("not shown")) << message.toStdString();
    for (const char* name : kQuickPanels) {
        w.showPanel(name);
        QTest::qWait(200);
    }
    for (ui::AnalysisPanel* panel : quickPanels(studio))
        EXPECT_TRUE(panel->showsSavedResult()) << panel->name().toStdString();
    expectQuickResultsOfTheProject(studio);
    EXPECT_EQ(forces.started(), 0);
    EXPECT_EQ(stresses.started(), 0);
    EXPECT_EQ(compaction.started(), 0);
    EXPECT_EQ(sensitivity.started(), 0);
    // Drawing another stress or tab is no new input: nothing computed.
    studio.panel<ui::StressPanel>()->applySettings({{"stress", "sigma"}});
    studio.panel<ui::SensitivityPanel>()->applySettings({{"plot", "tornado"}});
    QTest::qWait(300);
    EXPECT_EQ(stresses.started(), 0);
    EXPECT_EQ(sensitivity.started(), 0);

    // One input changed: that panel computes once, the others keep their saved results.
    w.showPanel("stresses");
    studio.panel<ui::StressPanel>()->applySettings({{"slip", 0.4}});
    ASSERT_TRUE(settled(*studio.panel<ui::StressPanel>()));
    QTest::qWait(300);
    EXPECT_EQ(stresses.started(), 1);
    EXPECT_FALSE(studio.panel<ui::StressPanel>()->showsSavedResult());
    const analysis::Inputs inputs = project::inputsOf(w.document()->project());
    analysis::StressSettings at_04 = project::panelSettingsFromJson<project::StressPanelSettings>(
                                         w.document()->project().panels.at("stresses"))
                                         ->analysis;
    EXPECT_EQ(at_04.slip, 0.4);
    EXPECT_TRUE(sameTable(studio.panel<ui::StressPanel>()->result().table,
                          analysis::computeStresses(inputs, at_04).table));
    for (const char* name : kQuickPanels) {
        w.showPanel(name);
        QTest::qWait(200);
    }
    EXPECT_EQ(forces.started(), 0);
    EXPECT_EQ(compaction.started(), 0);
    EXPECT_EQ(sensitivity.started(), 0);
    EXPECT_EQ(stresses.started(), 1);
}

TEST(SavedResultsWindow, ADamagedQuickSectionIsSaidAndComputedAgain) {
    QTemporaryDir dir;
    const QString path = dir.filePath("quick.terra");
    computeQuickAndSave(path);
    const std::string results_path = (path + ".results").toStdString();
    std::string text;
    ASSERT_FALSE(io::readFile(results_path, text));
    json results = json::parse(text);
    results["panels"]["compaction"]["result"]["passes"][1]["forces"]["fx"] = "x";
    results["panels"]["stresses"]["result"].erase("errors");
    ASSERT_FALSE(io::writeFileAtomically(results_path, results.dump()));

    Studio studio;
    MainWindow& w = studio.window;
    StartCounter forces(studio.panel<ui::ForcesPanel>()), stresses(studio.panel<ui::StressPanel>()),
        compaction(studio.panel<ui::CompactionPanel>());
    openAndWait(studio, path);
    const QString message = w.statusBar()->currentMessage();
    EXPECT_TRUE(
        message.contains("Compaction: compaction: passes: 1: forces: fx: \"x\" is not a "
                         "number"))
        << message.toStdString();
    EXPECT_TRUE(message.contains("Stresses: stresses: errors")) << message.toStdString();
    EXPECT_FALSE(studio.panel<ui::CompactionPanel>()->showsSavedResult());
    showQuickPanels(studio);
    QTest::qWait(300);
    // Computed again, once each, to the numbers of the project's inputs; the forces kept.
    EXPECT_EQ(stresses.started(), 1);
    EXPECT_EQ(compaction.started(), 1);
    EXPECT_EQ(forces.started(), 0);
    EXPECT_TRUE(studio.panel<ui::ForcesPanel>()->showsSavedResult());
    expectQuickResultsOfTheProject(studio);

    // Not JSON at all: the results cannot be read, the project opens and computes.
    ASSERT_FALSE(io::writeFileAtomically(results_path, "{\"format\": \"terrastudio-res"));
    Studio again;
    StartCounter forces_again(again.panel<ui::ForcesPanel>());
    openAndWait(again, path);
    EXPECT_TRUE(again.window.statusBar()->currentMessage().contains("cannot be read"))
        << again.window.statusBar()->currentMessage().toStdString();
    showQuickPanels(again);
    EXPECT_FALSE(again.panel<ui::ForcesPanel>()->showsSavedResult());
    EXPECT_GE(forces_again.started(), 1);
    expectQuickResultsOfTheProject(again);
}

}  // namespace
}  // namespace terra::app
