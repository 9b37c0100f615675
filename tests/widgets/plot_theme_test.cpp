// Plots follow the application's palette on screen (a dark desktop gets dark plots) and export
// light for reports unless asked to keep the screen colours.
#include "widgets/plots/plot_theme.h"

#include <gtest/gtest.h>
#include <qcustomplot.h>

#include <QApplication>
#include <QImage>
#include <QPalette>
#include <QTemporaryDir>

#include "core/analysis/forces.h"
#include "core/project/project.h"
#include "widgets/plots/figures.h"
#include "widgets/plots/plot_export.h"
#include "widgets/plots/sweep_plot.h"
#include "widgets_test_support.h"

namespace terra::ui {
namespace {

QPalette darkPalette() {
    QPalette p;
    p.setColor(QPalette::Window, QColor(45, 45, 48));
    p.setColor(QPalette::WindowText, QColor(220, 220, 220));
    p.setColor(QPalette::Base, QColor(30, 30, 30));
    p.setColor(QPalette::Text, QColor(230, 230, 230));
    p.setColor(QPalette::Button, QColor(45, 45, 48));
    p.setColor(QPalette::ButtonText, QColor(220, 220, 220));
    return p;
}

double lightness(const QColor& c) { return c.lightnessF(); }

/// Sets a dark application palette for one test and restores the previous one.
class DarkDesktop : public ::testing::Test {
protected:
    void SetUp() override {
        saved_ = QApplication::palette();
        QApplication::setPalette(darkPalette());
        analysis::Inputs in = project::inputsOf(ProjectDocument::defaultProject(test::resources()));
        in.conditions.slip_angles_deg = {5, 20};
        in.conditions.slip_count = 30;
        table_ = analysis::computeForceSweep(in).table;
    }
    void TearDown() override { QApplication::setPalette(saved_); }
    QPalette saved_;
    Table table_;
    QTemporaryDir dir_;
};

TEST_F(DarkDesktop, PlotFrameFollowsTheDarkPalette) {
    QCustomPlot plot;
    plot.resize(600, 400);
    plotSweep(plot, table_, sweepQuantities()[0], "dark");
    EXPECT_LT(lightness(plot.axisRect()->backgroundBrush().color()), 0.3);
    EXPECT_GT(lightness(plot.xAxis->tickLabelColor()), 0.7);
    EXPECT_GT(lightness(plot.yAxis->labelColor()), 0.7);
    EXPECT_GT(lightness(plot.xAxis->basePen().color()), 0.7);
    EXPECT_GT(lightness(plot.legend->textColor()), 0.7);
    // The grid sits between background and text: visible on dark, not glaring.
    const double grid = lightness(plot.xAxis->grid()->pen().color());
    EXPECT_GT(grid, 0.2);
    EXPECT_LT(grid, 0.5);
    // What is drawn on screen is dark too, outside the axis rect (QCustomPlot's own background
    // brush has no getter) and inside it.
    const QImage screen = plot.toPixmap(600, 400).toImage();
    EXPECT_LT(lightness(QColor(screen.pixel(2, 2))), 0.3);
    const QPoint inside = plot.axisRect()->rect().center();
    EXPECT_LT(lightness(QColor(screen.pixel(inside.x() + 3, inside.y() + 3))), 0.3);
}

TEST_F(DarkDesktop, ExportsStayLightUnlessAsked) {
    QCustomPlot plot;
    plot.resize(600, 400);
    plotSweep(plot, table_, sweepQuantities()[0], "dark");
    const QString light = dir_.filePath("light.png");
    QString error;
    ASSERT_TRUE(exportPlot(plot, light, {400, 300, 96, 1.0}, &error)) << error.toStdString();
    const QImage image(light);
    ASSERT_FALSE(image.isNull());
    EXPECT_EQ(QColor(image.pixel(0, 0)), QColor(Qt::white));
    EXPECT_EQ(QColor(image.pixel(image.width() - 1, image.height() - 1)), QColor(Qt::white));
    // The screen keeps its dark frame after the export.
    EXPECT_LT(lightness(plot.axisRect()->backgroundBrush().color()), 0.3);
    EXPECT_GT(lightness(plot.xAxis->tickLabelColor()), 0.7);

    ExportOptions screen{400, 300, 96, 1.0};
    screen.screen_colours = true;
    const QString dark = dir_.filePath("dark.png");
    ASSERT_TRUE(exportPlot(plot, dark, screen, &error)) << error.toStdString();
    EXPECT_LT(lightness(QColor(QImage(dark).pixel(0, 0))), 0.3);
}

// A plot drawn with its own frame colours (not through resetPlot/plotSweep) keeps them on screen
// and in the file: the export only re-colours plots that follow the palette.
TEST_F(DarkDesktop, PlotsWithTheirOwnColoursAreLeftAlone) {
    QCustomPlot plot;
    plot.resize(400, 300);
    plot.yAxis->setTickLabelColor(QColor(214, 39, 40));
    plot.yAxis->setBasePen(QPen(QColor(214, 39, 40)));
    QString error;
    ASSERT_TRUE(exportPlot(plot, dir_.filePath("own.png"), {400, 300, 96, 1.0}, &error))
        << error.toStdString();
    EXPECT_FALSE(followsPalette(plot));
    EXPECT_EQ(plot.yAxis->tickLabelColor(), QColor(214, 39, 40));
    EXPECT_EQ(plot.yAxis->basePen().color(), QColor(214, 39, 40));
}

TEST_F(DarkDesktop, ChangingThePaletteRethemesDrawnPlots) {
    QApplication::setPalette(saved_);  // start light
    QCustomPlot plot;
    analysis::SensitivityResult empty;
    plotTornado(plot, empty, 0.3, "tornado");  // through resetPlot()
    EXPECT_GT(lightness(plot.axisRect()->backgroundBrush().color()), 0.7);
    QApplication::setPalette(darkPalette());  // the desktop switches to dark
    QCoreApplication::processEvents();
    EXPECT_LT(lightness(plot.axisRect()->backgroundBrush().color()), 0.3);
    EXPECT_GT(lightness(plot.xAxis->tickLabelColor()), 0.7);
}

TEST(PlotTheme, LightThemeIsQCustomPlotsLook) {
    const PlotTheme light = PlotTheme::light();
    EXPECT_EQ(light.background, QColor(Qt::white));
    EXPECT_EQ(light.foreground, QColor(Qt::black));
    EXPECT_FALSE(light.isDark());
    EXPECT_TRUE(PlotTheme::fromPalette(darkPalette()).isDark());
}

}  // namespace
}  // namespace terra::ui
