#pragma once
/// @file main_window.h
/// The studio's main window: wiring only. Project tree (left), analysis panels (centre), property
/// editors (right), menus, toolbar, status bar, recent files, layout in QSettings, autosave and
/// the ask-before-losing-changes rule. Everything it shows lives in widgets/.

#include <QMainWindow>
#include <vector>

#include "core/io/parameters_json.h"

class QStackedWidget;
class QTabWidget;
class QMenu;
class QTimer;

namespace terra::ui {
class AnalysisPanel;
class HelpDialog;
class ProjectDocument;
}  // namespace terra::ui

namespace terra::app {

class MainWindow : public QMainWindow {
    Q_OBJECT
public:
    explicit MainWindow(const io::PresetLocations& locations, QWidget* parent = nullptr);

    ui::ProjectDocument* document() const { return document_; }
    /// Opens a project file; false (and a message box unless `quiet`) when it cannot be read.
    bool openProject(const QString& path, bool quiet = false);
    /// Shows the panel with this name ("forces", "stresses", "compaction", "sensitivity",
    /// "identification", "global-sensitivity", "rover").
    void showPanel(const QString& name);
    /// Where the crash-recovery copy of the open project is kept.
    static QString autosavePath();
    /// Waits for each analysis panel's result, grabs the window showing it into
    /// DIR/studio-<panel>.png and returns an exit code (the GUI smoke test and docs/images).
    int takeScreenshots(const QString& dir);
    /// The in-app help (Help ▸ User guide, F1; Keyboard shortcuts, Ctrl+/).
    void showHelp(bool shortcuts);
    ui::HelpDialog* helpDialog() const { return help_; }
    /// docs/user-guide.md where the program is installed (or built).
    static QString userGuidePath();

protected:
    void closeEvent(QCloseEvent* event) override;

private:
    void createMenus();  // main_window_menus.cpp, with the exports, recent files and help
    void fitToScreen();
    bool maybeSave();
    bool save();
    bool saveTo(const QString& path);
    bool saveAs();
    void newProject();
    /// The identification panel's data (a CSV chosen, listed or dropped), the panel on screen.
    void useData(const QString& path);
    void adoptPanelSettings();
    void exportCurrentPlot();
    void exportCurrentData();
    void addRecent(const QString& path);
    void rebuildRecentMenu();
    void updateTitle();
    void autosave();
    void offerRecovery();
    ui::AnalysisPanel* currentPanel() const;

    io::PresetLocations locations_;
    ui::ProjectDocument* document_;
    QTabWidget* tabs_;
    QStackedWidget* editors_;
    std::vector<ui::AnalysisPanel*> panels_;
    QMenu* recent_menu_ = nullptr;
    QTimer* autosave_timer_;
    ui::HelpDialog* help_ = nullptr;
};

}  // namespace terra::app
