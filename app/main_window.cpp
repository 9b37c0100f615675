#include "app/main_window.h"

#include <qcustomplot.h>

#include <QApplication>
#include <QCloseEvent>
#include <QDir>
#include <QDockWidget>
#include <QEventLoop>
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
#include <cstdio>

#include "widgets/document/project_document.h"
#include "widgets/document/suggested_paths.h"
#include "widgets/editors/project_tree.h"
#include "widgets/editors/property_editors.h"
#include "widgets/panels/compaction_panel.h"
#include "widgets/panels/experiment_actions.h"
#include "widgets/panels/file_drops.h"
#include "widgets/panels/forces_panel.h"
#include "widgets/panels/global_sensitivity_panel.h"
#include "widgets/panels/identification_panel.h"
#include "widgets/panels/rover_panel.h"
#include "widgets/panels/sensitivity_panel.h"
#include "widgets/panels/stress_panel.h"

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

    tabs_ = new QTabWidget(this);
    tabs_->setDocumentMode(true);
    auto* identification = new ui::IdentificationPanel(document_, tabs_);
    auto* global = new ui::GlobalSensitivityPanel(document_, tabs_);
    auto* forces = new ui::ForcesPanel(document_, tabs_);
    forces->setPresetLocations(locations_);  // "Compare with…" lists the soil presets
    panels_ = {forces,
               new ui::StressPanel(document_, tabs_),
               new ui::CompactionPanel(document_, locations_, tabs_),
               new ui::SensitivityPanel(document_, tabs_),
               identification,
               new ui::RoverPanel(document_, locations_, tabs_),
               global};
    const QStringList titles{"Forces vs slip", "Stresses",       "Compaction",        "Sensitivity",
                             "Identification", "Rover scenario", "Global sensitivity"};
    // The identified soil's covariance feeds the global study's "identified soil" source.
    connect(identification, &ui::AnalysisPanel::resultShown, global, [identification, global] {
        const analysis::IdentificationResult& r = identification->result();
        if (r.report && r.report->usable())
            global->setIdentification(r.identified, r.report->uncertainty);
    });
    for (std::size_t i = 0; i < panels_.size(); ++i) {
        ui::AnalysisPanel* panel = panels_[i];
        // A panel whose controls need more room than a small screen leaves scrolls instead of
        // widening the window past the screen (the window was ≥ 1497 px wide).
        tabs_->addTab(scrollable(panel), titles[static_cast<int>(i)]);
        panel->installPlotMenus();
        connect(panel, &ui::AnalysisPanel::exportRequested, this, &MainWindow::exportCurrentPlot);
        // The status bar speaks of the tab on screen only ("Sensitivity updated…" stayed there
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
    connect(tabs_, &QTabWidget::currentChanged, statusBar(), &QStatusBar::clearMessage);
    setCentralWidget(tabs_);

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
                         [this](const QString& text) { statusBar()->showMessage(text, 8000); }});
    connect(data_list, &QListWidget::itemDoubleClicked, this,
            [this](QListWidgetItem* item) { useData(item->text()); });

    // Both docks on the left, the tree above the properties: the plots get the width (1024 px
    // screens leave them ~680 px). The properties scroll when the screen is short.
    auto* project_dock = dock(this, "Project", "project_dock", tree);
    auto* properties_dock = dock(this, "Properties", "properties_dock", scrollable(editors_));
    addDockWidget(Qt::LeftDockWidgetArea, project_dock);
    addDockWidget(Qt::LeftDockWidgetArea, properties_dock);
    splitDockWidget(project_dock, properties_dock, Qt::Vertical);
    resizeDocks({project_dock}, {330}, Qt::Horizontal);
    resizeDocks({project_dock, properties_dock}, {170, 500}, Qt::Vertical);
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
    const QSettings settings;
    restoreGeometry(settings.value("window/geometry").toByteArray());
    restoreState(settings.value("window/state").toByteArray());
    fitToScreen();
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
        if (panels_[i]->name() == name) tabs_->setCurrentIndex(static_cast<int>(i));
    }
}

ui::AnalysisPanel* MainWindow::currentPanel() const {
    const int i = tabs_->currentIndex();
    return i < 0 ? nullptr : panels_[static_cast<std::size_t>(i)];
}

bool MainWindow::openProject(const QString& path, bool quiet) {
    auto project = ui::ProjectDocument::load(path, &locations_);
    if (!project) {
        if (!quiet)
            QMessageBox::warning(this, "Cannot open project",
                                 QString::fromStdString(project.message()));
        return false;
    }
    document_->reset(*project, QFileInfo(path).absoluteFilePath());
    for (ui::AnalysisPanel* panel : panels_) {
        const std::string name = panel->name().toStdString();
        if (project->panels.contains(name)) panel->applySettings(project->panels[name]);
    }
    // The panels taking the file's settings write them back (in their own form, defaults
    // filled in): that is not an edit. The opened project is what is on disk.
    adoptPanelSettings();
    addRecent(QFileInfo(path).absoluteFilePath());
    statusBar()->showMessage("Opened " + path, 4000);
    return true;
}

void MainWindow::newProject() {
    if (!maybeSave()) return;
    document_->reset(ui::ProjectDocument::defaultProject(locations_));
    adoptPanelSettings();
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
    statusBar()->showMessage("Saved " + document_->filePath(), 4000);
    return true;
}

bool MainWindow::saveAs() {
    QString path = QFileDialog::getSaveFileName(this, "Save project",
                                                document_->filePath().isEmpty()
                                                    ? ui::suggestedPath({}, {}, ".terra")
                                                    : document_->filePath(),
                                                "TerraStudio project (*.terra)");
    if (path.isEmpty()) return false;
    if (!path.endsWith(".terra")) path += ".terra";
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
    QFile::remove(autosavePath());
    QSettings settings;
    settings.setValue("window/geometry", saveGeometry());
    settings.setValue("window/state", saveState());
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

int MainWindow::takeScreenshots(const QString& dir) {
    QDir().mkpath(dir);
    QFile::remove(autosavePath());
    int failures = 0;
    for (int i = 0; i < tabs_->count(); ++i) {
        tabs_->setCurrentIndex(i);
        ui::AnalysisPanel* panel = panels_[static_cast<std::size_t>(i)];
        if (panel) {
            QEventLoop loop;
            QTimer::singleShot(60000, &loop, &QEventLoop::quit);
            connect(panel, &ui::AnalysisPanel::resultShown, &loop, &QEventLoop::quit);
            connect(panel, &ui::AnalysisPanel::failed, &loop, &QEventLoop::quit);
            const bool on_request = panel->name() == "identification" || panel->name() == "rover";
            if (on_request || panel->isBusy() || panel->lastLatencyMs() == 0.0) {
                if (on_request) panel->recompute();
                loop.exec();
            }
        }
        QEventLoop settle;
        QTimer::singleShot(300, &settle, &QEventLoop::quit);
        settle.exec();
        const QString name = panel ? panel->name() : QString("panel%1").arg(i);
        const QString path = dir + "/studio-" + name + ".png";
        if (!grab().save(path)) ++failures;
        std::printf("wrote %s\n", qPrintable(path));
    }
    // "Compare with…" (docs/images/studio-compare.png): the soil pinned, φ edited to 35°, then
    // the edit undone and the comparison cleared, so the project ends as it began.
    if (auto* forces = dynamic_cast<ui::ForcesPanel*>(panels_.front())) {
        tabs_->setCurrentIndex(0);
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
    document_->undoStack()->setClean();
    return failures == 0 ? 0 : 1;
}

}  // namespace terra::app
