#include "widgets/plots/figures.h"

#include <qcustomplot.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>

#include "core/soil/soil_parameters.h"
#include "widgets/plots/plot_legend.h"
#include "widgets/plots/plot_theme.h"
#include "widgets/plots/sweep_plot.h"

namespace terra::ui {
namespace {

QColor paletteColor(int index) {
    static const QColor colors[] = {QColor(31, 119, 180),  QColor(214, 39, 40),
                                    QColor(44, 160, 44),   QColor(255, 127, 14),
                                    QColor(148, 103, 189), QColor(140, 86, 75)};
    return colors[index % 6];
}

QVector<double> column(const Table& table, const std::string& name) {
    const auto values = table.values(name);
    return QVector<double>(values.begin(), values.end());
}

QCPGraph* addLine(QCustomPlot& plot, const QVector<double>& x, const QVector<double>& y,
                  const QString& name, const QColor& color, Qt::PenStyle style = Qt::SolidLine) {
    QCPGraph* graph = plot.addGraph();
    graph->setData(x, y, true);
    graph->setName(name);
    QPen pen(color);
    pen.setWidthF(1.8);
    pen.setStyle(style);
    graph->setPen(pen);
    return graph;
}

void finish(QCustomPlot& plot) {
    plot.legend->setVisible(plot.graphCount() > 0);
    plot.rescaleAxes();
    const QCPRange y = plot.yAxis->range();
    const double floor = 0.05 * std::max(std::abs(y.center()), 1e-3);
    if (y.size() < floor) {
        plot.yAxis->setRange(y.center() - floor, y.center() + floor);
    } else {
        plot.yAxis->scaleRange(1.1, y.center());
    }
    placeLegend(plot);
    plot.replot();
}

/// "φ" and "deg" of a soil field key ("phi_deg"); the key itself when unknown.
std::pair<QString, QString> fieldSymbol(const std::string& key) {
    const soil::SoilField* field = soil::findSoilField(key);
    if (!field) return {QString::fromStdString(key), QString()};
    return {QString::fromUtf8(field->symbol), QString::fromUtf8(field->unit)};
}

const char* stressLabel(const std::string& stress) {
    if (stress == "sigma") return "σ";
    if (stress == "tau") return "τ";
    if (stress == "tau_t") return "τ_t";
    return "τ_l";
}

/// Puts the legend back inside the axis rect (layOutLegend() of plot_legend.h places it after).
void legendInside(QCustomPlot& plot) {
    QCPLayoutInset* inset = plot.axisRect()->insetLayout();
    if (inset->elementCount() > 0 && inset->elementAt(0) == plot.legend) return;
    if (plot.legend->layout()) plot.legend->layout()->take(plot.legend);
    plot.plotLayout()->simplify();
    inset->addElement(plot.legend, Qt::AlignRight | Qt::AlignTop);
    plot.legend->setWrap(0);
    plot.legend->setFillOrder(QCPLayoutGrid::foRowsFirst);
}

}  // namespace

// Pairs in a row (the exact and quadratic of one stress) read better than the width's fill.
void legendBelow(QCustomPlot& plot, int columns) {
    setLegendColumns(plot, columns);
    layOutLegend(plot);
}

void resetPlot(QCustomPlot& plot, const QString& title) {
    legendInside(plot);
    setLegendColumns(plot, 0);  // the next figure's own
    plot.clearGraphs();
    plot.clearItems();
    plot.clearPlottables();
    plot.yAxis->setTicker(QSharedPointer<QCPAxisTicker>(new QCPAxisTicker));
    plot.yAxis->setTickLabelRotation(0);
    if (plot.plotLayout()->rowCount() > 1) plot.plotLayout()->removeAt(0);
    plot.plotLayout()->simplify();
    plot.plotLayout()->insertRow(0);
    auto* heading = new QCPTextElement(&plot, title, QFont("sans", 11, QFont::Bold));
    // A long title (soil and wheel names) must not set the plot's minimum width: on a narrow
    // screen it would widen the panel past the window. Narrower than its text, it is clipped.
    heading->setMinimumSize(1, 0);
    plot.plotLayout()->addElement(0, 0, heading);
    plot.legend->setVisible(false);
    followPalette(plot);  // frame colours of the palette on screen; exports stay light
}

void removeColorScales(QCustomPlot& plot) {
    for (int i = plot.plotLayout()->elementCount() - 1; i >= 0; --i) {
        if (auto* scale = qobject_cast<QCPColorScale*>(plot.plotLayout()->elementAt(i)))
            plot.plotLayout()->remove(scale);
    }
    plot.plotLayout()->simplify();
}

QString plotTitle(const QCustomPlot& plot) {
    if (plot.plotLayout()->rowCount() < 2) return {};
    auto* title = qobject_cast<QCPTextElement*>(plot.plotLayout()->element(0, 0));
    return title ? title->text() : QString();
}

void setPlotTitle(QCustomPlot& plot, const QString& text) {
    if (plot.plotLayout()->rowCount() < 2) return;
    auto* title = qobject_cast<QCPTextElement*>(plot.plotLayout()->element(0, 0));
    if (!title) return;
    title->setText(text);
    plot.replot();
}

void plotStresses(QCustomPlot& plot, const analysis::StressResult& result,
                  const std::string& stress, const QString& title) {
    resetPlot(plot, title);
    plot.xAxis->setLabel("Contact angle θ [deg]");
    plot.yAxis->setLabel("Stress [kPa]");
    if (result.table.rows.empty()) {
        plot.replot();
        return;
    }
    const QVector<double> theta = column(result.table, "theta_deg");
    const std::vector<std::string> all{"sigma", "tau", "tau_t", "tau_l"};
    for (std::size_t i = 0; i < all.size(); ++i) {
        if (stress != "all" && stress != all[i]) continue;
        const QString symbol = stressLabel(all[i]);
        addLine(plot, theta, column(result.table, all[i] + "_kPa"), symbol + " exact",
                paletteColor(int(i)));
        addLine(plot, theta, column(result.table, all[i] + "_quad_kPa"),
                QString("%1 quadratic (RMSE %2, MAE %3 kPa)")
                    .arg(symbol)
                    .arg(result.errors[i].rmse / 1e3, 0, 'f', 3)
                    .arg(result.errors[i].mae / 1e3, 0, 'f', 3),
                paletteColor(int(i)), Qt::DashLine);
    }
    finish(plot);
    legendBelow(plot, 2);  // exact and quadratic of one stress side by side, under the plot
    plot.replot();
}

void plotSensitivityFamily(QCustomPlot& plot, const analysis::SensitivityResult& result,
                           const std::string& key, const std::string& column_name,
                           const QString& title) {
    resetPlot(plot, title);
    plot.xAxis->setLabel("Slip ratio s [-]");
    plot.yAxis->setLabel(column_name == "Fx_N" ? "Drawbar pull F_x [N]" : "Side force F_s [N]");
    const Table& table = result.family.table;
    if (table.rows.empty()) {
        plot.replot();
        return;
    }
    const std::size_t k = table.column(key), s = table.column("slip"),
                      v = table.column(column_name);
    std::map<double, std::pair<QVector<double>, QVector<double>>> curves;
    for (const auto& row : table.rows) {
        if (!std::isfinite(row[v])) continue;
        curves[row[k]].first.push_back(row[s]);
        curves[row[k]].second.push_back(row[v]);
    }
    int index = 0;
    for (const auto& [value, data] : curves) {
        const auto [symbol, unit] = fieldSymbol(key);
        addLine(plot, data.first, data.second,
                QString("%1 = %2 %3")
                    .arg(symbol)
                    .arg(value)
                    .arg(unit == "-" ? QString() : unit)
                    .trimmed(),
                paletteColor(index++));
    }
    finish(plot);
}

void plotTornado(QCustomPlot& plot, const analysis::SensitivityResult& result, double slip,
                 const QString& title) {
    resetPlot(plot, title);
    const Table& t = result.tornado;
    if (t.rows.empty()) {
        plot.replot();
        return;
    }
    const std::size_t lo = t.column("Fx_low_N"), hi = t.column("Fx_high_N"),
                      base = t.column("Fx_base_N");
    std::vector<std::size_t> order(t.rows.size());
    std::iota(order.begin(), order.end(), 0);
    // Influence: the largest change either extreme makes (|high − low| would rank a parameter
    // whose two extremes both raise F_x below one that moves it less but in opposite directions).
    auto reach = [&](std::size_t i) {
        return std::max(std::abs(t.rows[i][lo] - t.rows[i][base]),
                        std::abs(t.rows[i][hi] - t.rows[i][base]));
    };
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return reach(a) < reach(b); });
    // Bars run along x (ΔF_x) with the parameters on the y axis: keyAxis = yAxis. The low and high
    // variations sit side by side in each parameter's row (high above, low below), so both stay
    // visible when they move F_x the same way and one is shorter.
    auto* low = new QCPBars(plot.yAxis, plot.xAxis);
    auto* high = new QCPBars(plot.yAxis, plot.xAxis);
    low->setName("lowest value of Table 4.1");
    high->setName("highest value of Table 4.1");
    low->setBrush(QColor(31, 119, 180));
    high->setBrush(QColor(214, 39, 40));
    low->setPen(Qt::NoPen);
    high->setPen(Qt::NoPen);
    low->setWidth(kTornadoBarWidth);
    high->setWidth(kTornadoBarWidth);
    QSharedPointer<QCPAxisTickerText> ticker(new QCPAxisTickerText);
    for (std::size_t rank = 0; rank < order.size(); ++rank) {
        const auto& row = t.rows[order[rank]];
        const double position = static_cast<double>(rank + 1);
        low->addData(position - kTornadoBarOffset, row[lo] - row[base]);
        high->addData(position + kTornadoBarOffset, row[hi] - row[base]);
        const auto [symbol, unit] = fieldSymbol(result.tornado_keys[order[rank]]);
        ticker->addTick(position, unit.isEmpty() ? symbol : QString("%1 [%2]").arg(symbol, unit));
    }
    // The base soil's F_x: a line at zero change.
    auto* zero = new QCPItemStraightLine(&plot);
    zero->point1->setCoords(0.0, 0.0);
    zero->point2->setCoords(0.0, 1.0);
    zero->setPen(QPen(QColor(128, 128, 128), 1.0));  // readable on light and dark frames
    plot.yAxis->setTicker(ticker);
    plot.yAxis->setLabel("Soil parameter");
    plot.xAxis->setLabel(QString("Change of F_x at s = %1 from the base soil [N]").arg(slip));
    plot.legend->setVisible(true);
    plot.rescaleAxes();
    plot.yAxis->setRange(0.3, static_cast<double>(order.size()) + 0.7);
    plot.xAxis->scaleRange(1.15, 0.0);
    const double extent =
        std::max(std::abs(plot.xAxis->range().lower), std::abs(plot.xAxis->range().upper));
    plot.xAxis->setRange(-extent, extent);
    plot.replot();
}

void plotBulldozing(QCustomPlot& plot, const analysis::SoilCurves& curves, const QString& title) {
    resetPlot(plot, title);
    plot.xAxis->setLabel("Sinkage h [mm]");
    plot.yAxis->setLabel("Bulldozing resistance F_b [N]");
    const Table& t = curves.bulldozing;
    if (t.rows.empty()) {
        plot.replot();
        return;
    }
    const QVector<double> h = column(t, "sinkage_mm");
    addLine(plot, h, column(t, "Fb_bekker_N"), "Bekker coefficients (used in F_s)",
            paletteColor(0));
    addLine(plot, h, column(t, "Fb_hegedus_N"), "Hegedus coefficients", paletteColor(1),
            Qt::DashLine);
    finish(plot);
    // F_b starts at 0: keep the origin in view rather than the symmetric margin of finish().
    plot.yAxis->setRangeLower(0.0);
    plot.xAxis->setRangeLower(0.0);
    placeLegend(plot);
    plot.replot();
}

void plotStaticSinkage(QCustomPlot& plot, const analysis::SoilCurves& curves,
                       const QString& title) {
    resetPlot(plot, title);
    plot.xAxis->setLabel("Vertical load W [N]");
    plot.yAxis->setLabel("Static sinkage h_s [mm]");
    const Table& t = curves.static_sinkage;
    if (t.rows.empty()) {
        plot.replot();
        return;
    }
    const QVector<double> w = column(t, "load_N");
    auto finite = [&](const std::string& name, QVector<double>& x, QVector<double>& y) {
        const QVector<double> values = column(t, name);
        for (int i = 0; i < values.size(); ++i) {
            if (std::isfinite(values[i])) x.push_back(w[i]), y.push_back(values[i]);
        }
    };
    QVector<double> x, y;
    finite("h_bekker_mm", x, y);
    addLine(plot, x, y, "Bekker, Eq. 2.8 (front half, corrected √(2r))", paletteColor(0));
    x.clear(), y.clear();
    finite("h_eq27_front_mm", x, y);
    addLine(plot, x, y, "Eq. 2.7 over the front half 0..θ_s", paletteColor(2), Qt::DashLine);
    x.clear(), y.clear();
    finite("h_eq27_mm", x, y);
    addLine(plot, x, y, "Eq. 2.7 over −θ_s..θ_s (as printed)", paletteColor(1), Qt::DashDotLine);
    finish(plot);
    plot.yAxis->setRangeLower(0.0);
    plot.xAxis->setRangeLower(0.0);
    if (curves.load_n > 0.0) {
        auto* marker = new QCPItemStraightLine(&plot);
        marker->point1->setCoords(curves.load_n, 0.0);
        marker->point2->setCoords(curves.load_n, 1.0);
        marker->setPen(QPen(QColor(128, 128, 128), 1.0, Qt::DotLine));
        auto* label = new QCPItemText(&plot);
        label->position->setType(QCPItemPosition::ptPlotCoords);
        label->position->setCoords(curves.load_n, plot.yAxis->range().upper);
        label->setPositionAlignment(Qt::AlignLeft | Qt::AlignTop);
        label->setPadding(QMargins(4, 2, 4, 2));
        label->setText(QString("W = %1 N").arg(curves.load_n));
        label->setColor(QColor(128, 128, 128));
    }
    placeLegend(plot);
    plot.replot();
}

void plotValidation(QCustomPlot& plot, const analysis::ValidationResult& result,
                    const std::string& channel, const QString& title) {
    const auto& channels = io::experimentChannels();
    std::size_t c = 0;
    while (c < channels.size() && channels[c].name != channel) ++c;
    if (c == channels.size()) throw std::invalid_argument("no channel \"" + channel + "\"");
    const bool sinkage = channel == "sinkage_m";
    const double factor = sinkage ? 1e3 : 1.0;  // sinkage in mm
    const QString unit = sinkage ? "mm" : channel == "My_Nm" ? "N·m" : "N";
    const QString label = channel == "Fx_N"    ? "Drawbar pull F_x [N]"
                          : channel == "My_Nm" ? "Resistance torque M_y [N·m]"
                          : sinkage            ? "Sinkage h [mm]"
                          : channel == "Fy_N"  ? "Side force F_y [N]"
                                               : "Vertical force F_z [N]";
    const bool measured = std::any_of(
        result.before.points.begin(), result.before.points.end(),
        [c](const analysis::PointComparison& p) { return p.point.measured[c].has_value(); });
    resetPlot(plot, measured ? title : title + " (not measured in this test)");
    plot.xAxis->setLabel("Slip ratio s [-]");
    plot.yAxis->setLabel(label);
    const analysis::ValidationRun* calibrated =
        result.calibration && result.calibration->report.usable() && result.calibration->after
            ? &*result.calibration->after
            : nullptr;
    auto rmse = [&](const analysis::ValidationRun& run) {
        const auto& m = run.metrics[c];
        return m ? QString(", RMSE %1 %2").arg(m->rmse * factor, 0, 'g', 3).arg(unit) : QString();
    };
    // The groups of the curves table, in its order.
    const Table& curves = result.before.curves;
    std::vector<std::pair<double, double>> groups;
    for (const auto& row : curves.rows) {
        const std::pair<double, double> g{row[0], row[1]};
        if (std::find(groups.begin(), groups.end(), g) == groups.end()) groups.push_back(g);
    }
    const std::size_t y = curves.column(channel);
    for (std::size_t k = 0; k < groups.size(); ++k) {
        // Plain variables: clang 14 cannot capture structured bindings in the lambda below.
        const double load = groups[k].first, beta = groups[k].second;
        const QColor color = paletteColor(static_cast<int>(k));
        QString at = QString("W = %1 N").arg(load, 0, 'g', 4);
        if (beta != 0.0) at += QString(", β = %1°").arg(beta, 0, 'g', 3);
        auto curve = [&](const analysis::ValidationRun& run, const QString& name, const QColor& pen,
                         Qt::PenStyle style) {
            QVector<double> s, v;
            for (const auto& row : run.curves.rows) {
                if (row[0] != load || row[1] != beta || !std::isfinite(row[y])) continue;
                s.push_back(row[2]);
                v.push_back(row[y] * factor);
            }
            addLine(plot, s, v, name, pen, style);
        };
        curve(result.before,
              QString("%1, %2%3")
                  .arg(QString::fromStdString(result.before.soil.name), at,
                       groups.size() == 1 ? rmse(result.before) : QString()),
              color, Qt::SolidLine);
        if (calibrated) {
            curve(*calibrated,
                  QString("calibrated, %1%2")
                      .arg(at, groups.size() == 1 ? rmse(*calibrated) : QString()),
                  groups.size() == 1 ? paletteColor(3) : color, Qt::DashLine);
        }
        // Points the calibration used (discs) and held out (rings: predicted, not fitted).
        QVector<double> s[2], v[2];
        for (const analysis::PointComparison& p : result.before.points) {
            if (p.point.load_n != load || p.point.slip_angle_deg != beta || !p.point.measured[c])
                continue;
            const int held_out = calibrated && !p.in_fit ? 1 : 0;
            s[held_out].push_back(p.point.slip);
            v[held_out].push_back(*p.point.measured[c] * factor);
        }
        for (int held_out = 0; held_out < 2; ++held_out) {
            if (s[held_out].isEmpty()) continue;
            QCPGraph* points = plot.addGraph();
            points->setData(s[held_out], v[held_out]);
            points->setName((held_out ? "measured, held out, " : "measured, ") + at);
            points->setPen(QPen(color, held_out ? 1.8 : 1.0));
            points->setLineStyle(QCPGraph::lsNone);
            points->setScatterStyle(
                QCPScatterStyle(held_out ? QCPScatterStyle::ssCircle : QCPScatterStyle::ssDisc, 8));
        }
    }
    finish(plot);
    // Measured points often sit at the ends of the slip range (s = 0, the largest slip tested):
    // a margin keeps them whole.
    plot.xAxis->scaleRange(1.08, plot.xAxis->range().center());
    plot.replot();
}

void plotIdentification(QCustomPlot& plot, const analysis::IdentificationResult& result,
                        const std::string& channel, const QString& title) {
    resetPlot(plot, title);
    plot.xAxis->setLabel("Slip ratio s [-]");
    const QString label = channel == "Fx_N"   ? "Drawbar pull F_x [N]"
                          : channel == "Fz_N" ? "Vertical force F_z [N]"
                                              : "Resistance torque M_y [N·m]";
    plot.yAxis->setLabel(label);
    if (result.curves.rows.empty()) {
        plot.replot();
        return;
    }
    const QVector<double> slip = column(result.curves, "slip");
    const QVector<double> measured = column(result.curves, channel);
    std::string fitted = channel;
    fitted.insert(channel.rfind('_'), "_fit");
    // One colour per sweep (per load): its data points and its fitted line, each in the legend
    // with the load (three sweeps used to share one "data" entry). Sweeps are never joined.
    const QVector<double> fit = column(result.curves, fitted);
    const QVector<double> load = column(result.curves, "W_N");
    struct Sweep {
        QVector<double> slip, data, fit;
    };
    std::map<double, Sweep> sweeps;
    for (int i = 0; i < slip.size(); ++i) {
        Sweep& sweep = sweeps[std::isnan(load[i]) ? 0.0 : load[i]];
        sweep.slip.push_back(slip[i]);
        sweep.data.push_back(measured[i]);
        sweep.fit.push_back(fit[i]);
    }
    const QString model = result.report ? "full model, global fit" : "decoupled fit";
    int index = 0;
    for (const auto& [w, sweep] : sweeps) {
        const QColor color = paletteColor(index++);
        const QString at = sweeps.size() > 1 || w > 0.0 ? QString(", W = %1 N").arg(w) : QString();
        QCPGraph* data = plot.addGraph();
        data->setData(sweep.slip, sweep.data);  // unsorted: keep the measured order
        // One legend entry per load (its line); the points share one "data" entry.
        data->setName("data (points, coloured by load)");
        if (index > 1) data->removeFromLegend();
        data->setPen(QPen(color));
        data->setLineStyle(QCPGraph::lsNone);
        data->setScatterStyle(QCPScatterStyle(QCPScatterStyle::ssCircle, 4));
        QCPGraph* line = plot.addGraph();
        line->setData(sweep.slip, sweep.fit);
        line->setPen(QPen(color, 1.8));
        line->setName(at.isEmpty() ? model : at.mid(2) + ", " + model);
    }
    finish(plot);
}

}  // namespace terra::ui
