#include "widgets/plots/plot_theme.h"

#include <qcustomplot.h>

#include <QEvent>
#include <QPalette>

namespace terra::ui {
namespace {

constexpr const char* kFollowsPalette = "terraFollowsPalette";

QColor mix(const QColor& a, const QColor& b, double t) {
    return QColor::fromRgbF(static_cast<float>(a.redF() + (b.redF() - a.redF()) * t),
                            static_cast<float>(a.greenF() + (b.greenF() - a.greenF()) * t),
                            static_cast<float>(a.blueF() + (b.blueF() - a.blueF()) * t));
}

/// Re-applies the palette's theme when the palette changes.
class PaletteFollower : public QObject {
public:
    using QObject::QObject;
    bool eventFilter(QObject* watched, QEvent* event) override {
        if (event->type() == QEvent::PaletteChange ||
            event->type() == QEvent::ApplicationPaletteChange) {
            auto* plot = static_cast<QCustomPlot*>(watched);
            applyPlotTheme(*plot, PlotTheme::fromPalette(plot->palette()));
            plot->replot(QCustomPlot::rpQueuedReplot);
        }
        return false;
    }
};

}  // namespace

PlotTheme PlotTheme::light() {
    return {Qt::white,
            Qt::black,
            QColor(200, 200, 200),
            QColor(220, 220, 220),
            QColor(200, 200, 200),
            QColor(255, 255, 255, 230)};
}

PlotTheme PlotTheme::fromPalette(const QPalette& palette) {
    const QColor background = palette.color(QPalette::Active, QPalette::Base);
    const QColor foreground = palette.color(QPalette::Active, QPalette::Text);
    QColor legend = background;
    legend.setAlpha(230);
    return {background,
            foreground,
            mix(background, foreground, 0.25),
            mix(background, foreground, 0.13),
            mix(background, foreground, 0.35),
            legend};
}

void applyPlotTheme(QCustomPlot& plot, const PlotTheme& theme) {
    plot.setBackground(QBrush(theme.background));
    for (int r = 0; r < plot.axisRectCount(); ++r) {
        QCPAxisRect* rect = plot.axisRect(r);
        rect->setBackground(QBrush(theme.background));
        for (QCPAxis* axis : rect->axes()) {
            axis->setBasePen(QPen(theme.foreground, 0));
            axis->setTickPen(QPen(theme.foreground, 0));
            axis->setSubTickPen(QPen(theme.foreground, 0));
            axis->setTickLabelColor(theme.foreground);
            axis->setLabelColor(theme.foreground);
            axis->setSelectedTickLabelColor(theme.foreground);
            axis->grid()->setPen(QPen(theme.grid, 0, Qt::DotLine));
            axis->grid()->setSubGridPen(QPen(theme.sub_grid, 0, Qt::DotLine));
            axis->grid()->setZeroLinePen(QPen(theme.zero_line, 0, Qt::SolidLine));
        }
    }
    plot.legend->setBrush(QBrush(theme.legend_background));
    plot.legend->setBorderPen(QPen(theme.foreground, 0));
    plot.legend->setTextColor(theme.foreground);
    for (int i = 0; i < plot.plotLayout()->elementCount(); ++i) {
        if (auto* text = qobject_cast<QCPTextElement*>(plot.plotLayout()->elementAt(i))) {
            text->setTextColor(theme.foreground);
        }
    }
}

void followPalette(QCustomPlot& plot) {
    if (!followsPalette(plot)) {
        plot.setProperty(kFollowsPalette, true);
        plot.installEventFilter(new PaletteFollower(&plot));
    }
    applyPlotTheme(plot, PlotTheme::fromPalette(plot.palette()));
}

bool followsPalette(const QCustomPlot& plot) { return plot.property(kFollowsPalette).toBool(); }

}  // namespace terra::ui
