// Issue 27, item 1: any plot of a panel in a dock of its own (widgets/panels/plot_docking.h), on
// real widgets under QT_QPA_PLATFORM=offscreen: torn off from its right-click menu, the same plot
// keeps being drawn by its panel (even while the panel is hidden), its Copy data is its own, and
// Put back or closing the dock returns it to its tab at its index.
#include "widgets/panels/plot_docking.h"

#include <gtest/gtest.h>
#include <qcustomplot.h>

#include <QApplication>
#include <QClipboard>
#include <QDockWidget>
#include <QLabel>
#include <QMainWindow>
#include <QMenu>
#include <QPushButton>
#include <QSplitter>
#include <QTabWidget>
#include <QTest>
#include <QVBoxLayout>

#include "widgets/panels/compaction_panel.h"
#include "widgets/panels/global_sensitivity_panel.h"
#include "widgets/panels/identification_panel.h"
#include "widgets/panels/rover_panel.h"
#include "widgets/panels/sensitivity_panel.h"
#include "widgets/panels/stress_panel.h"
#include "widgets_test_support.h"

namespace terra::ui {
namespace {

/// The action named `name` of the plot's right-click menu, as a user opens it.
QAction* plotMenuAction(QCustomPlot& plot, const QString& name) {
    emit plot.customContextMenuRequested(QPoint(20, 20));
    const QList<QMenu*> menus = plot.findChildren<QMenu*>();
    if (menus.isEmpty()) return nullptr;
    QMenu* menu = menus.back();
    menu->close();  // WA_DeleteOnClose: gone once the action has run
    return menu->findChild<QAction*>(name);
}

// Export plot… of the streaming page's detection plot exported the estimates plot (the page's
// currentPlot()): the menu now names its own plot.
TEST(PlotMenuExport, EachPlotsMenuExportsThatPlot) {
    ProjectDocument document;
    test::resetToDefault(document);
    IdentificationPanel panel(&document);
    panel.installPlotMenus();
    std::vector<QCustomPlot*> asked;
    QObject::connect(&panel, &AnalysisPanel::exportRequested,
                     [&asked](QCustomPlot* plot) { asked.push_back(plot); });
    for (const auto& [name, plot] : panel.plots()) {
        QAction* action = plotMenuAction(*plot, "plot.export");
        ASSERT_NE(action, nullptr) << name.toStdString();
        action->trigger();
        ASSERT_FALSE(asked.empty()) << name.toStdString();
        EXPECT_EQ(asked.back(), plot) << name.toStdString();
    }
    EXPECT_EQ(asked.size(), panel.plots().size());
}

/// A window holding the forces panel in a dock, as the studio's panel area does.
struct DockedForces {
    DockedForces() {
        test::resetToDefault(document);
        panel = new ForcesPanel(&document);
        home = new QDockWidget("Forces vs slip", &window);
        home->setObjectName("panel.forces");
        home->setWidget(panel);
        window.addDockWidget(Qt::TopDockWidgetArea, home);
        docking.addPanel(panel, home, "Forces vs slip");
        window.resize(1300, 700);
        window.show();
    }
    ProjectDocument document;
    QMainWindow window;
    ForcesPanel* panel;
    QDockWidget* home;
    PlotDocking docking{&window};
};

TEST(PlotDocking, ATornOffPlotKeepsUpdatingAndGoesBackToItsTab) {
    DockedForces f;
    ASSERT_TRUE(test::waitForResult(*f.panel));
    auto* tabs = f.panel->findChild<QTabWidget*>();
    ASSERT_NE(tabs, nullptr);
    QStringList texts, tooltips;
    for (int i = 0; i < tabs->count(); ++i) {
        texts << tabs->tabText(i);
        tooltips << tabs->tabToolTip(i);
    }
    QCustomPlot* fx = test::namedPlot(*f.panel, "Fx_N-vs-slip");
    QCustomPlot* sinkage = test::namedPlot(*f.panel, "static-sinkage-vs-load");
    ASSERT_NE(fx, nullptr);
    ASSERT_NE(sinkage, nullptr);
    const int index = tabs->indexOf(fx);
    ASSERT_GE(index, 0);

    // Torn off from its right-click menu: the same plot, in a dock of the window.
    QAction* own = plotMenuAction(*fx, "plot.own_dock");
    ASSERT_NE(own, nullptr);
    EXPECT_EQ(own->text(), "Show in its own dock");
    own->trigger();
    QDockWidget* dock = f.docking.dockOf(fx);
    ASSERT_NE(dock, nullptr);
    EXPECT_EQ(dock->objectName(), "plot.forces.Fx_N-vs-slip");
    EXPECT_EQ(dock->widget(), fx);
    EXPECT_EQ(f.window.dockWidgetArea(dock), Qt::RightDockWidgetArea);
    EXPECT_EQ(dock->windowTitle(), "Forces vs slip — " + texts[index]);
    EXPECT_EQ(f.docking.tornOff(), QStringList{"plot.forces.Fx_N-vs-slip"});
    // Its tab keeps its place, name and tooltip, and says where the plot went.
    ASSERT_EQ(tabs->count(), texts.size());
    EXPECT_EQ(tabs->tabText(index), texts[index]);
    EXPECT_EQ(tabs->tabToolTip(index), tooltips[index]);
    QWidget* placeholder = tabs->widget(index);
    ASSERT_NE(placeholder, fx);
    auto* said = placeholder->findChild<QLabel*>();
    ASSERT_NE(said, nullptr);
    EXPECT_TRUE(said->text().contains("shown in its own dock")) << said->text().toStdString();
    EXPECT_EQ(plotMenuAction(*fx, "plot.own_dock")->text(), "Put back into Forces vs slip");

    // Two plots of the panel side by side: the sinkage in the panel, F_x beside it.
    tabs->setCurrentWidget(sinkage);
    QTest::qWait(100);
    EXPECT_FALSE(fx->visibleRegion().isEmpty());
    EXPECT_FALSE(sinkage->visibleRegion().isEmpty());
    EXPECT_LT(sinkage->mapTo(&f.window, QPoint(0, 0)).x(), fx->mapTo(&f.window, QPoint(0, 0)).x());

    // Copy data of the torn-off plot is its data (the sweep), not the sinkage tab's, and the
    // panel stays on the tab it showed.
    plotMenuAction(*fx, "plot.copy_data")->trigger();
    const QString csv = QApplication::clipboard()->text();
    EXPECT_TRUE(csv.startsWith("slip_angle_deg,slip,")) << csv.left(80).toStdString();
    EXPECT_EQ(tabs->currentWidget(), sinkage);
    plotMenuAction(*sinkage, "plot.copy_data")->trigger();
    EXPECT_FALSE(QApplication::clipboard()->text().startsWith("slip_angle_deg,slip,"));

    // An edit that recomputes redraws the torn-off plot, even with the panel itself hidden.
    f.home->close();
    QTest::qWait(50);
    ASSERT_FALSE(f.panel->isVisible());
    ASSERT_TRUE(fx->isVisible());
    const double before = fx->graph(0)->data()->at(50)->value;
    ASSERT_TRUE(f.document.setSoilValue("phi_deg", 25.0));
    ASSERT_TRUE(test::waitForResult(*f.panel));
    const Table& table = f.panel->result().table;
    const double after = fx->graph(0)->data()->at(50)->value;
    EXPECT_NE(after, before);
    EXPECT_DOUBLE_EQ(after, table.rows[50][table.column("Fx_N")]);
    f.home->show();

    // Put back (the placeholder's button): at its index, with its name and tooltip; no dock left.
    auto* put_back = placeholder->findChild<QPushButton*>("plot.put_back");
    ASSERT_NE(put_back, nullptr);
    put_back->click();
    EXPECT_EQ(f.docking.dockOf(fx), nullptr);
    EXPECT_EQ(tabs->indexOf(fx), index);
    for (int i = 0; i < tabs->count(); ++i) {
        EXPECT_EQ(tabs->tabText(i), texts[i]);
        EXPECT_EQ(tabs->tabToolTip(i), tooltips[i]);
    }
    EXPECT_EQ(tabs->currentWidget(), sinkage);  // the tab on screen stays on screen
    QCoreApplication::sendPostedEvents(nullptr, QEvent::DeferredDelete);
    EXPECT_EQ(f.window.findChild<QDockWidget*>("plot.forces.Fx_N-vs-slip"), nullptr);
    EXPECT_TRUE(f.docking.tornOff().isEmpty());

    // Closing its dock puts it back too.
    QDockWidget* again = f.docking.tearOff(fx);
    ASSERT_NE(again, nullptr);
    again->close();
    EXPECT_EQ(f.docking.dockOf(fx), nullptr);
    EXPECT_EQ(tabs->indexOf(fx), index);
}

TEST(PlotDocking, RestoringNamesTearsOffKnownPlotsAndIgnoresOthers) {
    DockedForces f;
    ASSERT_TRUE(test::waitForResult(*f.panel));
    EXPECT_EQ(f.docking.restore({"plot.forces.no-such-plot", "plot.gone.Fx_N-vs-slip", "",
                                 "plot.forces.Fb-vs-sinkage", "plot.forces.Fz_N-vs-slip"}),
              2);
    EXPECT_EQ(f.docking.tornOff(),
              (QStringList{"plot.forces.Fb-vs-sinkage", "plot.forces.Fz_N-vs-slip"}));
    ASSERT_NE(f.window.findChild<QDockWidget*>("plot.forces.Fz_N-vs-slip"), nullptr);
    // The two docks one under the other, beside the panel.
    QDockWidget* fb = f.docking.dockOf(test::namedPlot(*f.panel, "Fb-vs-sinkage"));
    QDockWidget* fz = f.docking.dockOf(test::namedPlot(*f.panel, "Fz_N-vs-slip"));
    ASSERT_NE(fb, nullptr);
    ASSERT_NE(fz, nullptr);
    QTest::qWait(50);
    EXPECT_LT(fb->geometry().bottom(), fz->geometry().top());
    EXPECT_LT(f.home->geometry().right(), fz->geometry().left());
    f.docking.putAllBack();
    EXPECT_TRUE(f.docking.tornOff().isEmpty());
    EXPECT_TRUE(f.docking.docks().empty());
}

// A plot laid out in its panel (no tab): the placeholder takes its place in the layout, and Put
// back returns it there.
TEST(PlotDocking, APlotInALayoutGoesBackToItsPlace) {
    ProjectDocument document;
    test::resetToDefault(document);
    QMainWindow window;
    auto* panel = new StressPanel(&document);
    auto* home = new QDockWidget("Stresses", &window);
    home->setWidget(panel);
    window.addDockWidget(Qt::TopDockWidgetArea, home);
    PlotDocking docking(&window);
    docking.addPanel(panel, home, "Stresses");
    window.resize(1000, 600);
    window.show();
    ASSERT_TRUE(test::waitForResult(*panel));
    QCustomPlot* plot = panel->plots().front().second;
    QWidget* parent = plot->parentWidget();
    ASSERT_NE(parent->layout(), nullptr);
    const int at = parent->layout()->indexOf(plot);
    ASSERT_GE(at, 0);
    QDockWidget* dock = docking.tearOff(plot);
    ASSERT_NE(dock, nullptr);
    EXPECT_EQ(dock->objectName(), "plot.stresses.stresses");
    EXPECT_EQ(parent->layout()->indexOf(plot), -1);
    EXPECT_EQ(parent->layout()->itemAt(at)->widget()->objectName(), "plot.placeholder");
    docking.putBack(plot);
    EXPECT_EQ(plot->parentWidget(), parent);
    EXPECT_EQ(parent->layout()->indexOf(plot), at);
    EXPECT_TRUE(plot->isVisible());
}

/// Where a plot sits in its panel: its parent and its index there (a tab's, a splitter's or a
/// layout's).
std::pair<QWidget*, int> placeOf(QCustomPlot* plot) {
    QWidget* parent = plot->parentWidget();
    if (auto* tabs = qobject_cast<QTabWidget*>(parent->parentWidget());
        tabs && tabs->indexOf(plot) >= 0)
        return {tabs, tabs->indexOf(plot)};
    if (auto* splitter = qobject_cast<QSplitter*>(parent))
        return {splitter, splitter->indexOf(plot)};
    return {parent, parent->layout() ? parent->layout()->indexOf(plot) : -1};
}

// Every plot of every panel (in tabs, in a tab's layout, in a splitter, in the panel's layout)
// goes into a dock of its own and back to the same place.
TEST(PlotDocking, EveryPlotOfEveryPanelGoesBackWhereItWas) {
    ProjectDocument document;
    test::resetToDefault(document);
    QMainWindow window;
    PlotDocking docking(&window);
    std::vector<AnalysisPanel*> panels{new ForcesPanel(&document),
                                       new StressPanel(&document),
                                       new CompactionPanel(&document, test::resources()),
                                       new SensitivityPanel(&document),
                                       new IdentificationPanel(&document),
                                       new RoverPanel(&document, test::resources()),
                                       new GlobalSensitivityPanel(&document)};
    for (AnalysisPanel* panel : panels) {
        auto* home = new QDockWidget(panel->name(), &window);
        home->setWidget(panel);
        window.addDockWidget(Qt::TopDockWidgetArea, home);
        docking.addPanel(panel, home, panel->name());
    }
    window.resize(1300, 700);
    window.show();
    int plots = 0;
    for (AnalysisPanel* panel : panels) {
        for (const auto& [name, plot] : panel->plots()) {
            const auto [parent, index] = placeOf(plot);
            ASSERT_GE(index, 0) << name.toStdString();
            QDockWidget* dock = docking.tearOff(plot);
            ASSERT_NE(dock, nullptr) << name.toStdString();
            EXPECT_EQ(dock->widget(), plot) << name.toStdString();
            EXPECT_TRUE(dock->objectName().startsWith("plot." + panel->name() + "."));
            EXPECT_NE(placeOf(plot).first, parent) << name.toStdString();
            docking.putBack(plot);
            EXPECT_EQ(placeOf(plot), std::make_pair(parent, index)) << name.toStdString();
            ++plots;
        }
    }
    EXPECT_GE(plots, 20);
    EXPECT_TRUE(docking.docks().empty());
}

}  // namespace
}  // namespace terra::ui
