#include "widgets/plots/compaction_figures.h"

#include <qcustomplot.h>

#include <algorithm>
#include <stdexcept>

#include "widgets/plots/figures.h"
#include "widgets/plots/plot_theme.h"

namespace terra::ui {
namespace {

const QColor kSigmaZColor(31, 119, 180);
const QColor kMeanColor(148, 103, 189);
const QColor kMajorColor(140, 86, 75);
const QColor kPrecompressionColor(128, 128, 128);  // readable on light and dark frames
const QColor kRedLineColor(214, 39, 40);
// The red band reaches this many times the view's width to the right, so zooming out still
// shows red beyond 1.1 σ_pc (items: a double-click's rescaleAxes() ignores them).
constexpr double kRedBandReach = 100.0;

QCPGraph* addDepthCurve(QCustomPlot& plot, const QVector<double>& depth,
                        const QVector<double>& stress, const QString& name, const QColor& color,
                        Qt::PenStyle style = Qt::SolidLine, double width = 1.8) {
    QCPGraph* graph = plot.addGraph(plot.yAxis, plot.xAxis);  // key: depth, value: stress
    graph->setData(depth, stress, true);
    graph->setName(name);
    graph->setPen(QPen(color, width, style));
    return graph;
}

void addBand(QCustomPlot& plot, double x0, double x1, double top, double bottom,
             const QColor& fill) {
    auto* rect = new QCPItemRect(&plot);
    rect->setLayer("background");  // behind the grid and the curves
    rect->topLeft->setCoords(x0, top);
    rect->bottomRight->setCoords(x1, bottom);
    rect->setPen(Qt::NoPen);
    rect->setBrush(fill);
}

/// A legend entry for a band (bars draw a filled box as their icon; they hold no data).
void addBandLegend(QCustomPlot& plot, const QString& name, const QColor& fill) {
    auto* bars = new QCPBars(plot.xAxis, plot.yAxis);
    bars->setName(name);
    bars->setBrush(fill);
    bars->setPen(Qt::NoPen);
}

void emptyNote(QCustomPlot& plot, const QString& text) {
    auto* note = new QCPItemText(&plot);
    note->position->setType(QCPItemPosition::ptAxisRectRatio);
    note->position->setCoords(0.5, 0.5);
    note->setText(text);
    note->setColor(QColor(128, 128, 128));
}

/// σ_pc of each layer [Pa] before pass `pass` (0: the untouched profile's, as for pass 1).
std::vector<double> precompressionBefore(const analysis::CompactionResult& result, int pass) {
    const auto& layers = result.profile->layers;
    if (pass >= 2) {
        const std::vector<double>& after = result.passes[std::size_t(pass - 2)].precompression_pa;
        if (after.size() == layers.size()) return after;
    }
    std::vector<double> out;
    for (const soil::SoilLayer& layer : layers) out.push_back(soil::precompressionStress(layer));
    return out;
}

/// The precompression step line and the risk bands down to `z_end`; returns the largest
/// 1.1 σ_pc drawn [kPa].
double drawRisk(QCustomPlot& plot, const analysis::CompactionResult& result, int pass,
                double z_end) {
    const std::vector<double> pc = precompressionBefore(result, pass);
    QVector<double> z, value;
    double red_start = 0.0;
    std::vector<std::pair<double, double>> spans;  // each layer's [top, bottom] in view
    for (std::size_t l = 0; l < pc.size(); ++l) {
        const soil::SoilLayer& layer = result.profile->layers[l];
        if (layer.top_m >= z_end) break;
        const double bottom = std::min(layer.bottom_m, z_end), kpa = pc[l] / 1e3;
        z << layer.top_m << bottom;
        value << kpa << kpa;
        spans.emplace_back(layer.top_m, bottom);
        red_start = std::max(red_start, compaction::kRedRatio * kpa);
    }
    addDepthCurve(plot, z, value, pass >= 2 ? QString("σ_pc before pass %1").arg(pass) : "σ_pc",
                  kPrecompressionColor, Qt::SolidLine, 2.4);
    const double reach = kRedBandReach * std::max(red_start, 1.0);
    for (std::size_t l = 0; l < spans.size(); ++l) {
        const double kpa = value[int(2 * l)], top = spans[l].first, bottom = spans[l].second;
        addBand(plot, 0.0, compaction::kYellowRatio * kpa, top, bottom,
                riskBandColor(analysis::Risk::kGreen));
        addBand(plot, compaction::kYellowRatio * kpa, compaction::kRedRatio * kpa, top, bottom,
                riskBandColor(analysis::Risk::kYellow));
        addBand(plot, compaction::kRedRatio * kpa, reach, top, bottom,
                riskBandColor(analysis::Risk::kRed));
    }
    addBandLegend(plot, "green: σ ≤ 0.5 σ_pc", riskBandColor(analysis::Risk::kGreen));
    addBandLegend(plot, "yellow: ≤ 1.1 σ_pc", riskBandColor(analysis::Risk::kYellow));
    addBandLegend(plot, "red: > 1.1 σ_pc", riskBandColor(analysis::Risk::kRed));
    return red_start;
}

void markRedZone(QCustomPlot& plot, double depth_m) {
    auto* line = new QCPItemStraightLine(&plot);
    line->point1->setCoords(0.0, depth_m);
    line->point2->setCoords(1.0, depth_m);
    line->setPen(QPen(kRedLineColor, 1.5, Qt::DashLine));
    auto* label = new QCPItemText(&plot);
    label->position->setTypeX(QCPItemPosition::ptAxisRectRatio);
    label->position->setTypeY(QCPItemPosition::ptPlotCoords);
    label->position->setCoords(0.99, depth_m);
    label->setPositionAlignment(Qt::AlignRight | Qt::AlignBottom);
    label->setText(QString("red zone to z = %1 m").arg(depth_m, 0, 'f', 3));
    label->setColor(kRedLineColor);
}

}  // namespace

QColor riskBandColor(analysis::Risk risk) {
    switch (risk) {
        case analysis::Risk::kGreen:
            return QColor(44, 160, 44, 40);
        case analysis::Risk::kYellow:
            return QColor(240, 200, 0, 60);
        case analysis::Risk::kRed:
            break;
    }
    return QColor(214, 39, 40, 45);
}

Completion compactionCompletion(const analysis::CompactionResult& result) {
    if (result.ok()) return Completion::kComplete;
    return result.cancelled ? Completion::kCancelled : Completion::kFailed;
}

QString compactionStatus(const analysis::CompactionResult& result) {
    return completionMark(compactionCompletion(result));
}

QString compactionTitle(const QString& title, const analysis::CompactionResult& result) {
    return markedTitle(title, compactionCompletion(result));
}

void plotCompactionProfile(QCustomPlot& plot, const analysis::CompactionResult& result, int pass,
                           const QString& title) {
    if (pass < 0 || pass > static_cast<int>(result.passes.size())) {
        throw std::out_of_range("pass " + std::to_string(pass) + " of " +
                                std::to_string(result.passes.size()) + " computed");
    }
    const std::vector<analysis::DepthValues>& rows =
        pass == 0 ? result.envelope : result.passes[std::size_t(pass - 1)].profile;
    resetPlot(plot, title);
    plot.xAxis->setLabel("stress [kPa]");
    plot.yAxis->setLabel("depth z [m]");
    plot.yAxis->setRangeReversed(true);
    if (rows.empty()) {
        emptyNote(plot, result.ok() ? "No depth below the wheel" : "No pass computed");
        plot.replot();
        return;
    }
    QVector<double> z, sigma_z, mean, major;
    double x_low = 0.0, x_high = 0.0;
    for (const analysis::DepthValues& v : rows) {
        z << v.depth_m;
        sigma_z << v.max.sigma_z / 1e3;
        mean << v.max.mean / 1e3;
        major << v.max.major / 1e3;
        for (double s : {v.max.sigma_z, v.max.mean, v.max.major}) {
            x_low = std::min(x_low, s / 1e3);
            x_high = std::max(x_high, s / 1e3);
        }
    }
    const double z_end = z.back();
    if (result.profile) x_high = std::max(x_high, drawRisk(plot, result, pass, z_end));
    // σ₁ is close to σ_z under a wheel: drawn first (dashed), σ_z on top of it.
    QCPGraph* major_graph = addDepthCurve(plot, z, major, "σ₁", kMajorColor, Qt::DashLine, 1.4);
    QCPGraph* mean_graph = addDepthCurve(plot, z, mean, "p", kMeanColor);
    QCPGraph* sigma_z_graph = addDepthCurve(plot, z, sigma_z, "σ_z", kSigmaZColor, Qt::SolidLine);
    // The legend lists the curves first, then σ_pc and the bands.
    plot.legend->clearItems();
    for (QCPAbstractPlottable* curve : {static_cast<QCPAbstractPlottable*>(sigma_z_graph),
                                        static_cast<QCPAbstractPlottable*>(mean_graph),
                                        static_cast<QCPAbstractPlottable*>(major_graph)})
        curve->addToLegend();
    for (int i = 0; i < plot.plottableCount(); ++i) {
        QCPAbstractPlottable* other = plot.plottable(i);
        if (other != sigma_z_graph && other != mean_graph && other != major_graph)
            other->addToLegend();
    }
    const std::optional<double> red =
        pass == 0 ? result.red_to_depth_m : result.passes[std::size_t(pass - 1)].red_to_depth_m;
    if (red && *red > 0.0) markRedZone(plot, *red);
    if (!(x_high > x_low)) x_high = x_low + 1.0;
    plot.xAxis->setRange(x_low, x_low + 1.08 * (x_high - x_low));
    plot.yAxis->setRange(0.0, 1.03 * z_end);
    plot.legend->setVisible(true);
    legendBelow(plot, 4);
    plot.replot();
}

void plotCompactionMap(QCustomPlot& plot, const analysis::CompactionResult& result,
                       const QString& title) {
    removeColorScales(plot);
    resetPlot(plot, title);
    plot.xAxis->setLabel("x along travel [m]");
    plot.yAxis->setLabel("depth z [m]");
    plot.yAxis->setRangeReversed(true);
    const Table& map = result.map;
    if (map.rows.empty()) {
        emptyNote(plot, "No stress map (no pass computed)");
        plot.xAxis->setRange(-1.0, 1.0);
        plot.yAxis->setRange(0.0, 1.0);
        plot.replot();
        return;
    }
    const std::size_t xc = map.column("x_m"), zc = map.column("z_m"),
                      sc = map.column("sigma_z_kPa");
    std::size_t nx = 0;
    while (nx < map.rows.size() && map.rows[nx][zc] == map.rows.front()[zc]) ++nx;
    const std::size_t nz = map.rows.size() / nx;
    double highest = 0.0;
    for (const auto& row : map.rows) highest = std::max(highest, row[sc]);
    const double lowest = highest > 0.0 ? 1e-3 * highest : 1e-3;
    auto* colors = new QCPColorMap(plot.xAxis, plot.yAxis);
    colors->setName("σ_z");
    colors->data()->setSize(int(nx), int(nz));
    colors->data()->setRange(QCPRange(map.rows.front()[xc], map.rows[nx - 1][xc]),
                             QCPRange(map.rows.front()[zc], map.rows[(nz - 1) * nx][zc]));
    for (std::size_t iz = 0; iz < nz; ++iz) {
        for (std::size_t ix = 0; ix < nx; ++ix)
            colors->data()->setCell(int(ix), int(iz), std::max(map.rows[iz * nx + ix][sc], lowest));
    }
    auto* scale = new QCPColorScale(&plot);
    plot.plotLayout()->addElement(1, 1, scale);
    scale->setType(QCPAxis::atRight);
    scale->setDataScaleType(QCPAxis::stLogarithmic);
    scale->axis()->setTicker(QSharedPointer<QCPAxisTickerLog>(new QCPAxisTickerLog));
    scale->axis()->setLabel("σ_z [kPa]");
    colors->setColorScale(scale);
    colors->setGradient(QCPColorGradient::gpThermal);
    colors->setDataRange(QCPRange(lowest, std::max(highest, 10.0 * lowest)));
    QCPMarginGroup* group = plot.axisRect()->marginGroup(QCP::msTop);
    if (!group) group = new QCPMarginGroup(&plot);
    plot.axisRect()->setMarginGroup(QCP::msTop | QCP::msBottom, group);
    scale->setMarginGroup(QCP::msTop | QCP::msBottom, group);
    plot.rescaleAxes();
    plot.yAxis->setRangeLower(0.0);  // the surface in view: the wheel presses from there
    followPalette(plot);             // the colour scale's axis takes the frame's colours too
    plot.replot();
}

void plotCompactionPasses(QCustomPlot& plot, const analysis::CompactionResult& result,
                          const QString& title) {
    resetPlot(plot, title);
    plot.xAxis->setLabel("pass");
    plot.yAxis->setLabel("sinkage, rut depth [mm]");
    plot.yAxis->setRangeReversed(false);
    plot.yAxis2->setVisible(true);
    plot.yAxis2->setLabel("drawbar pull F_x [N]");
    QSharedPointer<QCPAxisTickerFixed> ticker(new QCPAxisTickerFixed);
    ticker->setTickStep(1.0);
    ticker->setScaleStrategy(QCPAxisTickerFixed::ssMultiples);
    plot.xAxis->setTicker(ticker);
    if (result.passes.empty()) {
        emptyNote(plot, "No pass computed");
        plot.replot();
        return;
    }
    QVector<double> pass, sinkage, rut, fx;
    for (const analysis::CompactionPass& p : result.passes) {
        pass << p.pass;
        sinkage << p.sinkage_m * 1e3;
        rut << p.rut_depth_m * 1e3;
        fx << p.forces.fx;
    }
    auto add = [&](QCPAxis* value_axis, const QVector<double>& y, const QString& name,
                   const QColor& color, QCPScatterStyle::ScatterShape shape) {
        QCPGraph* graph = plot.addGraph(plot.xAxis, value_axis);
        graph->setData(pass, y, true);
        graph->setName(name);
        graph->setPen(QPen(color, 1.8));
        graph->setScatterStyle(QCPScatterStyle(shape, 7));
    };
    add(plot.yAxis, sinkage, "sinkage", kSigmaZColor, QCPScatterStyle::ssDisc);
    add(plot.yAxis, rut, "rut after the pass", QColor(255, 127, 14), QCPScatterStyle::ssSquare);
    add(plot.yAxis2, fx, "F_x (right axis)", QColor(44, 160, 44), QCPScatterStyle::ssTriangle);
    plot.rescaleAxes();
    plot.xAxis->setRange(0.5, result.passes.size() + 0.5);
    plot.yAxis->setRange(0.0, 1.15 * std::max(plot.yAxis->range().upper, 1e-3));
    const QCPRange f = plot.yAxis2->range();
    const double low = std::min(f.lower, 0.0), high = std::max(f.upper, 0.0);
    const double margin = 0.12 * std::max(high - low, 1e-3);
    plot.yAxis2->setRange(low - margin, high + margin);
    plot.legend->setVisible(true);
    legendBelow(plot, 3);
    plot.replot();
}

}  // namespace terra::ui
