#pragma once
/// @file interruptible.h
/// Long core calls from Python that Ctrl-C stops and that can report progress.
///
/// The work runs on a worker thread with the GIL released. The calling thread wakes every
/// 50 ms, takes the GIL and runs Python's signal handlers (PyErr_CheckSignals: Ctrl-C raises
/// KeyboardInterrupt there) and, when given, the progress callback with the fraction done. On
/// an exception from either, the work's cancel flag is set, the worker is joined (the core's
/// loops check the flag about every 1 % of the work) and the exception propagates to Python.
/// Nothing is returned from a cancelled call: a partial result is the CLI's business, not a
/// function's.

#include <pybind11/pybind11.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <functional>
#include <mutex>
#include <optional>
#include <thread>
#include <utility>

namespace terra::python {

namespace py = pybind11;

/// What the work gets: the flag to poll and where to report the fraction done.
struct WorkControl {
    const std::atomic<bool>* cancel = nullptr;
    std::function<void(double)> progress;
};

/// Runs `work(WorkControl)` interruptibly (see the file comment) and returns its result. Call
/// with the GIL held. `progress`: None or a callable taking the fraction done in [0, 1].
template <class Work>
auto runInterruptible(Work&& work, const py::object& progress) {
    using Result = decltype(work(std::declval<const WorkControl&>()));
    std::atomic<bool> cancel{false};
    std::atomic<double> fraction{0.0};
    std::mutex mutex;
    std::condition_variable finished;
    bool done = false;
    std::optional<Result> result;
    std::exception_ptr failure;
    WorkControl control{&cancel, [&fraction](double f) { fraction.store(f); }};

    std::optional<py::error_already_set> python_error;
    {
        py::gil_scoped_release release;
        std::thread worker([&] {
            try {
                result.emplace(work(control));
            } catch (...) {
                failure = std::current_exception();
            }
            const std::lock_guard lock(mutex);
            done = true;
            finished.notify_one();
        });
        double reported = -1.0;
        for (;;) {
            {
                std::unique_lock lock(mutex);
                if (finished.wait_for(lock, std::chrono::milliseconds(50), [&] { return done; }))
                    break;
            }
            if (cancel.load()) continue;  // interrupted already: wait for the worker to stop
            const py::gil_scoped_acquire acquire;
            if (PyErr_CheckSignals() != 0) {
                python_error.emplace();  // fetches the pending KeyboardInterrupt
                cancel.store(true);
                continue;
            }
            const double f = fraction.load();
            if (!progress.is_none() && f != reported) {
                try {
                    progress(f);
                    reported = f;
                } catch (py::error_already_set& e) {
                    python_error.emplace(std::move(e));
                    cancel.store(true);
                }
            }
        }
        worker.join();
    }
    if (python_error) throw std::move(*python_error);
    if (failure) std::rethrow_exception(failure);
    if (!progress.is_none()) progress(1.0);
    return std::move(*result);
}

}  // namespace terra::python
