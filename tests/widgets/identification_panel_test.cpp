// Streaming playback in the identification panel, on real widgets offscreen: a synthetic drive
// from sandy loam onto clay played at full speed shows a change point at the border it was built
// with; stopping mid-run leaves a consistent panel and no stale frame ever reaches a newer run;
// a bad CSV row is reported with its line number.
#include "widgets/panels/identification_panel.h"

#include <gtest/gtest.h>
#include <qcustomplot.h>

#include <QPushButton>
#include <QSignalSpy>
#include <QTemporaryDir>
#include <QTest>
#include <cmath>
#include <fstream>
#include <sstream>

#include "core/common/units.h"
#include "core/identification/synthetic.h"
#include "core/io/parameters_json.h"
#include "widgets_test_support.h"

namespace terra::ui {
namespace {

using State = StreamingPlayback::State;

// Waits for the playback to end (finished, stopped or failed).
bool waitForEnd(IdentificationPanel& panel, int timeout_ms = 60000) {
    if (!panel.playback().isActive()) return true;
    QSignalSpy ended(&panel, &IdentificationPanel::playbackEnded);
    return ended.wait(timeout_ms);
}

QPushButton* button(IdentificationPanel& panel, const QString& starts_with) {
    for (auto* b : panel.findChildren<QPushButton*>()) {
        if (b->text().contains(starts_with)) return b;
    }
    return nullptr;
}

// The "sample" column of the streamed table must be 0, 1, 2, … with no repeat and no gap: frames
// of another run would break it.
void expectOneRunInOrder(IdentificationPanel& panel, std::size_t expected_count) {
    const Table t = panel.currentTable();
    ASSERT_EQ(t.rows.size(), expected_count);
    const std::size_t col = t.column("sample");
    for (std::size_t i = 0; i < t.rows.size(); ++i)
        ASSERT_EQ(t.rows[i][col], static_cast<double>(i)) << i;
    EXPECT_EQ(panel.streamingFigures().frameCount(), expected_count);
    EXPECT_EQ(panel.streamingFigures().graph("phi")->dataCount(), static_cast<int>(expected_count));
    EXPECT_EQ(panel.streamingFigures().graph("fx_measured")->dataCount(),
              static_cast<int>(expected_count));
}

TEST(IdentificationStreaming, SandyLoamThenClayAtFullSpeedShowsTheBorder) {
    ProjectDocument document;
    test::resetToDefault(document);
    IdentificationPanel panel(&document);
    panel.resize(1200, 700);
    panel.show();
    panel.showPage(1);
    panel.setStreamSource("", "clayey-soil");
    panel.setStreamSpeed(0.0);
    panel.play();
    ASSERT_TRUE(waitForEnd(panel)) << panel.streamStatus().toStdString();
    ASSERT_EQ(panel.playback().state(), State::kFinished) << panel.streamStatus().toStdString();

    // Construction: 101 slips of sandy loam (all carried at 58.86 N on wheel A), then 101 of clay.
    ASSERT_EQ(panel.streamSampleCount(), 202u);
    ASSERT_TRUE(panel.streamTrueBorder().has_value());
    const std::size_t border = *panel.streamTrueBorder();
    EXPECT_EQ(border, 101u);
    expectOneRunInOrder(panel, 202);

    const auto& changes = panel.streamingFigures().changePoints();
    ASSERT_EQ(changes.size(), 1u) << panel.streamStatus().toStdString();
    EXPECT_LE(std::abs(static_cast<long>(changes[0]) - static_cast<long>(border)), 3) << changes[0];
    EXPECT_TRUE(
        panel.streamStatus().contains(QString("change of soil at sample %1").arg(changes[0])))
        << panel.streamStatus().toStdString();

    // The estimates follow the soils where the decoupled model's bias leaves them able to: the
    // shear modulus K of clay (10 mm) is well below sandy loam's (25 mm). (φ and c are not
    // compared: on one load the decoupled fit trades them off, docs/identification.md §2.)
    const Table t = panel.currentTable();
    const double k_before = t.rows[border - 1][t.column("K_m")];
    const double k_after = t.rows.back()[t.column("K_m")];
    EXPECT_LT(k_after, 0.6 * k_before);
    // Right after the border the window restarts: no estimate until it has 12 samples again.
    const std::size_t confirmed = changes[0] + 2;
    EXPECT_EQ(t.rows[confirmed][t.column("estimated")], 0.0);
    // The prediction before the border is the decoupled model's at each sample (finite, and of
    // the measured magnitude: within 30 % of F_z at this load).
    const double fx_pred = t.rows[border - 1][t.column("Fx_predicted_N")];
    EXPECT_TRUE(std::isfinite(fx_pred));
    EXPECT_LT(std::abs(fx_pred - t.rows[border - 1][t.column("Fx_N")]), 0.3 * 58.86);
    // Buttons back to idle.
    EXPECT_TRUE(button(panel, "Play")->isEnabled());
    EXPECT_FALSE(button(panel, "Pause")->isEnabled());
    EXPECT_FALSE(button(panel, "Stop")->isEnabled());
}

TEST(IdentificationStreaming, StopMidRunLeavesAConsistentPanelAndNothingStaleArrives) {
    ProjectDocument document;
    test::resetToDefault(document);
    IdentificationPanel panel(&document);
    panel.resize(1200, 700);
    panel.show();
    panel.showPage(1);
    panel.setStreamSource("", "clayey-soil");
    panel.setStreamSpeed(0.1);  // 202 samples at 100 Hz: 20 s
    panel.play();
    EXPECT_TRUE(button(panel, "Stop")->isEnabled());
    EXPECT_FALSE(button(panel, "Play")->isEnabled());
    ASSERT_TRUE(QTest::qWaitFor([&] { return panel.streamingFigures().frameCount() >= 5; }, 30000));

    // Pause: nothing more arrives; resume goes on.
    panel.pausePlayback();
    EXPECT_EQ(panel.playback().state(), State::kPaused);
    EXPECT_TRUE(button(panel, "Resume")->isEnabled());
    QTest::qWait(100);  // a frame already under way may still land
    const std::size_t paused_at = panel.streamingFigures().frameCount();
    QTest::qWait(400);
    EXPECT_EQ(panel.streamingFigures().frameCount(), paused_at);
    panel.play();  // = resume
    EXPECT_EQ(panel.playback().state(), State::kPlaying);
    ASSERT_TRUE(
        QTest::qWaitFor([&] { return panel.streamingFigures().frameCount() > paused_at; }, 30000));

    panel.stopPlayback();
    EXPECT_EQ(panel.playback().state(), State::kStopped);
    const std::size_t shown = panel.streamingFigures().frameCount();
    EXPECT_LT(shown, 202u);
    QTest::qWait(500);  // the worker may finish its sample: it must not reach the screen
    expectOneRunInOrder(panel, shown);
    EXPECT_TRUE(panel.streamStatus().contains(QString("Stopped after %1 of 202").arg(shown)))
        << panel.streamStatus().toStdString();
    EXPECT_TRUE(button(panel, "Play")->isEnabled());
    EXPECT_FALSE(button(panel, "Pause")->isEnabled());
    EXPECT_FALSE(button(panel, "Stop")->isEnabled());

    // A new run replaces the partial one completely.
    panel.setStreamSpeed(0.0);
    panel.play();
    ASSERT_TRUE(waitForEnd(panel));
    EXPECT_EQ(panel.playback().state(), State::kFinished);
    expectOneRunInOrder(panel, 202);
}

TEST(IdentificationStreaming, RestartingWhilePlayingNeverMixesTheRuns) {
    ProjectDocument document;
    test::resetToDefault(document);
    IdentificationPanel panel(&document);
    panel.showPage(1);
    panel.setStreamSource("", "clayey-soil");
    panel.setStreamSpeed(1.0);
    panel.play();
    ASSERT_TRUE(
        QTest::qWaitFor([&] { return panel.streamingFigures().frameCount() >= 20; }, 30000));
    // Restart on another soil at full speed while the first run is still producing frames.
    panel.setStreamSource("", "dry-sand");
    panel.setStreamSpeed(0.0);
    QSignalSpy ended(&panel, &IdentificationPanel::playbackEnded);
    panel.play();
    ASSERT_EQ(ended.count(), 1);  // the first run, stopped by the restart
    EXPECT_TRUE(panel.streamStatus().startsWith("Playing")) << panel.streamStatus().toStdString();
    ASSERT_TRUE(ended.wait(60000));
    EXPECT_EQ(panel.playback().state(), State::kFinished);
    QTest::qWait(300);
    ASSERT_TRUE(panel.streamTrueBorder().has_value());
    expectOneRunInOrder(panel, panel.streamSampleCount());
    EXPECT_TRUE(panel.streamStatus().contains("dry sand") ||
                panel.streamStatus().contains("dry-sand"))
        << panel.streamStatus().toStdString();
}

TEST(IdentificationStreaming, ABadCsvRowIsReportedWithItsLineNumber) {
    // 20 good samples as CSV, then line 6 (header = line 1) broken.
    identification::SyntheticSpec spec;
    for (int i = 0; i < 20; ++i) spec.slips.push_back(0.05 + 0.04 * i);
    auto soil = io::resolveSoil(test::resources(), "sandy-loam");
    auto wheel = io::resolveWheel(test::resources(), "A");
    ASSERT_TRUE(soil && wheel);
    const auto data =
        identification::synthesize(contact::makeContactParameters(*soil, *wheel), spec).data;
    ASSERT_EQ(data.samples.size(), 20u);
    std::istringstream in(identification::toCsv(data));
    std::vector<std::string> lines;
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    lines[5] = "0.25,abc," + lines[5].substr(lines[5].find(',', lines[5].find(',') + 1) + 1);
    QTemporaryDir dir;
    const std::string path = dir.filePath("broken.csv").toStdString();
    {
        std::ofstream out(path);
        for (const auto& line : lines) out << line << '\n';
    }

    ProjectDocument document;
    test::resetToDefault(document);
    IdentificationPanel panel(&document);
    panel.showPage(1);
    panel.setStreamSource(QString::fromStdString(path));
    panel.setStreamSpeed(0.0);
    panel.play();
    ASSERT_TRUE(waitForEnd(panel));
    EXPECT_EQ(panel.playback().state(), State::kFailed);
    EXPECT_TRUE(panel.streamStatus().contains("broken.csv:6"))
        << panel.streamStatus().toStdString();
    EXPECT_EQ(panel.streamingFigures().frameCount(), 0u);
    EXPECT_TRUE(button(panel, "Play")->isEnabled());

    // Skipping bad rows plays the other 19 and says which line was left out.
    panel.applySettings({{"stream_skip_bad_rows", true}});
    panel.play();
    ASSERT_TRUE(waitForEnd(panel));
    EXPECT_EQ(panel.playback().state(), State::kFinished) << panel.streamStatus().toStdString();
    expectOneRunInOrder(panel, 19);
    EXPECT_TRUE(panel.streamStatus().contains("broken.csv:6"))
        << panel.streamStatus().toStdString();
}

TEST(IdentificationStreaming, SettingsRoundTrip) {
    ProjectDocument document;
    test::resetToDefault(document);
    IdentificationPanel panel(&document);
    panel.applySettings({{"page", "streaming"},
                         {"stream_second_soil", "dry-sand"},
                         {"stream_speed", 10.0},
                         {"stream_noise_percent", 2.5}});
    const nlohmann::json s = panel.settings();
    EXPECT_EQ(s["page"], "streaming");
    EXPECT_EQ(s["stream_second_soil"], "dry-sand");
    EXPECT_DOUBLE_EQ(s["stream_speed"].get<double>(), 10.0);
    EXPECT_DOUBLE_EQ(s["stream_noise_percent"].get<double>(), 2.5);
    EXPECT_EQ(panel.currentPlot(), panel.plots()[3].second);  // the streaming page's figure
}

}  // namespace
}  // namespace terra::ui
