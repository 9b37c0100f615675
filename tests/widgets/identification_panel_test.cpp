// Streaming playback in the identification panel, on real widgets offscreen: a synthetic drive
// from sandy loam onto clay played at full speed shows a change point at the border it was built
// with; stopping mid-run leaves a consistent panel and no stale frame ever reaches a newer run;
// a bad CSV row is reported with its line number.
#include "widgets/panels/identification_panel.h"

#include <gtest/gtest.h>
#include <qcustomplot.h>

#include <QApplication>
#include <QDoubleSpinBox>
#include <QLabel>
#include <QProgressBar>
#include <QPushButton>
#include <QRegularExpression>
#include <QSignalSpy>
#include <QTemporaryDir>
#include <QTest>
#include <QUndoStack>
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
    // ±σ bands around every estimate: below and above it by the std the frame carries.
    const auto& figures = panel.streamingFigures();
    ASSERT_EQ(figures.graph("K_lo")->dataCount(), 202);
    const double k_std = t.rows.back()[t.column("K_m_std")];
    EXPECT_GT(k_std, 0.0);
    EXPECT_NEAR((figures.graph("K_hi")->data()->constEnd() - 1)->value, k_after + k_std, 1e-12);
    EXPECT_NEAR((figures.graph("K_lo")->data()->constEnd() - 1)->value, k_after - k_std, 1e-12);
    // The confirmed change is marked where it was confirmed, after it began.
    ASSERT_EQ(figures.confirmedAt().size(), 1u);
    EXPECT_GE(figures.confirmedAt()[0], changes[0]);
    EXPECT_LE(figures.confirmedAt()[0], border + 10);
    // Right after the confirmation the estimator re-initialises from the change point: no estimate
    // until it has its 30 initialisation samples again.
    ASSERT_EQ(panel.streamingFigures().confirmedAt().size(), 1u);
    const std::size_t confirmed = panel.streamingFigures().confirmedAt()[0];
    EXPECT_EQ(t.rows[confirmed][t.column("estimated")], 0.0);
    // The prediction before the border is the full model's at each sample (finite, and of the
    // measured magnitude: within 30 % of F_z at this load).
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
    EXPECT_TRUE(panel.streamStatus().contains(QString("stopped after %1 of 202").arg(shown)))
        << panel.streamStatus().toStdString();
    // Marked as every panel marks a cancelled run: the status and the plot's title (issue 27).
    EXPECT_TRUE(panel.streamStatus().contains("CANCELLED (partial)"))
        << panel.streamStatus().toStdString();
    EXPECT_TRUE(panel.streamingFigures().title().endsWith(" — CANCELLED (partial)"))
        << panel.streamingFigures().title().toStdString();
    EXPECT_TRUE(button(panel, "Play")->isEnabled());
    EXPECT_FALSE(button(panel, "Pause")->isEnabled());
    EXPECT_FALSE(button(panel, "Stop")->isEnabled());

    // A new run replaces the partial one completely.
    panel.setStreamSpeed(0.0);
    panel.play();
    ASSERT_TRUE(waitForEnd(panel));
    EXPECT_EQ(panel.playback().state(), State::kFinished);
    EXPECT_FALSE(panel.streamingFigures().title().contains("CANCELLED"));
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
    // It does not hang on "preparing…": the position bar says the run failed.
    const auto* position = panel.findChild<QProgressBar*>();
    ASSERT_NE(position, nullptr);
    EXPECT_FALSE(position->format().contains("preparing")) << position->format().toStdString();
    EXPECT_TRUE(position->format().contains("failed")) << position->format().toStdString();

    // Skipping bad rows plays the other 19 and says which line was left out.
    panel.applySettings({{"stream_skip_bad_rows", true}});
    panel.play();
    ASSERT_TRUE(waitForEnd(panel));
    EXPECT_EQ(panel.playback().state(), State::kFinished) << panel.streamStatus().toStdString();
    expectOneRunInOrder(panel, 19);
    EXPECT_TRUE(panel.streamStatus().contains("broken.csv:6"))
        << panel.streamStatus().toStdString();
}

// A CSV of clayey soil at three loads with 1 % noise, j_max = none (so that the fit's model is
// the data's): the file and its truth.
std::string clayCsv(const QTemporaryDir& dir) {
    identification::SyntheticSpec spec;
    spec.loads_n = {30.0, 58.86, 90.0};
    for (int i = 0; i < 20; ++i) spec.slips.push_back(0.05 + 0.04 * i);
    spec.noise.fx.relative = spec.noise.fz.relative = spec.noise.my.relative = 0.01;
    spec.seed = 3;
    auto clay = io::resolveSoil(test::resources(), "clayey-soil");
    auto wheel = io::resolveWheel(test::resources(), "A");
    EXPECT_TRUE(clay && wheel);
    soil::SoilParameters soil = clay.value();
    soil.max_shear_deformation_m = INFINITY;
    const auto data =
        identification::synthesize(contact::makeContactParameters(soil, *wheel), spec).data;
    const std::string path = dir.filePath("clay.csv").toStdString();
    std::ofstream(path) << identification::toCsv(data);
    return path;
}

// Issue 12: the batch fit of a CSV gives the same answer whatever soil the project holds (it
// used to start from the project's soil), and the panel says what it starts from.
TEST(IdentificationPanel, BatchFitOfACsvDoesNotDependOnTheProjectSoil) {
    QTemporaryDir dir;
    const std::string csv = clayCsv(dir);
    ProjectDocument document;
    test::resetToDefault(document);  // sandy loam
    IdentificationPanel panel(&document);
    panel.applySettings({{"refine", true}});
    panel.setDataFile(QString::fromStdString(csv));
    EXPECT_TRUE(panel.startDescription().contains("global search"))
        << panel.startDescription().toStdString();
    EXPECT_TRUE(panel.startDescription().contains("project's soil is not used"));
    panel.recompute();
    ASSERT_TRUE(test::waitForResult(panel, 120000));
    ASSERT_TRUE(panel.result().message.empty()) << panel.result().message;
    const Table first = panel.result().parameters;

    // An unrelated project field changes: the project's soil becomes snow, edited.
    auto preset = io::resolveSoil(test::resources(), "snow");
    ASSERT_TRUE(preset);
    soil::SoilParameters snow = preset.value();
    snow.friction_angle_rad = units::degToRad(40.0);
    snow.max_shear_deformation_m = 0.005;
    ASSERT_TRUE(document.setSoil(snow, "snow"));
    panel.recompute();
    ASSERT_TRUE(test::waitForResult(panel, 120000));
    const Table second = panel.result().parameters;
    ASSERT_EQ(first.columns, second.columns);
    for (std::size_t c = 0; c < first.columns.size(); ++c)
        EXPECT_EQ(first.rows[0][c], second.rows[0][c]) << first.columns[c];
    // And the answer is the data's soil (resources/soils/clayey-soil.json: φ = 13°, c = 4.14 kPa),
    // within three reported std.
    EXPECT_NEAR(second.rows[0][second.column("phi_deg")], 13.0,
                3.0 * second.rows[0][second.column("phi_deg_std")]);
    EXPECT_NEAR(second.rows[0][second.column("c_kPa")], 4.14,
                3.0 * second.rows[0][second.column("c_kPa_std")]);
    EXPECT_TRUE(panel.fitReport().contains("global search")) << panel.fitReport().toStdString();
    // The solver's first-order check in a user's words (issue 27: no "Newton decrement 2.2e-09").
    EXPECT_TRUE(panel.fitReport().contains("one more step would lower χ² by"))
        << panel.fitReport().toStdString();
    EXPECT_TRUE(panel.fitReport().contains("at a minimum: less than 0.1"))
        << panel.fitReport().toStdString();
    EXPECT_FALSE(panel.fitReport().contains("Newton"));
    EXPECT_TRUE(panel.fitReport().contains("ambiguity: none"));
}

// The panel saves the analysis's settings struct (its keys: "priors", "folds", "loss", …) and
// still opens a project saved before it did ("prior_items" text, "validation" name): the fit it
// runs is the same either way.
TEST(IdentificationPanel, SavesTheFitsSettingsStructAndOpensTheOldKeys) {
    ProjectDocument document;
    test::resetToDefault(document);
    IdentificationPanel panel(&document);
    panel.applySettings({{"refine", true},
                         {"prior_items", "phi_deg=30±5, c_kPa=2±1"},
                         {"validation", "folds"},
                         {"loss", "huber"}});
    const analysis::IdentificationSettings fit = panel.fitSettings();
    EXPECT_EQ(fit.prior_items, (std::vector<std::string>{"phi_deg=30±5", "c_kPa=2±1"}));
    EXPECT_EQ(fit.folds, project::kPanelFolds);
    EXPECT_EQ(fit.holdout_fraction, 0.0);
    EXPECT_EQ(fit.loss, identification::Loss::kHuber);
    const nlohmann::json saved = panel.settings();
    EXPECT_EQ(saved["priors"], nlohmann::json({"phi_deg=30±5", "c_kPa=2±1"}));
    EXPECT_EQ(saved["folds"], project::kPanelFolds);
    EXPECT_EQ(saved["loss"], "huber");
    EXPECT_FALSE(saved.contains("prior_items"));
    EXPECT_FALSE(saved.contains("validation"));

    IdentificationPanel reopened(&document);
    reopened.applySettings(saved);
    EXPECT_EQ(reopened.settings(), saved);
    EXPECT_EQ(analysis::toJson(reopened.fitSettings()), analysis::toJson(fit));
}

// Prior against posterior, the held-out error and the ambiguity line, as the panel shows them.
TEST(IdentificationPanel, ShowsPriorAgainstPosteriorAndTheHeldOutError) {
    QTemporaryDir dir;
    const std::string csv = clayCsv(dir);
    ProjectDocument document;
    test::resetToDefault(document);
    IdentificationPanel panel(&document);
    panel.applySettings({{"refine", true}});
    panel.setDataFile(QString::fromStdString(csv));
    panel.setFitOptions("", "phi_deg=12±2", "folds", "l2");
    EXPECT_TRUE(panel.startDescription().contains("prior: phi_deg=12±2"))
        << panel.startDescription().toStdString();
    panel.recompute();
    ASSERT_TRUE(test::waitForResult(panel, 120000));
    ASSERT_TRUE(panel.result().report.has_value()) << panel.result().message;
    const auto& report = *panel.result().report;
    // Row of φ in the table (the field table's order: a0, a1, Ks, n0, n1, c, phi, K).
    int phi_row = -1;
    for (int row = 0; row < 8; ++row) {
        if (panel.parameterCell(row, 0).startsWith("φ")) phi_row = row;
    }
    ASSERT_GE(phi_row, 0);
    EXPECT_EQ(panel.parameterCell(phi_row, 3), "12 ± 2");
    const auto& c = report.prior[identification::kPhi];
    ASSERT_TRUE(c.active);
    EXPECT_EQ(panel.parameterCell(phi_row, 4), QString::number(c.std_ratio, 'f', 2));
    EXPECT_LT(c.std_ratio, 1.0);  // three loads see φ
    // Five folds: every sample is predicted once.
    EXPECT_TRUE(report.holdout.computed);
    EXPECT_EQ(report.holdout.samples, 60u);
    EXPECT_TRUE(panel.fitReport().contains("held-out RMS in noise σ</b>: 60 samples, 5 fold(s)"))
        << panel.fitReport().toStdString();
    // Issue 26: the panel shows the core summary, the numbers `identify` prints: each estimate
    // and its std in the table, the prior in its column, every other number in the report.
    const analysis::Summary summary = analysis::identificationSummary(panel.result());
    const QString shown = panel.fitReport();
    int estimates = 0, numbers = 0;
    for (const analysis::SummaryRow& row : summary) {
        int table_row = -1;
        for (int r = 0; r < 9 && row.json.size() > 1; ++r) {
            const auto field = analysis::identifiedFields()[static_cast<std::size_t>(r)];
            if (row.json == "/" + std::string(field.key) && row.label == field.symbol)
                table_row = r;
        }
        if (table_row >= 0) {
            const QString value = panel.parameterCell(table_row, 1);
            const QString sd = panel.parameterCell(table_row, 2);
            EXPECT_EQ((sd == "–" ? value : value + " ± " + sd).toStdString(), row.value)
                << row.label;
            ++estimates;
        } else if (row.json.starts_with("/prior/")) {
            EXPECT_TRUE(
                QString::fromStdString(row.value).startsWith(panel.parameterCell(phi_row, 3)))
                << row.value;
        } else if (std::isfinite(row.number) && !row.json.starts_with("/steps/")) {
            EXPECT_TRUE(shown.contains(QString::fromStdString(row.value)))
                << row.label << " " << row.value << " in " << shown.toStdString();
            ++numbers;
        }
    }
    EXPECT_GE(estimates, 7);  // a0, a1, K_s, n0, c, φ, K (j_max: none)
    EXPECT_GE(numbers, 5);    // samples, χ², gradient, one more step, held-out, adequacy
    // A bad prior item is named and nothing runs.
    panel.setFitOptions("", "phi_deg=12", "none", "l2");
    button(panel, "Fit")->click();
    EXPECT_TRUE(panel.fitStatus().contains("phi_deg=12")) << panel.fitStatus().toStdString();
    EXPECT_FALSE(panel.isBusy());
}

// Issue 12: a bad CSV row is reported with its line number in the batch fit too.
TEST(IdentificationPanel, ABadCsvRowIsReportedWithItsLineNumberInTheBatchFit) {
    QTemporaryDir dir;
    const std::string path = dir.filePath("broken.csv").toStdString();
    std::ofstream(path) << "slip,entry_angle_deg,Fx_N,Fz_N,My_Nm\n"
                           "0.1,12,1,58,0.5\n0.2,12.5,2,58,0.6\n0.3,13,3,58,0.7\n"
                           "0.4,13.5,4,58,0.8\n0.5,abc,5,58,0.9\n0.6,14.5,6,58,1.0\n";
    ProjectDocument document;
    test::resetToDefault(document);
    IdentificationPanel panel(&document);
    panel.setDataFile(QString::fromStdString(path));
    panel.recompute();
    ASSERT_TRUE(test::waitForResult(panel, 60000));
    EXPECT_TRUE(panel.fitStatus().contains("broken.csv:6")) << panel.fitStatus().toStdString();
    EXPECT_TRUE(panel.fitStatus().contains("abc")) << panel.fitStatus().toStdString();
}

// Issue 12: the table and the report name parameters and channels by symbol and unit, like the
// other panels, never by the file keys ("Fx_N", "phi_deg").
TEST(IdentificationPanel, TableAndReportShowSymbolsWithUnitsNotFileKeys) {
    ProjectDocument document;
    test::resetToDefault(document);
    IdentificationPanel panel(&document);
    panel.applySettings({{"refine", true}});
    panel.setFitOptions("", "", "holdout", "l2");
    panel.recompute();
    ASSERT_TRUE(test::waitForResult(panel, 120000));
    ASSERT_TRUE(panel.result().message.empty()) << panel.result().message;
    const QRegularExpression key(
        "Fx_N|Fz_N|My_Nm|sinkage_m|phi_deg|c_kPa|Ks_kPa|K_m|\\bn0\\b|\\bn1\\b|\\ba0\\b|\\ba1\\b");
    QStringList symbols;
    for (int row = 0; row < 8; ++row) {
        symbols << panel.parameterCell(row, 0);
        for (int column = 0; column < 6; ++column) {
            EXPECT_FALSE(panel.parameterCell(row, column).contains(key))
                << row << " " << column << ": " << panel.parameterCell(row, column).toStdString();
        }
    }
    for (int column = 0; column < 6; ++column)
        EXPECT_FALSE(panel.parameterHeader(column).contains(key)) << column;
    // The field table's order: a0, a1, Ks, n0, n1, c, phi, K.
    EXPECT_EQ(symbols, (QStringList{"a₀", "a₁", "K_s [kPa/m^n]", "n₀", "n₁", "c [kPa]", "φ [deg]",
                                    "K [m]"}));
    const QString report = panel.fitReport();
    EXPECT_FALSE(report.contains(key)) << report.toStdString();
    EXPECT_TRUE(report.contains("held-out RMS")) << report.toStdString();
    EXPECT_TRUE(report.contains("F_x")) << report.toStdString();
}

// Issue 27: the status line is one sentence (the time, whether the solver's steps converged) so
// that the page fits 1024×700 with every parameter row in view; each step, with its time and how
// it ended in a user's words, is at the end of the report.
TEST(IdentificationPanel, TheStatusLineSaysTheFitConvergedAndTheReportListsItsSteps) {
    for (const bool refine : {false, true}) {
        ProjectDocument document;
        test::resetToDefault(document);
        IdentificationPanel panel(&document);
        panel.applySettings({{"refine", refine}});
        panel.recompute();
        ASSERT_TRUE(test::waitForResult(panel, 120000));
        ASSERT_TRUE(panel.result().message.empty()) << panel.result().message;
        const QString status = panel.fitStatus();
        EXPECT_TRUE(status.startsWith("Fit in ")) << status.toStdString();
        EXPECT_TRUE(status.contains(refine ? ", converged" : ", every step converged"))
            << status.toStdString();
        EXPECT_FALSE(status.contains("|r|") || status.contains("<br>")) << status.toStdString();
        const QString report = panel.fitReport();
        const auto steps = panel.result().steps();
        ASSERT_GE(steps.size(), 3u);
        for (const auto& step : steps) {
            const QString name =
                QString::fromStdString(step.name.worded(identification::ParameterNaming::kSymbol));
            EXPECT_TRUE(report.contains(name.toHtmlEscaped())) << name.toStdString();
        }
        EXPECT_TRUE(report.contains("converged (the fit stopped improving)") ||
                    report.contains("converged (the slope vanished at the minimum)"))
            << report.toStdString();
        // The steps come after the rest of the report.
        EXPECT_GT(report.indexOf("step "), report.indexOf("samples")) << report.toStdString();
    }
}

// Issue 26: the solver's advice names the parameters through the field table — by symbol in the
// panel's report, as the core summary words it, by key in the JSON of the same result (what
// `identify --json` prints). One load cannot separate c and φ: the fit says so.
TEST(IdentificationPanel, TheAdviceNamesParametersBySymbolWhereTheJsonHasKeys) {
    ProjectDocument document;
    test::resetToDefault(document);
    IdentificationPanel panel(&document);
    panel.applySettings({{"refine", true}, {"three_loads", false}});
    panel.recompute();
    ASSERT_TRUE(test::waitForResult(panel, 120000));
    ASSERT_TRUE(panel.result().usable()) << panel.result().message;
    const QString report = panel.fitReport();
    EXPECT_TRUE(report.contains("c and φ trade off")) << report.toStdString();
    const QRegularExpression key("Ks_kPa|c_kPa|phi_deg|K_m|jmax_m|\\bn0\\b|\\ba0\\b|\\ba1\\b");
    EXPECT_FALSE(report.contains(key)) << report.toStdString();
    bool keyed = false;
    const nlohmann::json json = analysis::toJson(panel.result());
    for (const nlohmann::json& flag : json.at("flags"))
        keyed |= flag.get<std::string>().starts_with("c_kPa and phi_deg trade off");
    EXPECT_TRUE(keyed);
}

// Issue 26: a parameter named by an old key — in a project's saved priors, or typed in the prior
// field — is read as its new one with the note the command line gives, in the panel's status.
TEST(IdentificationPanel, AnOldParameterKeyIsReadWithTheCommandLinesNote) {
    ProjectDocument document;
    test::resetToDefault(document);
    IdentificationPanel panel(&document);
    panel.applySettings({{"refine", true}, {"priors", {"Ks=1500±500"}}});
    EXPECT_TRUE(panel.fitStatus().contains(
        "priors: prior 'Ks=1500±500': parameter key 'Ks' is deprecated: use 'Ks_kPa'"))
        << panel.fitStatus().toStdString();
    EXPECT_EQ(panel.settings()["priors"], nlohmann::json({"Ks_kPa=1500±500"}));  // saved so

    panel.setFitOptions("", "n=0.7±0.1", "none", "l2");
    panel.recompute();
    ASSERT_TRUE(test::waitForResult(panel, 120000));
    ASSERT_TRUE(panel.result().usable()) << panel.result().message;
    EXPECT_TRUE(panel.fitStatus().contains(
        "priors: prior 'n=0.7±0.1': parameter key 'n' is deprecated: use 'n0'"))
        << panel.fitStatus().toStdString();
}

// Issue 27, item 3: the batch fit has a Cancel, as every long computation does; a cancelled fit
// says so the way every panel does ("CANCELLED (partial)"), applies nothing, and keeps no curve
// of the fit before it on screen.
TEST(IdentificationPanel, ACancelledFitSaysSoAndShowsNoOlderFit) {
    ProjectDocument document;
    test::resetToDefault(document);
    IdentificationPanel panel(&document);
    panel.show();
    panel.applySettings({{"refine", true}});
    panel.recompute();
    ASSERT_TRUE(test::waitForResult(panel, 120000));
    ASSERT_TRUE(panel.result().usable());
    auto* fit = panel.findChild<QPushButton*>("identification.cancel");
    ASSERT_NE(fit, nullptr);
    EXPECT_FALSE(fit->isEnabled());  // nothing to cancel
    QSignalSpy busy(&panel, &AnalysisPanel::busyChanged);
    panel.recompute();
    if (!panel.isBusy()) {
        ASSERT_TRUE(busy.wait(10000));
    }
    ASSERT_TRUE(fit->isEnabled());
    QTest::mouseClick(fit, Qt::LeftButton);
    ASSERT_TRUE(test::waitForResult(panel, 120000));
    EXPECT_TRUE(panel.result().cancelled);
    EXPECT_EQ(panel.completion(), Completion::kCancelled);
    EXPECT_TRUE(panel.fitStatus().contains("CANCELLED (partial)"))
        << panel.fitStatus().toStdString();
    EXPECT_TRUE(panel.fitStatus().contains("nothing to apply")) << panel.fitStatus().toStdString();
    EXPECT_FALSE(panel.identifiedSoil().has_value());
    EXPECT_FALSE(fit->isEnabled());
    for (const auto& [name, plot] : panel.plots()) {
        if (name.contains("streaming")) continue;  // the other page's, not the fit's
        EXPECT_EQ(plot->plottableCount(), 0) << name.toStdString();
    }
}

// Issue 12: "Apply identified soil to project" puts the fit into the project as one undo step,
// and Undo gives the soil back exactly.
TEST(IdentificationPanel, ApplyingTheIdentifiedSoilIsOneUndoStep) {
    ProjectDocument document;
    test::resetToDefault(document);  // sandy loam, wheel A
    const std::string before = io::toJson(document.project().soil).dump();
    IdentificationPanel panel(&document);
    QPushButton* apply = button(panel, "Apply identified soil");
    ASSERT_NE(apply, nullptr);
    EXPECT_FALSE(apply->isEnabled());  // nothing fitted yet
    EXPECT_FALSE(panel.applyIdentifiedSoil());
    EXPECT_EQ(document.undoStack()->count(), 0);

    panel.applySettings({{"refine", true}});
    panel.recompute();
    ASSERT_TRUE(test::waitForResult(panel, 120000));
    ASSERT_TRUE(panel.result().report && panel.result().report->usable());
    EXPECT_TRUE(apply->isEnabled());
    const identification::DecoupledParameters& fit = panel.result().identified;
    apply->click();
    ASSERT_EQ(document.undoStack()->count(), 1);
    EXPECT_EQ(document.undoStack()->undoText(), "Apply identified soil (synthetic)");
    const soil::SoilParameters& soil = document.project().soil;
    EXPECT_EQ(soil.name, "sandy loam (identified)");
    EXPECT_TRUE(document.project().soil_preset.empty());
    EXPECT_EQ(soil.friction_angle_rad, fit.friction_angle_rad);
    EXPECT_EQ(soil.cohesion_pa, fit.cohesion_pa);
    EXPECT_EQ(soil.shear_modulus_m, fit.shear_modulus_m);
    EXPECT_EQ(soil.sinkage_exponent, fit.n0);
    EXPECT_EQ(soil.max_stress_a0, fit.a0);
    EXPECT_EQ(soil.max_stress_a1, fit.a1);
    // K_s = k_c/b + k_φ (Eq. 2.9) on wheel A (b = 0.107 m) is the identified one; k_c : k_φ and
    // γ are the project soil's (Table 2.1: 5.3 kN/m^(n+1), 1515 kN/m^(n+2), 15.2 kN/m³).
    EXPECT_NEAR(soil.cohesive_modulus / 0.107 + soil.frictional_modulus, fit.pressure_modulus,
                1e-9 * fit.pressure_modulus);
    EXPECT_NEAR(soil.cohesive_modulus / soil.frictional_modulus, 5.3 / 1515.0, 1e-12);
    EXPECT_EQ(soil.unit_weight_n_m3, 15.2e3);

    document.undoStack()->undo();
    EXPECT_EQ(io::toJson(document.project().soil).dump(), before);
    EXPECT_EQ(document.project().soil_preset, "sandy-loam");
}

// Issue 25, item 6: data from wheel A beside a sidecar that names wheel A, in a project whose
// wheel is B (r = 0.135 m, b = 0.165 m). The panel states the data's wheel and fits with it: the
// answer is the data's soil within three std (with B it missed: φ = 17°, a₁ < 0). Choosing the
// project's wheel instead is stated as "not the data's". Without a sidecar the project's wheel is
// the default, and the panel says so.
TEST(IdentificationPanel, FitsWithTheDataWheelAndSaysWhich) {
    QTemporaryDir dir;
    const std::string csv = clayCsv(dir);  // wheel A
    ProjectDocument document;
    test::resetToDefault(document);
    auto b = io::resolveWheel(test::resources(), "B");
    ASSERT_TRUE(b);
    ASSERT_TRUE(document.setWheel(b.value(), "B"));
    IdentificationPanel panel(&document);
    panel.applySettings({{"refine", true}});
    panel.setDataFile(QString::fromStdString(csv));
    EXPECT_FALSE(panel.dataWheel().has_value());
    EXPECT_EQ(panel.chosenWheel().radius_m, 0.135);
    EXPECT_TRUE(panel.wheelDescription().contains("the project's wheel (the data name no wheel)"))
        << panel.wheelDescription().toStdString();
    auto* note = panel.findChild<QLabel*>("identification.wheel_note");
    ASSERT_NE(note, nullptr);
    EXPECT_EQ(note->text(), panel.wheelDescription());

    // The sidecar names wheel A (r = 0.092 m, b = 0.107 m): it becomes the default.
    std::ofstream(dir.filePath("clay.json").toStdString())
        << R"({"format": "terrastudio-experiment", "format_version": 1,
               "wheel": {"name": "A", "r_m": 0.092, "b_m": 0.107}})";
    panel.setDataFile("");
    panel.setDataFile(QString::fromStdString(csv));
    ASSERT_TRUE(panel.dataWheel().has_value());
    EXPECT_EQ(panel.chosenWheel().radius_m, 0.092);
    EXPECT_EQ(panel.chosenWheel().width_m, 0.107);
    EXPECT_TRUE(panel.wheelDescription().contains("the data's wheel (clay.json)"))
        << panel.wheelDescription().toStdString();
    EXPECT_EQ(note->text(), panel.wheelDescription());
    panel.recompute();
    ASSERT_TRUE(test::waitForResult(panel, 120000));
    ASSERT_TRUE(panel.result().report && panel.result().report->usable());
    EXPECT_EQ(panel.fitWheel().radius_m, 0.092);
    const Table& t = panel.result().parameters;
    EXPECT_NEAR(t.rows[0][t.column("phi_deg")], 13.0, 3.0 * t.rows[0][t.column("phi_deg_std")]);
    EXPECT_NEAR(t.rows[0][t.column("c_kPa")], 4.14, 3.0 * t.rows[0][t.column("c_kPa_std")]);
    EXPECT_TRUE(panel.fitReport().contains("the residuals look like noise"))
        << panel.fitReport().toStdString();

    panel.setWheelChoice("project");
    EXPECT_EQ(panel.chosenWheel().radius_m, 0.135);
    EXPECT_TRUE(panel.wheelDescription().contains("not the data's"))
        << panel.wheelDescription().toStdString();
    const nlohmann::json saved = panel.settings();
    EXPECT_EQ(saved["wheel"], "project");
}

// Issue 25, items 3 and 6: synthetic data of sandy loam (j_max = 20 mm) fitted with j_max none
// are flagged as a systematic misfit; with j_max identified, the table shows j_max near 20 mm
// and the residuals are noise again.
TEST(IdentificationPanel, OffersTheShearLimitAndShowsTheAdequacyFlag) {
    ProjectDocument document;
    test::resetToDefault(document);  // sandy loam (j_max = 20 mm), wheel A
    IdentificationPanel panel(&document);
    panel.applySettings({{"refine", true}, {"noise_percent", 1.0}});
    auto* value = panel.findChild<QDoubleSpinBox*>("identification.jmax_value");
    ASSERT_NE(value, nullptr);
    panel.setShearLimit("none");
    EXPECT_FALSE(value->isEnabled());
    EXPECT_TRUE(std::isinf(*panel.fitSettings().max_shear_deformation_m));
    panel.recompute();
    ASSERT_TRUE(test::waitForResult(panel, 120000));
    ASSERT_TRUE(panel.result().report && panel.result().report->usable());
    EXPECT_TRUE(panel.result().report->adequacy.flag);
    EXPECT_TRUE(panel.fitReport().contains("systematic misfit")) << panel.fitReport().toStdString();

    panel.setShearLimit("fixed", 15.0);
    EXPECT_TRUE(value->isEnabled());
    EXPECT_DOUBLE_EQ(*panel.fitSettings().max_shear_deformation_m, 0.015);
    panel.setShearLimit("fit");
    EXPECT_TRUE(panel.fitSettings().fit_max_shear_deformation);
    panel.recompute();
    ASSERT_TRUE(test::waitForResult(panel, 120000));
    const auto& report = *panel.result().report;
    ASSERT_TRUE(report.usable());
    EXPECT_FALSE(report.adequacy.flag);
    const double jmax = report.parameters[identification::kJmax];
    EXPECT_NEAR(jmax, 0.02, 3.0 * report.uncertainty.std[identification::kJmax]);
    int row = -1;
    for (int r = 0; r < 9; ++r) {
        if (panel.parameterCell(r, 0).startsWith("j_max")) row = r;
    }
    ASSERT_GE(row, 0);
    EXPECT_EQ(panel.parameterCell(row, 5), "0.02");  // the truth: the project's soil
    EXPECT_NE(panel.parameterCell(row, 2), "–");     // a std
    EXPECT_TRUE(panel.fitReport().contains("the residuals look like noise"));
    const nlohmann::json saved = panel.settings();
    EXPECT_EQ(saved["jmax"], "fit");
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

// The true border's label and a change's label next to it do not run into each other (issue
// 27: "true border" and "change at 101" touched over the estimates at every playback of the
// shipped border): with a change one sample after the border, the two labels' boxes are apart in
// both figures; with a change far from the border, the border's label stays at the top.
TEST(StreamingFigures, TheBorderAndAChangeNextToItAreLabelledApart) {
    auto labelled = [](QCustomPlot& plot, const QString& start) -> QCPItemText* {
        for (int i = 0; i < plot.itemCount(); ++i) {
            auto* text = qobject_cast<QCPItemText*>(plot.item(i));
            if (text && text->text().startsWith(start)) return text;
        }
        return nullptr;
    };
    for (const std::size_t change : {std::size_t{101}, std::size_t{160}}) {
        QCustomPlot estimates, detection;
        estimates.resize(600, 450);
        detection.resize(500, 450);
        StreamingFigures figures(&estimates, &detection);
        figures.reset("Estimates", 202, std::size_t{100}, 13.8);
        analysis::StreamFrame frame;
        frame.estimate.index = change + 3;
        frame.estimate.change_detected = true;
        frame.estimate.change_at = change;
        figures.append({frame});
        estimates.show();
        detection.show();
        QApplication::processEvents();
        figures.replot();
        for (QCustomPlot* plot : {&estimates, &detection}) {
            QCPItemText* border = labelled(*plot, "true border");
            QCPItemText* found = labelled(*plot, "change at");
            ASSERT_NE(border, nullptr);
            ASSERT_NE(found, nullptr);
            const QRectF a(border->topLeft->pixelPosition(), border->bottomRight->pixelPosition());
            const QRectF b(found->topLeft->pixelPosition(), found->bottomRight->pixelPosition());
            EXPECT_FALSE(a.intersects(b.adjusted(-2, -2, 2, 2)))
                << "change at " << change << ": " << a.top() << " " << a.bottom() << " / "
                << b.top() << " " << b.bottom();
            if (change == 160) {
                EXPECT_LT(a.bottom(), b.bottom() + 1.0);  // both at the top
            } else {
                EXPECT_GT(a.top(), b.bottom());  // the border's below the change's
            }
        }
    }
}

}  // namespace
}  // namespace terra::ui
