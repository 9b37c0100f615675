#include "widgets/plots/experiment_overlay.h"

#include <qcustomplot.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "widgets/plots/number_format.h"

namespace terra::ui {
namespace {

// A load or slip angle of the test equals the project's to this (both typed as decimals).
constexpr double kSameCondition = 1e-9;

QString conditionsName(double load_n, double beta_deg) {
    return QString("W = %1 N, β = %2°").arg(load_n).arg(beta_deg);
}

bool shownByPlot(const analysis::OperatingConditions& shown, double load_n, double beta_deg) {
    if (std::abs(shown.load_n - load_n) > kSameCondition) return false;
    return std::any_of(shown.slip_angles_deg.begin(), shown.slip_angles_deg.end(),
                       [beta_deg](double b) { return std::abs(b - beta_deg) <= kSameCondition; });
}

}  // namespace

std::optional<io::ExperimentChannel> measuredChannel(const std::string& column) {
    if (column == "Fx_N") return io::kExpFx;
    if (column == "Fs_N") return io::kExpFy;
    if (column == "Fz_N") return io::kExpFz;
    if (column == "My_Nm") return io::kExpMy;
    if (column == "sinkage_m") return io::kExpSinkage;
    return std::nullopt;
}

QString channelLabel(io::ExperimentChannel channel) {
    switch (channel) {
        case io::kExpFx:
            return "F_x [N]";
        case io::kExpMy:
            return "M_y [N·m]";
        case io::kExpSinkage:
            return "h [mm]";
        case io::kExpFy:
            return "F_s [N]";
        case io::kExpFz:
            return "F_z [N]";
        case io::kExperimentChannelCount:
            break;
    }
    return {};
}

QString channelValue(io::ExperimentChannel channel, double value_si, double scale_si) {
    const double factor = channel == io::kExpSinkage ? 1e3 : 1.0;  // m → mm
    const QString unit = channelLabel(channel).section('[', 1).section(']', 0, 0);
    return QString("%1 %2").arg(formatNumber(value_si * factor, scale_si * factor), unit);
}

QString relativeError(double fraction) {
    if (std::isnan(fraction)) return QString::fromUtf8("–");
    return QString("%1 %").arg(fraction * 100.0, 0, 'f', 1);
}

void overlayExperiment(QCustomPlot& plot, const SweepQuantity& quantity,
                       const io::Experiment& experiment, const std::vector<TestSweep>& sweeps,
                       const analysis::OperatingConditions& shown) {
    const std::optional<io::ExperimentChannel> channel = measuredChannel(quantity.column);
    if (!channel || !experiment.measures(*channel)) return;
    // The measured points of the channel by their conditions (load, β).
    std::map<std::pair<double, double>, std::pair<QVector<double>, QVector<double>>> measured;
    for (const io::ExperimentPoint& p : experiment.points) {
        if (!p.measured[*channel]) continue;
        auto& series = measured[{p.load_n, p.slip_angle_deg}];
        series.first.push_back(p.slip);
        series.second.push_back(*p.measured[*channel] * quantity.scale);
    }
    // The model at the conditions of the measured points, where the plot does not show it.
    for (const TestSweep& sweep : sweeps) {
        const Table& t = sweep.table;
        const std::size_t beta = t.column("slip_angle_deg"), slip = t.column("slip"),
                          value = t.column(quantity.column);
        std::map<double, std::pair<QVector<double>, QVector<double>>> curves;
        for (const auto& row : t.rows) {
            if (!measured.contains({sweep.load_n, row[beta]})) continue;
            if (!std::isfinite(row[slip]) || !std::isfinite(row[value])) continue;
            curves[row[beta]].first.push_back(row[slip]);
            curves[row[beta]].second.push_back(row[value] * quantity.scale);
        }
        for (const auto& [angle, data] : curves) {
            if (shownByPlot(shown, sweep.load_n, angle)) continue;
            QCPGraph* graph = plot.addGraph();
            graph->setData(data.first, data.second, true);
            graph->setName("model, " + conditionsName(sweep.load_n, angle));
            QPen pen(QColor(60, 60, 60));
            pen.setWidthF(1.6);
            pen.setStyle(Qt::DashLine);
            graph->setPen(pen);
        }
    }
    static const QCPScatterStyle::ScatterShape shapes[] = {
        QCPScatterStyle::ssCircle, QCPScatterStyle::ssSquare, QCPScatterStyle::ssTriangle,
        QCPScatterStyle::ssDiamond};
    int index = 0;
    for (const auto& [conditions, data] : measured) {
        QCPGraph* graph = plot.addGraph();
        graph->setObjectName("measured");
        graph->setData(data.first, data.second, true);
        graph->setName("measured, " + conditionsName(conditions.first, conditions.second));
        graph->setLineStyle(QCPGraph::lsNone);
        QPen pen(Qt::black);
        pen.setWidthF(1.6);
        graph->setPen(pen);
        graph->setScatterStyle(
            QCPScatterStyle(shapes[index % 4], pen, QBrush(QColor(255, 215, 0)), 9.0));
        ++index;
    }
    fitSweepAxes(plot);
    // A marker on the edge of the axes (s = 0) would be cut in half by the axis: room for it.
    double low = std::numeric_limits<double>::infinity(), high = -low;
    for (const auto& [conditions, data] : measured) {
        for (double s : data.first) {
            low = std::min(low, s);
            high = std::max(high, s);
        }
    }
    QCPRange x = plot.xAxis->range();
    const double margin = 0.025 * x.size();
    if (low - x.lower < 0.4 * margin) x.lower -= margin;
    if (x.upper - high < 0.4 * margin) x.upper += margin;
    plot.xAxis->setRange(x);
    plot.replot();
}

Table tableWithTest(const Table& sweep, double project_load_n, const io::Experiment& experiment,
                    const std::vector<TestSweep>& sweeps) {
    Table out;
    out.columns = sweep.columns;
    out.columns.insert(out.columns.end(), {"load_N", "measured"});
    auto append = [&out](const Table& t, double load_n) {
        for (std::vector<double> row : t.rows) {
            row.insert(row.end(), {load_n, 0.0});
            out.rows.push_back(std::move(row));
        }
    };
    append(sweep, project_load_n);
    for (const TestSweep& s : sweeps) append(s.table, s.load_n);
    constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
    const std::size_t beta = sweep.column("slip_angle_deg"), slip = sweep.column("slip");
    for (const io::ExperimentPoint& p : experiment.points) {
        std::vector<double> row(out.columns.size(), kNaN);
        row[beta] = p.slip_angle_deg;
        row[slip] = p.slip;
        for (const std::string& column : sweep.columns) {
            const std::optional<io::ExperimentChannel> channel = measuredChannel(column);
            if (channel && p.measured[*channel]) row[sweep.column(column)] = *p.measured[*channel];
        }
        row[out.columns.size() - 2] = p.load_n;
        row[out.columns.size() - 1] = 1.0;
        out.rows.push_back(std::move(row));
    }
    return out;
}

}  // namespace terra::ui
