// The forces panel as a person uses it, on real widgets under QT_QPA_PLATFORM=offscreen: edits
// of the document recompute the plots, undo restores them, and the edit→repaint time is reported.
#include <gtest/gtest.h>
#include <qcustomplot.h>

#include <QApplication>
#include <QUndoStack>
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/common/units.h"
#include "core/contact/contact_parameters.h"
#include "core/contact/wheel_forces.h"
#include "widgets/editors/property_editors.h"
#include "widgets/editors/validated_spin_box.h"
#include "widgets/panels/forces_panel.h"
#include "widgets_test_support.h"

namespace terra::ui {
namespace {

QCustomPlot* plotOf(ForcesPanel& panel, const QString& symbol) {
    for (const auto& [name, plot] : panel.plots()) {
        if (plot->yAxis->label().contains(symbol)) return plot;
    }
    return nullptr;
}

TEST(ForcesPanel, ShowsOneCurvePerSlipAngleFromTheModel) {
    ProjectDocument document;
    test::resetToDefault(document);
    ForcesPanel panel(&document);
    panel.resize(1000, 600);
    panel.show();
    ASSERT_TRUE(test::waitForResult(panel));
    const Table& table = panel.result().table;
    EXPECT_EQ(table.rows.size(), 600u);  // 6 slip angles × 100 slips, all in equilibrium
    ASSERT_EQ(panel.plots().size(), 6u);
    for (const auto& [name, plot] : panel.plots()) EXPECT_EQ(plot->graphCount(), 6);
    // The plotted drawbar pull at β = 5°, s = 0.5 is the model's value at the solved entry angle,
    // with the parameters typed from Table 2.1 (not read from the preset file).
    const auto& row = table.rows[50];
    ASSERT_DOUBLE_EQ(row[table.column("slip")], 0.5);
    ASSERT_DOUBLE_EQ(row[table.column("slip_angle_deg")], 5.0);
    QCustomPlot* fx = plotOf(panel, "F_x");
    ASSERT_NE(fx, nullptr);
    const double plotted = fx->graph(0)->data()->at(50)->value;
    const double deg = units::kPi / 180.0;
    const contact::ContactParameters<double> p{0.092, 0.107, 0.7, 0.0, 5.3e3 / 0.107 + 1.515e6, 1.7e3,
                                               29.0 * deg, 0.025, 15.2e3, 0.2, 0.3, 0.02};
    const contact::OperatingPoint<double> op{0.5, 5.0 * deg, row[table.column("entry_angle_deg")] * deg, 0.0,
                                             std::nullopt};
    EXPECT_NEAR(plotted, contact::computeForces(p, op).fx, 1e-9);
}

TEST(ForcesPanel, EditingTheSoilUpdatesModelAndPlotAndUndoRestoresBoth) {
    ProjectDocument document;
    test::resetToDefault(document);
    ForcesPanel panel(&document);
    SoilEditor editor(&document, test::resources());
    ASSERT_TRUE(test::waitForResult(panel));
    QCustomPlot* fx = plotOf(panel, "F_x");
    const double before = fx->graph(0)->data()->at(50)->value;

    editor.spinBox("phi_deg")->setValue(35.0);  // what a user's arrow keys or slider do
    EXPECT_NEAR(document.project().soil.friction_angle_rad, units::degToRad(35.0), 1e-12);
    ASSERT_TRUE(test::waitForResult(panel));
    const double after = fx->graph(0)->data()->at(50)->value;
    EXPECT_GT(after, before + 1.0);  // more friction, more drawbar pull (Fig. 4.3)

    document.undoStack()->undo();
    EXPECT_DOUBLE_EQ(editor.spinBox("phi_deg")->value(), 29.0);
    ASSERT_TRUE(test::waitForResult(panel));
    EXPECT_DOUBLE_EQ(fx->graph(0)->data()->at(50)->value, before);
    document.undoStack()->redo();
    ASSERT_TRUE(test::waitForResult(panel));
    EXPECT_DOUBLE_EQ(fx->graph(0)->data()->at(50)->value, after);
}

TEST(ForcesPanel, EditingTheLoadRecomputesEquilibrium) {
    ProjectDocument document;
    test::resetToDefault(document);
    ForcesPanel panel(&document);
    ConditionsEditor editor(&document);
    ASSERT_TRUE(test::waitForResult(panel));
    editor.loadBox()->setValue(80.0);
    ASSERT_TRUE(test::waitForResult(panel));
    const Table& table = panel.result().table;
    ASSERT_FALSE(table.rows.empty());
    for (double fz : table.values("Fz_N")) EXPECT_NEAR(fz, 80.0, 1e-6);
}

TEST(ForcesPanel, AStaleResultIsNeverShown) {
    ProjectDocument document;
    test::resetToDefault(document);
    ForcesPanel panel(&document);
    ASSERT_TRUE(test::waitForResult(panel));
    // A burst of edits: only the last state may reach the screen.
    for (double load : {60.0, 65.0, 70.0, 75.0}) ASSERT_TRUE(document.setLoad(load));
    ASSERT_TRUE(test::waitForResult(panel));
    for (double fz : panel.result().table.values("Fz_N")) EXPECT_NEAR(fz, 75.0, 1e-6);
}

// Instrumented, not timed: reports the edit → repainted-plot latency of the full forces panel
// (6 slip angles × 100 slips with entry-angle solves). The ≤ 50 ms target is checked by reading
// the printed numbers (docs/performance.md), not asserted: timing depends on the machine's load.
TEST(ForcesPanel, ReportsEditToRepaintLatency) {
    ProjectDocument document;
    test::resetToDefault(document);
    ForcesPanel panel(&document);
    panel.resize(1000, 600);
    panel.show();
    ASSERT_TRUE(test::waitForResult(panel));
    std::vector<double> latencies, drawing;
    for (int i = 0; i < 15; ++i) {
        ASSERT_TRUE(document.setSoilValue("phi_deg", 29.0 + 0.25 * (i + 1)));
        ASSERT_TRUE(test::waitForResult(panel));
        latencies.push_back(panel.lastLatencyMs());
        drawing.push_back(panel.lastPresentMs());
    }
    std::sort(drawing.begin(), drawing.end());
    std::sort(latencies.begin(), latencies.end());
    std::printf("[ latency  ] forces panel edit -> repaint (600 points, full model): median %.1f ms, "
                "min %.1f ms, max %.1f ms over %zu edits\n",
                latencies[latencies.size() / 2], latencies.front(), latencies.back(), latencies.size());
    std::printf("[ latency  ] of which on the GUI thread (drawing six plots): median %.1f ms, max %.1f ms\n",
                drawing[drawing.size() / 2], drawing.back());
    RecordProperty("median_latency_ms", std::to_string(latencies[latencies.size() / 2]));
    EXPECT_EQ(panel.result().table.rows.size(), 600u);
}

}  // namespace
}  // namespace terra::ui
