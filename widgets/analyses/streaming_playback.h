#pragma once
/// @file streaming_playback.h
/// Streaming identification played back in the studio (issue 5, "streaming playback"; the
/// identifier is core/identification/streaming.h): the samples of a data set are fed one at a time
/// through a StreamingIdentifier on a worker thread, paced by the samples' time stamps at a chosen
/// speed (or as fast as possible), with pause, resume and stop at any time.
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

#include "core/common/issue.h"
#include "core/identification/data_set.h"
#include "core/identification/decoupled_fit.h"
#include "core/identification/streaming.h"
#include "core/soil/soil_parameters.h"
#include "core/wheel/wheel_parameters.h"

namespace terra::ui {

/// A data set to play and, when it was synthesised, where its soil changes.
struct StreamSource {
    identification::DataSet data;
    std::optional<std::size_t> true_border;  ///< index of the first sample of the second soil
    std::string description;                 ///< "sandy loam → clayey soil, 1 % noise", "log.csv"
    std::vector<std::string> warnings;       ///< rows skipped, points the soil could not carry
    /// Synthetic data: the parameters each stretch was made with, from its first sample on (for
    /// drawing the truth beside the estimates; K_s = k_c/b + k_φ).
    std::vector<std::pair<std::size_t, identification::DecoupledParameters>> truth;
};

/// A synthetic drive over a soil border: the slip sweep of the first soil, then of the second,
/// each in a scrambled but fixed order (a robot's slip wanders; a monotone sweep is not what a
/// streaming identifier sees), with Gaussian noise (Eq. 5.1). Samples are 10 ms apart (100 Hz).
struct SoilBorderSpec {
    soil::SoilParameters first;
    soil::SoilParameters second;
    wheel::WheelParameters wheel;
    double load_n = 58.86;          ///< W [N]
    double noise_relative = 0.01;   ///< σ per channel as a fraction of its largest value
    std::uint64_t seed = 1;         ///< the second soil uses seed + 1
    int samples_per_soil = 101;     ///< slips 0.05 … 0.9
    double sample_period_s = 0.01;  ///< time between samples [s]
};
/// Throws std::invalid_argument for an invalid soil, wheel, load or noise.
StreamSource synthesiseSoilBorder(const SoilBorderSpec& spec);

/// Reads a CSV for playback (data_set.h columns). Bad rows either stop the read, every one listed
/// with its line number, or are skipped and listed in `warnings`.
Result<StreamSource> readStreamSource(const std::string& path, bool skip_bad_rows);

/// What the studio shows of one sample.
struct StreamFrame {
    identification::StreamUpdate update;  ///< the identifier's state after the sample
    double time_s = 0.0;                  ///< the sample's time (its time_s, or index × 10 ms)
    double fx_measured_n = 0.0;           ///< F_x of the sample [N]
    /// F_x the estimate *before* this sample predicts at its slip and entry angle (decoupled model,
    /// Eq. 4.4) [N]; NaN while there is no estimate.
    double fx_predicted_n = 0.0;
};

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
               identification::StreamingOptions options, double speed);
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
              identification::StreamingOptions options);
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
