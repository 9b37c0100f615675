#pragma once
/// @file main_window.h
/// The studio's main window: wiring only. Project tree (left), analysis panels (centre), property
/// editors (right), menus, toolbar, status bar, recent files, layout in QSettings, autosave and
/// the ask-before-losing-changes rule. Everything it shows lives in widgets/.

#include <QFutureWatcher>
#include <QMainWindow>
#include <optional>
#include <string>
#include <vector>

#include "core/io/parameters_json.h"
#include "core/project/project.h"
#include "core/project/results.h"

class QCustomPlot;
class QDockWidget;
class QStackedWidget;
class QMenu;
class QTimer;

namespace terra::ui {
class AnalysisPanel;
class GlobalSensitivityPanel;
class IdentificationPanel;
class HelpDialog;
class PlotDocking;
class ProjectDocument;
}  // namespace terra::ui

namespace terra::app {

class MainWindow : public QMainWindow {
    Q_OBJECT
public:
    explicit MainWindow(const io::PresetLocations& locations, QWidget* parent = nullptr);

    ui::ProjectDocument* document() const { return document_; }
    /// Opens a project file; false (and a message box unless `quiet`) when it cannot be read.
    /// Its saved results (NAME.terra.results) are read off the GUI thread afterwards and shown
    /// where their inputs are unchanged (savedResultsShown() once done); meanwhile no panel
    /// starts a computation by itself.
    bool openProject(const QString& path, bool quiet = false);
    /// Shows the panel with this name ("forces", "stresses", "compaction", "sensitivity",
    /// "identification", "global-sensitivity", "rover").
    void showPanel(const QString& name);
    /// The name of the panel the user works in (the one shown or clicked last), "" for none.
    QString currentPanelName() const;
    /// The dock holding the panel with this name, nullptr for none.
    QDockWidget* panelDock(const QString& name) const;
    /// The main window (the central widget) whose docks are the panels.
    QMainWindow* panelArea() const { return panel_area_; }
    /// The plots shown in docks of their own (a plot's right-click "Show in its own dock").
    ui::PlotDocking* plotDocking() const { return plot_docking_; }

    /// The arrangements of View ▸ Layout. Each panel is a dock (tear it off, drag it beside
    /// another, tab it), and so is each plot shown in a dock of its own; these put them back in
    /// order. None makes a panel on screen scroll sideways: a panel gets at least the width it
    /// needs (ui::dockMinimumWidth), and panels that cannot all be beside each other are tabbed.
    enum class Layout {
        kDefault,     ///< project and properties left, the panels tabbed: 1366×768 and up;
                      ///< every plot back in its panel
        kCompact,     ///< a narrower column, a short tree: 1024×700; every plot back in its panel
        kSideBySide,  ///< the current panel and, beside it, its plots in docks of their own or
                      ///< else the next panel that fits beside it (under it when none fits
                      ///< beside it: 1024 px screens)
        kTiled,       ///< the panels in two rows, as many beside each other as fit the width
                      ///< (the others tabbed with them); plots in docks tabbed with their panel
    };
    void applyLayout(Layout layout);
    /// The version of the saved window state (QSettings "window/state" and "window/panels", the
    /// panels' arrangement): a state of another
    /// version (older studios had fixed tabs) is ignored and the layout for the screen applied.
    /// The plots in docks of their own are saved as "window/plots" (their dock names) and torn
    /// off again before the panel area's state is restored; a name of no plot is ignored.
    static constexpr int kLayoutVersion = 2;

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

signals:
    /// The opened project's saved results were read and those that hold are shown (the status
    /// bar says which, and which not and why).
    void savedResultsShown();
    /// A save's results sidecar (NAME.terra.results) was written off the GUI thread: `error` is
    /// empty, or says why it was not (the project itself was saved).
    void resultsSaved(const QString& path, const QString& error);

public:
    /// Whether the opened project's saved results are still being read.
    bool readingSavedResults() const { return reading_results_; }
    /// Whether a save's results are still being written.
    bool writingResults() const { return writing_results_ != nullptr; }
    /// Waits for a save's results still being written (opening a project, quitting and a next
    /// save do; a test may). Returns at once when none is.
    void finishWritingResults();

    ~MainWindow() override;

protected:
    void closeEvent(QCloseEvent* event) override;

private:
    void createMenus();  // main_window_menus.cpp, with the exports, recent files and help
    void fitToScreen();
    bool maybeSave();
    bool save();
    bool saveTo(const QString& path);
    /// The results write of the last save is done: the status bar says so, resultsSaved().
    void resultsWritten();
    bool saveAs();
    void newProject();
    /// The identification panel's data (a CSV chosen, listed or dropped), the panel on screen.
    void useData(const QString& path);
    void adoptPanelSettings();
    /// The document becomes `project` (at `file_path`, empty for a new one): the panels drop what
    /// runs and what they show, take its settings, and wait while `hold` (its results are read).
    void replaceProject(const project::Project& project, const QString& file_path, bool hold);
    void showSavedResults(const QString& path, const Result<project::SavedResults>& results);
    /// The identification's fit as the global study's "identified soil" source.
    void shareIdentification();
    void exportCurrentPlot();
    /// The export dialog for `plot` of `panel` (its right-click menu's Export plot…).
    void exportPlot(ui::AnalysisPanel& panel, QCustomPlot& plot);
    void exportCurrentData();
    void addRecent(const QString& path);
    void rebuildRecentMenu();
    void updateTitle();
    void autosave();
    void offerRecovery();
    ui::AnalysisPanel* currentPanel() const { return current_; }
    void setCurrentPanel(ui::AnalysisPanel* panel);
    /// The layout that fits the window's screen: compact below 1366×768.
    Layout layoutForScreen() const;
    /// The arrangement saved by saveWindowState(), else the layout for the screen
    /// (main_window_layout.cpp).
    void restoreWindowState();
    void saveWindowState() const;
    /// Side by side and tiled: main_window_layout.cpp.
    void arrangeSideBySide(std::size_t current_index, int column);
    void arrangeTiles(int column);
    /// The width [px] the panel area has beside a left column `column` px wide (0: hidden).
    int panelAreaWidth(int column) const;
    /// Hides the Project and Properties panes (side by side and tiled, when two panels do not
    /// fit beside them) and says so in the status bar.
    void giveThePanelsTheWidth();

    io::PresetLocations locations_;
    ui::ProjectDocument* document_;
    QStackedWidget* editors_;
    std::vector<ui::AnalysisPanel*> panels_;
    std::vector<QDockWidget*> panel_docks_;  // panel_docks_[i] holds panels_[i]
    QDockWidget* project_dock_ = nullptr;
    QDockWidget* properties_dock_ = nullptr;
    ui::AnalysisPanel* current_ = nullptr;
    /// The panels' docks live in a main window of their own, the central widget: the window's
    /// width changes go to the panels, never to the project and properties column (without a
    /// central widget QMainWindow split a 1024 px window half and half).
    QMainWindow* panel_area_ = nullptr;
    ui::PlotDocking* plot_docking_ = nullptr;
    int last_window_width_ = 0;  // the project and properties docks' [px]; 0: not yet laid out
    QMenu* recent_menu_ = nullptr;
    ui::IdentificationPanel* identification_ = nullptr;
    ui::GlobalSensitivityPanel* global_ = nullptr;
    int opening_ = 0;  // counts openings: results read for an earlier one are dropped
    // The layout applyLayout was last asked for: what its deferred re-apply applies.
    Layout chosen_layout_ = Layout::kDefault;
    bool reading_results_ = false;  // the opened project's saved results are being read
    /// The results sidecar being written off the GUI thread by the last save (nullptr: none).
    QFutureWatcher<std::optional<std::string>>* writing_results_ = nullptr;
    QString writing_results_path_;  // the project whose results it writes
    QTimer* autosave_timer_;
    ui::HelpDialog* help_ = nullptr;
};

}  // namespace terra::app
