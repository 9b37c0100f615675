#include "widgets/plots/reference_overlay.h"

#include <qcustomplot.h>

#include <cmath>
#include <limits>
#include <map>

namespace terra::ui {
namespace {

QCPGraph* addReferenceGraph(QCustomPlot& plot, const QVector<double>& x, const QVector<double>& y,
                            const QColor& color, const QString& name) {
    QCPGraph* graph = plot.addGraph();
    graph->setObjectName("reference");
    graph->setData(x, y, true);
    graph->setName(name);
    QPen pen(color);
    pen.setWidthF(1.8);
    pen.setStyle(Qt::DashLine);
    graph->setPen(pen);
    return graph;
}

/// The finite (x, y) pairs of two columns of a table, y × scale.
std::pair<QVector<double>, QVector<double>> finiteColumns(const Table& t, const std::string& x,
                                                          const std::string& y,
                                                          double scale = 1.0) {
    std::pair<QVector<double>, QVector<double>> out;
    if (t.rows.empty()) return out;
    const std::size_t ix = t.column(x), iy = t.column(y);
    for (const auto& row : t.rows) {
        if (!std::isfinite(row[ix]) || !std::isfinite(row[iy])) continue;
        out.first.push_back(row[ix]);
        out.second.push_back(row[iy] * scale);
    }
    return out;
}

const QColor kReferenceGrey(105, 105, 105);

/// Widens the axes to the reference's data, keeping the origin the soil plots show.
void widenToOrigin(QCustomPlot& plot) {
    plot.rescaleAxes();
    plot.xAxis->setRangeLower(0.0);
    plot.yAxis->setRangeLower(0.0);
    plot.yAxis->setRangeUpper(plot.yAxis->range().upper * 1.05);
    placeLegend(plot);
    plot.replot();
}

}  // namespace

void overlayReferenceSweep(QCustomPlot& plot, const SweepQuantity& quantity, const Table& sweep,
                           const QString& name) {
    if (sweep.rows.empty()) return;
    const std::size_t beta = sweep.column("slip_angle_deg"), slip = sweep.column("slip"),
                      value = sweep.column(quantity.column);
    std::map<double, std::pair<QVector<double>, QVector<double>>> curves;
    for (const auto& row : sweep.rows) {
        if (!std::isfinite(row[slip]) || !std::isfinite(row[value])) continue;
        curves[row[beta]].first.push_back(row[slip]);
        curves[row[beta]].second.push_back(row[value] * quantity.scale);
    }
    int index = 0;
    for (const auto& [angle, data] : curves) {
        QCPGraph* graph = addReferenceGraph(plot, data.first, data.second, sweepColor(index),
                                            QString("%1, β = %2°").arg(name).arg(angle));
        if (index == 0 && curves.size() > 1) graph->setName(name + ", dashed");
        if (index > 0) graph->removeFromLegend();
        ++index;
    }
    fitSweepAxes(plot);
}

void overlayReferenceBulldozing(QCustomPlot& plot, const analysis::SoilCurves& curves,
                                const QString& name) {
    const auto [h, fb] = finiteColumns(curves.bulldozing, "sinkage_mm", "Fb_bekker_N");
    if (h.isEmpty()) return;
    addReferenceGraph(plot, h, fb, kReferenceGrey, name + ", Bekker");
    widenToOrigin(plot);
}

void overlayReferenceStaticSinkage(QCustomPlot& plot, const analysis::SoilCurves& curves,
                                   const QString& name) {
    const auto [w, h] = finiteColumns(curves.static_sinkage, "load_N", "h_bekker_mm");
    if (w.isEmpty()) return;
    addReferenceGraph(plot, w, h, kReferenceGrey, name + ", Bekker Eq. 2.8");
    widenToOrigin(plot);
}

Table tableWithReference(const Table& shown, const std::string& shown_name, const Table& reference,
                         const std::string& reference_name, double load_n) {
    Table out = shown;
    out.label_column = "soil";
    out.labels.assign(shown.rows.size(), shown_name);
    constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
    // Where each column of `shown` is in the reference (or what fills it).
    std::vector<std::ptrdiff_t> source(shown.columns.size(), -1);
    std::vector<double> fill(shown.columns.size(), kNaN);
    for (std::size_t c = 0; c < shown.columns.size(); ++c) {
        for (std::size_t r = 0; r < reference.columns.size(); ++r) {
            if (reference.columns[r] == shown.columns[c])
                source[c] = static_cast<std::ptrdiff_t>(r);
        }
        if (shown.columns[c] == "measured") fill[c] = 0.0;
        if (shown.columns[c] == "load_N") fill[c] = load_n;
    }
    for (const auto& row : reference.rows) {
        std::vector<double> mapped(shown.columns.size());
        for (std::size_t c = 0; c < shown.columns.size(); ++c)
            mapped[c] = source[c] >= 0 ? row[static_cast<std::size_t>(source[c])] : fill[c];
        out.rows.push_back(std::move(mapped));
        out.labels.push_back(reference_name);
    }
    return out;
}

}  // namespace terra::ui
