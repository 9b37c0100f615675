#include "widgets/panels/analysis_runner.h"

#include <QtConcurrent/QtConcurrentRun>
#include <exception>

namespace terra::ui {

AnalysisRunner::AnalysisRunner(QObject* parent) : QObject(parent) {
    connect(&watcher_, &QFutureWatcher<Outcome>::finished, this, &AnalysisRunner::ended);
}

AnalysisRunner::~AnalysisRunner() {
    pending_ = nullptr;
    cancel();
    watcher_.waitForFinished();
}

bool AnalysisRunner::start(Job job) {
    if (watcher_.isRunning()) return false;
    const int revision = revision_;
    cancel_ = std::make_shared<std::atomic<bool>>(false);
    auto cancel = cancel_;
    // Progress reaches the GUI thread through the event loop, and only while the job is the
    // newest: a superseded job's progress would move a bar that already shows the next one.
    auto progress = [this, revision](double fraction) {
        QMetaObject::invokeMethod(
            this,
            [this, revision, fraction] {
                if (revision == revision_) emit progressed(fraction);
            },
            Qt::QueuedConnection);
    };
    const bool was_busy = busy_;
    busy_ = true;
    if (!was_busy) emit busyChanged(true);
    watcher_.setFuture(QtConcurrent::run([job = std::move(job), revision, cancel, progress]() {
        Outcome out;
        out.revision = revision;
        try {
            out.value = job(analysis::Control{cancel.get(), progress});
        } catch (const std::exception& e) {
            out.error = QString::fromUtf8(e.what());
        }
        out.cancelled = cancel->load();
        return out;
    }));
    return true;
}

void AnalysisRunner::submit(Job job) {
    supersede();
    if (watcher_.isRunning()) {
        cancel();
        pending_ = std::move(job);  // replaces a job submitted before, never started
        return;
    }
    start(std::move(job));
}

int AnalysisRunner::supersede() { return ++revision_; }

void AnalysisRunner::cancel() {
    if (cancel_) cancel_->store(true);
}

void AnalysisRunner::dropPending() { pending_ = nullptr; }

void AnalysisRunner::ended() {
    const Outcome outcome = watcher_.result();
    if (outcome.revision != revision_)
        emit superseded(outcome);
    else
        emit finished(outcome);
    // A handler may have started the next job already; else the one submitted meanwhile runs.
    if (!watcher_.isRunning() && pending_) {
        Job next = std::move(pending_);
        pending_ = nullptr;
        start(std::move(next));
    }
    if (!watcher_.isRunning() && busy_) {
        busy_ = false;
        emit busyChanged(false);
    }
}

}  // namespace terra::ui
