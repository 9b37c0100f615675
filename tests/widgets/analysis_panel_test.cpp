// AnalysisPanel scheduling: edits faster than one computation still move the plot (intermediate
// frames at least every kMaxFrameGapMs plus one computation), stale results of cancelled runs are
// never shown, and the last state of a burst is always the one left on screen.
#include <gtest/gtest.h>

#include <QCoreApplication>
#include <QElapsedTimer>
#include <chrono>
#include <thread>
#include <vector>

#include "widgets_test_support.h"

namespace terra::ui {
namespace {

// A panel whose computation takes `work_ms` (checking its cancel flag every millisecond) and
// returns the document revision it was started from.
class SlowPanel : public AnalysisPanel {
public:
    SlowPanel(ProjectDocument* document, int work_ms)
        : AnalysisPanel(document, "slow"), work_ms_(work_ms) {}
    std::vector<std::pair<QString, QCustomPlot*>> plots() const override { return {}; }
    QCustomPlot* currentPlot() const override { return nullptr; }
    Table currentTable() const override { return {}; }

    std::vector<int> shown;  // revisions presented, in order

protected:
    Job makeJob() override {
        const int revision = document_->revision();
        const int work_ms = work_ms_;
        return [revision, work_ms](const std::atomic<bool>& cancel) -> std::any {
            for (int i = 0; i < work_ms; ++i) {
                if (cancel.load()) return std::any(-revision);  // partial: must never be shown
                std::this_thread::sleep_for(std::chrono::milliseconds(1));
            }
            return std::any(revision);
        };
    }
    void present(const std::any& value) override { shown.push_back(std::any_cast<int>(value)); }

private:
    int work_ms_;
};

// Edits every 10 ms for 1.2 s against a 60 ms computation: without intermediate frames every run
// would be cancelled by the next edit and nothing would be drawn until the drag stops.
TEST(AnalysisPanel, ContinuousEditsStillDrawIntermediateFrames) {
    ProjectDocument document;
    test::resetToDefault(document);
    SlowPanel panel(&document, 60);
    double phi = 29.0;
    QElapsedTimer clock;
    clock.start();
    while (clock.elapsed() < 1200) {
        phi = phi == 29.0 ? 29.5 : 29.0;
        ASSERT_TRUE(document.setSoilValue("phi_deg", phi));
        const qint64 until = clock.elapsed() + 10;
        while (clock.elapsed() < until) QCoreApplication::processEvents(QEventLoop::AllEvents, 2);
    }
    const std::size_t during_drag = panel.shown.size();
    // 1.2 s at one frame per ≤ 150 ms + a 60 ms computation: ≥ 5 frames even with slack for a
    // loaded machine (starvation gave 0).
    EXPECT_GE(during_drag, 3u) << "frames drawn while edits kept arriving";
    for (const int revision : panel.shown)
        EXPECT_GT(revision, 0) << "a cancelled (partial) result was drawn";

    ASSERT_TRUE(test::waitForResult(panel, 10000));
    ASSERT_FALSE(panel.shown.empty());
    EXPECT_EQ(panel.shown.back(), document.revision())
        << "the final state of the burst is on screen";
}

// A burst shorter than the frame gap cancels the running computation: only the last state is drawn.
TEST(AnalysisPanel, ShortBurstShowsOnlyTheLastState) {
    ProjectDocument document;
    test::resetToDefault(document);
    SlowPanel panel(&document, 200);
    panel.recompute();
    ASSERT_TRUE(test::waitForResult(panel, 10000));
    panel.shown.clear();
    for (const double phi : {30.0, 31.0, 32.0}) {
        ASSERT_TRUE(document.setSoilValue("phi_deg", phi));
        QCoreApplication::processEvents();
    }
    ASSERT_TRUE(test::waitForResult(panel, 10000));
    ASSERT_EQ(panel.shown.size(), 1u);
    EXPECT_EQ(panel.shown.back(), document.revision());
}

}  // namespace
}  // namespace terra::ui
