#pragma once
/// @file analysis_runner.h
/// Runs the studio's computations off the GUI thread (the shared thread pool, QtConcurrent), one
/// at a time, each with a cancel flag and a progress callback, and hands the outcome back on the
/// GUI thread. Used by every analysis panel (AnalysisPanel), the calibration dialog and the
/// identification panel's data preview; the panels keep their policy (when to recompute, what to
/// show), the runner the plumbing:
/// - Newest wins: every job is tagged with the runner's revision when it starts; supersede()
///   moves the revision on, so the outcome of a job started before arrives as superseded()
///   (a client drops it, or shows it as an intermediate frame) instead of finished(). submit()
///   supersedes and cancels the running job and starts the new one when the worker is free.
/// - Cancel keeps the partial result: cancel() sets the running job's flag; the job stops soon and
///   returns what it has, which arrives as finished() marked `cancelled`.
/// - busyChanged(true) when a job starts on an idle runner, busyChanged(false) when the last one
///   ends and nothing was started in its place (a superseded job replaced by a newer one keeps the
///   runner busy without a false in between).
/// The destructor cancels the running job and waits for it: a job must stop soon on its flag.

#include <QFutureWatcher>
#include <QObject>
#include <QString>
#include <any>
#include <atomic>
#include <functional>
#include <memory>

#include "core/analysis/analysis.h"

namespace terra::ui {

class AnalysisRunner : public QObject {
    Q_OBJECT
public:
    /// A computation: inputs captured by value on the GUI thread, run on a worker; may throw
    /// std::exception (the outcome's `error`). `control` (core/analysis/analysis.h) holds its
    /// cancel flag (set when the job is superseded and cancelled, or the user cancels: stop soon
    /// and return what there is) and its progress, a fraction in [0, 1] reported from the worker
    /// that reaches progressed() on the GUI thread.
    using Job = std::function<std::any(const analysis::Control& control)>;
    /// How a job ended.
    struct Outcome {
        int revision = 0;        ///< the runner's revision when the job started
        std::any value;          ///< what the job returned (empty when it threw)
        QString error;           ///< the exception's message, if it threw
        bool cancelled = false;  ///< the job saw its cancel flag set (its value may be partial)
    };

    explicit AnalysisRunner(QObject* parent = nullptr);
    ~AnalysisRunner() override;  ///< cancels the running job and waits for its worker

    /// Starts `job` now, tagged with the current revision; false (nothing started) while a job
    /// runs.
    bool start(Job job);
    /// Newest wins: supersedes whatever was started (its outcome arrives as superseded()),
    /// cancels the running job and starts `job` as soon as the worker is free (a job submitted
    /// meanwhile replaces this one).
    void submit(Job job);
    /// Moves the revision on: the outcome of every job started so far is superseded. Does not
    /// cancel (a client may let a stale job finish, e.g. as an intermediate frame). Returns the
    /// new revision.
    int supersede();
    /// Sets the running job's cancel flag (no-op when idle). Its outcome keeps the partial value.
    void cancel();
    /// Cancels and forgets a job submitted but not started yet.
    void dropPending();

    /// A job runs on a worker now.
    bool isRunning() const { return watcher_.isRunning(); }
    /// What busyChanged() said last: true from the start of a job until the last one ended and
    /// its outcome was handed over.
    bool isBusy() const { return busy_; }
    int revision() const { return revision_; }

signals:
    void busyChanged(bool busy);
    /// A job of the current revision ended (completed, cancelled with its partial value, or
    /// failed with `error`).
    void finished(const terra::ui::AnalysisRunner::Outcome& outcome);
    /// A job started before the last supersede() ended: its result is stale.
    void superseded(const terra::ui::AnalysisRunner::Outcome& outcome);
    /// Progress of the running job of the current revision, a fraction in [0, 1].
    void progressed(double fraction);

private:
    void ended();

    QFutureWatcher<Outcome> watcher_;
    std::shared_ptr<std::atomic<bool>> cancel_;
    Job pending_;
    int revision_ = 0;
    bool busy_ = false;
};

}  // namespace terra::ui
