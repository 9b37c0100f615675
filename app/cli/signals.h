#pragma once
/// @file signals.h
/// Ending long commands cleanly on SIGINT (Ctrl-C), SIGTERM (kill, a supervisor, a job system) and
/// SIGHUP (the terminal closed): while a SignalCancellation is alive, the first of these signals
/// only sets a flag; the command stops at its next check, writes what it has computed, marked
/// cancelled, and exits with 128 + the signal number (130, 143, 129: what a shell reports for a
/// process killed by that signal; docs/cli.md, "Exit codes"). A second signal ends the process at
/// once, as it would have without the handler.

#include <atomic>
#include <string>

namespace terra::app {

class SignalCancellation {
public:
    /// Installs the handlers (one SignalCancellation at a time) and clears the flag.
    SignalCancellation();
    /// Restores the handlers that were there before.
    ~SignalCancellation();
    SignalCancellation(const SignalCancellation&) = delete;
    SignalCancellation& operator=(const SignalCancellation&) = delete;

    /// The cancel flag to hand to core loops (scenario runner, sweeps, synthesis).
    const std::atomic<bool>* flag() const;
    /// True once a signal has arrived.
    bool requested() const;
    /// "SIGTERM": the signal that cancelled the command ("" when none did).
    std::string signalName() const;
    /// 128 + the signal number (0 when no signal arrived).
    int exitCode() const;
};

/// After a command has written its partial results: prints `message` on stderr and throws
/// CLI::RuntimeError with the cancellation's exit code.
[[noreturn]] void exitCancelled(const SignalCancellation& cancellation, const std::string& message);

}  // namespace terra::app
