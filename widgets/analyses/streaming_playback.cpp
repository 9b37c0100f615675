#include "widgets/analyses/streaming_playback.h"

#include <QMetaObject>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <filesystem>
#include <limits>
#include <mutex>
#include <numeric>
#include <stdexcept>

#include "core/contact/contact_parameters.h"
#include "core/identification/decoupled_fit.h"
#include "core/identification/synthetic.h"

namespace terra::ui {
namespace {

namespace id = identification;
using Clock = std::chrono::steady_clock;

constexpr double kDefaultPeriodS = 0.01;  // 100 Hz when the data carry no time

// One soil's sweep in a scrambled, fixed order (stride coprime to the count).
std::vector<id::Sample> scrambledSweep(const soil::SoilParameters& soil, const SoilBorderSpec& spec,
                                       std::uint64_t seed, std::vector<std::string>& warnings) {
    id::SyntheticSpec s;
    s.loads_n = {spec.load_n};
    const int n = spec.samples_per_soil;
    for (int i = 0; i < n; ++i) s.slips.push_back(n == 1 ? 0.3 : 0.05 + 0.85 * i / (n - 1));
    s.noise.fx.relative = s.noise.fz.relative = s.noise.my.relative = spec.noise_relative;
    s.seed = seed;
    id::SyntheticData d = id::synthesize(contact::makeContactParameters(soil, spec.wheel), s);
    for (auto& w : d.warnings) warnings.push_back(soil.name + ": " + w);
    const std::size_t count = d.data.samples.size();
    std::size_t stride = 37;
    while (count > 1 && std::gcd(stride, count) != 1) ++stride;
    std::vector<id::Sample> out;
    out.reserve(count);
    for (std::size_t i = 0; i < count; ++i) out.push_back(d.data.samples[(i * stride) % count]);
    return out;
}

// Sample times for pacing: the data's own when every sample has one and they never go back,
// else 10 ms apart.
std::vector<double> sampleTimes(const id::DataSet& data) {
    std::vector<double> t(data.samples.size());
    bool own = !data.samples.empty();
    for (std::size_t i = 0; i < t.size() && own; ++i) {
        own = data.samples[i].time_s.has_value() && std::isfinite(*data.samples[i].time_s) &&
              (i == 0 || *data.samples[i].time_s >= *data.samples[i - 1].time_s);
        if (own) t[i] = *data.samples[i].time_s;
    }
    if (!own) {
        for (std::size_t i = 0; i < t.size(); ++i) t[i] = static_cast<double>(i) * kDefaultPeriodS;
    }
    return t;
}

id::DecoupledParameters truthOf(const soil::SoilParameters& s, const wheel::WheelParameters& w) {
    id::DecoupledParameters p;
    p.a0 = s.max_stress_a0;
    p.a1 = s.max_stress_a1;
    p.pressure_modulus = s.cohesive_modulus / w.width_m + s.frictional_modulus;
    p.n0 = s.sinkage_exponent;
    p.n1 = s.sinkage_exponent_slip;
    p.cohesion_pa = s.cohesion_pa;
    p.friction_angle_rad = s.friction_angle_rad;
    p.shear_modulus_m = s.shear_modulus_m;
    return p;
}

}  // namespace

StreamSource synthesiseSoilBorder(const SoilBorderSpec& spec) {
    if (spec.samples_per_soil < 1) {
        throw std::invalid_argument("samples_per_soil = " + std::to_string(spec.samples_per_soil) +
                                    " must be ≥ 1");
    }
    if (!(spec.sample_period_s > 0.0)) throw std::invalid_argument("sample_period_s must be > 0");
    StreamSource out;
    std::vector<id::Sample> samples = scrambledSweep(spec.first, spec, spec.seed, out.warnings);
    out.true_border = samples.size();
    const std::vector<id::Sample> second =
        scrambledSweep(spec.second, spec, spec.seed + 1, out.warnings);
    samples.insert(samples.end(), second.begin(), second.end());
    for (std::size_t i = 0; i < samples.size(); ++i)
        samples[i].time_s = static_cast<double>(i) * spec.sample_period_s;
    out.data.samples = std::move(samples);
    out.truth = {{0, truthOf(spec.first, spec.wheel)},
                 {*out.true_border, truthOf(spec.second, spec.wheel)}};
    const auto percent = static_cast<int>(std::lround(spec.noise_relative * 100.0));
    out.description =
        spec.first.name + " → " + spec.second.name + ", " + std::to_string(percent) + " % noise";
    return out;
}

Result<StreamSource> readStreamSource(const std::string& path, bool skip_bad_rows) {
    auto read = id::readDataSet(path, skip_bad_rows ? id::BadRows::kSkip : id::BadRows::kStop);
    if (!read) return read.issues();
    StreamSource out;
    out.data = read->data;
    out.description = std::filesystem::path(path).filename().string();
    for (const Issue& issue : read->skipped)
        out.warnings.push_back("skipped " + issue.where + ": " + issue.message);
    if (out.data.samples.empty()) return std::vector<Issue>{{path, "no valid samples"}};
    return out;
}

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
                              identification::StreamingOptions options, double speed) {
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
                             identification::StreamingOptions options) {
    auto finish = [&](bool completed, std::string error) {
        std::lock_guard lock(run->mutex);
        run->done = true;
        run->completed = completed;
        run->error = std::move(error);
        post(run);
    };
    StreamSource source;
    std::optional<id::StreamingIdentifier> identifier;
    try {
        source = make_source();
        if (source.data.samples.empty()) throw std::invalid_argument("the data set has no samples");
        identifier.emplace(wheel, options);
    } catch (const std::exception& e) {
        finish(false, e.what());
        return;
    }
    const std::vector<id::Sample> samples = std::move(source.data.samples);
    source.data.samples.clear();
    const std::vector<double> times = sampleTimes(id::DataSet{samples});
    {
        std::lock_guard lock(run->mutex);
        run->source = std::move(source);
        run->sample_count = samples.size();
        post(run);
    }

    Clock::time_point anchor_wall = Clock::now();
    double anchor_t = times.front();
    std::optional<id::DecoupledParameters> estimate;  // before the sample being played
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
        const id::Sample& s = samples[i];
        StreamFrame frame;
        frame.time_s = times[i];
        frame.fx_measured_n = s.fx_n;
        frame.fx_predicted_n =
            estimate ? id::decoupledForward(*estimate, wheel, s.slip, s.entry_angle_rad).fx_n
                     : std::numeric_limits<double>::quiet_NaN();
        try {
            frame.update = identifier->push(s);
        } catch (const std::exception& e) {
            finish(false, "sample " + std::to_string(i) + ": " + e.what());
            return;
        }
        if (frame.update.estimated) {
            estimate = frame.update.parameters;
        } else {
            estimate.reset();
        }
        std::lock_guard lock(run->mutex);
        run->frames.push_back(std::move(frame));
        post(run);
    }
    finish(true, {});
}

}  // namespace terra::ui
