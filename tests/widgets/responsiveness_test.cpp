// GUI-thread responsiveness (issue 5: "the GUI thread never blocks longer than 50 ms during any
// analysis or scenario run"), instrumented, not timed: a QTimer heartbeat every 5 ms on the GUI
// thread records the gaps between its beats while the real panels work (offscreen), and the test
// REPORTS the longest gap and the 99th percentile per case. It asserts only a loose freeze guard
// (< 1 s), because on a loaded machine the scheduler alone can delay a beat by tens of ms; the
// figures and the machine load they were taken at are in docs/performance.md ("Studio
// responsiveness").
#include <gtest/gtest.h>
#include <qcustomplot.h>

#include <QElapsedTimer>
#include <QPushButton>
#include <QSignalSpy>
#include <QSlider>
#include <QTest>
#include <QTimer>
#include <QVBoxLayout>
#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "widgets/editors/property_editors.h"
#include "widgets/panels/forces_panel.h"
#include "widgets/panels/identification_panel.h"
#include "widgets/panels/rover_panel.h"
#include "widgets_test_support.h"

namespace terra::ui {
namespace {

constexpr double kFreezeGuardMs = 1000.0;  // a real freeze, not scheduling noise

// Beats every 5 ms on the GUI thread; the gaps between beats are how long the thread was busy
// (plus the 5 ms period).
class Heartbeat {
public:
    Heartbeat() {
        timer_.setTimerType(Qt::PreciseTimer);
        timer_.setInterval(5);
        QObject::connect(&timer_, &QTimer::timeout, [this] {
            const qint64 now = clock_.nsecsElapsed();
            gaps_ms_.push_back(static_cast<double>(now - last_ns_) / 1e6);
            last_ns_ = now;
        });
    }
    void start() {
        gaps_ms_.clear();
        clock_.start();
        last_ns_ = 0;
        timer_.start();
    }
    void stop() { timer_.stop(); }

    struct Stats {
        double max_ms = 0.0, p99_ms = 0.0, median_ms = 0.0;
        std::size_t beats = 0, over_50ms = 0;
    };
    Stats stats() const {
        Stats s;
        std::vector<double> g = gaps_ms_;
        if (g.empty()) return s;
        std::sort(g.begin(), g.end());
        s.beats = g.size();
        s.max_ms = g.back();
        s.median_ms = g[g.size() / 2];
        s.p99_ms = g[std::min(g.size() - 1,
                              static_cast<std::size_t>(0.99 * static_cast<double>(g.size())))];
        s.over_50ms = static_cast<std::size_t>(
            std::count_if(g.begin(), g.end(), [](double x) { return x > 50.0; }));
        return s;
    }

private:
    QTimer timer_;
    QElapsedTimer clock_;
    qint64 last_ns_ = 0;
    std::vector<double> gaps_ms_;
};

std::string loadAverage() {
    std::FILE* f = std::fopen("/proc/loadavg", "r");
    if (!f) return "?";
    char buffer[64] = {};
    const std::size_t n = std::fread(buffer, 1, sizeof buffer - 1, f);
    std::fclose(f);
    std::string s(buffer, n);
    return s.substr(0, s.find(' ', s.find(' ', s.find(' ') + 1) + 1));  // the 1, 5, 15 min averages
}

void report(const char* name, const Heartbeat::Stats& s, const std::string& extra) {
    std::printf(
        "[ gui gap  ] %-34s max %6.1f ms  p99 %5.1f ms  median %4.1f ms  >50 ms: %zu of %zu beats%s"
        "  (load %s)\n",
        name, s.max_ms, s.p99_ms, s.median_ms, s.over_50ms, s.beats, extra.c_str(),
        loadAverage().c_str());
    std::fflush(stdout);
    ::testing::Test::RecordProperty(std::string(name) + "_max_gap_ms", std::to_string(s.max_ms));
    ::testing::Test::RecordProperty(std::string(name) + "_p99_gap_ms", std::to_string(s.p99_ms));
}

QPushButton* buttonWithText(QWidget& parent, const QString& text) {
    for (auto* b : parent.findChildren<QPushButton*>()) {
        if (b->text().contains(text)) return b;
    }
    return nullptr;
}

// The baseline: nothing to do but beat. What this shows above the 5 ms period is the machine's
// scheduling (other processes), not the studio.
TEST(Responsiveness, IdleBaseline) {
    Heartbeat beat;
    beat.start();
    QTest::qWait(2000);
    beat.stop();
    const auto s = beat.stats();
    report("idle (baseline)", s, "");
    EXPECT_LT(s.max_ms, kFreezeGuardMs);
}

// (a) A user drags the friction-angle slider back and forth (60 position updates per second,
// the slider held down as in a drag) for 3 s while the forces panel recomputes live.
TEST(Responsiveness, DraggingASoilSliderOnTheForcesPanel) {
    ProjectDocument document;
    test::resetToDefault(document);
    QWidget window;
    auto* layout = new QHBoxLayout(&window);
    auto* editor = new SoilEditor(&document, test::resources(), &window);
    auto* panel = new ForcesPanel(&document, &window);
    layout->addWidget(editor);
    layout->addWidget(panel, 1);
    window.resize(1400, 800);
    window.show();
    ASSERT_TRUE(test::waitForResult(*panel));
    auto* slider = editor->findChild<QSlider*>("soil.phi_deg.slider");
    ASSERT_NE(slider, nullptr);
    const int centre = slider->value();
    const int swing = std::max(10, (slider->maximum() - slider->minimum()) / 20);

    std::vector<double> present_ms;
    QObject::connect(panel, &AnalysisPanel::resultShown,
                     [&] { present_ms.push_back(panel->lastPresentMs()); });
    std::vector<double> edit_ms;
    int edits = 0;
    QObject::connect(&document, &ProjectDocument::changed, [&] { ++edits; });
    Heartbeat beat;
    QTimer drag;
    int step = 0;
    QObject::connect(&drag, &QTimer::timeout, [&] {
        // A triangle wave over ±swing: repeated drags across the value.
        const int phase = step++ % 60;
        const int offset =
            phase < 30 ? -swing + 2 * swing * phase / 30 : swing - 2 * swing * (phase - 30) / 30;
        QElapsedTimer edit;
        edit.start();
        slider->setSliderPosition(centre + offset);  // slider → spin box → undo command → document
        edit_ms.push_back(static_cast<double>(edit.nsecsElapsed()) / 1e6);
    });
    slider->setSliderDown(true);
    beat.start();
    drag.start(16);
    QTest::qWait(3000);
    drag.stop();
    slider->setSliderDown(false);
    ASSERT_TRUE(test::waitForResult(*panel));  // the last state reaches the screen
    QTest::qWait(200);
    beat.stop();
    const auto s = beat.stats();
    std::sort(present_ms.begin(), present_ms.end());
    std::sort(edit_ms.begin(), edit_ms.end());
    char extra[240];
    std::snprintf(extra, sizeof extra,
                  "; %zu redraws for %d edits, drawing max %.1f ms, median %.1f ms; %zu slider "
                  "moves, handling "
                  "max %.1f ms, median %.1f ms",
                  present_ms.size(), edits, present_ms.empty() ? 0.0 : present_ms.back(),
                  present_ms.empty() ? 0.0 : present_ms[present_ms.size() / 2], edit_ms.size(),
                  edit_ms.back(), edit_ms[edit_ms.size() / 2]);
    report("forces panel, slider drag", s, extra);
    EXPECT_GT(step, 100);
    // At least the final state reaches the screen. How many intermediate states do depends on
    // whether one computation fits between two moves (machine load): reported, not asserted.
    EXPECT_GE(present_ms.size(), 1u);
    EXPECT_FALSE(panel->isBusy());
    EXPECT_LT(s.max_ms, kFreezeGuardMs);
}

// (b) The 60 s pulse-steering scenario run from the rover panel's Run button, through its
// progress updates and the drawing of the result.
TEST(Responsiveness, RoverScenarioRun) {
    ProjectDocument document;
    test::resetToDefault(document);
    RoverPanel panel(&document, test::resources());
    panel.resize(1200, 700);
    panel.show();
    panel.applySettings({{"scenario", "pulse-steering"}});
    QPushButton* run = buttonWithText(panel, "Run");
    ASSERT_NE(run, nullptr);
    QSignalSpy shown(&panel, &AnalysisPanel::resultShown);
    Heartbeat beat;
    beat.start();
    QTest::mouseClick(run, Qt::LeftButton);
    ASSERT_TRUE(shown.wait(300000));
    QTest::qWait(300);  // queued repaints after present()
    beat.stop();
    const auto s = beat.stats();
    QStringList replots;
    for (const auto& [name, plot] : panel.plots())
        replots << QString::number(plot->replotTime(), 'f', 1);
    char extra[240];
    std::snprintf(extra, sizeof extra,
                  "; run %.0f ms, drawing the result %.1f ms (replots %s ms), %zu series rows",
                  panel.lastLatencyMs(), panel.lastPresentMs(), qPrintable(replots.join("/")),
                  panel.result().series.rows.size());
    report("rover panel, pulse-steering run", s, extra);
    EXPECT_EQ(panel.result().status, scenario::RunResult::Status::kCompleted);
    EXPECT_LT(s.max_ms, kFreezeGuardMs);
}

// (c) An identification fit (three loads, full-model refinement), then the streaming playback of
// the sandy-loam → clay drive at full speed and at 10×.
TEST(Responsiveness, IdentificationFitAndStreamingPlayback) {
    ProjectDocument document;
    test::resetToDefault(document);
    IdentificationPanel panel(&document);
    panel.resize(1200, 700);
    panel.show();
    panel.applySettings({{"noise_percent", 1.0}, {"refine", true}, {"three_loads", true}});
    {
        Heartbeat beat;
        beat.start();
        panel.recompute();
        ASSERT_TRUE(test::waitForResult(panel, 300000));
        QTest::qWait(300);
        beat.stop();
        const auto s = beat.stats();
        char extra[128];
        std::snprintf(extra, sizeof extra, "; fit %.0f ms, drawing %.1f ms",
                      panel.result().fit_time_ms, panel.lastPresentMs());
        report("identification fit", s, extra);
        EXPECT_LT(s.max_ms, kFreezeGuardMs);
    }
    panel.showPage(1);
    panel.setStreamSource("", "clayey-soil");
    for (double speed : {0.0, 10.0}) {
        panel.setStreamSpeed(speed);
        QSignalSpy ended(&panel, &IdentificationPanel::playbackEnded);
        Heartbeat beat;
        beat.start();
        QElapsedTimer wall;
        wall.start();
        panel.play();
        ASSERT_TRUE(ended.wait(120000));
        const double wall_ms = static_cast<double>(wall.elapsed());
        QTest::qWait(300);
        beat.stop();
        const auto s = beat.stats();
        EXPECT_EQ(panel.playback().state(), StreamingPlayback::State::kFinished);
        double replot_ms = 0.0;
        for (int i : {3, 4})
            replot_ms = std::max(replot_ms,
                                 panel.plots()[static_cast<std::size_t>(i)].second->replotTime());
        char extra[160];
        std::snprintf(extra, sizeof extra, "; %zu samples in %.0f ms, last replot %.1f ms",
                      panel.streamSampleCount(), wall_ms, replot_ms);
        report(speed == 0.0 ? "streaming playback, max speed" : "streaming playback, 10x", s,
               extra);
        EXPECT_LT(s.max_ms, kFreezeGuardMs);
    }
}

}  // namespace
}  // namespace terra::ui
