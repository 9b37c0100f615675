#include "app/cli/signals.h"

#include <CLI/CLI.hpp>
#include <cassert>
#include <csignal>
#include <iostream>

namespace terra::app {
namespace {

constexpr int kSignals[] = {SIGINT, SIGTERM, SIGHUP};

// Lock-free atomics: the only state a signal handler may touch.
std::atomic<bool> g_cancel{false};
std::atomic<int> g_signal{0};
std::atomic<bool> g_installed{false};
struct sigaction g_previous[std::size(kSignals)];

extern "C" void onCancelSignal(int signal) {
    int none = 0;
    if (!g_signal.compare_exchange_strong(none, signal)) {
        // The second signal: the default action now (signal and raise are async-signal-safe).
        std::signal(signal, SIG_DFL);
        std::raise(signal);
        return;
    }
    g_cancel.store(true);
}

}  // namespace

SignalCancellation::SignalCancellation() {
    [[maybe_unused]] const bool was_installed = g_installed.exchange(true);
    assert(!was_installed && "one SignalCancellation at a time");
    g_cancel.store(false);
    g_signal.store(0);
    struct sigaction action {};
    action.sa_handler = onCancelSignal;
    sigemptyset(&action.sa_mask);
    // No SA_RESTART: a blocking read or sleep returns early, so the loop can look at the flag.
    for (std::size_t i = 0; i < std::size(kSignals); ++i) {
        ::sigaction(kSignals[i], &action, &g_previous[i]);
    }
}

SignalCancellation::~SignalCancellation() {
    for (std::size_t i = 0; i < std::size(kSignals); ++i) {
        ::sigaction(kSignals[i], &g_previous[i], nullptr);
    }
    g_installed.store(false);
}

const std::atomic<bool>* SignalCancellation::flag() const { return &g_cancel; }

bool SignalCancellation::requested() const { return g_cancel.load(); }

std::string SignalCancellation::signalName() const {
    switch (g_signal.load()) {
        case SIGINT:
            return "SIGINT";
        case SIGTERM:
            return "SIGTERM";
        case SIGHUP:
            return "SIGHUP";
        default:
            return "";
    }
}

int SignalCancellation::exitCode() const {
    const int signal = g_signal.load();
    return signal == 0 ? 0 : 128 + signal;
}

void exitCancelled(const SignalCancellation& cancellation, const std::string& message) {
    std::cerr << message << '\n';
    throw CLI::RuntimeError(cancellation.exitCode());
}

}  // namespace terra::app
