#include "widgets/analyses/streaming_playback.h"

#include <QMetaObject>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <mutex>
#include <stdexcept>

namespace terra::ui {
namespace {

namespace id = identification;
using Clock = std::chrono::steady_clock;

}  // namespace

// The state a worker shares with the GUI thread (everything under `mutex`).
struct StreamingPlayback::Run {
    std::mutex mutex;
    std::condition_variable wake;
    bool stop = false;
    bool paused = false;
    bool reanchor = false;  // the speed changed or playback resumed: restart the pacing clock
    double speed = 1.0;
    bool notify_pending = false;
    std::optional<StreamSource> source;  // without samples, until delivered
    std::size_t sample_count = 0;
    std::vector<StreamFrame> frames;
    bool done = false;
    bool completed = false;
    std::string error;
};

StreamingPlayback::StreamingPlayback(QObject* parent) : QObject(parent) {}

StreamingPlayback::~StreamingPlayback() {
    for (auto& [run, thread] : workers_) {
        {
            std::lock_guard lock(run->mutex);
            run->stop = true;
        }
        run->wake.notify_all();
    }
    for (auto& [run, thread] : workers_) thread.join();
}

void StreamingPlayback::reapFinishedWorkers() {
    for (auto it = workers_.begin(); it != workers_.end();) {
        bool done;
        {
            std::lock_guard lock(it->first->mutex);
            done = it->first->done;
        }
        if (done) {
            it->second.join();  // it has returned already: no wait
            it = workers_.erase(it);
        } else {
            ++it;
        }
    }
}

void StreamingPlayback::start(SourceFactory source, wheel::WheelParameters wheel,
                              identification::StreamingEstimatorOptions options, double speed) {
    stop();
    reapFinishedWorkers();
    auto run = std::make_shared<Run>();
    run->speed = speed;
    current_ = run;
    ++run_number_;
    setState(State::kPlaying);
    workers_.emplace_back(
        run, std::thread([this, run, source = std::move(source), wheel = std::move(wheel),
                          options] { work(run, source, wheel, options); }));
}

void StreamingPlayback::pause() {
    if (!current_ || state_ != State::kPlaying) return;
    {
        std::lock_guard lock(current_->mutex);
        current_->paused = true;
    }
    setState(State::kPaused);
}

void StreamingPlayback::resume() {
    if (!current_ || state_ != State::kPaused) return;
    {
        std::lock_guard lock(current_->mutex);
        current_->paused = false;
        current_->reanchor = true;
    }
    current_->wake.notify_all();
    setState(State::kPlaying);
}

void StreamingPlayback::stop() {
    if (!current_) return;
    {
        std::lock_guard lock(current_->mutex);
        current_->stop = true;
    }
    current_->wake.notify_all();
    current_.reset();  // nothing of this run is delivered from now on
    if (isActive()) setState(State::kStopped);
}

void StreamingPlayback::setSpeed(double speed) {
    if (!current_) return;
    {
        std::lock_guard lock(current_->mutex);
        current_->speed = speed;
        current_->reanchor = true;
    }
    current_->wake.notify_all();
}

void StreamingPlayback::setState(State state) {
    if (state_ == state) return;
    state_ = state;
    emit stateChanged(state);
}

void StreamingPlayback::post(const std::shared_ptr<Run>& run) {
    // Called with run->mutex held. One notification in flight at most: the GUI thread takes
    // everything that accumulated when it gets to it.
    if (run->notify_pending) return;
    run->notify_pending = true;
    QMetaObject::invokeMethod(
        this, [this, run] { deliver(run); }, Qt::QueuedConnection);
}

void StreamingPlayback::deliver(const std::shared_ptr<Run>& run) {
    if (run != current_) return;  // stopped or superseded: never shown
    std::optional<StreamSource> source;
    std::size_t count = 0;
    std::vector<StreamFrame> frames;
    bool done = false, completed = false;
    std::string error;
    {
        std::lock_guard lock(run->mutex);
        run->notify_pending = false;
        source.swap(run->source);
        count = run->sample_count;
        frames.swap(run->frames);
        done = run->done;
        completed = run->completed;
        error = run->error;
    }
    if (source) emit sourceReady(*source, count);
    if (!frames.empty()) emit framesReady(frames);
    if (done && run == current_) {
        current_.reset();
        if (!error.empty()) {
            emit failed(
                QString::fromStdString(error));  // before the state: listeners read the message
            setState(State::kFailed);
        } else {
            setState(completed ? State::kFinished : State::kStopped);
        }
    }
}

void StreamingPlayback::work(std::shared_ptr<Run> run, SourceFactory make_source,
                             wheel::WheelParameters wheel,
                             identification::StreamingEstimatorOptions options) {
    auto finish = [&](bool completed, std::string error) {
        std::lock_guard lock(run->mutex);
        run->done = true;
        run->completed = completed;
        run->error = std::move(error);
        post(run);
    };
    StreamSource source;
    std::optional<analysis::StreamingRun> streaming;
    try {
        source = make_source();
        if (source.data.samples.empty()) throw std::invalid_argument("the data set has no samples");
        options.columns = source.data.columns;
        streaming.emplace(wheel, options);
    } catch (const std::exception& e) {
        finish(false, e.what());
        return;
    }
    const std::vector<id::Sample> samples = std::move(source.data.samples);
    source.data.samples.clear();
    const std::vector<double> times = analysis::sampleTimes(id::DataSet{samples});
    {
        std::lock_guard lock(run->mutex);
        run->source = std::move(source);
        run->sample_count = samples.size();
        post(run);
    }

    Clock::time_point anchor_wall = Clock::now();
    double anchor_t = times.front();
    for (std::size_t i = 0; i < samples.size(); ++i) {
        {
            // Pacing: sample i is due at anchor_wall + (t_i − anchor_t) / speed.
            std::unique_lock lock(run->mutex);
            for (;;) {
                if (run->stop) break;
                if (run->reanchor) {
                    anchor_wall = Clock::now();
                    anchor_t = i == 0 ? times.front() : times[i - 1];
                    run->reanchor = false;
                }
                if (run->paused) {
                    run->wake.wait(lock);
                    continue;
                }
                if (!(run->speed > 0.0) || !std::isfinite(run->speed)) break;
                const auto due =
                    anchor_wall +
                    std::chrono::duration_cast<Clock::duration>(
                        std::chrono::duration<double>((times[i] - anchor_t) / run->speed));
                if (Clock::now() >= due) break;
                run->wake.wait_until(lock, due);
            }
            if (run->stop) {
                lock.unlock();
                finish(false, {});
                return;
            }
        }
        StreamFrame frame;
        try {
            frame = streaming->push(samples[i], times[i]);
        } catch (const std::exception& e) {
            finish(false, "sample " + std::to_string(i) + ": " + e.what());
            return;
        }
        std::lock_guard lock(run->mutex);
        run->frames.push_back(std::move(frame));
        post(run);
    }
    finish(true, {});
}

}  // namespace terra::ui
