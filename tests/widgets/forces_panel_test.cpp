// The forces panel as a person uses it, on real widgets under QT_QPA_PLATFORM=offscreen.
#include <gtest/gtest.h>
#include <qcustomplot.h>

#include <QApplication>
#include <QDoubleSpinBox>
#include <QImage>
#include <QSignalSpy>
#include <QTemporaryDir>
#include <cmath>

#include "core/contact/contact_parameters.h"
#include "core/contact/wheel_forces.h"
#include "widgets/panels/forces_panel.h"
#include "widgets/plots/sweep_plot.h"

namespace terra::ui {
namespace {

io::PresetLocations resources() { return {{TERRA_RESOURCE_DIR}}; }

bool waitForSweep(ForcesPanel& panel) {
    QSignalSpy spy(&panel, &ForcesPanel::sweepFinished);
    return spy.wait(20000);
}

TEST(ForcesPanel, ShowsOneCurvePerSlipAngleFromTheModel) {
    ForcesPanel panel(resources());
    panel.resize(1000, 600);
    panel.show();
    ASSERT_TRUE(waitForSweep(panel));
    const Table& table = panel.result().table;
    EXPECT_EQ(table.rows.size(), 600u);  // 6 slip angles × 100 slips, all in equilibrium
    const auto plots = panel.findChildren<QCustomPlot*>();
    ASSERT_EQ(plots.size(), 6);
    for (QCustomPlot* plot : plots) EXPECT_EQ(plot->graphCount(), 6);
    // The plotted drawbar pull at β = 5°, s = 0.5 is the model's value at the solved entry angle.
    const auto& row = table.rows[50];
    ASSERT_DOUBLE_EQ(row[table.column("slip")], 0.5);
    ASSERT_DOUBLE_EQ(row[table.column("slip_angle_deg")], 5.0);
    QCustomPlot* fx = nullptr;
    for (QCustomPlot* plot : plots) {
        if (plot->yAxis->label().contains("F_x")) fx = plot;
    }
    ASSERT_NE(fx, nullptr);
    const double plotted = fx->graph(0)->data()->at(50)->value;
    const double deg = 3.14159265358979323846 / 180.0;
    const contact::ContactParameters<double> p{0.092, 0.107, 0.7, 0.0, 5.3e3 / 0.107 + 1.515e6, 1.7e3,
                                               29.0 * deg, 0.025, 15.2e3, 0.2, 0.3, 0.02};
    const contact::OperatingPoint<double> op{0.5, 5.0 * deg, row[table.column("entry_angle_deg")] * deg,
                                             0.0, std::nullopt};
    EXPECT_NEAR(plotted, contact::computeForces(p, op).fx, 1e-9);
}

TEST(ForcesPanel, EditingTheLoadRecomputes) {
    ForcesPanel panel(resources());
    ASSERT_TRUE(waitForSweep(panel));
    auto* load = panel.findChild<QDoubleSpinBox*>();
    ASSERT_NE(load, nullptr);
    load->setValue(80.0);
    ASSERT_TRUE(waitForSweep(panel));
    const Table& table = panel.result().table;
    ASSERT_FALSE(table.rows.empty());
    for (double fz : table.values("Fz_N")) EXPECT_NEAR(fz, 80.0, 1e-8);
}

TEST(SweepPlot, ExportsAPngOfTheAskedSizeThatIsNotBlank) {
    ForcesPanel panel(resources());
    ASSERT_TRUE(waitForSweep(panel));
    QCustomPlot plot;
    plotSweep(plot, panel.result().table, sweepQuantities()[0], "test");
    QTemporaryDir dir;
    const QString path = dir.filePath("fx.png");
    QString error;
    ASSERT_TRUE(exportPng(plot, path, 640, 480, &error)) << error.toStdString();
    const QImage image(path);
    ASSERT_FALSE(image.isNull());
    EXPECT_EQ(image.width(), 640);
    EXPECT_EQ(image.height(), 480);
    int coloured = 0;  // pixels of the curves (saturated colours), not the white background
    for (int y = 0; y < image.height(); y += 2) {
        for (int x = 0; x < image.width(); x += 2) {
            if (QColor(image.pixel(x, y)).saturation() > 100) ++coloured;
        }
    }
    EXPECT_GT(coloured, 200);
    EXPECT_FALSE(QFile::exists(path + ".part.png"));
    EXPECT_FALSE(exportPng(plot, dir.filePath("missing/dir/fx.png"), 640, 480, &error));
}

}  // namespace
}  // namespace terra::ui

int main(int argc, char** argv) {
    qputenv("QT_QPA_PLATFORM", "offscreen");
    QApplication application(argc, argv);
    ::testing::InitGoogleTest(&argc, argv);
    return RUN_ALL_TESTS();
}
