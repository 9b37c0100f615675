#pragma once
/// @file analysis_panel.h
/// Base of the studio's analysis panels: follows the project document, recomputes off the GUI
/// thread (QtConcurrent) when the project or the panel's settings change, and always ends on the
/// result of the newest state (by revision). An edit asks the running computation to cancel and
/// drops its result, unless nothing new has been drawn for kMaxFrameGapMs: then it runs to the end
/// and is shown as an intermediate frame before the newest state is computed, so that a continuous
/// drag keeps the plot moving. A run the user cancels shows what it computed, and every panel says
/// so the same way (completion.h): its progress bar stays where the run stopped ("8 %
/// (cancelled)"), its status line and plot titles carry "CANCELLED (partial)", and so do the
/// studio's status bar (resultMessage()) and the exported figures (their titles). Reports the time
/// from the edit to the repainted plot.

#include <QElapsedTimer>
#include <QPointer>
#include <QWidget>
#include <any>
#include <atomic>
#include <functional>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <vector>

#include "core/common/table.h"
#include "core/project/results.h"
#include "widgets/panels/analysis_runner.h"
#include "widgets/plots/completion.h"

class QCustomPlot;
class QLabel;
class QProgressBar;
class QPushButton;

namespace terra::ui {

class ProjectDocument;
struct PlotMenuHooks;
struct PlotDockHooks;

class AnalysisPanel : public QWidget {
    Q_OBJECT
public:
    AnalysisPanel(ProjectDocument* document, const QString& name, QWidget* parent = nullptr);
    ~AnalysisPanel() override;

    QString name() const { return name_; }
    /// The plots of the panel with a short name each (for export).
    virtual std::vector<std::pair<QString, QCustomPlot*>> plots() const = 0;
    /// The plot the user is looking at, and the data behind it.
    virtual QCustomPlot* currentPlot() const = 0;
    virtual Table currentTable() const = 0;
    /// Panel settings (saved in the project's "panels" object).
    virtual nlohmann::json settings() const { return nlohmann::json::object(); }
    virtual void applySettings(const nlohmann::json&) {}
    /// Remembers the panel's settings as they are now as its defaults (the window calls it once
    /// its panels are built, before any project is opened).
    void rememberDefaultSettings() { default_settings_ = settings(); }
    /// A project file's settings of this panel, whole: the keys the file leaves out (a writer
    /// leaves out a default or an absent value, e.g. no fixed θ_f) take the defaults, never the
    /// values of the project open before.
    void applyFileSettings(const nlohmann::json& file);

    bool isBusy() const { return runner_.isRunning(); }
    double lastLatencyMs() const { return last_latency_ms_; }
    /// GUI-thread time of the last present() (drawing the result) [ms]: the GUI thread's only
    /// work per update, the rest runs on workers.
    double lastPresentMs() const { return last_present_ms_; }
    /// Starts a computation now (the identification panel's "Fit"; also for tests), even one that
    /// does not start by itself (startsByItself()).
    void recompute() {
        requested_ = true;
        scheduleUpdate();
    }
    /// Asks the running computation to stop; it shows what it has (cancelled runs keep results).
    void cancelRunning();
    /// Stops the running computation and never shows its result, even as an intermediate frame
    /// (a project is being opened: the result is of the project before).
    void discardRunning();
    /// What the panel's Run, Fit or Compute button does (the studio's Ctrl+R); a plain recompute
    /// for the panels that follow the project by themselves.
    virtual void requestRun() { recompute(); }
    /// Whether a result is on screen, and how complete it is (a cancelled run's is partial).
    bool hasResult() const { return has_result_; }
    Completion completion() const { return completion_; }
    /// The studio's status-bar line about the result on screen, for the tab titled `tab`:
    /// "Global sensitivity updated in 120 ms", or "Global sensitivity: CANCELLED (partial) after
    /// 2964 ms — what was computed is shown".
    QString resultMessage(const QString& tab) const;
    /// `text` for the panel's status line, led by the mark of a partial result in bold
    /// ("<b>CANCELLED (partial)</b> — 1024 model evaluations"); as is when complete.
    QString markedStatus(const QString& text) const;
    /// Gives every plot of plots() the right-click menu (plot_menu.h): "Export plot…" emits
    /// exportRequested(), "Copy data" copies currentTable(); `extend`, when set, wraps each
    /// plot's hooks and gives its docking ones (the studio's plot docking, plot_docking.h).
    void installPlotMenus(
        const std::function<void(QCustomPlot&, PlotMenuHooks&, PlotDockHooks&)>& extend = nullptr);
    /// A plot of plots() shown outside the panel (torn off into a dock of its own,
    /// plot_docking.h) or back inside it: while such a plot is on screen the panel computes even
    /// when it is hidden itself (behind another panel's tab).
    void setPlotOutside(QCustomPlot* plot, bool outside);
    /// A plot outside the panel was shown: an update that waited for the panel to be shown runs
    /// now. A panel drawing its plots lazily draws this one.
    virtual void plotShownOutside(QCustomPlot* plot);

    /// The results on screen for the project's results file (core/project/results.h), by
    /// section: name() for the panel's main result, "name.part" for another of its results
    /// (the identification's streaming run, the global study's bands), each with the hash of
    /// the inputs that produced it. Empty when there is none or the panel does not save its
    /// results (its computations are quick: it computes them again when shown).
    virtual std::map<std::string, project::SavedResult> savedResults() const { return {}; }
    /// What became of a saved section offered to restoreResult.
    struct Restored {
        enum class Kind {
            kShown,          ///< on screen, nothing computed
            kInputsChanged,  ///< not shown: the panel's inputs differ from those that produced it
            kUnreadable,     ///< not shown: not a result this studio reads (`message` says why)
        };
        Kind kind = Kind::kUnreadable;
        std::string message;
        bool shown() const { return kind == Kind::kShown; }
    };
    /// Shows a saved section (one of savedResults()' names) when the panel's inputs still hash as
    /// those that produced it, without computing; else changes nothing and says why. Saved
    /// results are never shown for other inputs: they are invalidated, not marked stale.
    virtual Restored restoreResult(const std::string& section, const project::SavedResult& saved);
    /// Whether the result on screen is a saved one shown by restoreResult (nothing recomputed
    /// since).
    bool showsSavedResult() const { return !restored_hash_.empty(); }
    /// While held, no computation starts by itself (the project's saved results are being read
    /// off the GUI thread: a panel shown meanwhile must not start what the file may hold); the
    /// updates asked meanwhile run when released, unless a saved result was shown.
    void holdUpdates(bool hold);
    /// Another project was opened (or a new one made) and no saved result of it is shown here:
    /// the result on screen is the project before's, never shown as this one's. It is dropped
    /// (not saved with this project, not offered for export as its own) and the panel computes
    /// again, or says "not computed" when its study does not start by itself. A panel holding
    /// results of its own (a fit, a run, indices) clears them, then calls this.
    virtual void projectReplaced();
    /// The hash of what the panel's next computation would read (resultInputs()).
    std::string inputsHash() const { return project::inputsHash(resultInputs()); }

signals:
    void resultShown(double latency_ms);  ///< a new result is on screen, after the given time [ms]
    void failed(const QString& message);
    void busyChanged(bool busy);
    /// "Export plot…" of the right-click menu of `plot` (one of plots(); on a page showing two
    /// plots it need not be currentPlot()).
    void exportRequested(QCustomPlot* plot);

protected:
    void showEvent(QShowEvent* event) override;

    /// A computation: inputs captured by value on the GUI thread, run on a worker. `cancel` is set
    /// when the result is superseded (it will be dropped) or the user cancels (cancelRunning(): the
    /// partial result is shown); the job should then stop soon and return what it has.
    using Job = std::function<std::any(const std::atomic<bool>& cancel)>;
    virtual Job makeJob() = 0;
    /// Shows a result (GUI thread); replots.
    virtual void present(const std::any& result) = 0;
    /// What the panel's result depends on, hashed to tell whether a saved result still holds: by
    /// default the project's soil, wheel and conditions and the panel's settings.
    virtual nlohmann::json resultInputs() const;
    /// The inputs' hash of the result being presented (in present()), or of the one on screen.
    const std::string& presentedInputsHash() const { return presented_hash_; }
    /// Shows `value` (what makeJob's job returns) as a result saved for inputs hashing `hash`,
    /// partial or not, without computing; the pending automatic update is dropped while the
    /// inputs keep that hash.
    void showSaved(const std::any& value, const std::string& hash, bool partial);
    /// The restoreResult answers a panel gives: shown, inputs changed, unreadable.
    static Restored restoredShown() { return {Restored::Kind::kShown, {}}; }
    static Restored inputsChanged() {
        return {Restored::Kind::kInputsChanged, "its inputs changed since it was computed"};
    }
    static Restored unreadable(const std::string& why) {
        return {Restored::Kind::kUnreadable, why};
    }
    /// The result on screen as the panel's one section (name()) of the results file: the hash
    /// of the inputs that produced it (presentedInputsHash()), partial when it is; nothing when
    /// no result is on screen, or when it is partial and `keep_partial` is false (a quick panel
    /// computes it again rather than reopen on a cancelled run).
    std::map<std::string, project::SavedResult> savedSection(int version, nlohmann::json result,
                                                             std::string summary,
                                                             bool keep_partial) const;
    /// How a panel reads its section back into what its job returns (present()'s value);
    /// throws std::invalid_argument saying what is wrong when the JSON is not such a result.
    using SectionReader =
        std::function<std::any(const nlohmann::json& result, const std::string& where)>;
    /// restoreResult for a panel with one section (savedSection): shown without computing
    /// (showSaved) when `section` is name(), of form `version`, its inputs hash as the panel's do
    /// now and `read` reads it (throwing std::invalid_argument with what is wrong); else
    /// nothing changes and the answer says why.
    Restored restoreSection(const std::string& section, const project::SavedResult& saved,
                            int version, const SectionReader& read);
    /// A core reader's result for a SectionReader: its value, or its message thrown.
    template <typename T>
    static T valueOrThrow(Result<T> read) {
        if (!read) throw std::invalid_argument(read.message());
        return std::move(read).value();
    }
    /// The "Not computed" state of a run too large to start by itself (startsByItself()):
    /// `status` says `text`, `compute` (when given) is shown, and each plot of `cleared` is
    /// emptied under the title "Not computed: press Compute". The compaction and global
    /// sensitivity panels share it.
    static void showNotComputed(QLabel* status, const QString& text,
                                const std::vector<QCustomPlot*>& cleared,
                                QPushButton* compute = nullptr);

    /// Whether an update nobody asked for (the panel's first show, a project edit) may start now,
    /// asked just before it would. A panel whose computation can be heavy says no, and shows why
    /// ("not computed: press Compute"); recompute() starts regardless.
    virtual bool startsByItself() { return true; }

    /// How complete the result being presented is, when the result knows better than the cancel
    /// flag (a run that diverged, or completed before the cancel arrived): call in present(),
    /// before drawing. Before present() it is kCancelled when the run saw its cancel flag.
    void setCompletion(Completion completion) { completion_ = completion; }
    /// The panel's progress bar, kept honest here for every panel: 0 % when a run starts, 100 %
    /// only when the result shown is complete, else where it stopped with the reason
    /// ("8 % (cancelled)").
    void trackProgress(QProgressBar* bar);

    /// Recompute after the current event (coalescing a burst of edits).
    void scheduleUpdate();
    /// Whether project edits recompute automatically (false: only recompute()).
    void setLive(bool live) { live_ = live; }
    /// Enables drag/zoom, a read-out in `readout` of the curve point nearest the mouse with the
    /// axes' units ("Slip ratio s = 0.25, Drawbar pull F_x = 120 N — β = 0°"; plot_readout.h),
    /// cleared when the mouse leaves the plot or the plot is hidden (another tab), and a legend
    /// the user can drag, hide and put back under the axes (plot_legend.h).
    static void makeInteractive(QCustomPlot* plot, QLabel* readout);
    void storeSettings();
    /// The panel's settings with `changes` over them, for applySettings: an object of some keys
    /// changes only those (a .terra file's are whole; core/project/panels.h checks them).
    nlohmann::json withChanges(const nlohmann::json& changes) const;

    ProjectDocument* document_;

private:
    nlohmann::json default_settings_ = nlohmann::json::object();
    bool from_defaults_ = false;  // applyFileSettings: withChanges starts from the defaults
    /// Longest time the screen may go without a new result while edits keep arriving [ms].
    static constexpr qint64 kMaxFrameGapMs = 150;
    bool start();  // true when a computation runs after it
    void finished(const AnalysisRunner::Outcome& outcome);
    void presentOutcome(const AnalysisRunner::Outcome& outcome);

    QString name_;
    AnalysisRunner runner_;         // the worker plumbing; the revisions are its
    std::string running_hash_;      // inputs hash of the job running or last ended
    int first_shown_revision_ = 0;  // results of older revisions are never shown (discardRunning)
    bool start_queued_ = false;
    bool deferred_ = false;  // an update waits until the panel is shown
    bool live_ = true;
    bool requested_ = false;  // recompute() asked for the next computation
    bool wanted_ = false;     // an update was asked since the last start or discard
    bool held_ = false;       // holdUpdates(true)
    QElapsedTimer since_edit_;
    QElapsedTimer since_shown_;  // since the last present()
    double last_latency_ms_ = 0.0;
    double last_present_ms_ = 0.0;
    bool has_result_ = false;
    Completion completion_ = Completion::kComplete;
    QProgressBar* progress_bar_ = nullptr;
    std::string presented_hash_;
    std::string restored_hash_;               // the saved result's, while it is on screen
    std::vector<QPointer<QWidget>> outside_;  // setPlotOutside
};

}  // namespace terra::ui
