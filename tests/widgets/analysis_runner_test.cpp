// The worker plumbing of the studio's panels and dialogs (widgets/panels/analysis_runner.h), on
// real Qt objects: jobs run on a worker thread, a superseded result is dropped (newest wins), a
// cancelled job keeps its partial result and says it was cancelled, progress reaches the GUI
// thread, and the busy signal goes true once and false once around a chain of jobs.
#include "widgets/panels/analysis_runner.h"

#include <gtest/gtest.h>

#include <QCoreApplication>
#include <QTest>
#include <QThread>
#include <chrono>
#include <memory>
#include <stdexcept>
#include <thread>
#include <vector>

namespace terra::ui {
namespace {

// What a runner said, in order.
struct RunnerRecord {
    explicit RunnerRecord(AnalysisRunner& runner) {
        QObject::connect(&runner, &AnalysisRunner::finished,
                         [this](const AnalysisRunner::Outcome& o) { finished.push_back(o); });
        QObject::connect(&runner, &AnalysisRunner::superseded,
                         [this](const AnalysisRunner::Outcome& o) { superseded.push_back(o); });
        QObject::connect(&runner, &AnalysisRunner::busyChanged,
                         [this](bool busy) { busy_changes.push_back(busy); });
        QObject::connect(&runner, &AnalysisRunner::progressed,
                         [this](double fraction) { progress.push_back(fraction); });
    }
    std::vector<AnalysisRunner::Outcome> finished, superseded;
    std::vector<bool> busy_changes;
    std::vector<double> progress;
};

// A job that waits until `gate` opens or its cancel flag is set, then returns `id`; it notes
// whether it ran off the GUI thread.
AnalysisRunner::Job gatedJob(std::shared_ptr<std::atomic<bool>> gate, int id,
                             std::shared_ptr<std::atomic<bool>> on_worker = nullptr) {
    return [gate, id, on_worker](const analysis::Control& control) -> std::any {
        if (on_worker)
            on_worker->store(QThread::currentThread() != QCoreApplication::instance()->thread());
        while (!gate->load() && !control.cancelled())
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
        return id;
    };
}

TEST(AnalysisRunner, RunsTheJobOnAWorkerAndHandsItsResultBackWhenItEnds) {
    AnalysisRunner runner;
    RunnerRecord record(runner);
    auto gate = std::make_shared<std::atomic<bool>>(false);
    auto on_worker = std::make_shared<std::atomic<bool>>(false);
    ASSERT_TRUE(runner.start(gatedJob(gate, 7, on_worker)));
    EXPECT_TRUE(runner.isRunning());
    EXPECT_TRUE(runner.isBusy());
    // One job at a time: start refuses while one runs.
    EXPECT_FALSE(runner.start(gatedJob(gate, 8)));
    // The GUI thread is free meanwhile: its event loop turns while the job waits.
    QTest::qWait(20);
    EXPECT_TRUE(record.finished.empty());
    gate->store(true);
    ASSERT_TRUE(QTest::qWaitFor([&] { return !record.finished.empty(); }, 10000));
    EXPECT_TRUE(on_worker->load());
    ASSERT_EQ(record.finished.size(), 1U);
    EXPECT_EQ(std::any_cast<int>(record.finished[0].value), 7);
    EXPECT_FALSE(record.finished[0].cancelled);
    EXPECT_TRUE(record.finished[0].error.isEmpty());
    EXPECT_TRUE(record.superseded.empty());
    EXPECT_EQ(record.busy_changes, (std::vector<bool>{true, false}));
    EXPECT_FALSE(runner.isBusy());
}

TEST(AnalysisRunner, ASupersededResultIsDroppedAndTheNewestIsShown) {
    AnalysisRunner runner;
    RunnerRecord record(runner);
    auto gate = std::make_shared<std::atomic<bool>>(false);
    runner.submit(gatedJob(gate, 1));  // starts now
    runner.submit(gatedJob(gate, 2));  // cancels job 1, waits for the worker
    runner.submit(gatedJob(gate, 3));  // replaces job 2, which never starts
    gate->store(true);
    ASSERT_TRUE(QTest::qWaitFor([&] { return !record.finished.empty(); }, 10000));
    QTest::qWait(20);  // nothing else arrives
    ASSERT_EQ(record.finished.size(), 1U);
    EXPECT_EQ(std::any_cast<int>(record.finished[0].value), 3);
    EXPECT_FALSE(record.finished[0].cancelled);
    // Job 1 ended as superseded, cancelled by the newer submission; job 2 never ran.
    ASSERT_EQ(record.superseded.size(), 1U);
    EXPECT_EQ(std::any_cast<int>(record.superseded[0].value), 1);
    EXPECT_TRUE(record.superseded[0].cancelled);
    // Busy from the first start to the end of the last job, with no "idle" in between.
    EXPECT_EQ(record.busy_changes, (std::vector<bool>{true, false}));
}

TEST(AnalysisRunner, SupersedeWithoutCancelLetsTheStaleJobFinishAsSuperseded) {
    // AnalysisPanel's intermediate frames: a stale job is let run to its end, and its result
    // arrives complete but marked stale, for the panel to show or drop.
    AnalysisRunner runner;
    RunnerRecord record(runner);
    auto gate = std::make_shared<std::atomic<bool>>(false);
    ASSERT_TRUE(runner.start(gatedJob(gate, 4)));
    const int before = runner.revision();
    EXPECT_EQ(runner.supersede(), before + 1);
    gate->store(true);
    ASSERT_TRUE(QTest::qWaitFor(
        [&] { return !record.busy_changes.empty() && !record.busy_changes.back(); }, 10000));
    EXPECT_TRUE(record.finished.empty());
    ASSERT_EQ(record.superseded.size(), 1U);
    EXPECT_EQ(record.superseded[0].revision, before);
    EXPECT_EQ(std::any_cast<int>(record.superseded[0].value), 4);
    EXPECT_FALSE(record.superseded[0].cancelled);
}

TEST(AnalysisRunner, CancelKeepsThePartialResultAndSaysItWasCancelled) {
    AnalysisRunner runner;
    RunnerRecord record(runner);
    constexpr int kSteps = 1000000;
    // Counts steps until cancelled, reporting progress: what it returns is the partial count.
    ASSERT_TRUE(runner.start([](const analysis::Control& control) -> std::any {
        int steps = 0;
        for (; steps < kSteps && !control.cancelled(); ++steps) {
            control.report(static_cast<double>(steps + 1) / kSteps);
            std::this_thread::sleep_for(std::chrono::microseconds(100));
        }
        return steps;
    }));
    ASSERT_TRUE(QTest::qWaitFor([&] { return !record.progress.empty(); }, 10000));
    runner.cancel();
    ASSERT_TRUE(QTest::qWaitFor([&] { return !record.finished.empty(); }, 10000));
    const AnalysisRunner::Outcome& outcome = record.finished[0];
    EXPECT_TRUE(outcome.cancelled);
    EXPECT_TRUE(outcome.error.isEmpty());
    const int steps = std::any_cast<int>(outcome.value);
    EXPECT_GT(steps, 0);
    EXPECT_LT(steps, kSteps);
    // Progress arrived on the GUI thread as fractions of the whole, increasing.
    for (std::size_t i = 0; i < record.progress.size(); ++i) {
        EXPECT_GT(record.progress[i], 0.0);
        EXPECT_LE(record.progress[i], 1.0);
        if (i > 0) {
            EXPECT_GE(record.progress[i], record.progress[i - 1]);
        }
    }
    EXPECT_EQ(record.busy_changes, (std::vector<bool>{true, false}));
}

TEST(AnalysisRunner, AJobThatThrowsEndsWithItsMessage) {
    AnalysisRunner runner;
    RunnerRecord record(runner);
    ASSERT_TRUE(runner.start([](const analysis::Control&) -> std::any {
        throw std::invalid_argument("prior: no soil preset 'loam'");
    }));
    ASSERT_TRUE(QTest::qWaitFor([&] { return !record.finished.empty(); }, 10000));
    EXPECT_EQ(record.finished[0].error, "prior: no soil preset 'loam'");
    EXPECT_FALSE(record.finished[0].value.has_value());
    EXPECT_FALSE(record.finished[0].cancelled);
    EXPECT_EQ(record.busy_changes, (std::vector<bool>{true, false}));
}

TEST(AnalysisRunner, DestroyedWhileAJobRunsCancelsItAndWaitsForIt) {
    auto saw_cancel = std::make_shared<std::atomic<bool>>(false);
    {
        AnalysisRunner runner;
        ASSERT_TRUE(runner.start([saw_cancel](const analysis::Control& control) -> std::any {
            while (!control.cancelled()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
            saw_cancel->store(true);
            return 0;
        }));
    }
    // The destructor returned only once the job had seen its flag and ended.
    EXPECT_TRUE(saw_cancel->load());
}

}  // namespace
}  // namespace terra::ui
