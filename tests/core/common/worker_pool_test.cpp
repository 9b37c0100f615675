// WorkerPool (core/common/worker_pool.h): every index once, in contiguous parts, exceptions
// carried back to the caller, the pool usable again afterwards.
#include "core/common/worker_pool.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>
#include <vector>

namespace terra {
namespace {

TEST(WorkerPool, EveryIndexOnceOnEveryThreadCount) {
    for (const int threads : {1, 2, 3, 8}) {
        WorkerPool pool(threads);
        EXPECT_EQ(pool.threads(), threads);
        for (const std::size_t n : {0u, 1u, 2u, 5u, 91u}) {
            std::vector<std::atomic<int>> seen(n);
            std::atomic<int> parts{0};
            pool.forEach(n, [&](std::size_t begin, std::size_t end) {
                EXPECT_LE(begin, end);
                if (begin < end) ++parts;
                for (std::size_t i = begin; i < end; ++i) ++seen[i];
            });
            for (std::size_t i = 0; i < n; ++i) EXPECT_EQ(seen[i], 1) << threads << ", " << n;
            // One part per thread at most, and never more parts than indices.
            EXPECT_LE(parts.load(), std::min<int>(threads, static_cast<int>(n)));
        }
    }
}

TEST(WorkerPool, EveryIndexOnceInterleaved) {
    // forEachIndex: thread k takes k, k + threads, …; every index once whatever the counts.
    for (const int threads : {1, 2, 3}) {
        WorkerPool pool(threads);
        for (const std::size_t n : {0u, 1u, 2u, 7u, 91u}) {
            std::vector<std::atomic<int>> seen(n);
            pool.forEachIndex(n, [&](std::size_t i) { ++seen[i]; });
            for (std::size_t i = 0; i < n; ++i) EXPECT_EQ(seen[i], 1) << threads << ", " << n;
        }
    }
    // Two threads: the even indices on one thread, the odd on the other.
    WorkerPool pool(2);
    std::vector<std::thread::id> by(10);
    pool.forEachIndex(10, [&](std::size_t i) { by[i] = std::this_thread::get_id(); });
    for (std::size_t i = 2; i < 10; ++i) EXPECT_EQ(by[i], by[i - 2]) << i;
    EXPECT_NE(by[0], by[1]);
}

TEST(WorkerPool, RunsThePartsOnSeveralThreads) {
    WorkerPool pool(2);
    std::set<std::thread::id> ids;
    std::mutex mutex;
    pool.forEach(2, [&](std::size_t, std::size_t) {
        const std::lock_guard lock(mutex);
        ids.insert(std::this_thread::get_id());
    });
    EXPECT_EQ(ids.size(), 2u);
    EXPECT_EQ(ids.count(std::this_thread::get_id()), 1u);  // the caller ran one
}

TEST(WorkerPool, AnExceptionOfAPartReachesTheCallerAndThePoolGoesOn) {
    WorkerPool pool(2);
    // The worker's part (the second half) throws.
    EXPECT_THROW(pool.forEach(10,
                              [](std::size_t begin, std::size_t) {
                                  if (begin > 0) throw std::runtime_error("worker");
                              }),
                 std::runtime_error);
    // The caller's part throws, after waiting for the worker.
    std::atomic<int> done{0};
    EXPECT_THROW(pool.forEach(10,
                              [&](std::size_t begin, std::size_t) {
                                  if (begin == 0) throw std::invalid_argument("caller");
                                  ++done;
                              }),
                 std::invalid_argument);
    EXPECT_EQ(done, 1);
    int sum = 0;
    std::mutex mutex;
    pool.forEach(4, [&](std::size_t begin, std::size_t end) {
        const std::lock_guard lock(mutex);
        for (std::size_t i = begin; i < end; ++i) sum += static_cast<int>(i);
    });
    EXPECT_EQ(sum, 0 + 1 + 2 + 3);
}

TEST(WorkerPool, AForEachInsideAForEachIsRefused) {
    // It would wait for itself: refused with std::logic_error, from the caller's part (a
    // worker's part would rethrow the same through the caller), and the pool goes on.
    WorkerPool pool(2);
    EXPECT_THROW(pool.forEach(2,
                              [&](std::size_t begin, std::size_t) {
                                  if (begin == 0) pool.forEach(1, [](std::size_t, std::size_t) {});
                              }),
                 std::logic_error);
    std::atomic<int> count{0};
    pool.forEach(
        2, [&](std::size_t begin, std::size_t end) { count += static_cast<int>(end - begin); });
    EXPECT_EQ(count, 2);
}

}  // namespace
}  // namespace terra
