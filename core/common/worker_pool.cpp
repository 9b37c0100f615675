#include "core/common/worker_pool.h"

#include <algorithm>
#include <chrono>
#include <stdexcept>

namespace terra {
namespace {

// Spins, for at most 200 µs, until ready() holds; whether it did. Sleeping on a condition
// variable and being woken costs a futex call each way, tens of µs on a virtual machine: as much
// as a thread's share of one of the search's descent evaluations (12 of 24 samples, ~30 µs).
// Between such evaluations a thread waits a few µs, so it rarely sleeps; past 200 µs (the end
// of a search's parallel phase) it sleeps as before. Each turn yields the processor, so that
// with more threads than processors (two identifications at once on two cores) the spinning
// thread gives way to the one it waits for: a pause instruction instead made that case 2.6×
// slower. Measured in docs/performance.md ("Sixth pass").
template <typename Ready>
bool spinUntil(Ready ready) {
    constexpr auto kSpin = std::chrono::microseconds(200);
    const auto deadline = std::chrono::steady_clock::now() + kSpin;
    for (int k = 0;; ++k) {
        if (ready()) return true;
        std::this_thread::yield();
        if ((k & 7) == 7 && std::chrono::steady_clock::now() > deadline) return false;
    }
}

}  // namespace

WorkerPool::WorkerPool(int threads) {
    const int count = std::max(1, threads);
    errors_.resize(static_cast<std::size_t>(count));
    try {
        for (int t = 1; t < count; ++t) workers_.emplace_back([this, t] { work(t); });
    } catch (...) {
        stopWorkers();  // the threads started so far (a joinable std::thread may not be dropped)
        throw;
    }
}

WorkerPool::~WorkerPool() { stopWorkers(); }

void WorkerPool::stopWorkers() {
    {
        const std::lock_guard lock(mutex_);
        stop_ = true;
    }
    start_.notify_all();
    for (std::thread& t : workers_) t.join();
    workers_.clear();
}

std::pair<std::size_t, std::size_t> WorkerPool::part(int index) const {
    const std::size_t parts = workers_.size() + 1;
    const std::size_t i = static_cast<std::size_t>(index);
    return {n_ * i / parts, n_ * (i + 1) / parts};
}

void WorkerPool::forEach(std::size_t n, const std::function<void(std::size_t, std::size_t)>& body) {
    if (busy_.exchange(true)) {
        throw std::logic_error(
            "WorkerPool::forEach: already running (called from inside a forEach of the same "
            "pool, or from two threads at once)");
    }
    struct Idle {
        std::atomic<bool>& busy;
        ~Idle() { busy = false; }
    } idle{busy_};
    if (workers_.empty() || n < 2) {
        body(0, n);
        return;
    }
    {
        const std::lock_guard lock(mutex_);
        body_ = &body;
        n_ = n;
        pending_ = static_cast<int>(workers_.size());
        std::fill(errors_.begin(), errors_.end(), nullptr);
        ++generation_;
    }
    start_.notify_all();
    const auto [begin, end] = part(0);
    try {
        body(begin, end);
    } catch (...) {
        errors_[0] = std::current_exception();
    }
    if (!spinUntil([this] { return pending_.load() == 0; })) {
        std::unique_lock lock(mutex_);
        done_.wait(lock, [this] { return pending_ == 0; });
    }
    body_ = nullptr;
    for (const std::exception_ptr& e : errors_) {
        if (e) std::rethrow_exception(e);
    }
}

void WorkerPool::forEachIndex(std::size_t n, const std::function<void(std::size_t)>& body) {
    const std::size_t stride =
        std::min<std::size_t>(workers_.size() + 1, std::max<std::size_t>(n, 1));
    forEach(stride, [&](std::size_t begin, std::size_t end) {
        for (std::size_t k = begin; k < end; ++k) {
            for (std::size_t i = k; i < n; i += stride) body(i);
        }
    });
}

void WorkerPool::work(int index) {
    unsigned long seen = 0;
    for (;;) {
        const std::function<void(std::size_t, std::size_t)>* body = nullptr;
        std::pair<std::size_t, std::size_t> range;
        spinUntil([&] { return stop_.load() || generation_.load() != seen; });
        {
            std::unique_lock lock(mutex_);
            start_.wait(lock, [&] { return stop_ || generation_ != seen; });
            if (stop_) return;
            seen = generation_;
            body = body_;
            range = part(index);
        }
        std::exception_ptr error;
        try {
            if (range.first < range.second) (*body)(range.first, range.second);
        } catch (...) {
            error = std::current_exception();
        }
        {
            const std::lock_guard lock(mutex_);
            errors_[static_cast<std::size_t>(index)] = error;
            if (--pending_ == 0) done_.notify_one();
        }
    }
}

}  // namespace terra
