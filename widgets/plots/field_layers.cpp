#include "widgets/plots/field_layers.h"

#include <qcustomplot.h>

#include <algorithm>
#include <cmath>

#include "widgets/plots/figures.h"
#include "widgets/plots/plot_theme.h"

namespace terra::ui {
namespace {

const char* const kClassEntryName = "field layer class";

// The colours of a continuous layer (scenario::layerColors, shared with the maps' PNGs).
QCPColorGradient gradientFor(const scenario::MapLayer& layer, const LayerDisplay& display) {
    scenario::LayerScale scale;
    scale.lower = display.lower;
    scale.upper = display.upper;
    QCPColorGradient g;
    QMap<double, QColor> map;
    for (const scenario::ColorStop& stop : scenario::layerColors(layer, scale))
        map.insert(stop.at, QColor(stop.color.r, stop.color.g, stop.color.b));
    g.setColorStops(map);
    g.setColorInterpolation(QCPColorGradient::ciRGB);
    g.setNanHandling(QCPColorGradient::nhTransparent);
    return g;
}

// The layout cell of the plot's axis rect.
std::pair<int, int> axisRectCell(QCustomPlot& plot) {
    QCPLayoutGrid* grid = plot.plotLayout();
    for (int i = 0; i < grid->elementCount(); ++i) {
        if (grid->elementAt(i) != plot.axisRect()) continue;
        int row = 0, col = 0;
        grid->indexToRowCol(i, row, col);
        return {row, col};
    }
    return {1, 0};
}

double shown(double v, const LayerDisplay& display) {
    if (display.clear_zero && v == 0.0) return std::nan("");
    return v * display.factor;
}

void fill(QCPColorMap& map, const LayerDisplay& display, const field::Raster& view) {
    QCPColorMapData* data = map.data();
    // Rows run south to north in the colour map, north to south in the raster.
    for (int row = 0; row < view.rows; ++row) {
        for (int col = 0; col < view.cols; ++col)
            data->setCell(col, view.rows - 1 - row, shown(view.value(col, row), display));
    }
}

}  // namespace

LayerDisplay layerDisplay(const scenario::MapLayer& layer, const field::Raster& final_view) {
    const scenario::LayerScale scale = scenario::layerScale(layer, final_view);
    LayerDisplay d;
    d.factor = scale.factor;
    d.unit = QString::fromStdString(scale.unit);
    d.title = QString::fromStdString(scale.title);
    d.lower = scale.lower;
    d.upper = scale.upper;
    d.clear_zero = scale.clear_zero;
    return d;
}

QColor classColor(int index) {
    // Distinct but soft, under a dark path and robot: field, wet, headland, lanes, ...
    static const QColor colors[] = {QColor(222, 196, 150), QColor(120, 155, 195),
                                    QColor(165, 185, 105), QColor(205, 135, 100),
                                    QColor(165, 165, 165), QColor(175, 145, 195)};
    return colors[index % 6];
}

QCPColorMap* topViewLayer(QCustomPlot& plot) {
    for (int i = 0; i < plot.plottableCount(); ++i) {
        auto* map = qobject_cast<QCPColorMap*>(plot.plottable(i));
        if (map && map->name() == kFieldLayerName) return map;
    }
    return nullptr;
}

void removeTopViewLayer(QCustomPlot& plot) {
    for (int i = plot.plottableCount() - 1; i >= 0; --i) {
        QCPAbstractPlottable* p = plot.plottable(i);
        if (p->name() == kFieldLayerName || p->objectName() == kClassEntryName)
            plot.removePlottable(p);
    }
    removeColorScales(plot);
}

void drawTopViewLayer(QCustomPlot& plot, const scenario::MapLayer& layer,
                      const LayerDisplay& display, const field::Raster& view) {
    removeTopViewLayer(plot);
    if (view.cols <= 0 || view.rows <= 0) return;
    auto* map = new QCPColorMap(plot.xAxis, plot.yAxis);
    map->setName(kFieldLayerName);
    map->removeFromLegend();
    map->setLayer("grid");  // above the base soil, below the path and the robot
    map->setInterpolate(false);
    map->setTightBoundary(true);
    const double h = view.cell_m;
    map->data()->setSize(view.cols, view.rows);
    map->data()->setRange(QCPRange(view.x_min_m + 0.5 * h, view.xMax() - 0.5 * h),
                          QCPRange(view.y_min_m + 0.5 * h, view.yMax() - 0.5 * h));
    fill(*map, display, view);
    if (layer.kind == scenario::LayerKind::kClasses) {
        // A colour per class, by its place in the legend; the codes read through a lookup so
        // that codes need not be consecutive.
        const int n = static_cast<int>(layer.classes.size());
        QMap<double, QColor> stops;
        for (int i = 0; i < n; ++i)
            stops.insert(n > 1 ? static_cast<double>(i) / (n - 1) : 0.0, classColor(i));
        QCPColorGradient g;
        g.setColorStops(stops);
        g.setLevelCount(std::max(n, 2));
        g.setNanHandling(QCPColorGradient::nhTransparent);
        map->setGradient(g);
        QCPColorMapData* data = map->data();
        for (int row = 0; row < view.rows; ++row) {
            for (int col = 0; col < view.cols; ++col) {
                const double code = view.value(col, row);
                double index = std::nan("");
                for (int i = 0; i < n; ++i) {
                    if (layer.classes[static_cast<std::size_t>(i)].first == code) index = i;
                }
                data->setCell(col, view.rows - 1 - row, index);
            }
        }
        map->setDataRange(QCPRange(0.0, std::max(n - 1, 1)));
        for (int i = 0; i < n; ++i) {
            auto* entry = plot.addGraph();
            entry->setObjectName(kClassEntryName);
            entry->setLineStyle(QCPGraph::lsNone);
            entry->setScatterStyle(
                QCPScatterStyle(QCPScatterStyle::ssSquare, QColor(60, 60, 60), classColor(i), 10));
            entry->setName(
                QString::fromStdString(layer.classes[static_cast<std::size_t>(i)].second));
        }
        plot.legend->setVisible(true);
        return;
    }
    auto* scale = new QCPColorScale(&plot);
    scale->setObjectName(kFieldLayerName);
    const auto [row, col] = axisRectCell(plot);
    plot.plotLayout()->addElement(row, col + 1, scale);
    scale->setType(QCPAxis::atRight);
    scale->axis()->setLabel(display.title);
    scale->setBarWidth(12);
    // The scale gives the map its gradient and range when joined: both are set after.
    map->setColorScale(scale);
    map->setGradient(gradientFor(layer, display));
    map->setDataRange(QCPRange(display.lower, display.upper));
    if (layer.key == "passes") {
        QSharedPointer<QCPAxisTickerFixed> ticker(new QCPAxisTickerFixed);
        ticker->setTickStep(1.0);
        ticker->setScaleStrategy(QCPAxisTickerFixed::ssMultiples);
        scale->axis()->setTicker(ticker);
    }
    QCPMarginGroup* group = plot.axisRect()->marginGroup(QCP::msTop);
    if (!group) group = new QCPMarginGroup(&plot);
    plot.axisRect()->setMarginGroup(QCP::msTop | QCP::msBottom, group);
    scale->setMarginGroup(QCP::msTop | QCP::msBottom, group);
    followPalette(plot);  // the scale's axis takes the frame's colours too
}

void updateTopViewLayer(QCustomPlot& plot, const LayerDisplay& display, const field::Raster& view) {
    QCPColorMap* map = topViewLayer(plot);
    if (!map || map->data()->keySize() != view.cols || map->data()->valueSize() != view.rows)
        return;
    fill(*map, display, view);
}

}  // namespace terra::ui
