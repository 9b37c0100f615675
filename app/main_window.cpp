#include "app/main_window.h"

#include <qcustomplot.h>

#include <QApplication>
#include <QCloseEvent>
#include <QDir>
#include <QDockWidget>
#include <QFileDialog>
#include <QFileInfo>
#include <QLabel>
#include <QListWidget>
#include <QMenuBar>
#include <QMessageBox>
#include <QPushButton>
#include <QScreen>
#include <QScrollArea>
#include <QSettings>
#include <QStackedWidget>
#include <QStandardPaths>
#include <QStatusBar>
#include <QTabWidget>
#include <QTimer>
#include <QToolBar>
#include <QUndoStack>
#include <QVBoxLayout>
#include <QtConcurrent/QtConcurrentRun>

#include "core/project/results.h"
#include "widgets/document/project_document.h"
#include "widgets/document/saved_results_reader.h"
#include "widgets/document/suggested_paths.h"
#include "widgets/editors/project_tree.h"
#include "widgets/editors/property_editors.h"
#include "widgets/panels/compaction_panel.h"
#include "widgets/panels/experiment_actions.h"
#include "widgets/panels/file_drops.h"
#include "widgets/panels/forces_panel.h"
#include "widgets/panels/global_sensitivity_panel.h"
#include "widgets/panels/identification_panel.h"
#include "widgets/panels/plot_docking.h"
#include "widgets/panels/rover_panel.h"
#include "widgets/panels/sensitivity_panel.h"
#include "widgets/panels/stress_panel.h"
#include "widgets/plots/export_dialog.h"

namespace terra::app {
namespace {

constexpr int kAutosaveIntervalMs = 30000;

/// The widget in a frameless scroll area that resizes it: it fills the area when there is room and
/// scrolls when the area is smaller than its minimum size.
QScrollArea* scrollable(QWidget* content) {
    auto* area = new QScrollArea;
    area->setWidget(content);
    area->setWidgetResizable(true);
    area->setFrameShape(QFrame::NoFrame);
    return area;
}

QDockWidget* dock(QMainWindow* window, const QString& title, const QString& name,
                  QWidget* content) {
    auto* d = new QDockWidget(title, window);
    d->setObjectName(name);  // QSettings restores docks by object name
    d->setWidget(content);
    return d;
}

}  // namespace

MainWindow::MainWindow(const io::PresetLocations& locations, QWidget* parent)
    : QMainWindow(parent), locations_(locations), document_(new ui::ProjectDocument(this)) {
    document_->reset(ui::ProjectDocument::defaultProject(locations_));

    auto* identification = new ui::IdentificationPanel(document_, this);
    auto* global = new ui::GlobalSensitivityPanel(document_, this);
    auto* forces = new ui::ForcesPanel(document_, this);
    forces->setPresetLocations(locations_);  // "Compare with…" lists the soil presets
    panels_ = {forces,
               new ui::StressPanel(document_, this),
               new ui::CompactionPanel(document_, locations_, this),
               new ui::SensitivityPanel(document_, this),
               identification,
               new ui::RoverPanel(document_, locations_, this),
               global};
    const QStringList titles{"Forces vs slip", "Stresses",       "Compaction",        "Sensitivity",
                             "Identification", "Rover scenario", "Global sensitivity"};
    for (ui::AnalysisPanel* panel : panels_) panel->rememberDefaultSettings();
    identification_ = identification;
    global_ = global;
    // The identified soil's covariance feeds the global study's "identified soil" source.
    connect(identification, &ui::AnalysisPanel::resultShown, this,
            &MainWindow::shareIdentification);
    // Every analysis is a dock (View ▸ Layout): torn off, put beside another or tabbed with it.
    panel_area_ = new QMainWindow(this);
    panel_area_->setObjectName("panel_area");
    panel_area_->setWindowFlags(Qt::Widget);
    panel_area_->setDockOptions(QMainWindow::AllowNestedDocks | QMainWindow::AllowTabbedDocks |
                                QMainWindow::AnimatedDocks | QMainWindow::GroupedDragging);
    panel_area_->setTabPosition(Qt::AllDockWidgetAreas, QTabWidget::North);
    setCentralWidget(panel_area_);
    plot_docking_ = new ui::PlotDocking(panel_area_, this);
    for (std::size_t i = 0; i < panels_.size(); ++i) {
        ui::AnalysisPanel* panel = panels_[i];
        // A panel whose controls need more room than a small screen leaves scrolls instead of
        // widening the window past the screen (the window was ≥ 1497 px wide).
        QDockWidget* d = dock(panel_area_, titles[static_cast<int>(i)], "panel." + panel->name(),
                              scrollable(panel));
        panel_docks_.push_back(d);
        // The panel brought to front or clicked is the one Run, Export and the status bar mean.
        connect(d, &QDockWidget::visibilityChanged, this, [this, panel](bool visible) {
            if (visible) setCurrentPanel(panel);
        });
        // Any of its plots in a dock of its own (its right-click menu), beside the panels.
        plot_docking_->addPanel(panel, d, titles[static_cast<int>(i)]);
        connect(panel, &ui::AnalysisPanel::exportRequested, this, [this, panel](QCustomPlot* plot) {
            setCurrentPanel(panel);
            exportPlot(*panel, *plot);
        });
        // The status bar speaks of the panel in use only ("Sensitivity updated…" stayed there
        // on other tabs); a panel's own status line keeps its news.
        connect(panel, &ui::AnalysisPanel::resultShown, this,
                [this, panel, title = titles[static_cast<int>(i)]] {
                    if (panel == currentPanel())
                        statusBar()->showMessage(panel->resultMessage(title), 5000);
                });
        connect(panel, &ui::AnalysisPanel::failed, this, [this, panel](const QString& message) {
            if (panel == currentPanel()) statusBar()->showMessage("Error: " + message, 8000);
        });
    }
    connect(qApp, &QApplication::focusChanged, this, [this](QWidget*, QWidget* now) {
        for (ui::AnalysisPanel* panel : panels_) {
            if (now && panel->isAncestorOf(now)) setCurrentPanel(panel);
        }
    });
    current_ = panels_.front();

    auto* tree = new ui::ProjectTree(document_, this);
    editors_ = new QStackedWidget(this);
    editors_->addWidget(new ui::SoilEditor(document_, locations_, editors_));
    editors_->addWidget(new ui::WheelEditor(document_, locations_, editors_));
    editors_->addWidget(new ui::ConditionsEditor(document_, editors_));
    auto* data_page = new QWidget(editors_);
    auto* data_list = new QListWidget(data_page);
    auto* load_data = new QPushButton("Load CSV for identification…", data_page);
    auto* data_layout = new QVBoxLayout(data_page);
    data_layout->addWidget(data_list);
    data_layout->addWidget(load_data);
    editors_->addWidget(data_page);
    auto* scenarios = new QLabel(
        "Scenarios: resources/scenarios/*.json (docs/dynamics.md). Pick and run one in the Rover "
        "scenario panel.",
        editors_);
    scenarios->setWordWrap(true);
    editors_->addWidget(scenarios);
    editors_->addWidget(
        ui::experimentPage(editors_, *document_, locations_, [this] { showPanel("forces"); }));
    connect(tree, &ui::ProjectTree::pageRequested, editors_, &QStackedWidget::setCurrentIndex);
    connect(load_data, &QPushButton::clicked, this, [this] {
        const QString path =
            QFileDialog::getOpenFileName(this, "Load identification data",
                                         ui::startFolder(document_->filePath()), "CSV (*.csv)");
        if (!path.isEmpty()) useData(path);
    });
    connect(document_, &ui::ProjectDocument::dataSetsChanged, data_list, [this, data_list] {
        data_list->clear();
        for (const std::string& path : document_->project().data_sets)
            data_list->addItem(QString::fromStdString(path));
    });
    ui::acceptFileDrops(this, *document_, locations_,
                        {[this](const QString& path) { return maybeSave() && openProject(path); },
                         [this](const QString& path) { useData(path); },
                         [this](const QString& panel) { showPanel(panel); },
                         [this](const QString& path) {
                             findChild<ui::RoverPanel*>()->chooseScenario(path);
                             showPanel("rover");
                         },
                         [this](const QString& path, QString* error) {
                             if (!findChild<ui::RoverPanel*>()->useRobotFile(path, error))
                                 return false;
                             showPanel("rover");
                             return true;
                         },
                         [this](const QString& text) { statusBar()->showMessage(text, 8000); }});
    connect(data_list, &QListWidget::itemDoubleClicked, this,
            [this](QListWidgetItem* item) { useData(item->text()); });

    project_dock_ = dock(this, "Project", "project_dock", tree);
    properties_dock_ = dock(this, "Properties", "properties_dock", scrollable(editors_));
    for (QTabWidget* tabs : findChildren<QTabWidget*>()) {
        tabs->setUsesScrollButtons(true);  // tabs that do not fit scroll, never widen the window
        tabs->setElideMode(Qt::ElideNone);
    }
    createMenus();

    adoptPanelSettings();
    connect(document_, &ui::ProjectDocument::modifiedChanged, this, &MainWindow::updateTitle);
    connect(document_, &ui::ProjectDocument::filePathChanged, this, &MainWindow::updateTitle);
    updateTitle();
    autosave_timer_ = new QTimer(this);
    autosave_timer_->setInterval(kAutosaveIntervalMs);
    connect(autosave_timer_, &QTimer::timeout, this, &MainWindow::autosave);
    autosave_timer_->start();

    resize(1440, 860);
    restoreGeometry(QSettings().value("window/geometry").toByteArray());
    fitToScreen();
    restoreWindowState();
    QTimer::singleShot(0, this, &MainWindow::offerRecovery);
}

void MainWindow::fitToScreen() {
    // On the screen, title bar included: a window taller or wider than the screen hides its
    // title-bar buttons (a 1366×768 laptop got 1497×860). Room is left for the frame.
    const QScreen* s = screen() ? screen() : QGuiApplication::primaryScreen();
    if (!s) return;
    const QRect available = s->availableGeometry();
    const QSize frame(16, 40);
    const QSize fitted = size().boundedTo(available.size() - frame).expandedTo(minimumSizeHint());
    if (fitted != size()) resize(fitted);
    if (!available.contains(frameGeometry().topLeft()) ||
        !available.contains(frameGeometry().bottomRight()))
        move(available.topLeft());
}

void MainWindow::useData(const QString& path) {
    findChild<ui::IdentificationPanel*>()->setDataFile(path);
    showPanel("identification");
}

void MainWindow::showPanel(const QString& name) {
    for (std::size_t i = 0; i < panels_.size(); ++i) {
        if (panels_[i]->name() != name) continue;
        panel_docks_[i]->show();
        panel_docks_[i]->raise();  // the front tab of its group
        setCurrentPanel(panels_[i]);
    }
}

void MainWindow::setCurrentPanel(ui::AnalysisPanel* panel) {
    if (panel == current_) return;
    current_ = panel;
    statusBar()->clearMessage();
}

QString MainWindow::currentPanelName() const { return current_ ? current_->name() : QString(); }

QDockWidget* MainWindow::panelDock(const QString& name) const {
    for (std::size_t i = 0; i < panels_.size(); ++i) {
        if (panels_[i]->name() == name) return panel_docks_[i];
    }
    return nullptr;
}

bool MainWindow::openProject(const QString& path, bool quiet) {
    finishWritingResults();  // a project saved a moment ago opens with its results
    auto project = ui::ProjectDocument::load(path, &locations_);
    if (!project) {
        if (!quiet)
            QMessageBox::warning(this, "Cannot open project",
                                 QString::fromStdString(project.message()));
        return false;
    }
    const QString absolute = QFileInfo(path).absoluteFilePath();
    // The results saved beside it, read off the GUI thread (a rover run is 10⁵ numbers) and shown
    // where the inputs are unchanged: nothing is recomputed, and nothing starts meanwhile.
    const int opening = ++opening_;
    const QString results_path =
        QString::fromStdString(project::resultsPathFor(absolute.toStdString()).string());
    reading_results_ = QFileInfo::exists(results_path);
    replaceProject(*project, absolute, reading_results_);
    addRecent(absolute);
    if (!reading_results_) {
        statusBar()->showMessage("Opened " + path, 6000);
        return true;
    }
    statusBar()->showMessage("Opened " + path + "; reading its saved results…");
    ui::readSavedResults(results_path, this,
                         [this, opening, path](const Result<project::SavedResults>& results) {
                             // Another project was opened (or a new one) since: not its results.
                             if (opening == opening_) showSavedResults(path, results);
                         });
    return true;
}

void MainWindow::newProject() {
    if (!maybeSave()) return;
    ++opening_;  // saved results still being read are of the project before: never shown
    reading_results_ = false;
    replaceProject(ui::ProjectDocument::defaultProject(locations_), {}, false);
}

void MainWindow::replaceProject(const project::Project& project, const QString& file_path,
                                bool hold) {
    // What runs for the project being closed is dropped, never shown over the new one.
    for (ui::AnalysisPanel* panel : panels_) panel->discardRunning();
    document_->reset(project, file_path);
    for (ui::AnalysisPanel* panel : panels_) {
        // A panel the file does not name (a project saved before the panel existed, or a new
        // project) takes its defaults, never the state of the project open before.
        panel->applyFileSettings(
            project.panels.value(panel->name().toStdString(), nlohmann::json::object()));
    }
    // The panels taking the file's settings write them back (in their own form, defaults
    // filled in): that is not an edit. The opened project is what is on disk.
    adoptPanelSettings();
    // What the panels show is of the project before: dropped from every panel (held while a
    // results file is read, so that the quick panels' updates wait for it), before the file's
    // sections are restored over it, section by section.
    for (ui::AnalysisPanel* panel : panels_) {
        panel->holdUpdates(hold);
        panel->projectReplaced();
    }
}

void MainWindow::adoptPanelSettings() {
    // The panels' settings as the project's starting point: storing them again (Run stores the
    // scenario) or undoing back to it is no change, and leaves no "*".
    for (ui::AnalysisPanel* panel : panels_)
        document_->setPanelSettings(panel->name().toStdString(), panel->settings());
    document_->markUnmodified();
}

bool MainWindow::save() {
    return document_->filePath().isEmpty() ? saveAs() : saveTo(document_->filePath());
}

bool MainWindow::saveTo(const QString& path) {
    for (ui::AnalysisPanel* panel : panels_)
        document_->setPanelSettings(panel->name().toStdString(), panel->settings());
    QString error;
    if (!document_->save(path, &error)) {
        QMessageBox::warning(this, "Save failed", error);  // the document stays modified
        return false;
    }
    QFile::remove(autosavePath());
    addRecent(document_->filePath());
    // The results on screen beside the project (core/project/results.h), so that reopening it
    // shows them; a failure here loses no input, so it is said and the project stays saved.
    // The panels describe their results here (their JSON: ~9 ms for a 60 s rover run); writing
    // them (text and disk: ~30 ms more, docs/performance.md) runs off the GUI thread. A save
    // still writing when the next one starts, a project opens or the studio quits is waited for.
    finishWritingResults();
    project::SavedResults results;
    for (ui::AnalysisPanel* panel : panels_) results.panels.merge(panel->savedResults());
    const QString saved = document_->filePath();
    statusBar()->showMessage("Saved " + saved + "; writing its results…");
    writing_results_ = new QFutureWatcher<std::optional<std::string>>(this);
    writing_results_path_ = saved;
    connect(writing_results_, &QFutureWatcherBase::finished, this, &MainWindow::resultsWritten);
    writing_results_->setFuture(QtConcurrent::run(
        [file = project::resultsPathFor(path.toStdString()), results = std::move(results)] {
            return project::saveResults(file, results);
        }));
    return true;
}

void MainWindow::finishWritingResults() {
    if (!writing_results_) return;
    writing_results_->waitForFinished();
    resultsWritten();  // its report now, not when the event loop delivers the watcher's signal
}

void MainWindow::resultsWritten() {
    if (!writing_results_) return;  // reported already (finishWritingResults)
    const std::optional<std::string> failed = writing_results_->result();
    writing_results_->deleteLater();
    writing_results_ = nullptr;
    const QString saved = writing_results_path_;
    const QString error = failed ? QString::fromStdString(*failed) : QString();
    statusBar()->showMessage(
        error.isEmpty() ? "Saved " + saved : "Saved " + saved + "; its results were not: " + error,
        error.isEmpty() ? 4000 : 8000);
    emit resultsSaved(saved, error);
}

MainWindow::~MainWindow() {
    // A sidecar being written is finished, never cut off half-way (it is atomic either way).
    if (writing_results_) writing_results_->waitForFinished();
}

bool MainWindow::saveAs() {
    QString path = QFileDialog::getSaveFileName(this, "Save project",
                                                document_->filePath().isEmpty()
                                                    ? ui::suggestedPath({}, {}, ".terra")
                                                    : document_->filePath(),
                                                "TerraStudio project (*.terra)");
    if (path.isEmpty()) return false;
    if (!path.endsWith(".terra")) path += ".terra";
    if (!ui::offerMissingFolder(this, path)) return false;  // declined: nothing saved
    return saveTo(path);
}

bool MainWindow::maybeSave() {
    if (!document_->isModified()) return true;
    const auto answer =
        QMessageBox::warning(this, "Unsaved changes", "The project has unsaved changes. Save them?",
                             QMessageBox::Save | QMessageBox::Discard | QMessageBox::Cancel);
    if (answer == QMessageBox::Save) return save();
    return answer == QMessageBox::Discard;
}

void MainWindow::closeEvent(QCloseEvent* event) {
    if (!maybeSave()) {
        event->ignore();
        return;
    }
    finishWritingResults();
    QFile::remove(autosavePath());
    saveWindowState();
    event->accept();
}

void MainWindow::updateTitle() {
    const QString name = document_->filePath().isEmpty()
                             ? "untitled.terra"
                             : QFileInfo(document_->filePath()).fileName();
    setWindowTitle(name + "[*] — TerraStudio");
    setWindowModified(document_->isModified());
}

QString MainWindow::autosavePath() {
    const QString dir = QStandardPaths::writableLocation(QStandardPaths::AppDataLocation);
    QDir().mkpath(dir);
    return dir + "/recovery.terra.autosave";
}

void MainWindow::autosave() {
    if (!document_->isModified()) return;
    for (ui::AnalysisPanel* panel : panels_)
        document_->setPanelSettings(panel->name().toStdString(), panel->settings());
    QString error;
    if (!document_->save(autosavePath(), &error))
        statusBar()->showMessage("Autosave failed: " + error, 5000);
}

void MainWindow::offerRecovery() {
    const QString path = autosavePath();
    if (!QFileInfo::exists(path)) return;
    const auto answer = QMessageBox::question(
        this, "Recover project",
        "TerraStudio did not close cleanly. Recover the unsaved project from the autosave?");
    if (answer == QMessageBox::Yes) {
        auto project = ui::ProjectDocument::load(path, &locations_);
        if (project) {
            document_->reset(*project);
            document_->undoStack()->resetClean();  // recovered, not yet saved anywhere
        }
    }
    QFile::remove(path);
}

}  // namespace terra::app
