// The main window's menus, toolbar, exports and help (main_window.h); split from
// main_window.cpp to keep each file small. Every shortcut of docs/user-guide.md is set explicitly:
// the platform's standard keys are empty on some desktops (Save As, Ctrl+Y under a plain X11
// window manager), and the guide promises them everywhere.
#include <qcustomplot.h>

#include <QApplication>
#include <QDir>
#include <QDockWidget>
#include <QFileDialog>
#include <QFileInfo>
#include <QMenuBar>
#include <QMessageBox>
#include <QSettings>
#include <QStatusBar>
#include <QTabWidget>
#include <QToolBar>
#include <QUndoStack>

#include "app/cli/cli_support.h"
#include "app/main_window.h"
#include "core/common/build_info.h"
#include "widgets/document/project_document.h"
#include "widgets/document/suggested_paths.h"
#include "widgets/editors/field_shortcuts.h"
#include "widgets/help/help_dialog.h"
#include "widgets/panels/analysis_panel.h"
#include "widgets/panels/experiment_actions.h"
#include "widgets/panels/plot_docking.h"
#include "widgets/plots/export_dialog.h"

namespace terra::app {
namespace {

constexpr int kMaxRecent = 8;

QKeySequence keys(QKeyCombination combination) { return QKeySequence(combination); }

}  // namespace

void MainWindow::createMenus() {
    QMenu* file = menuBar()->addMenu("&File");
    QToolBar* bar = addToolBar("Main");
    bar->setObjectName("main_toolbar");
    auto add = [&](QMenu* menu, const QString& text, const QList<QKeySequence>& shortcuts,
                   const QString& name, auto slot, bool toolbar = false) {
        QAction* action = menu->addAction(text, this, slot);
        action->setShortcuts(shortcuts);
        // Also from a panel or plot torn off into a window of its own (a floating dock); a modal
        // dialog still blocks them (Qt's application shortcuts respect modality).
        action->setShortcutContext(Qt::ApplicationShortcut);
        action->setObjectName(name);
        if (toolbar) bar->addAction(action);
        return action;
    };
    add(
        file, "&New", {keys(Qt::CTRL | Qt::Key_N)}, "action.new", [this] { newProject(); }, true);
    add(
        file, "&Open…", {keys(Qt::CTRL | Qt::Key_O)}, "action.open",
        [this] {
            if (!maybeSave()) return;
            const QString path = QFileDialog::getOpenFileName(
                this, "Open project", ui::startFolder(document_->filePath()),
                "TerraStudio project (*.terra)");
            if (!path.isEmpty()) openProject(path);
        },
        true);
    recent_menu_ = file->addMenu("Open &Recent");
    rebuildRecentMenu();
    add(
        file, "&Save", {keys(Qt::CTRL | Qt::Key_S)}, "action.save", [this] { save(); }, true);
    add(file, "Save &As…", {keys(Qt::CTRL | Qt::SHIFT | Qt::Key_S)}, "action.save_as",
        [this] { saveAs(); });
    file->addSeparator();
    add(file, "Load E&xperiment…", {keys(Qt::CTRL | Qt::Key_L)}, "action.load_experiment", [this] {
        if (ui::promptLoadExperiment(this, *document_, locations_)) showPanel("forces");
    });
    file->addSeparator();
    add(
        file, "&Export Plot…", {keys(Qt::CTRL | Qt::Key_E)}, "action.export_plot",
        [this] { exportCurrentPlot(); }, true);
    add(file, "Export &Data (CSV)…", {keys(Qt::CTRL | Qt::SHIFT | Qt::Key_E)}, "action.export_data",
        [this] { exportCurrentData(); });
    file->addSeparator();
    add(file, "&Quit", {keys(Qt::CTRL | Qt::Key_Q)}, "action.quit", [this] { close(); });

    QMenu* edit = menuBar()->addMenu("&Edit");
    QAction* undo = document_->undoStack()->createUndoAction(this, "&Undo");
    undo->setShortcuts({keys(Qt::CTRL | Qt::Key_Z)});
    undo->setObjectName("action.undo");
    QAction* redo = document_->undoStack()->createRedoAction(this, "&Redo");
    redo->setShortcuts({keys(Qt::CTRL | Qt::SHIFT | Qt::Key_Z), keys(Qt::CTRL | Qt::Key_Y)});
    redo->setObjectName("action.redo");
    for (QAction* action : {undo, redo}) action->setShortcutContext(Qt::ApplicationShortcut);
    edit->addActions({undo, redo});
    bar->addSeparator();
    // The toolbar's own Undo and Redo: short names that keep the toolbar's width, the step they
    // would undo or redo in the tooltip (the Edit menu's entries name it, as Qt's do).
    QUndoStack* stack = document_->undoStack();
    auto* bar_undo = bar->addAction("Undo", stack, &QUndoStack::undo);
    bar_undo->setObjectName("action.toolbar_undo");
    auto* bar_redo = bar->addAction("Redo", stack, &QUndoStack::redo);
    bar_redo->setObjectName("action.toolbar_redo");
    const auto sync = [stack, bar_undo, bar_redo] {
        bar_undo->setEnabled(stack->canUndo());
        bar_redo->setEnabled(stack->canRedo());
        bar_undo->setToolTip(stack->canUndo() ? "Undo " + stack->undoText() + " (Ctrl+Z)"
                                              : "Nothing to undo");
        bar_redo->setToolTip(stack->canRedo() ? "Redo " + stack->redoText() + " (Ctrl+Shift+Z)"
                                              : "Nothing to redo");
    };
    connect(stack, &QUndoStack::indexChanged, this, sync);  // push, undo, redo, clear
    sync();

    // The tab's Run, Fit or Compute (the live panels recompute): one key for every panel.
    QMenu* run = menuBar()->addMenu("&Run");
    add(run, "&Run / Fit / Compute the tab", {keys(Qt::CTRL | Qt::Key_R), keys(Qt::Key_F5)},
        "action.run", [this] {
            if (ui::AnalysisPanel* panel = currentPanel()) panel->requestRun();
        });

    QMenu* view = menuBar()->addMenu("&View");
    // Ctrl+1 … Ctrl+7 bring a panel to front (shown again if its dock was closed).
    for (std::size_t i = 0; i < panels_.size() && i < 9; ++i) {
        const QString name = panels_[i]->name();
        add(view, panel_docks_[i]->windowTitle(),
            {QKeySequence(Qt::CTRL | (Qt::Key_1 + static_cast<int>(i)))},
            QString("action.panel%1").arg(i + 1), [this, name] { showPanel(name); });
    }
    view->addSeparator();
    QMenu* layout = view->addMenu("&Layout");
    add(layout, "&Default (1366×768 and up)", {keys(Qt::CTRL | Qt::SHIFT | Qt::Key_0)},
        "action.layout_default", [this] { applyLayout(Layout::kDefault); });
    add(layout, "&Compact (1024×700)", {}, "action.layout_compact",
        [this] { applyLayout(Layout::kCompact); });
    add(layout, "&Side by side", {}, "action.layout_side_by_side",
        [this] { applyLayout(Layout::kSideBySide); });
    add(layout, "&Tile all panels", {}, "action.layout_tiled",
        [this] { applyLayout(Layout::kTiled); });
    // The current panel's plots, each in a dock of its own or back in its panel (as the plot's
    // right-click menu does), and every plot back at once.
    QMenu* plot_docks = view->addMenu("P&lots in their own docks");
    plot_docks->setObjectName("menu.plot_docks");
    connect(plot_docks, &QMenu::aboutToShow, this, [this, plot_docks] {
        plot_docks->clear();
        if (ui::AnalysisPanel* panel = currentPanel()) {
            for (const auto& [name, plot] : panel->plots()) {
                QCustomPlot* p = plot;
                QAction* a = plot_docks->addAction(name, this, [this, p](bool own) {
                    if (own)
                        plot_docking_->tearOff(p);
                    else
                        plot_docking_->putBack(p);
                });
                a->setCheckable(true);
                a->setChecked(plot_docking_->dockOf(p) != nullptr);
            }
        }
        plot_docks->addSeparator();
        QAction* back = plot_docks->addAction("Put every plot back", plot_docking_,
                                              &ui::PlotDocking::putAllBack);
        back->setObjectName("action.plots_put_back");
        back->setEnabled(!plot_docking_->docks().empty());
    });
    QMenu* shown = view->addMenu("&Panels and panes");
    shown->addAction(project_dock_->toggleViewAction());
    shown->addAction(properties_dock_->toggleViewAction());
    shown->addSeparator();
    for (QDockWidget* d : panel_docks_) shown->addAction(d->toggleViewAction());

    ui::passWindowShortcutsThroughFields(this);  // Ctrl+E from a field exports, as the guide says

    QMenu* help = menuBar()->addMenu("&Help");
    add(help, "&User guide", {keys(Qt::Key_F1)}, "action.help", [this] { showHelp(false); });
    add(help, "&Keyboard shortcuts", {keys(Qt::CTRL | Qt::Key_Slash)}, "action.shortcuts",
        [this] { showHelp(true); });
    help->addAction("&About TerraStudio", this, [this] {
        QMessageBox::about(this, "About TerraStudio",
                           QString("<b>TerraStudio %1</b><br>Wheel–soil interaction for "
                                   "agricultural robots: the model of thesis chapter 2 with the "
                                   "corrections of docs/model.md.<br>Help ▸ User guide (F1) "
                                   "explains the studio.")
                               .arg(build_info::kVersion));
    });
}

QString MainWindow::userGuidePath() {
    // The docs are installed beside the data (docs/install.md); the build tree mirrors the layout.
    return QString::fromStdString(
        (executableDirectory() / build_info::kDocDirFromExecutable / "user-guide.md")
            .lexically_normal()
            .string());
}

void MainWindow::showHelp(bool shortcuts) {
    if (!help_) {
        help_ = new ui::HelpDialog(userGuidePath(), findChildren<QAction*>(), this);
        help_->setObjectName("help_dialog");
    }
    shortcuts ? help_->showShortcuts() : help_->showGuide();
    help_->show();
    help_->raise();
    help_->activateWindow();
}

namespace {

/// "rover-path", "forces-Fx_N-vs-slip": the tab and the plot on screen, for a file name.
QString plotName(const ui::AnalysisPanel& panel, const QCustomPlot* shown) {
    for (const auto& [name, plot] : panel.plots()) {
        if (plot != shown) continue;
        return name.startsWith(panel.name()) ? name : panel.name() + "-" + name;
    }
    return panel.name();
}

QString plotName(const ui::AnalysisPanel& panel) { return plotName(panel, panel.currentPlot()); }

}  // namespace

void MainWindow::exportCurrentPlot() {
    ui::AnalysisPanel* panel = currentPanel();
    if (!panel) return;
    exportPlot(*panel, *panel->currentPlot());
}

void MainWindow::exportPlot(ui::AnalysisPanel& panel, QCustomPlot& plot) {
    const QString suggested =
        ui::suggestedPath(document_->filePath(), plotName(panel, &plot), ".png");
    QStringList written;
    if (ui::ExportDialog::exportWithDialog(this, plot, panel.currentTable(), suggested, &written)) {
        ui::rememberFolder(written.front());
        statusBar()->showMessage("Exported " + written.join(" and "), 8000);
    }
}

void MainWindow::exportCurrentData() {
    ui::AnalysisPanel* panel = currentPanel();
    if (!panel) return;
    const QString path = QFileDialog::getSaveFileName(
        this, "Export data", ui::suggestedPath(document_->filePath(), plotName(*panel), ".csv"),
        "CSV (*.csv)");
    if (path.isEmpty()) return;
    QString error;
    if (!ui::offerMissingFolder(this, path, &error)) {
        statusBar()->showMessage(
            "Not exported: " + (error.isEmpty() ? "the folder " + QFileInfo(path).absolutePath() +
                                                      " does not exist"
                                                : error),
            8000);
        return;
    }
    ui::rememberFolder(path);
    if (!ui::exportTable(panel->currentTable(), path, &error)) {
        QMessageBox::warning(this, "Export failed", error);
        return;
    }
    statusBar()->showMessage("Exported " + path, 8000);
}

void MainWindow::addRecent(const QString& path) {
    ui::rememberFolder(path);  // the next Open, Save As or Export starts there
    QSettings settings;
    QStringList recent = settings.value("recentFiles").toStringList();
    recent.removeAll(path);
    recent.prepend(path);
    while (recent.size() > kMaxRecent) recent.removeLast();
    settings.setValue("recentFiles", recent);
    rebuildRecentMenu();
}

void MainWindow::rebuildRecentMenu() {
    recent_menu_->clear();
    const QStringList recent = QSettings().value("recentFiles").toStringList();
    for (const QString& path : recent) {
        recent_menu_
            ->addAction(QFileInfo(path).fileName(), this,
                        [this, path] {
                            if (maybeSave()) openProject(path);
                        })
            ->setToolTip(path);
    }
    recent_menu_->setEnabled(!recent.isEmpty());
}

}  // namespace terra::app
