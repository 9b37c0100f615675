#pragma once
/// @file progress.h
/// The terminal progress of every long command (docs/cli.md, "Progress and stopping"): a bar on
/// stderr, only when stderr is a terminal, redrawn at most 10 times a second; when stderr is a
/// file or a pipe nothing at all is written, so logs and scripts see only the messages. The core's
/// loops report a fraction done through analysis::Control::progress (or a spec's `progress`);
/// callback() gives the function to hand them.
///
/// `gsa` and `bands` keep their `--progress` flag: "progress: N %" lines every 10 % on any stderr
/// (Mode::kLines), for logs of long studies.

#include <chrono>
#include <functional>
#include <memory>
#include <mutex>
#include <string>

namespace terra::app {

/// Whether stderr is a terminal (isatty).
bool stderrIsTerminal();

class TerminalProgress {
public:
    enum class Mode {
        kBar,    ///< a bar redrawn in place, on a terminal only
        kLines,  ///< a line "progress: N %" every 10 %, wherever stderr goes
    };

    /// `label` starts the bar ("synth", "run forces (1/3)"). kBar on a stderr that is not a
    /// terminal is inactive: it writes nothing.
    explicit TerminalProgress(std::string label, Mode mode = Mode::kBar);
    /// finish()
    ~TerminalProgress();
    TerminalProgress(const TerminalProgress&) = delete;
    TerminalProgress& operator=(const TerminalProgress&) = delete;

    /// Whether anything is drawn at all.
    bool active() const { return active_; }

    /// The fraction done, in [0, 1] (clamped; NaN ignored). May be called from any thread and as
    /// often as the loop likes: the first call and the complete state (1) are drawn at once,
    /// others at most every 100 ms (kBar) or at each new tenth (kLines).
    void update(double fraction);

    /// update() as a callback for the core, bound to this object (which must outlive the
    /// computation); empty when inactive, so the core skips the calls.
    std::function<void(double)> callback();

    /// Erases the bar, so that the caller can print a line on stderr; the next update redraws.
    void clear();

    /// Draws the last state (a cancelled run's bar stays where it stopped) and ends the line.
    /// Later updates draw nothing. Call it before printing the results' messages.
    void finish();

private:
    void draw(double fraction);  // with mutex_ held

    std::string label_;
    Mode mode_;
    bool active_ = false;
    std::mutex mutex_;
    bool finished_ = false;
    bool shown_ = false;    // a bar is on the line now (kBar)
    double latest_ = -1.0;  // the last fraction reported
    double drawn_ = -1.0;   // the fraction on the screen
    int last_tenth_ = -1;   // kLines: the last tenth printed
    std::chrono::steady_clock::time_point drawn_at_{};
};

}  // namespace terra::app
