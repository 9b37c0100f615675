// Issue 27, item 3 (honest states): a cancelled or partial result says so everywhere, the same
// way on every panel — the progress bar stays where the run stopped ("37 % (cancelled)"), the
// status line, every plot title (so every export) and the studio's status-bar line carry
// "CANCELLED (partial)" — and a Revert after a cancel leaves every tab on the same run.
#include "widgets/plots/completion.h"

#include <gtest/gtest.h>
#include <qcustomplot.h>

#include <QElapsedTimer>
#include <QFile>
#include <QLabel>
#include <QProgressBar>
#include <QSignalSpy>
#include <QTemporaryDir>
#include <QTest>
#include <functional>
#include <nlohmann/json.hpp>

#include "widgets/panels/compaction_panel.h"
#include "widgets/panels/global_sensitivity_panel.h"
#include "widgets/panels/rover_panel.h"
#include "widgets/plots/figures.h"
#include "widgets/plots/plot_export.h"
#include "widgets_test_support.h"

namespace terra::ui {
namespace {

/// Whether some label of the panel shows `text`.
bool labelSays(const QWidget& panel, const QString& text) {
    for (const QLabel* label : panel.findChildren<QLabel*>()) {
        if (label->text().contains(text)) return true;
    }
    return false;
}

/// Starts the panel's computation, cancels it once it runs (and, with a progress bar, once that
/// moved) and waits for what it shows.
void runAndCancel(AnalysisPanel& panel, const std::function<void()>& start) {
    QSignalSpy busy(&panel, &AnalysisPanel::busyChanged);
    QSignalSpy shown(&panel, &AnalysisPanel::resultShown);
    start();
    ASSERT_TRUE(busy.count() > 0 || busy.wait(10000));
    if (auto* progress = panel.findChild<QProgressBar*>()) {
        QElapsedTimer waited;
        waited.start();
        while (progress->value() <= 0 && waited.elapsed() < 20000) QTest::qWait(10);
    }
    panel.cancelRunning();
    ASSERT_TRUE(shown.count() > 0 || shown.wait(120000));
}

TEST(PlotCompletionWords, TheSameWordsForEveryKindOfPartialResult) {
    EXPECT_EQ(completionMark(Completion::kComplete), "");
    EXPECT_EQ(completionMark(Completion::kCancelled), "CANCELLED (partial)");
    EXPECT_EQ(markedTitle("sandy loam", Completion::kDiverged), "sandy loam — DIVERGED (partial)");
    EXPECT_EQ(markedTitle("sandy loam", Completion::kComplete), "sandy loam");
    // Two lines: the mark on a third, not at the end of the second (cut on a narrow plot).
    EXPECT_EQ(markedTitle("sandy loam, wheel A\ns = 0.1", Completion::kCancelled),
              "sandy loam, wheel A\ns = 0.1\nCANCELLED (partial)");
    EXPECT_EQ(progressFormat(Completion::kComplete), "%p %");
    EXPECT_EQ(progressFormat(Completion::kCancelled), "%p % (cancelled)");
    EXPECT_EQ(progressFormat(Completion::kFailed), "%p % (failed)");
}

// It showed 100 %, "Global sensitivity updated in 2964 ms" and an unmarked title after a cancel.
TEST(PanelHonestStates, ACancelledGlobalStudySaysSoInTheBarTheStatusTheTitleAndTheStatusBar) {
    ProjectDocument document;
    test::resetToDefault(document);
    GlobalSensitivityPanel panel(&document);
    panel.resize(1000, 600);
    panel.setSamples(1 << 16);  // long enough to be cancelled
    runAndCancel(panel, [&panel] { panel.compute(); });
    ASSERT_TRUE(panel.indices().has_value());
    ASSERT_EQ(panel.indices()->status(), gsa::StudyStatus::kCancelled);
    EXPECT_EQ(panel.completion(), Completion::kCancelled);

    auto* progress = panel.findChild<QProgressBar*>();
    ASSERT_NE(progress, nullptr);
    EXPECT_LT(progress->value(), 100);
    EXPECT_TRUE(progress->text().endsWith("% (cancelled)")) << progress->text().toStdString();
    EXPECT_TRUE(labelSays(panel, "CANCELLED (partial)"));
    const QString title = plotTitle(*panel.plots().front().second);
    // On a line of its own: after the title's second line it was cut at both ends (1024×700).
    EXPECT_TRUE(title.endsWith("\nCANCELLED (partial)")) << title.toStdString();
    const QString line = panel.resultMessage("Global sensitivity");
    EXPECT_TRUE(line.startsWith("Global sensitivity: CANCELLED (partial) after"))
        << line.toStdString();
    EXPECT_FALSE(line.contains("updated")) << line.toStdString();

    // Saved and shown again (a reopened project): how far it got is not saved, so its bar says
    // what it is instead of "0 % (cancelled)" (a new user's audit, issue 27).
    const auto saved = panel.savedResults();
    ASSERT_EQ(saved.count("global-sensitivity"), 1u);
    {
        GlobalSensitivityPanel reopened(&document);
        reopened.applySettings(panel.settings());
        ASSERT_TRUE(
            reopened.restoreResult("global-sensitivity", saved.at("global-sensitivity")).shown());
        auto* bar = reopened.findChild<QProgressBar*>();
        ASSERT_NE(bar, nullptr);
        EXPECT_EQ(bar->text(), "CANCELLED (partial) — saved");
        EXPECT_EQ(reopened.completion(), Completion::kCancelled);
    }

    // A complete study afterwards is 100 % and unmarked everywhere.
    QSignalSpy shown(&panel, &AnalysisPanel::resultShown);
    panel.setSamples(32);
    panel.compute();
    ASSERT_TRUE(shown.wait(30000));
    EXPECT_EQ(panel.completion(), Completion::kComplete);
    EXPECT_EQ(progress->value(), 100);
    EXPECT_EQ(progress->text(), "100 %");
    EXPECT_FALSE(plotTitle(*panel.plots().front().second).contains("CANCELLED"));
    EXPECT_FALSE(labelSays(panel, "CANCELLED"));
    EXPECT_TRUE(panel.resultMessage("Global sensitivity").startsWith("Global sensitivity updated"));
}

// The compaction panel marked its titles; the status bar said "updated" all the same.
TEST(PanelHonestStates, ACancelledCompactionRunIsMarkedInTheStatusBarLineToo) {
    ProjectDocument document;
    test::resetToDefault(document);
    CompactionPanel panel(&document, test::resources());
    ASSERT_TRUE(test::waitForResult(panel));
    EXPECT_EQ(panel.completion(), Completion::kComplete);
    runAndCancel(panel, [&panel] { panel.applySettings({{"passes", 50}}); });
    ASSERT_FALSE(panel.result().ok());
    EXPECT_EQ(panel.completion(), Completion::kCancelled);
    EXPECT_TRUE(panel.resultMessage("Compaction").contains("CANCELLED (partial)"));
    EXPECT_TRUE(panel.summary().contains("<b>CANCELLED (partial)</b>"))
        << panel.summary().toStdString();
}

/// The pulse-steering scenario, edited to `duration_s`.
void editDuration(RoverPanel& panel, double duration_s) {
    auto json = nlohmann::json::parse(panel.scenarioText().toStdString());
    json["duration_s"] = duration_s;
    QString error;
    ASSERT_TRUE(panel.setScenarioText(QString::fromStdString(json.dump(2)), &error))
        << error.toStdString();
}

// After a cancel and Revert, the top view said "not run yet" while the other tabs showed the
// cancelled run, and exporting the top view wrote a "not run yet" figure.
TEST(PanelHonestStates, RevertAfterACancelledRoverRunLeavesEveryTabOnThatRun) {
    ProjectDocument document;
    test::resetToDefault(document);
    RoverPanel panel(&document, test::resources());
    panel.applySettings({{"scenario", "pulse-steering"}});
    editDuration(panel, 40.0);
    ASSERT_TRUE(panel.isEdited());
    runAndCancel(panel, [&panel] { panel.recompute(); });
    ASSERT_EQ(panel.result().status, scenario::RunResult::Status::kCancelled);
    ASSERT_GT(panel.result().series.rows.size(), 1u);
    for (const auto& [name, plot] : panel.plots()) {
        EXPECT_TRUE(plotTitle(*plot).contains("CANCELLED (partial)"))
            << name.toStdString() << ": " << plotTitle(*plot).toStdString();
    }

    panel.revertScenario();
    EXPECT_FALSE(panel.isEdited());
    auto* progress = panel.findChild<QProgressBar*>();
    ASSERT_NE(progress, nullptr);
    EXPECT_TRUE(progress->text().endsWith("% (cancelled)")) << progress->text().toStdString();
    // Every tab, the top view included, shows the cancelled run and says the scenario changed.
    for (const auto& [name, plot] : panel.plots()) {
        const QString title = plotTitle(*plot);
        EXPECT_FALSE(title.contains("not run yet")) << name.toStdString();
        EXPECT_TRUE(title.contains("pulse-steering (edited) — CANCELLED (partial)"))
            << name.toStdString() << ": " << title.toStdString();
        EXPECT_TRUE(title.contains("press Run")) << name.toStdString();
    }
    EXPECT_TRUE(labelSays(panel, "CANCELLED (partial)"));
    // And so do the exported files: the top view as SVG (its title is text there) and as PDF.
    QTemporaryDir dir;
    QString error;
    ASSERT_TRUE(exportPlot(*panel.topView(), dir.filePath("top.svg"), {}, &error))
        << error.toStdString();
    QFile svg(dir.filePath("top.svg"));
    ASSERT_TRUE(svg.open(QIODevice::ReadOnly));
    const QString written = QString::fromUtf8(svg.readAll());
    EXPECT_TRUE(written.contains("CANCELLED (partial)"));
    EXPECT_FALSE(written.contains("not run yet"));
    ASSERT_TRUE(exportPlot(*panel.topView(), dir.filePath("top.pdf"), {}, &error))
        << error.toStdString();
    QFile pdf(dir.filePath("top.pdf"));
    ASSERT_TRUE(pdf.open(QIODevice::ReadOnly));
    EXPECT_TRUE(pdf.read(5) == "%PDF-");

    // Back to the edit that ran: the titles are the run's own again.
    editDuration(panel, 40.0);
    for (const auto& [name, plot] : panel.plots()) {
        EXPECT_EQ(plotTitle(*plot), "pulse-steering (edited) — CANCELLED (partial)")
            << name.toStdString();
    }
}

}  // namespace
}  // namespace terra::ui
