#include "widgets/panels/analysis_panel.h"

#include <qcustomplot.h>

#include <QLabel>
#include <QProgressBar>
#include <QPushButton>
#include <QShowEvent>
#include <QTimer>
#include <algorithm>

#include "core/io/parameters_json.h"
#include "widgets/document/project_document.h"
#include "widgets/plots/figures.h"
#include "widgets/plots/plot_legend.h"
#include "widgets/plots/plot_menu.h"
#include "widgets/plots/plot_readout.h"

namespace terra::ui {

AnalysisPanel::AnalysisPanel(ProjectDocument* document, const QString& name, QWidget* parent)
    : QWidget(parent), document_(document), name_(name) {
    // Each ended job: the newest or a superseded one (finished() tells them apart).
    connect(&runner_, &AnalysisRunner::finished, this, &AnalysisPanel::finished);
    connect(&runner_, &AnalysisRunner::superseded, this, &AnalysisPanel::finished);
    connect(document_, &ProjectDocument::changed, this, [this] {
        if (live_) scheduleUpdate();
    });
}

AnalysisPanel::~AnalysisPanel() = default;  // the runner cancels its job and waits for it

void AnalysisPanel::scheduleUpdate() {
    wanted_ = true;
    runner_.supersede();
    since_edit_.start();
    // The running result is stale now: cancel it, unless the screen has not changed for
    // kMaxFrameGapMs. Then it finishes and is shown as an intermediate frame, so a continuous drag
    // (edits faster than one computation) still moves the plot instead of starving it.
    const bool starving = !since_shown_.isValid() || since_shown_.elapsed() >= kMaxFrameGapMs;
    if (!(starving && runner_.isRunning())) runner_.cancel();
    if (start_queued_) return;
    start_queued_ = true;
    QTimer::singleShot(0, this, [this] {
        start_queued_ = false;
        start();
    });
}

void AnalysisPanel::cancelRunning() { runner_.cancel(); }

void AnalysisPanel::discardRunning() {
    wanted_ = false;  // what ran was the project before's: nothing follows it by itself
    runner_.cancel();
    first_shown_revision_ = runner_.supersede();
}

QString AnalysisPanel::resultMessage(const QString& tab) const {
    if (completion_ == Completion::kComplete)
        return QString("%1 updated in %2 ms").arg(tab).arg(last_latency_ms_, 0, 'f', 0);
    return QString("%1: %2 after %3 ms — what was computed is shown")
        .arg(tab, completionMark(completion_))
        .arg(last_latency_ms_, 0, 'f', 0);
}

QString AnalysisPanel::markedStatus(const QString& text) const {
    const QString mark = completionMark(completion_);
    if (mark.isEmpty()) return text;
    return text.isEmpty() ? "<b>" + mark + "</b>" : "<b>" + mark + "</b> — " + text;
}

void AnalysisPanel::trackProgress(QProgressBar* bar) {
    progress_bar_ = bar;
    bar->setObjectName("panel.progress");
    bar->setRange(0, 100);
    connect(this, &AnalysisPanel::busyChanged, bar, [bar](bool busy) {
        if (!busy) return;
        bar->setValue(0);
        bar->setFormat(progressFormat(Completion::kComplete));
    });
}

void AnalysisPanel::installPlotMenus(
    const std::function<void(QCustomPlot&, PlotMenuHooks&, PlotDockHooks&)>& extend) {
    for (const auto& [name, plot] : plots()) {
        QCustomPlot* shown = plot;
        PlotMenuHooks hooks{[this] { return currentTable(); },
                            [this, shown] { emit exportRequested(shown); }};
        PlotDockHooks dock;
        if (extend) extend(*plot, hooks, dock);
        installPlotMenu(*plot, std::move(hooks), std::move(dock));
    }
}

void AnalysisPanel::setPlotOutside(QCustomPlot* plot, bool outside) {
    std::erase_if(outside_, [plot](const QPointer<QWidget>& p) { return !p || p == plot; });
    if (outside) outside_.emplace_back(plot);
}

void AnalysisPanel::plotShownOutside(QCustomPlot*) {
    if (deferred_) scheduleUpdate();
}

void AnalysisPanel::showEvent(QShowEvent* event) {
    QWidget::showEvent(event);
    if (deferred_) scheduleUpdate();
}

bool AnalysisPanel::start() {
    // A hidden tab of a shown window waits until it is shown: the visible panel gets the cores.
    const bool plot_outside_shown = std::any_of(outside_.begin(), outside_.end(),
                                                [](const auto& p) { return p && p->isVisible(); });
    if (!isVisible() && !plot_outside_shown && window()->isVisible()) {
        deferred_ = true;
        return false;
    }
    if (held_) {
        deferred_ = true;
        return false;
    }
    deferred_ = false;
    if (runner_.isRunning()) return true;  // finished() restarts with the newest state
    if (!requested_ && !restored_hash_.empty()) {
        // A saved result is on screen: computed again only when the inputs changed since.
        if (inputsHash() == restored_hash_) return false;
    }
    if (!requested_ && !startsByItself()) return false;
    requested_ = false;
    restored_hash_.clear();
    Job job;
    try {
        job = makeJob();
    } catch (const std::exception& e) {
        emit failed(QString::fromUtf8(e.what()));
        return false;
    }
    running_hash_ = inputsHash();
    wanted_ = false;
    emit busyChanged(true);
    runner_.start([job](const analysis::Control& control) { return job(*control.cancel); });
    return true;
}

void AnalysisPanel::finished(const AnalysisRunner::Outcome& outcome) {
    if (outcome.revision != runner_.revision()) {
        // Stale. A computation that was let run to the end (see scheduleUpdate) is shown as an
        // intermediate frame; a cancelled one is dropped. Either way the newest state follows.
        if (!outcome.cancelled && outcome.error.isEmpty() &&
            outcome.revision >= first_shown_revision_)
            presentOutcome(outcome);
        // The newest state follows only when one was asked since (not after discardRunning: a
        // fit or run of the project before would start again by itself on Open or New).
        if (!wanted_ || !start()) emit busyChanged(false);  // waiting, or nothing asked
        return;
    }
    emit busyChanged(false);
    if (!outcome.error.isEmpty()) {
        emit failed(outcome.error);
        return;
    }
    presentOutcome(outcome);
    if (progress_bar_) {
        // Only a complete result is 100 %: a partial one stays where it stopped and says why.
        if (completion_ == Completion::kComplete) progress_bar_->setValue(100);
        progress_bar_->setFormat(progressFormat(completion_));
    }
    last_latency_ms_ = static_cast<double>(since_edit_.nsecsElapsed()) / 1e6;
    emit resultShown(last_latency_ms_);
}

void AnalysisPanel::presentOutcome(const AnalysisRunner::Outcome& outcome) {
    QElapsedTimer drawing;
    drawing.start();
    completion_ = outcome.cancelled ? Completion::kCancelled : Completion::kComplete;
    presented_hash_ = running_hash_;  // the job that ended: none starts before it is presented
    present(outcome.value);           // may refine completion_ from the result's own status
    has_result_ = true;
    last_present_ms_ = static_cast<double>(drawing.nsecsElapsed()) / 1e6;
    since_shown_.start();
}

nlohmann::json AnalysisPanel::resultInputs() const {
    const project::Project& p = document_->project();
    return {{"soil", io::toJson(p.soil)},
            {"wheel", io::toJson(p.wheel)},
            {"conditions", analysis::toJson(p.conditions)},
            {"settings", settings()}};
}

void AnalysisPanel::showSaved(const std::any& value, const std::string& hash, bool partial) {
    // Whatever was queued for the project's opening is not needed while the inputs hash the same,
    // and a computation still running (the panel's first result, from before the project was
    // opened) is stale: it is dropped, never drawn over the saved result.
    deferred_ = false;
    discardRunning();
    restored_hash_ = hash;
    presented_hash_ = hash;
    completion_ = partial ? Completion::kCancelled : Completion::kComplete;
    present(value);
    has_result_ = true;
    if (progress_bar_) {
        // How far a saved partial run got is not saved: its bar says what it is, not "0 %".
        progress_bar_->setValue(completion_ == Completion::kComplete ? 100 : 0);
        progress_bar_->setFormat(completion_ == Completion::kComplete
                                     ? progressFormat(completion_)
                                     : completionMark(completion_) + " — saved");
    }
}

AnalysisPanel::Restored AnalysisPanel::restoreResult(const std::string&,
                                                     const project::SavedResult&) {
    return unreadable("this panel does not save its results");
}

std::map<std::string, project::SavedResult> AnalysisPanel::savedSection(int version,
                                                                        nlohmann::json result,
                                                                        std::string summary,
                                                                        bool keep_partial) const {
    std::map<std::string, project::SavedResult> out;
    const bool partial = completion_ != Completion::kComplete;
    if (!has_result_ || presented_hash_.empty() || (partial && !keep_partial)) return out;
    project::SavedResult& saved = out[name_.toStdString()];
    saved.inputs_hash = presented_hash_;
    saved.version = version;
    saved.partial = partial;
    saved.summary = std::move(summary);
    saved.result = std::move(result);
    return out;
}

AnalysisPanel::Restored AnalysisPanel::restoreSection(const std::string& section,
                                                      const project::SavedResult& saved,
                                                      int version, const SectionReader& read) {
    if (section != name_.toStdString()) return unreadable("not a section of this panel");
    if (saved.version != version)
        return unreadable("saved in form version " + std::to_string(saved.version));
    const std::string hash = inputsHash();
    if (saved.inputs_hash != hash) return inputsChanged();
    std::any value;
    try {
        value = read(saved.result, section);
    } catch (const std::exception& e) {
        return unreadable(e.what());
    }
    showSaved(value, hash, saved.partial);
    return restoredShown();
}

void AnalysisPanel::showNotComputed(QLabel* status, const QString& text,
                                    const std::vector<QCustomPlot*>& cleared,
                                    QPushButton* compute) {
    status->setText(text);
    if (compute) compute->show();
    for (QCustomPlot* plot : cleared) {
        resetPlot(*plot, "Not computed: press Compute");
        plot->replot();
    }
}

void AnalysisPanel::holdUpdates(bool hold) {
    held_ = hold;
    if (!hold && deferred_) scheduleUpdate();
}

void AnalysisPanel::projectReplaced() {
    has_result_ = false;
    completion_ = Completion::kComplete;
    presented_hash_.clear();
    restored_hash_.clear();
    if (progress_bar_) {
        progress_bar_->setValue(0);
        progress_bar_->setFormat(progressFormat(completion_));
    }
    if (live_) scheduleUpdate();  // a panel computing on Run alone waits for it
}

void AnalysisPanel::makeInteractive(QCustomPlot* plot, QLabel* readout) {
    plot->setInteractions(QCP::iRangeDrag | QCP::iRangeZoom);
    // The read-out's text must never widen the panel (a scroll bar would come and go with the
    // mouse): with an explicit minimum, the layout may shrink it below its text when room is short.
    if (readout->minimumWidth() == 0) readout->setMinimumWidth(120);
    installReadout(*plot, readout);
    installLegendControls(*plot);
    // Double-click: back to the whole data.
    QObject::connect(plot, &QCustomPlot::mouseDoubleClick, plot, [plot](QMouseEvent*) {
        plot->rescaleAxes();
        plot->replot();
    });
}

nlohmann::json AnalysisPanel::withChanges(const nlohmann::json& changes) const {
    nlohmann::json all = from_defaults_ ? default_settings_ : settings();
    if (changes.is_object()) all.update(changes);
    return all;
}

void AnalysisPanel::applyFileSettings(const nlohmann::json& file) {
    from_defaults_ = true;
    applySettings(file);
    from_defaults_ = false;
}

void AnalysisPanel::storeSettings() {
    document_->setPanelSettings(name_.toStdString(), settings());
}

}  // namespace terra::ui
