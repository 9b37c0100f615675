#pragma once
/// @file worker_pool.h
/// A few threads kept for the life of one computation, for loops too short to start threads for
/// each time: an identification evaluates its model on ~100 samples a few hundred times, each
/// evaluation 0.05–2 ms (docs/identification.md §9, "Two threads"). A thread waiting for the
/// next loop or for the others' parts yields for up to 200 µs before it sleeps (worker_pool.cpp).

#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace terra {

class WorkerPool {
public:
    /// `threads` in all, the caller's included (threads − 1 workers are started); at least 1.
    explicit WorkerPool(int threads);
    ~WorkerPool();
    WorkerPool(const WorkerPool&) = delete;
    WorkerPool& operator=(const WorkerPool&) = delete;

    int threads() const { return static_cast<int>(workers_.size()) + 1; }

    /// Runs body(begin, end) on contiguous parts of [0, n), one per thread (the caller runs the
    /// first), and returns when all are done; an exception of a part is rethrown here (the first
    /// part's first). Not reentrant: a body that calls forEach of the same pool gets
    /// std::logic_error (it would wait for itself).
    void forEach(std::size_t n, const std::function<void(std::size_t, std::size_t)>& body);

    /// Runs body(i) for every i < n, thread k taking i = k, k + threads, k + 2·threads, …:
    /// interleaved, so that work that grows or shrinks along i (a slip sweep's samples) is shared
    /// evenly. The same rules as forEach.
    void forEachIndex(std::size_t n, const std::function<void(std::size_t)>& body);

private:
    void work(int index);
    void stopWorkers();
    std::pair<std::size_t, std::size_t> part(int index) const;

    std::vector<std::thread> workers_;
    std::mutex mutex_;
    std::condition_variable start_, done_;
    const std::function<void(std::size_t, std::size_t)>* body_ = nullptr;
    std::size_t n_ = 0;
    std::atomic<unsigned long> generation_{0};
    std::atomic<int> pending_{0};
    std::atomic<bool> stop_{false};
    std::atomic<bool> busy_{false};  // inside forEach
    std::vector<std::exception_ptr> errors_;
};

}  // namespace terra
