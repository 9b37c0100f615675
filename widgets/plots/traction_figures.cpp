#include "widgets/plots/traction_figures.h"

#include <qcustomplot.h>

#include <cmath>

#include "widgets/plots/figures.h"
#include "widgets/plots/plot_theme.h"

namespace terra::ui {
namespace {

const QColor kNominalColor(31, 119, 180);
const QColor kBandColor(31, 119, 180, 50);
const QColor kQuantileColor(214, 39, 40);

void verticalMarker(QCustomPlot& plot, double x, const QColor& color, const QString& text) {
    auto* line = new QCPItemStraightLine(&plot);
    line->point1->setCoords(x, 0.0);
    line->point2->setCoords(x, 1.0);
    line->setPen(QPen(color, 1.2, Qt::DashLine));
    auto* label = new QCPItemText(&plot);
    label->position->setTypeX(QCPItemPosition::ptPlotCoords);
    label->position->setTypeY(QCPItemPosition::ptAxisRectRatio);
    label->position->setCoords(x, 0.04);
    label->setPositionAlignment(Qt::AlignLeft | Qt::AlignTop);
    label->setPadding(QMargins(4, 0, 0, 0));
    label->setText(text);
    label->setColor(color);
}

}  // namespace

void plotTraction(QCustomPlot& plot, const analysis::TractionResult& result, const QString& title) {
    resetPlot(plot, title);
    const bool drawbar = result.objective == analysis::TractionObjective::kDrawbar;
    plot.xAxis->setLabel("Slip s [-]");
    plot.yAxis->setLabel(drawbar ? "Drawbar pull F_x [N]" : "Tractive efficiency η [-]");
    QVector<double> s, nominal;
    for (const analysis::TractionPoint& p : result.curve) {
        const double v = analysis::objectiveValue(result.objective, p);
        if (!std::isfinite(v)) continue;  // no equilibrium, or beyond the sinkage cap
        s.push_back(p.slip);
        nominal.push_back(v);
    }
    if (!result.band.empty()) {
        QVector<double> bs, p5, p95, q;
        for (const analysis::TractionBand& b : result.band) {
            if (b.samples == 0) continue;
            bs.push_back(b.slip);
            p5.push_back(b.p5);
            p95.push_back(b.p95);
            q.push_back(b.quantile);
        }
        QCPGraph* low = plot.addGraph();
        low->setData(bs, p5, true);
        low->setPen(Qt::NoPen);
        low->removeFromLegend();
        QCPGraph* high = plot.addGraph();
        high->setData(bs, p95, true);
        high->setPen(Qt::NoPen);
        high->setBrush(kBandColor);
        high->setChannelFillGraph(low);
        high->setName("posterior 5–95 %");
        QCPGraph* quantile = plot.addGraph();
        quantile->setData(bs, q, true);
        quantile->setPen(QPen(kQuantileColor, 1.5, Qt::DotLine));
        quantile->setName("posterior lower quantile");
    }
    QCPGraph* curve = plot.addGraph();
    curve->setData(s, nominal, true);
    curve->setPen(QPen(kNominalColor, 1.8));
    curve->setName(result.band.empty() ? "the soil" : "posterior mean soil");
    plot.rescaleAxes();
    if (result.optimal_slip) {
        verticalMarker(plot, *result.optimal_slip, kNominalColor,
                       QString("s* = %1").arg(*result.optimal_slip, 0, 'f', 3));
    }
    if (result.robust_slip) {
        verticalMarker(plot, *result.robust_slip, kQuantileColor,
                       QString("robust s* = %1").arg(*result.robust_slip, 0, 'f', 3));
    }
    legendBelow(plot, result.band.empty() ? 1 : 3);
    plot.replot();
}

}  // namespace terra::ui
