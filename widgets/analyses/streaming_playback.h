#pragma once
/// @file streaming_playback.h
/// Streaming identification played back in the studio: the frames of
/// core/analysis/streaming_identification.h (the same as `identify --stream` and a script's
/// "streaming" analysis compute) made on a worker thread one sample at a time, paced by the
/// samples' time stamps at a chosen speed (or as fast as possible), with pause, resume and stop
/// at any time.
///
/// The GUI thread never computes: the worker posts at most one notification at a time (coalesced),
/// and the GUI thread takes every frame produced since the last one, so a run at full speed cannot
/// flood the event loop. Each run is separate: once a run is stopped or superseded by a newer one,
/// nothing it produces afterwards is delivered.

#include <QObject>
#include <QString>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "core/analysis/streaming_identification.h"
#include "core/identification/streaming.h"
#include "core/wheel/wheel_parameters.h"

namespace terra::ui {

using analysis::StreamFrame;
using analysis::StreamSource;

/// Plays one data set at a time through a StreamingIdentifier on its own worker thread (not the
/// shared thread pool: a paced run sleeps most of the time and must not starve the analyses).
class StreamingPlayback : public QObject {
    Q_OBJECT
public:
    enum class State { kIdle, kPlaying, kPaused, kFinished, kStopped, kFailed };

    explicit StreamingPlayback(QObject* parent = nullptr);
    ~StreamingPlayback() override;  ///< stops every run and waits for its worker

    /// Produces the data on the worker (reading or synthesising is not done on the GUI thread);
    /// may throw (the run fails with the exception's message).
    using SourceFactory = std::function<StreamSource()>;

    /// Starts a new run; a running one is stopped first and nothing of it is delivered again.
    /// `speed`: sample time per wall time (1 = real time); ≤ 0 plays as fast as possible.
    void start(SourceFactory source, wheel::WheelParameters wheel,
               identification::StreamingEstimatorOptions options, double speed);
    void pause();
    void resume();
    /// Stops the current run now; the frames delivered so far stay valid (a partial run).
    void stop();
    /// Changes the speed of the current run from the sample being played on.
    void setSpeed(double speed);

    State state() const { return state_; }
    bool isActive() const { return state_ == State::kPlaying || state_ == State::kPaused; }
    /// Serial number of the current (or last) run; frames carry no run number because only the
    /// current run's frames are ever delivered.
    int runNumber() const { return run_number_; }

signals:
    /// The current run's data are ready: sample count, true border (synthetic), description.
    void sourceReady(const terra::ui::StreamSource& source_without_samples,
                     std::size_t sample_count);
    /// Frames of the current run, in order, since the last delivery.
    void framesReady(const std::vector<terra::ui::StreamFrame>& frames);
    void stateChanged(terra::ui::StreamingPlayback::State state);
    void failed(const QString& message);

private:
    struct Run;
    void work(std::shared_ptr<Run> run, SourceFactory source, wheel::WheelParameters wheel,
              identification::StreamingEstimatorOptions options);
    void post(
        const std::shared_ptr<Run>& run);  // worker: ask the GUI thread to deliver (coalesced)
    void deliver(const std::shared_ptr<Run>& run);  // GUI thread
    void setState(State state);
    void reapFinishedWorkers();

    std::shared_ptr<Run> current_;
    std::vector<std::pair<std::shared_ptr<Run>, std::thread>> workers_;
    State state_ = State::kIdle;
    int run_number_ = 0;
};

}  // namespace terra::ui
