// The stresses, sensitivity and identification panels against independent values: Bekker's
// pressure law, the Table 4.1 variations, and the soil the synthetic data came from.
#include <gtest/gtest.h>
#include <qcustomplot.h>

#include <cmath>

#include "core/common/units.h"
#include "widgets/panels/identification_panel.h"
#include "widgets/panels/rover_panel.h"
#include "widgets/panels/sensitivity_panel.h"
#include "widgets/panels/stress_panel.h"
#include "widgets_test_support.h"

namespace terra::ui {
namespace {

TEST(StressPanel, PlottedNormalStressFollowsBekkersLawInFrontOfTheMaximum) {
    ProjectDocument document;
    test::resetToDefault(document);
    StressPanel panel(&document);
    ASSERT_TRUE(test::waitForResult(panel));
    const StressResult& r = panel.result();
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
        EXPECT_NEAR(sigma->data()->at(i)->value, expected, 1e-9 * std::max(1.0, expected)) << theta_deg;
        ++checked;
    }
    EXPECT_GT(checked, 100);
    // The quadratic interpolates the exact σ at θ_m (Eq. 2.38): same value there.
    EXPECT_GT(r.errors[0].rmse, 0.0);
    EXPECT_LT(r.errors[0].mae, r.errors[0].rmse + 1e-12);  // MAE ≤ RMSE always
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
        EXPECT_GT(tornado.rows[i][tornado.column("Fx_high_N")], tornado.rows[i][tornado.column("Fx_base_N")]);
        EXPECT_LT(tornado.rows[i][tornado.column("Fx_low_N")], tornado.rows[i][tornado.column("Fx_base_N")]);
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
    for (const auto& [name, plot] : panel.plots()) EXPECT_GE(plot->graphCount(), 2) << name.toStdString();
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
}

}  // namespace
}  // namespace terra::ui
