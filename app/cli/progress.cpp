#include "app/cli/progress.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace terra::app {
namespace {

constexpr int kBarWidth = 30;
// Long labels would wrap the line on an 80-column terminal, and a wrapped bar is not redrawn in
// place.
constexpr std::size_t kMaxLabel = 32;
constexpr auto kRedrawInterval = std::chrono::milliseconds(100);

}  // namespace

bool stderrIsTerminal() { return ::isatty(STDERR_FILENO) == 1; }

TerminalProgress::TerminalProgress(std::string label, Mode mode)
    : label_(std::move(label)), mode_(mode) {
    if (label_.size() > kMaxLabel) label_ = label_.substr(0, kMaxLabel - 3) + "...";
    active_ = mode_ == Mode::kLines || stderrIsTerminal();
}

TerminalProgress::~TerminalProgress() { finish(); }

void TerminalProgress::update(double fraction) {
    if (!active_ || std::isnan(fraction)) return;
    fraction = std::clamp(fraction, 0.0, 1.0);
    const std::lock_guard lock(mutex_);
    if (finished_) return;
    latest_ = std::max(latest_, fraction);  // threads may report out of order
    if (mode_ == Mode::kLines) {
        const int percent = static_cast<int>(latest_ * 100.0);
        if (percent / 10 == last_tenth_) return;
        last_tenth_ = percent / 10;
        std::fprintf(stderr, "progress: %d %%\n", percent);
        std::fflush(stderr);
        return;
    }
    if (shown_ && latest_ == drawn_) return;
    // The first state (or the first after clear()) and the complete one at once, the rest
    // throttled: a loop may report a million times a second, a terminal needs ten.
    if (!shown_ || latest_ == 1.0 ||
        std::chrono::steady_clock::now() - drawn_at_ >= kRedrawInterval)
        draw(latest_);
}

std::function<void(double)> TerminalProgress::callback() {
    if (!active_) return {};
    return [this](double fraction) { update(fraction); };
}

void TerminalProgress::clear() {
    if (!active_ || mode_ != Mode::kBar) return;
    const std::lock_guard lock(mutex_);
    if (!shown_) return;
    std::fputs("\r\x1b[K", stderr);
    std::fflush(stderr);
    shown_ = false;
}

void TerminalProgress::finish() {
    if (!active_) return;
    const std::lock_guard lock(mutex_);
    if (finished_) return;
    finished_ = true;
    if (mode_ != Mode::kBar || latest_ < 0.0) return;  // nothing was ever reported
    if (!shown_ || drawn_ != latest_) draw(latest_);
    std::fputs("\n", stderr);
    std::fflush(stderr);
}

void TerminalProgress::draw(double fraction) {
    const int filled = static_cast<int>(fraction * kBarWidth);
    std::string bar(static_cast<std::size_t>(filled), '#');
    bar.resize(kBarWidth, '.');
    // \r: back to the start of the line; ESC [K: erase what a longer previous text left.
    std::fprintf(stderr, "\r%s [%s] %3d %%\x1b[K", label_.c_str(), bar.c_str(),
                 static_cast<int>(fraction * 100.0));
    std::fflush(stderr);
    shown_ = true;
    drawn_ = fraction;
    drawn_at_ = std::chrono::steady_clock::now();
}

}  // namespace terra::app
