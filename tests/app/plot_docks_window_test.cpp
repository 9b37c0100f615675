// Issue 27, item 1, in the studio's window on real widgets (QT_QPA_PLATFORM=offscreen): a plot of
// a panel shown in a dock of its own beside the panels comes back where it was with the window,
// stale names of torn-off plots are ignored, and View ▸ Layout's Side by side and Tile leave no
// panel on screen scrolling sideways at 1366×768 (a reviewer found them scrolling inside their
// docks).
#include <gtest/gtest.h>
#include <qcustomplot.h>

#include <QDockWidget>
#include <QScrollArea>
#include <QScrollBar>
#include <QSettings>
#include <QTabWidget>
#include <QTest>
#include <algorithm>

#include "app/main_window.h"
#include "widgets/document/project_document.h"
#include "widgets/panels/analysis_panel.h"
#include "widgets/panels/forces_panel.h"
#include "widgets/panels/plot_docking.h"
#include "window_test_support.h"

namespace terra::app {
namespace {

using test::Studio;

void wait(int ms = 200) { QTest::qWait(ms); }

const char* const kAllPanels[] = {"forces",         "stresses", "compaction",        "sensitivity",
                                  "identification", "rover",    "global-sensitivity"};

/// The window of a 1366×768 and of a 1024×700 screen, less the window manager's frame (Xvfb +
/// openbox).
constexpr QSize kWindowAt1366x768(1350, 728);
constexpr QSize kWindowAt1024x700(1008, 660);

bool onScreen(const QDockWidget* dock) {
    return dock->isVisible() && !dock->visibleRegion().isEmpty();
}

/// The panel's whole minimum width is in view: no sideways scroll bar in its dock.
void expectNoSidewaysScroll(MainWindow& w, const QString& name, const QString& context) {
    auto* area = qobject_cast<QScrollArea*>(w.panelDock(name)->widget());
    ASSERT_NE(area, nullptr) << name.toStdString();
    // A layout still settling on a loaded machine (ctest runs two tests a core) is given 3 s.
    static_cast<void>(QTest::qWaitFor(
        [area] {
            return area->widget()->minimumSizeHint().width() <= area->viewport()->width() &&
                   !area->horizontalScrollBar()->isVisible();
        },
        3000));
    EXPECT_LE(area->widget()->minimumSizeHint().width(), area->viewport()->width())
        << context.toStdString() << ": " << name.toStdString();
    EXPECT_FALSE(area->horizontalScrollBar()->isVisible())
        << context.toStdString() << ": " << name.toStdString();
}

/// The panels on screen, by name.
QStringList panelsShown(MainWindow& w) {
    QStringList names;
    for (const char* name : kAllPanels)
        if (onScreen(w.panelDock(name))) names << name;
    return names;
}

/// How many panels are on screen, each checked for a sideways scroll bar.
int panelsOnScreen(MainWindow& w, const QString& context) {
    int shown = 0;
    for (const char* name : kAllPanels) {
        if (!onScreen(w.panelDock(name))) continue;
        ++shown;
        expectNoSidewaysScroll(w, name, context);
    }
    return shown;
}

QCustomPlot* forcesPlot(Studio& studio, const QString& name) {
    for (const auto& [n, plot] : studio.panel<ui::ForcesPanel>()->plots()) {
        if (n == name) return plot;
    }
    return nullptr;
}

/// The forces' drawbar pull in a dock of its own, then View ▸ Layout ▸ Side by side: its dock.
QDockWidget* forcesBesideItsDrawbarPull(Studio& studio) {
    studio.window.showPanel("forces");
    QDockWidget* fx = studio.window.plotDocking()->tearOff(forcesPlot(studio, "Fx_N-vs-slip"));
    studio.action("action.layout_side_by_side")->trigger();
    wait(300);
    return fx;
}

// Tile after every panel has drawn its result (as scripts/screenshots does): a drawn global
// study's plot asked ~600 px, its panel 1014 px, and the row it was tabbed into squeezed the panel
// beside it (under Xvfb and openbox the compaction panel, ~50 px short) into a sideways scroll.
TEST(PlotDocks, TiledAfterEveryPanelComputedDoesNotScrollSideways) {
    QSettings().remove("window");
    Studio studio;
    MainWindow& w = studio.window;
    w.resize(kWindowAt1366x768);
    wait();
    // Each panel's result drawn before the layout changes: on a loaded machine (ctest runs two
    // tests a core) a computation may take longer than a fixed wait.
    for (const char* name : kAllPanels) {
        w.showPanel(name);
        wait(300);
        const auto panels = w.findChildren<ui::AnalysisPanel*>();
        EXPECT_TRUE(QTest::qWaitFor(
            [&panels] {
                return std::none_of(panels.begin(), panels.end(),
                                    [](const ui::AnalysisPanel* p) { return p->isBusy(); });
            },
            60000))
            << name;
        wait(300);
    }
    EXPECT_LE(ui::dockMinimumWidth(*w.panelDock("global-sensitivity")), 700);
    w.showPanel("forces");
    studio.action("action.layout_side_by_side")->trigger();
    wait(300);
    w.showPanel("forces");
    studio.action("action.layout_tiled")->trigger();
    // The tiling settles over several event-loop turns; on a loaded machine (ctest runs two test
    // processes a core) a fixed wait was sometimes too short.
    EXPECT_TRUE(QTest::qWaitFor([&w] { return panelsShown(w).size() >= 4; }, 15000));
    wait(500);
    int shown = 0;
    for (const char* name : kAllPanels) {
        if (!onScreen(w.panelDock(name))) continue;
        ++shown;
        expectNoSidewaysScroll(w, name, "tiled after every panel computed");
    }
    EXPECT_GE(shown, 4);
    EXPECT_EQ(w.size(), kWindowAt1366x768);
    QSettings().remove("window");
}

// Tiled chosen before the event loop has turned after Side by side: the two panels side by side
// still held at their widths (until a zero timer releases them) once counted that width twice and
// packed one panel a row, two on screen (CI, under load, where a 300 ms wait was not enough).
TEST(PlotDocks, TiledRightAfterSideBySideShowsSeveralPanels) {
    QSettings().remove("window");
    Studio studio;
    MainWindow& w = studio.window;
    w.resize(kWindowAt1366x768);
    wait();
    // The tiling after a settled Side by side, then the same chosen before the event loop turns:
    // the same panels on screen (it gets the re-apply with the column hidden, as the other does).
    w.showPanel("forces");
    studio.action("action.layout_side_by_side")->trigger();
    wait(500);
    studio.action("action.layout_tiled")->trigger();
    wait(500);
    const QStringList settled = panelsShown(w);
    studio.action("action.layout_default")->trigger();
    wait(500);
    w.showPanel("forces");
    studio.action("action.layout_side_by_side")->trigger();
    studio.action("action.layout_tiled")->trigger();
    wait(500);
    EXPECT_GE(panelsOnScreen(w, "tiled right after side by side"), 4);
    EXPECT_EQ(panelsShown(w), settled);
    EXPECT_EQ(w.size(), kWindowAt1366x768);
    QSettings().remove("window");
}

TEST(PlotDocks, SideBySideAndTiledPanelsDoNotScrollSidewaysAt1366x768) {
    QSettings().remove("window");
    Studio studio;
    MainWindow& w = studio.window;
    w.resize(kWindowAt1366x768);
    wait();
    // Side by side from each panel: it and one beside it on screen, neither scrolling sideways.
    for (const char* current : kAllPanels) {
        w.showPanel(current);
        studio.action("action.layout_side_by_side")->trigger();
        wait(300);
        EXPECT_EQ(w.currentPanelName(), current);
        EXPECT_TRUE(onScreen(w.panelDock(current))) << current;
        EXPECT_EQ(panelsOnScreen(w, QString("side by side from ") + current), 2) << current;
        EXPECT_EQ(w.size(), kWindowAt1366x768) << current;
    }
    // Tiled (from Default, the Project and Properties column on screen): several panels on
    // screen, the others tabbed with one of them; none scrolls sideways, not even a tabbed one
    // brought to front.
    studio.action("action.layout_default")->trigger();
    wait();
    studio.action("action.layout_tiled")->trigger();
    wait(300);
    int shown = 0;
    for (const char* name : kAllPanels) {
        QDockWidget* dock = w.panelDock(name);
        if (onScreen(dock)) {
            ++shown;
            expectNoSidewaysScroll(w, name, "tiled");
        } else {
            EXPECT_FALSE(w.panelArea()->tabifiedDockWidgets(dock).isEmpty()) << name;
        }
    }
    EXPECT_GE(shown, 4);
    EXPECT_EQ(w.size(), kWindowAt1366x768);  // the window never grows past the screen
    for (const char* name : kAllPanels) {
        w.panelDock(name)->raise();
        wait(100);
        EXPECT_TRUE(onScreen(w.panelDock(name))) << name;
        expectNoSidewaysScroll(w, name, "tiled, brought to front");
    }
    // Side by side with a plot of the panel in a dock of its own: the panel and its plot.
    QDockWidget* fx = forcesBesideItsDrawbarPull(studio);
    ASSERT_NE(fx, nullptr);
    EXPECT_TRUE(onScreen(fx));
    EXPECT_LT(w.panelDock("forces")->geometry().right(), fx->geometry().left());
    expectNoSidewaysScroll(w, "forces", "side by side with its plot");
    EXPECT_EQ(w.size(), kWindowAt1366x768);
    for (const char* name : kAllPanels) {
        if (QString(name) != "forces") {
            EXPECT_FALSE(onScreen(w.panelDock(name))) << name;
        }
    }
    // Default puts every plot back into its panel.
    studio.action("action.layout_default")->trigger();
    wait();
    EXPECT_TRUE(w.plotDocking()->tornOff().isEmpty());
    EXPECT_NE(forcesPlot(studio, "Fx_N-vs-slip")->parentWidget()->parentWidget(), nullptr);
    EXPECT_TRUE(studio.panel<ui::ForcesPanel>()->isAncestorOf(forcesPlot(studio, "Fx_N-vs-slip")));
    QSettings().remove("window");
}

// At 1024×700 no panel fits beside another: Side by side puts the plot (or the next panel) under
// the panel instead, Tile one panel a row, and no panel on screen scrolls sideways.
TEST(PlotDocks, At1024x700SideBySidePutsThePlotUnderThePanel) {
    QSettings().remove("window");
    Studio studio;
    MainWindow& w = studio.window;
    w.resize(kWindowAt1024x700);
    wait();
    for (const char* current : {"forces", "identification"}) {
        w.showPanel(current);
        studio.action("action.layout_side_by_side")->trigger();
        wait(300);
        EXPECT_EQ(panelsOnScreen(w, QString("1024×700, side by side from ") + current), 2)
            << current;
    }
    QDockWidget* fx = forcesBesideItsDrawbarPull(studio);
    ASSERT_NE(fx, nullptr);
    EXPECT_TRUE(onScreen(fx));
    EXPECT_LT(w.panelDock("forces")->geometry().bottom(), fx->geometry().top());
    expectNoSidewaysScroll(w, "forces", "1024×700, side by side with its plot");
    studio.action("action.layout_tiled")->trigger();
    wait(300);
    EXPECT_EQ(panelsOnScreen(w, "1024×700, tiled"), 2);
    QSettings().remove("window");
}

TEST(PlotDocks, APlotInItsOwnDockComesBackWithTheWindow) {
    QSettings().remove("window");
    QRect panel_geometry, plot_geometry;
    {
        Studio studio;
        MainWindow& w = studio.window;
        w.resize(kWindowAt1366x768);
        wait();
        w.applyLayout(MainWindow::Layout::kDefault);
        w.showPanel("forces");
        wait();
        QDockWidget* dock = w.plotDocking()->tearOff(forcesPlot(studio, "Fx_N-vs-slip"));
        ASSERT_NE(dock, nullptr);
        wait();
        // Beside the panels, in the panel area.
        EXPECT_EQ(w.panelArea()->dockWidgetArea(dock), Qt::RightDockWidgetArea);
        EXPECT_TRUE(onScreen(dock));
        EXPECT_LT(w.panelDock("forces")->geometry().right(), dock->geometry().left());
        // Side by side: the panel and its plot, the panel not scrolling sideways.
        studio.action("action.layout_side_by_side")->trigger();
        wait(300);
        EXPECT_TRUE(onScreen(dock));
        EXPECT_LT(w.panelDock("forces")->geometry().right(), dock->geometry().left());
        expectNoSidewaysScroll(w, "forces", "beside its torn-off plot");
        panel_geometry = w.panelDock("forces")->geometry();
        plot_geometry = dock->geometry();
        w.close();
    }
    {
        Studio studio;
        MainWindow& w = studio.window;
        wait(300);
        auto* dock = w.panelArea()->findChild<QDockWidget*>("plot.forces.Fx_N-vs-slip");
        ASSERT_NE(dock, nullptr);
        QCustomPlot* fx = forcesPlot(studio, "Fx_N-vs-slip");
        EXPECT_EQ(dock->widget(), fx);
        EXPECT_EQ(w.plotDocking()->dockOf(fx), dock);
        EXPECT_TRUE(onScreen(dock));
        EXPECT_LT(w.panelDock("forces")->geometry().right(), dock->geometry().left());
        // (Its widths are those of the offscreen screen's window: not compared.)
        EXPECT_EQ(dock->geometry().top(), plot_geometry.top());
        EXPECT_EQ(w.panelDock("forces")->geometry().top(), panel_geometry.top());
        EXPECT_TRUE(onScreen(w.panelDock("forces")));
        // The panel still draws into it: an edit that recomputes redraws it.
        auto* forces = studio.panel<ui::ForcesPanel>();
        if (forces->isBusy() || !forces->hasResult()) {
            QSignalSpy shown(forces, &ui::AnalysisPanel::resultShown);
            ASSERT_TRUE(shown.wait(30000));
        }
        const double before = fx->graph(0)->data()->at(50)->value;
        QSignalSpy shown(forces, &ui::AnalysisPanel::resultShown);
        ASSERT_TRUE(w.document()->setSoilValue("phi_deg", 25.0));
        ASSERT_TRUE(shown.wait(30000));
        EXPECT_NE(fx->graph(0)->data()->at(50)->value, before);
        EXPECT_DOUBLE_EQ(fx->graph(0)->data()->at(50)->value,
                         forces->result().table.rows[50][forces->result().table.column("Fx_N")]);
    }
    // Names of plots no panel has (an older or newer studio's) are ignored; the others come back.
    QSettings().setValue("window/plots", QStringList{"plot.forces.gone", "plot.nowhere.x", "",
                                                     "plot.stresses.stresses"});
    {
        Studio studio;
        MainWindow& w = studio.window;
        wait();
        EXPECT_EQ(w.plotDocking()->tornOff(), QStringList{"plot.stresses.stresses"});
        EXPECT_EQ(w.panelArea()->findChild<QDockWidget*>("plot.forces.Fx_N-vs-slip"), nullptr);
        // Default puts it back; the window then saves no torn-off plot.
        studio.action("action.layout_default")->trigger();
        wait();
        w.close();
    }
    EXPECT_TRUE(QSettings().value("window/plots").toStringList().isEmpty());
    QSettings().remove("window");
}

}  // namespace
}  // namespace terra::app
