// The rover panel's traction figures and its comparison of the controllers (docs/traction.md
// §5–§6), offscreen with real widgets: the slip-control plot draws each wheel's set-point as the
// run held it, the energy plot ends at the energy ledger's motor work, η stays a ratio of work in
// [0, 1] near the run's mean efficiency, and "Compare controllers" runs the four controllers off
// the GUI thread and tabulates them without a NaN.
#include <gtest/gtest.h>
#include <qcustomplot.h>

#include <QComboBox>
#include <QPushButton>
#include <QSignalSpy>
#include <QTableWidget>
#include <cmath>
#include <nlohmann/json.hpp>
#include <optional>

#include "widgets/panels/rover_panel.h"
#include "widgets_test_support.h"

namespace terra::ui {
namespace {

QCustomPlot* plotNamed(const RoverPanel& panel, const QString& name) {
    for (const auto& [n, plot] : panel.plots())
        if (n == name) return plot;
    return nullptr;
}

using test::graphNamed;

/// A shipped traction scenario under `controller`, cut to `duration_s`, optionally with the fixed
/// set-point `slip`.
void load(RoverPanel& panel, const std::string& scenario, const std::string& controller,
          double duration_s, std::optional<double> slip = std::nullopt) {
    panel.applySettings({{"scenario", scenario}});
    auto json = nlohmann::json::parse(panel.scenarioText().toStdString());
    json["duration_s"] = duration_s;
    json["controller"]["type"] = controller;
    if (slip) json["controller"]["slip"] = *slip;
    QString error;
    ASSERT_TRUE(panel.setScenarioText(QString::fromStdString(json.dump(2)), &error))
        << error.toStdString();
}

TEST(RoverTractionPlots, SlipEnergyAndEfficiencyOfAFixedSlipRun) {
    ProjectDocument document;
    test::resetToDefault(document);
    RoverPanel panel(&document, test::resources());
    // 0.6: near sandy loam's best slip, a steady run (at the scenario's 0.45 the robot stalls
    // and creeps, docs/traction.md §6).
    load(panel, "traction-load-change", "fixed-slip", 8.0, 0.6);
    panel.recompute();
    ASSERT_TRUE(test::waitForResult(panel, 120000));
    const scenario::RunResult& run = panel.result();
    ASSERT_EQ(run.status, scenario::RunResult::Status::kCompleted) << run.message;

    // s and s* per wheel: the set-point drawn is 0.6 at every row.
    QCustomPlot* slip = plotNamed(panel, "rover-slip-control");
    ASSERT_NE(slip, nullptr);
    EXPECT_EQ(slip->graphCount(), 8);
    for (const char* w : {"FL", "FR", "RL", "RR"}) {
        QCPGraph* set = graphNamed(*slip, QString(w) + " s*");
        ASSERT_NE(set, nullptr) << w;
        ASSERT_EQ(set->data()->size(), static_cast<int>(run.series.rows.size()));
        for (auto it = set->data()->constBegin(); it != set->data()->constEnd(); ++it)
            EXPECT_EQ(it->value, 0.6) << w;
        ASSERT_NE(graphNamed(*slip, QString(w) + " s"), nullptr) << w;
    }

    // The drive motors' cumulative work ends at the energy ledger's (the summary's motor energy:
    // no steering on a straight run); the implement's below it (the drive's losses).
    QCustomPlot* energy = plotNamed(panel, "rover-energy");
    ASSERT_NE(energy, nullptr);
    ASSERT_EQ(energy->graphCount(), 2);
    const double drive_end = (energy->graph(0)->data()->constEnd() - 1)->value;
    EXPECT_NEAR(drive_end, run.summary.energy_j, 0.01 * run.summary.energy_j);
    const double pull_end = (energy->graph(1)->data()->constEnd() - 1)->value;
    EXPECT_GT(pull_end, 0.0);
    EXPECT_LT(pull_end, drive_end);
    // The implement's work by hand from the series: ∫ F_d v dt, rectangle rule on the rows.
    double by_hand = 0.0;
    const Table& t = run.series;
    for (std::size_t r = 1; r < t.rows.size(); ++r) {
        by_hand += t.rows[r][t.column("drawbar_N")] *
                   std::max(0.0, t.rows[r][t.column("forward_m_s")]) *
                   (t.rows[r][t.column("t_s")] - t.rows[r - 1][t.column("t_s")]);
    }
    EXPECT_NEAR(pull_end, by_hand, 0.02 * by_hand);

    // η: a ratio of work, finite and in [0, 1]; in the steady second half of a fixed-slip run
    // near the run's mean efficiency (∫ ΣF_x v_x dt / ∫ ΣM_y ω dt of the summary).
    QCustomPlot* efficiency = plotNamed(panel, "rover-efficiency");
    ASSERT_NE(efficiency, nullptr);
    ASSERT_EQ(efficiency->graphCount(), 1);
    ASSERT_TRUE(run.summary.mean_efficiency.has_value());
    int late = 0;
    for (auto it = efficiency->graph(0)->data()->constBegin();
         it != efficiency->graph(0)->data()->constEnd(); ++it) {
        ASSERT_TRUE(std::isfinite(it->value));
        EXPECT_GE(it->value, 0.0);
        EXPECT_LE(it->value, 1.0);
        if (it->key >= 4.0) {
            EXPECT_NEAR(it->value, *run.summary.mean_efficiency, 0.03) << "t = " << it->key;
            ++late;
        }
    }
    EXPECT_GT(late, 100);
}

TEST(RoverTractionPlots, ConstantSpeedRunHasNoSetPointAndLabelsItsEnergy) {
    ProjectDocument document;
    test::resetToDefault(document);
    RoverPanel panel(&document, test::resources());
    panel.applySettings({{"scenario", "straight"}});
    auto json = nlohmann::json::parse(panel.scenarioText().toStdString());
    json["duration_s"] = 1.0;
    QString error;
    ASSERT_TRUE(panel.setScenarioText(QString::fromStdString(json.dump(2)), &error));
    panel.recompute();
    ASSERT_TRUE(test::waitForResult(panel, 120000));
    QCustomPlot* slip = plotNamed(panel, "rover-slip-control");
    ASSERT_NE(slip, nullptr);
    EXPECT_EQ(slip->graphCount(), 4);  // s only: ideal servos hold no set-point
    QCustomPlot* energy = plotNamed(panel, "rover-energy");
    ASSERT_NE(energy, nullptr);
    ASSERT_EQ(energy->graphCount(), 1);  // no implement
    EXPECT_TRUE(energy->graph(0)->name().contains("ideal servos"));
}

TEST(RoverTractionPlots, CompareControllersTabulatesTheFourRunsOffTheGuiThread) {
    ProjectDocument document;
    test::resetToDefault(document);
    RoverPanel panel(&document, test::resources());
    load(panel, "traction-border", "optimal", 3.0);
    QSignalSpy busy(&panel, &AnalysisPanel::busyChanged);
    QSignalSpy shown(&panel, &AnalysisPanel::resultShown);
    panel.requestComparison();
    // The four runs go on a worker: the GUI thread sees the panel busy, Run and Compare disabled,
    // before any result.
    ASSERT_TRUE(busy.wait(10000));
    EXPECT_TRUE(busy.front().front().toBool());
    EXPECT_EQ(shown.count(), 0);
    EXPECT_FALSE(panel.compareButton()->isEnabled());
    ASSERT_TRUE(shown.wait(240000));
    EXPECT_TRUE(panel.compareButton()->isEnabled());

    const nlohmann::json& rows = panel.comparison();
    ASSERT_EQ(rows.size(), 4u);
    QTableWidget* table = panel.comparisonTable();
    ASSERT_EQ(table->rowCount(), 4);
    const char* names[] = {"constant-speed", "fixed-slip", "optimal", "oracle"};
    for (int r = 0; r < 4; ++r) {
        EXPECT_EQ(table->item(r, 0)->text().toStdString(), names[r]);
        for (int c = 1; c < table->columnCount(); ++c) {
            const QString text = table->item(r, c)->text();
            EXPECT_FALSE(text.contains("nan", Qt::CaseInsensitive)) << r << "," << c;
            EXPECT_FALSE(text.isEmpty()) << r << "," << c;
        }
    }
    // The oracle's pull against itself is 1; constant speed has no set-point to track.
    EXPECT_DOUBLE_EQ(rows[3]["drawbar_vs_oracle"].get<double>(), 1.0);
    EXPECT_TRUE(rows[0]["slip_tracking_rms"].is_null());
    EXPECT_EQ(table->item(0, 7)->text(), "–");
    // Each row is its own run: the distances differ between the controllers.
    EXPECT_NE(rows[0]["distance_m"], rows[3]["distance_m"]);
    // The figures show the chosen controller's run (optimal: the planned set-point's column).
    EXPECT_NO_THROW(panel.result().series.column("FL_slip_plan"));
    EXPECT_EQ(panel.shownScenario().controller.type, scenario::ControllerType::kOptimal);
    // The comparison's tab exports as a table with the controller as the label.
    const Table exported = panel.comparisonAsTable();
    ASSERT_EQ(exported.labels.size(), 4u);
    EXPECT_EQ(exported.labels[2], "optimal");
}

}  // namespace
}  // namespace terra::ui
