// Issue 27, item 4 (plots), on the forces panel as a person uses it (offscreen; every other
// panel's legends too, at the end): the legend sits off the data by default and never widens the
// plot, a drag moves it (without panning the axes) and it stays there through a redraw, the plot
// menu hides and shows it, an export lays it out the same way, and the read-out names the curve
// point nearest the mouse, not the mouse position.
#include <gtest/gtest.h>
#include <qcustomplot.h>

#include <QAction>
#include <QLabel>
#include <QMenu>
#include <QSignalSpy>
#include <QStackedWidget>
#include <QTemporaryDir>
#include <QTest>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <vector>

#include "widgets/panels/compaction_panel.h"
#include "widgets/panels/forces_panel.h"
#include "widgets/panels/global_sensitivity_panel.h"
#include "widgets/panels/rover_panel.h"
#include "widgets/panels/sensitivity_panel.h"
#include "widgets/panels/stress_panel.h"
#include "widgets/plots/plot_export.h"
#include "widgets/plots/plot_legend.h"
#include "widgets/plots/plot_menu.h"
#include "widgets/plots/plot_readout.h"
#include "widgets_test_support.h"

namespace terra::ui {
namespace {

/// The forces panel shown with its result, and its drawbar-pull plot laid out on screen.
struct Shown {
    Shown() {
        test::resetToDefault(document);
        panel = std::make_unique<ForcesPanel>(&document);
        panel->resize(1000, 640);
        panel->show();
        EXPECT_TRUE(test::waitForResult(*panel));
        plot = panel->currentPlot();
        plot->replot();
    }
    ProjectDocument document;
    std::unique_ptr<ForcesPanel> panel;
    QCustomPlot* plot = nullptr;
};

QAction* menuAction(QCustomPlot& plot, const QString& name, std::unique_ptr<QMenu>& holder) {
    holder.reset(makePlotMenu(plot, {}, nullptr));
    return holder->findChild<QAction*>(name);
}

/// Drags with the left button from `from` to `to` through the plot's own events.
void drag(QCustomPlot& plot, QPoint from, QPoint to) {
    QTest::mousePress(&plot, Qt::LeftButton, {}, from);
    QTest::mouseMove(&plot, (from + to) / 2);
    QTest::mouseMove(&plot, to);
    QTest::mouseRelease(&plot, Qt::LeftButton, {}, to);
    plot.replot();
}

// The six β curves' legend sat in a corner of the axes, over measured points and curves.
TEST(PlotLegend, SitsOffTheDataByDefaultAndNeverWidensThePlot) {
    Shown s;
    QCustomPlot& plot = *s.plot;
    ASSERT_TRUE(plot.legend->visible());
    ASSERT_EQ(plot.legend->itemCount(), 6);
    EXPECT_FALSE(plot.legend->outerRect().intersects(plot.axisRect()->rect()));
    // Narrow (a 1024 px screen, docks open): fewer entries a row, still within the plot.
    plot.resize(360, 400);
    plot.replot();
    EXPECT_LE(plot.legend->outerRect().width(), plot.width());
    EXPECT_LE(static_cast<QWidget&>(plot).minimumSizeHint().width(), 360);
    EXPECT_FALSE(plot.legend->outerRect().intersects(plot.axisRect()->rect()));
}

TEST(PlotLegend, ADragMovesItWithoutPanningAndItStaysThroughARedraw) {
    Shown s;
    QCustomPlot& plot = *s.plot;
    const QCPRange x = plot.xAxis->range(), y = plot.yAxis->range();
    const QRect axes = plot.axisRect()->rect();
    // Into the axes, near their top-left corner.
    drag(plot, plot.legend->outerRect().center(), axes.topLeft() + QPoint(80, 60));
    QRect at = plot.legend->outerRect();
    EXPECT_TRUE(plot.axisRect()->rect().contains(at)) << "inside the axes";
    EXPECT_EQ(plot.xAxis->range(), x) << "the drag did not pan";
    EXPECT_EQ(plot.yAxis->range(), y);
    // Once inside, it follows the mouse pixel for pixel.
    const QPoint delta(120, 70);
    drag(plot, at.center(), at.center() + delta);
    EXPECT_NEAR(plot.legend->outerRect().left(), at.left() + delta.x(), 1);
    EXPECT_NEAR(plot.legend->outerRect().top(), at.top() + delta.y(), 1);
    at = plot.legend->outerRect();
    // An edit redraws the figure: the legend stays where the user left it.
    ASSERT_TRUE(s.document.setSoilValue("phi_deg", 31.0));
    ASSERT_TRUE(test::waitForResult(*s.panel));
    plot.replot();
    EXPECT_EQ(plot.legend->outerRect().topLeft(), at.topLeft());
    // "Legend under the plot" puts it back off the data.
    std::unique_ptr<QMenu> menu;
    QAction* below = menuAction(plot, "plot.legend_below", menu);
    ASSERT_NE(below, nullptr);
    EXPECT_TRUE(below->isEnabled());
    below->trigger();
    plot.replot();
    EXPECT_FALSE(plot.legend->outerRect().intersects(plot.axisRect()->rect()));
}

TEST(PlotLegend, ThePlotMenuHidesAndShowsItThroughRedraws) {
    Shown s;
    QCustomPlot& plot = *s.plot;
    std::unique_ptr<QMenu> menu;
    QAction* legend = menuAction(plot, "plot.legend", menu);
    ASSERT_NE(legend, nullptr);
    EXPECT_TRUE(legend->isCheckable());
    EXPECT_TRUE(legend->isChecked());
    legend->trigger();
    plot.replot();
    EXPECT_FALSE(plot.legend->visible());
    const QRect axes_with_legend = plot.axisRect()->rect();
    ASSERT_TRUE(s.document.setSoilValue("phi_deg", 31.0));
    ASSERT_TRUE(test::waitForResult(*s.panel));
    plot.replot();
    EXPECT_FALSE(plot.legend->visible()) << "hidden through a redraw";
    EXPECT_GE(plot.axisRect()->rect().height(), axes_with_legend.height())
        << "a hidden legend leaves its row to the axes";
    legend = menuAction(plot, "plot.legend", menu);
    EXPECT_FALSE(legend->isChecked());
    legend->trigger();
    plot.replot();
    EXPECT_TRUE(plot.legend->visible());
}

// An export lays the legend out for its own width and leaves the screen's layout as it was.
TEST(PlotLegend, AnExportKeepsTheScreensPlacement) {
    Shown s;
    QCustomPlot& plot = *s.plot;
    QTemporaryDir dir;
    const QRect axes = plot.axisRect()->rect();
    drag(plot, plot.legend->outerRect().center(), axes.topLeft() + QPoint(80, 60));
    const QRect before = plot.legend->outerRect();
    const QCPLayoutInset* inset = plot.axisRect()->insetLayout();
    ASSERT_EQ(inset->elementAt(0), plot.legend);
    const QRectF fraction = inset->insetRect(0);
    QString error;
    ExportOptions options;
    options.width = 1600;
    options.height = 900;
    ASSERT_TRUE(exportPlot(plot, dir.filePath("fx.png"), options, &error)) << error.toStdString();
    plot.replot();
    EXPECT_EQ(inset->insetRect(0), fraction) << "the same place in the axes in the export";
    EXPECT_EQ(plot.legend->outerRect(), before);
    QImage image(dir.filePath("fx.png"));
    EXPECT_EQ(image.size(), QSize(1600, 900));
}

/// Every plot of `panel` with a legend, laid out at a 1024 px screen's plot size: the legend is
/// off the data by default, a drag puts it inside the axes, and the plot menu hides it.
void expectLegendsBehave(AnalysisPanel& panel, int* legends) {
    for (const auto& [name, plot] : panel.plots()) {
        // Its tab in front (a plot on a hidden tab gets no mouse events).
        for (QWidget* page = plot; page->parentWidget() != nullptr; page = page->parentWidget()) {
            if (auto* stack = qobject_cast<QStackedWidget*>(page->parentWidget()))
                stack->setCurrentWidget(page);
        }
        plot->resize(700, 460);
        plot->replot();
        if (!plot->legend || !plot->legend->visible() || plot->legend->itemCount() == 0) continue;
        ++*legends;
        const std::string where = panel.name().toStdString() + "/" + name.toStdString();
        EXPECT_FALSE(plot->legend->outerRect().intersects(plot->axisRect()->rect())) << where;
        EXPECT_LE(plot->legend->outerRect().width(), plot->width()) << where;
        const QRect axes = plot->axisRect()->rect();
        drag(*plot, plot->legend->outerRect().center(), axes.topLeft() + QPoint(40, 30));
        EXPECT_TRUE(axes.contains(plot->legend->outerRect().topLeft())) << where;
        EXPECT_TRUE(legendMoved(*plot)) << where;
        std::unique_ptr<QMenu> menu;
        QAction* shown = menuAction(*plot, "plot.legend", menu);
        ASSERT_NE(shown, nullptr) << where;
        shown->trigger();
        plot->replot();
        EXPECT_FALSE(plot->legend->visible()) << where;
        shown->trigger();  // back as it was, under the axes
        resetLegendPlacement(*plot);
        plot->replot();
        EXPECT_TRUE(plot->legend->visible()) << where;
    }
}

// Legend behaviour was tested on the forces panel only: every panel's legends now.
TEST(PlotLegend, EveryPanelsLegendsSitOffTheDataMoveAndHide) {
    ProjectDocument document;
    test::resetToDefault(document);
    int legends = 0;
    // Each made just before it is shown, so that its first result comes after the wait begins.
    const std::vector<std::function<std::unique_ptr<AnalysisPanel>()>> makers = {
        [&] { return std::make_unique<StressPanel>(&document); },
        [&] { return std::make_unique<SensitivityPanel>(&document); },
        [&] { return std::make_unique<CompactionPanel>(&document, test::resources()); },
        [&] { return std::make_unique<GlobalSensitivityPanel>(&document); }};
    for (const auto& make : makers) {
        const std::unique_ptr<AnalysisPanel> panel = make();
        panel->resize(1000, 640);
        panel->show();
        ASSERT_TRUE(test::waitForResult(*panel, 60000)) << panel->name().toStdString();
        expectLegendsBehave(*panel, &legends);
    }
    // The rover, on a 3 s run of the straight scenario.
    RoverPanel rover(&document, test::resources());
    rover.applySettings({{"scenario", "straight"}});
    auto json = nlohmann::json::parse(rover.scenarioText().toStdString());
    json["duration_s"] = 3.0;
    QString error;
    ASSERT_TRUE(rover.setScenarioText(QString::fromStdString(json.dump()), &error))
        << error.toStdString();
    rover.resize(1000, 640);
    rover.show();
    rover.recompute();
    ASSERT_TRUE(test::waitForResult(rover, 60000));
    expectLegendsBehave(rover, &legends);
    EXPECT_GE(legends, 15) << "too few legends were seen for the test to mean much";
}

// The read-out showed the mouse position ("s = 0.3012"), between the curves.
TEST(PlotReadout, NamesTheNearestCurvePointWithItsUnits) {
    Shown s;
    QCustomPlot& plot = *s.plot;
    ASSERT_EQ(plot.yAxis->label(), "Drawbar pull F_x [N]");
    // Pointed 4 px right of and 3 px below the 30th point of the first curve (β = 0°).
    const auto pointed = plot.graph(0)->data()->at(30);
    const QPoint at(qRound(plot.xAxis->coordToPixel(pointed->key)) + 4,
                    qRound(plot.yAxis->coordToPixel(pointed->value)) + 3);
    // The nearest drawn point of any curve, by brute force.
    const QCPGraph* nearest = nullptr;
    double key = 0, value = 0, best = 1e300;
    for (int g = 0; g < plot.graphCount(); ++g) {
        for (auto it = plot.graph(g)->data()->constBegin(); it != plot.graph(g)->data()->constEnd();
             ++it) {
            const double dx = plot.xAxis->coordToPixel(it->key) - at.x();
            const double dy = plot.yAxis->coordToPixel(it->value) - at.y();
            if (dx * dx + dy * dy < best) {
                best = dx * dx + dy * dy;
                nearest = plot.graph(g);
                key = it->key;
                value = it->value;
            }
        }
    }
    ASSERT_NE(nearest, nullptr);
    ASSERT_LE(best, 26.0) << "the point pointed at or one as near";
    QTest::mouseMove(&plot, at);
    QLabel* readout = nullptr;
    for (QLabel* label : s.panel->findChildren<QLabel*>()) {
        if (label->text().startsWith("Slip ratio")) readout = label;
    }
    ASSERT_NE(readout, nullptr);
    const QString expected = QString("Slip ratio s = %1,  Drawbar pull F_x = %2 N  — %3")
                                 .arg(key, 0, 'g', 4)
                                 .arg(value, 0, 'g', 4)
                                 .arg(nearest->name());
    EXPECT_EQ(readout->text(), expected);
    // A ring marks the point read.
    bool ring = false;
    for (int i = 0; i < plot.itemCount(); ++i) {
        auto* tracer = qobject_cast<QCPItemTracer*>(plot.item(i));
        if (tracer && tracer->position->coords() == QPointF(key, value)) ring = true;
    }
    EXPECT_TRUE(ring);
}

// The read-out beside the Model box was cut and squeezed the status into two lines, moving the
// plots by 6 px as the mouse moved (at 1024 px; a new user's audit): on a line of its own, at
// 700 px wide, its text whole and the plots still.
TEST(PlotReadout, AReadoutNeverMovesThePlotsAndIsShownWhole) {
    Shown s;
    s.panel->resize(700, 600);
    QTest::qWait(50);
    auto* tabs = s.panel->findChild<QTabWidget*>();
    ASSERT_NE(tabs, nullptr);
    const QRect before = tabs->geometry();
    const auto pointed = s.plot->graph(0)->data()->at(30);
    QTest::mouseMove(s.plot, QPoint(qRound(s.plot->xAxis->coordToPixel(pointed->key)),
                                    qRound(s.plot->yAxis->coordToPixel(pointed->value))));
    QTest::qWait(50);
    auto* readout = s.panel->findChild<QLabel*>("forces.readout");
    ASSERT_NE(readout, nullptr);
    ASSERT_TRUE(readout->text().startsWith("Slip ratio")) << readout->text().toStdString();
    EXPECT_EQ(tabs->geometry(), before);
    EXPECT_LE(readout->fontMetrics().horizontalAdvance(readout->text()), readout->width())
        << readout->text().toStdString();
}

// A category axis (the tornado's parameters) is read by its category, not by the bar's offset
// position on it: "Soil parameter = 0.81" (a new user's audit, issue 27).
TEST(PlotReadout, ACategoryAxisNamesTheCategory) {
    QCustomPlot plot;
    plot.resize(400, 300);
    auto ticker = QSharedPointer<QCPAxisTickerText>::create();
    ticker->addTick(1.0, "φ");
    ticker->addTick(2.0, "k_c");
    plot.xAxis->setTicker(ticker);
    plot.xAxis->setLabel("Soil parameter");
    plot.yAxis->setLabel("Change of F_x [%]");
    auto* bars = new QCPBars(plot.xAxis, plot.yAxis);
    bars->setName("φ −10 %");
    bars->addData(0.81, 5.0);
    bars->addData(1.81, -3.0);
    plot.xAxis->setRange(0.0, 3.0);
    plot.yAxis->setRange(-6.0, 6.0);
    plot.replot();
    const QPointF near_kc(plot.xAxis->coordToPixel(1.81) + 2, plot.yAxis->coordToPixel(-3.0) - 1);
    EXPECT_EQ(readoutText(plot, near_kc), "Soil parameter = k_c,  Change of F_x = -3 %  — φ −10 %");
    // A tick that names itself is shown as it is.
    ticker->clear();
    ticker->addTick(1.0, "s = 0.1");
    ticker->addTick(2.0, "s = 0.3");
    EXPECT_EQ(readoutText(plot, near_kc), "s = 0.3,  Change of F_x = -3 %  — φ −10 %");
}

}  // namespace
}  // namespace terra::ui
