// The stresses, sensitivity and identification panels against independent values: Bekker's
// pressure law, the Table 4.1 variations, and the soil the synthetic data came from.
#include <gtest/gtest.h>
#include <qcustomplot.h>

#include <QImage>
#include <QLabel>
#include <QProgressBar>
#include <QSignalSpy>
#include <QTextDocument>
#include <cmath>

#include "core/common/units.h"
#include "widgets/panels/identification_panel.h"
#include "widgets/panels/rover_panel.h"
#include "widgets/panels/sensitivity_panel.h"
#include "widgets/panels/stress_panel.h"
#include "widgets/plots/figures.h"
#include "widgets_test_support.h"

namespace terra::ui {
namespace {

TEST(StressPanel, PlottedNormalStressFollowsBekkersLawInFrontOfTheMaximum) {
    ProjectDocument document;
    test::resetToDefault(document);
    StressPanel panel(&document);
    ASSERT_TRUE(test::waitForResult(panel));
    const analysis::StressResult& r = panel.result();
    ASSERT_TRUE(r.message.empty()) << r.message;
    ASSERT_EQ(panel.currentPlot()->graphCount(), 8);  // 4 stresses × (exact, quadratic)
    // σ(θ) = K_s (r (cos θ − cos θ_f))^n for θ_m ≤ θ ≤ θ_f (Eq. 2.17), sandy loam of Table 2.1.
    const double ks = 5.3e3 / 0.107 + 1.515e6, r_m = 0.092, n = 0.7;
    const double theta_f = units::degToRad(r.entry_angle_deg);
    const QCPGraph* sigma = panel.currentPlot()->graph(0);
    int checked = 0;
    for (int i = 0; i < sigma->dataCount(); ++i) {
        const double theta_deg = sigma->data()->at(i)->key;
        if (theta_deg < r.max_stress_angle_deg) continue;
        const double theta = units::degToRad(theta_deg);
        const double expected = ks * std::pow(r_m * (std::cos(theta) - std::cos(theta_f)), n) / 1e3;
        EXPECT_NEAR(sigma->data()->at(i)->value, expected, 1e-9 * std::max(1.0, expected))
            << theta_deg;
        ++checked;
    }
    EXPECT_GT(checked, 100);
    // The quadratic interpolates the exact σ at θ_m (Eq. 2.38): same value there.
    EXPECT_GT(r.errors[0].rmse, 0.0);
    EXPECT_LT(r.errors[0].mae, r.errors[0].rmse + 1e-12);  // MAE ≤ RMSE always
}

// Issue 26 item 3: the results line under the plot is the core summary `terrastudio stresses`
// prints, in the panel's notation: θ_f (solved from F_z = W), θ_m and each stress's RMSE and MAE
// at the core's four decimals, from the result the panel holds.
TEST(StressPanel, TheResultsLineIsTheCoreSummary) {
    ProjectDocument document;
    test::resetToDefault(document);
    StressPanel panel(&document);
    ASSERT_TRUE(test::waitForResult(panel));
    const analysis::StressResult& r = panel.result();
    ASSERT_TRUE(r.message.empty()) << r.message;
    auto* line = panel.findChild<QLabel*>("stresses.summary");
    ASSERT_NE(line, nullptr);
    QTextDocument html;
    html.setHtml(line->text());
    const QString text = html.toPlainText();
    const auto fixed4 = [](double v) { return QString::number(v, 'f', 4); };
    EXPECT_TRUE(
        text.contains("θ_f: " + fixed4(r.entry_angle_deg) + " deg (from F_z = W = 58.86 N)"))
        << text.toStdString();
    EXPECT_TRUE(text.contains("θ_m: " + fixed4(r.max_stress_angle_deg) + " deg"))
        << text.toStdString();
    const char* names[] = {"σ", "τ", "τ_t", "τ_l"};
    for (int k = 0; k < 4; ++k) {
        EXPECT_TRUE(text.contains(
            QString("%1 RMSE: %2 kPa (MAE %3 kPa)")
                .arg(names[k], fixed4(r.errors[k].rmse / 1e3), fixed4(r.errors[k].mae / 1e3))))
            << names[k] << ": " << text.toStdString();
    }
    // Two lines: θ, then the approximation's errors under their heading.
    EXPECT_EQ(line->text().count("<br>"), 1) << line->text().toStdString();
}

// A tornado where both extremes of a parameter move F_x the same way (k_c: +2 and +6 N) must
// show both bars: side by side in the parameter's row, not one over the other.
TEST(Tornado, LowAndHighBarsSitSideBySideAndKeepTheirLengths) {
    analysis::SensitivityResult result;
    result.tornado.columns = {"parameter_index", "Fx_low_N", "Fx_high_N", "Fx_base_N"};
    result.tornado.rows = {{0, 8.0, 15.0, 10.0},   // n: −2, +5
                           {1, 12.0, 16.0, 10.0},  // kc: +2, +6 (same direction)
                           {2, 9.0, 10.5, 10.0}};  // phi: −1, +0.5
    result.tornado_keys = {"n", "kc", "phi_deg"};
    QCustomPlot plot;
    plot.resize(800, 500);
    plotTornado(plot, result, 0.3, "test");
    ASSERT_EQ(plot.plottableCount(), 2);
    auto* low = qobject_cast<QCPBars*>(plot.plottable(0));
    auto* high = qobject_cast<QCPBars*>(plot.plottable(1));
    ASSERT_NE(low, nullptr);
    ASSERT_NE(high, nullptr);
    EXPECT_NE(low->brush().color(), high->brush().color());
    EXPECT_TRUE(plot.legend->visible());
    EXPECT_TRUE(plot.legend->hasItemWithPlottable(low));
    EXPECT_TRUE(plot.legend->hasItemWithPlottable(high));
    ASSERT_EQ(low->dataCount(), 3);
    ASSERT_EQ(high->dataCount(), 3);
    // Rows sorted by the largest change either extreme makes: phi (1), n (5), kc (6) on top.
    const std::vector<std::string> order{"φ [deg]", "n [-]", "k_c [kN/m^(n+1)]"};  // field symbols
    const std::vector<std::pair<double, double>> changes{{-1.0, 0.5}, {-2.0, 5.0}, {2.0, 6.0}};
    for (int i = 0; i < 3; ++i) {
        const double row = i + 1;
        const double lo_key = low->data()->at(i)->key, hi_key = high->data()->at(i)->key;
        const double w_lo = low->width(), w_hi = high->width();
        // Both bars inside the row [row − 0.5, row + 0.5] and disjoint along the key axis.
        EXPECT_GE(lo_key - w_lo / 2, row - 0.5) << i;
        EXPECT_LE(hi_key + w_hi / 2, row + 0.5) << i;
        EXPECT_LE(lo_key + w_lo / 2, hi_key - w_hi / 2) << i;
        EXPECT_GT(w_lo, 0.2);
        // Lengths: the change of F_x from the base soil [N].
        EXPECT_DOUBLE_EQ(low->data()->at(i)->value, changes[i].first) << i;
        EXPECT_DOUBLE_EQ(high->data()->at(i)->value, changes[i].second) << i;
    }
    auto* ticker = dynamic_cast<QCPAxisTickerText*>(plot.yAxis->ticker().data());
    ASSERT_NE(ticker, nullptr);
    for (int i = 0; i < 3; ++i) EXPECT_EQ(ticker->ticks().value(i + 1).toStdString(), order[i]);
    // Both bars of the same-direction row are on screen: the shorter low bar is not covered.
    const QImage image = plot.toPixmap(800, 500).toImage();
    const int y_low = static_cast<int>(plot.yAxis->coordToPixel(low->data()->at(2)->key));
    const int y_high = static_cast<int>(plot.yAxis->coordToPixel(high->data()->at(2)->key));
    const int x = static_cast<int>(plot.xAxis->coordToPixel(1.0));  // inside both (0..2 and 0..6)
    EXPECT_EQ(QColor(image.pixel(x, y_low)), low->brush().color());
    EXPECT_EQ(QColor(image.pixel(x, y_high)), high->brush().color());
}

TEST(SensitivityPanel, OneCurvePerTable41ValueAndATornadoOfSixParameters) {
    ProjectDocument document;
    test::resetToDefault(document);
    SensitivityPanel panel(&document);
    ASSERT_TRUE(test::waitForResult(panel, 60000));
    const auto plots = panel.plots();
    ASSERT_EQ(plots.size(), 3u);
    EXPECT_EQ(plots[0].second->graphCount(), 4);  // φ = 25, 30, 35, 40
    const Table& tornado = panel.result().tornado;
    ASSERT_EQ(tornado.rows.size(), 6u);
    // φ: more friction, more drawbar pull (Fig. 4.3) — the highest value moves F_x up.
    for (std::size_t i = 0; i < tornado.rows.size(); ++i) {
        if (panel.result().tornado_keys[i] != "phi_deg") continue;
        EXPECT_GT(tornado.rows[i][tornado.column("Fx_high_N")],
                  tornado.rows[i][tornado.column("Fx_base_N")]);
        EXPECT_LT(tornado.rows[i][tornado.column("Fx_low_N")],
                  tornado.rows[i][tornado.column("Fx_base_N")]);
    }
}

TEST(IdentificationPanel, RecoversTheProjectSoilFromSyntheticData) {
    ProjectDocument document;
    test::resetToDefault(document);
    IdentificationPanel panel(&document);
    panel.applySettings({{"noise_percent", 0.2}, {"refine", true}, {"three_loads", true}});
    panel.recompute();
    ASSERT_TRUE(test::waitForResult(panel, 120000));
    const Table& p = panel.result().parameters;
    ASSERT_EQ(p.rows.size(), 1u);
    EXPECT_NEAR(p.rows[0][p.column("phi_deg")], 29.0, 1.0);  // the soil the data came from
    EXPECT_NEAR(p.rows[0][p.column("K_m")], 0.025, 0.003);
    EXPECT_GT(p.rows[0][p.column("phi_deg_std")], 0.0);
    for (const auto& [name, plot] : panel.plots())
        EXPECT_GE(plot->graphCount(), 2) << name.toStdString();
}

TEST(RoverPanel, RunsAScenarioAndPlotsThePathFromItsSeries) {
    ProjectDocument document;
    test::resetToDefault(document);
    RoverPanel panel(&document, test::resources());
    panel.applySettings({{"scenario", "straight"}});
    panel.recompute();
    ASSERT_TRUE(test::waitForResult(panel, 120000));
    const auto& r = panel.result();
    ASSERT_TRUE(r.usable());
    EXPECT_EQ(r.status, scenario::RunResult::Status::kCompleted);
    // The path plot holds the series' centre of mass, end point included.
    auto* curve = qobject_cast<QCPCurve*>(panel.plots()[0].second->plottable(0));
    ASSERT_NE(curve, nullptr);
    ASSERT_EQ(curve->dataCount(), static_cast<int>(r.series.rows.size()));
    EXPECT_DOUBLE_EQ((curve->data()->constEnd() - 1)->key, r.series.values("x_m").back());
    EXPECT_NEAR(r.series.values("x_m").back(), r.summary.x_m, 0.05);
    EXPECT_GT(r.summary.x_m, 0.0);  // driving forward
}

TEST(RoverPanel, CancelKeepsThePartialRunMarkedAsSuch) {
    ProjectDocument document;
    test::resetToDefault(document);
    RoverPanel panel(&document, test::resources());
    panel.applySettings({{"scenario", "pulse-steering"}});
    QSignalSpy busy(&panel, &AnalysisPanel::busyChanged);
    panel.recompute();
    ASSERT_TRUE(busy.wait(10000));
    panel.cancelRunning();
    ASSERT_TRUE(test::waitForResult(panel, 120000));
    EXPECT_EQ(panel.result().status, scenario::RunResult::Status::kCancelled);
    // Not "100 %": the bar stays where the run stopped and says it was cancelled.
    auto* progress = panel.findChild<QProgressBar*>();
    ASSERT_NE(progress, nullptr);
    EXPECT_LT(progress->value(), 100);
    EXPECT_TRUE(progress->format().contains("cancelled")) << progress->format().toStdString();
    const QString title = plotTitle(*panel.plots().back().second);  // the top view
    EXPECT_TRUE(title.contains("CANCELLED")) << title.toStdString();

    // A new run retitles the old plots at once: they are not this run's.
    QSignalSpy again(&panel, &AnalysisPanel::busyChanged);
    panel.recompute();
    ASSERT_TRUE(again.wait(10000));
    EXPECT_TRUE(plotTitle(*panel.plots().back().second).contains("previous run"));
    panel.cancelRunning();
    ASSERT_TRUE(test::waitForResult(panel, 120000));
}

// Before any run, the top view shows the scenario's soils and start, and the panel says which
// soils it runs on (its own, not the project's).
TEST(RoverPanel, SaysWhichSoilsAScenarioRunsOnBeforeARun) {
    ProjectDocument document;
    test::resetToDefault(document);
    RoverPanel panel(&document, test::resources());
    panel.applySettings({{"scenario", "pulse-steering"}});
    QCustomPlot* top = panel.plots().back().second;
    EXPECT_TRUE(plotTitle(*top).contains("not run yet")) << plotTitle(*top).toStdString();
    EXPECT_GE(top->itemCount(), 2);  // the base soil's rectangle and its label
    bool said = false;
    for (QLabel* label : panel.findChildren<QLabel*>())
        said = said || label->text().contains("own soils");
    EXPECT_TRUE(said);
}

// All four stresses: the legend sits under the axes, off the curves (it covered σ).
TEST(StressPanel, LegendOfAllStressesDoesNotCoverTheCurves) {
    ProjectDocument document;
    test::resetToDefault(document);
    StressPanel panel(&document);
    panel.resize(700, 500);
    panel.show();
    ASSERT_TRUE(test::waitForResult(panel));
    QCustomPlot* plot = panel.currentPlot();
    plot->replot();
    EXPECT_TRUE(plot->legend->visible());
    EXPECT_FALSE(plot->legend->outerRect().intersects(plot->axisRect()->rect()));
}

}  // namespace
}  // namespace terra::ui
