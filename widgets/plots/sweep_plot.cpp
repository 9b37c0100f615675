#include "widgets/plots/sweep_plot.h"

#include <qcustomplot.h>

#include <QFileInfo>
#include <QSaveFile>
#include <algorithm>
#include <cmath>
#include <map>

#include "widgets/plots/plot_export.h"
#include "widgets/plots/plot_legend.h"
#include "widgets/plots/plot_theme.h"

namespace terra::ui {

const std::vector<SweepQuantity>& sweepQuantities() {
    static const std::vector<SweepQuantity> quantities{
        {"Fx_N", "Drawbar pull F_x [N]"},   {"Fs_N", "Side force F_s [N]"},
        {"Fz_N", "Vertical force F_z [N]"}, {"My_Nm", "Resistance torque M_y [N·m]"},
        {"Mz_Nm", "Yaw moment M_z [N·m]"},  {"entry_angle_deg", "Entry angle θ_f [deg]"}};
    return quantities;
}

const SweepQuantity& sinkageQuantity() {
    static const SweepQuantity quantity{"sinkage_m", "Sinkage h [mm]", 1e3};
    return quantity;
}

QColor sweepColor(int index) {
    // Distinct on white and on a dark frame (no yellow on white).
    static const QColor colors[] = {
        QColor(31, 119, 180),  QColor(255, 127, 14), QColor(44, 160, 44),   QColor(214, 39, 40),
        QColor(148, 103, 189), QColor(140, 86, 75),  QColor(227, 119, 194), QColor(127, 127, 127)};
    return colors[((index % 8) + 8) % 8];
}

void plotSweep(QCustomPlot& plot, const Table& table, const SweepQuantity& quantity,
               const QString& title, bool replot) {
    plot.clearGraphs();
    plot.clearItems();
    if (plot.plotLayout()->rowCount() > 1) plot.plotLayout()->removeAt(0);
    plot.plotLayout()->simplify();
    const std::size_t beta = table.column("slip_angle_deg");
    const std::size_t slip = table.column("slip");
    const std::size_t value = table.column(quantity.column);
    std::map<double, std::pair<QVector<double>, QVector<double>>> curves;
    for (const auto& row : table.rows) {
        if (!std::isfinite(row[slip]) || !std::isfinite(row[value])) continue;
        auto& curve = curves[row[beta]];
        curve.first.push_back(row[slip]);
        curve.second.push_back(row[value] * quantity.scale);
    }
    int index = 0;
    for (const auto& [angle, data] : curves) {
        QCPGraph* graph = plot.addGraph();
        graph->setData(data.first, data.second, true);
        graph->setName(QString("β = %1°").arg(angle));
        QPen pen(sweepColor(index));
        pen.setWidthF(1.8);
        graph->setPen(pen);
        ++index;
    }
    plot.xAxis->setLabel("Slip ratio s [-]");
    plot.yAxis->setLabel(quantity.label);
    plot.legend->setVisible(true);
    plot.plotLayout()->insertRow(0);
    auto* heading = new QCPTextElement(&plot, title, QFont("sans", 11, QFont::Bold));
    // A long title (soil and wheel names) must not set the plot's minimum width: on a narrow
    // screen it would widen the panel past the window. Narrower than its text, it is clipped.
    heading->setMinimumSize(1, 0);
    plot.plotLayout()->addElement(0, 0, heading);
    followPalette(plot);  // frame colours of the palette on screen; exports stay light
    fitSweepAxes(plot, replot);
}

void fitSweepAxes(QCustomPlot& plot, bool replot) {
    plot.rescaleAxes();
    // A quantity held constant (F_z = W at equilibrium) would otherwise zoom into rounding noise.
    const QCPRange y = plot.yAxis->range();
    const double floor = 0.05 * std::max(std::abs(y.center()), 1e-3);
    if (y.size() < floor) {
        plot.yAxis->setRange(y.center() - floor, y.center() + floor);
    } else {
        plot.yAxis->scaleRange(1.1, y.center());
    }
    placeLegend(plot);
    if (replot) plot.replot();
}

void placeLegend(QCustomPlot& plot) { layOutLegend(plot); }

bool exportPng(QCustomPlot& plot, const QString& path, int width, int height, QString* error) {
    ExportOptions options;  // atomic: temporary file, then rename (plot_export.cpp)
    options.width = width;
    options.height = height;
    return exportPlot(plot, path, options, error);
}

}  // namespace terra::ui
