#include "widgets/plots/gsa_figures.h"

#include <qcustomplot.h>

#include <array>
#include <cmath>
#include <stdexcept>

#include "core/common/range.h"
#include "core/common/units.h"
#include "core/soil/soil_parameters.h"
#include "widgets/plots/figures.h"
#include "widgets/plots/plot_legend.h"

namespace terra::ui {
namespace {

// A group of bars per slip takes this share of the unit spacing between slips.
constexpr double kGroupWidth = 0.8;

// "F_x [N]" of an output column name ("Fx_N"), as the sweep figures label them.
QString outputLabel(const std::string& name) {
    static const std::array<std::pair<const char*, const char*>, 11> kLabels{{
        {"Fx_N", "Drawbar pull F_x [N]"},
        {"Fy_N", "F_y [N]"},
        {"Fz_N", "Vertical force F_z [N]"},
        {"Mx_Nm", "M_x [N·m]"},
        {"My_Nm", "Resistance torque M_y [N·m]"},
        {"Mz_Nm", "M_z [N·m]"},
        {"Fb_N", "Bulldozing resistance F_b [N]"},
        {"Fs_N", "Side force F_s [N]"},
        {"sinkage_m", "Sinkage h [m]"},
        {"entry_angle_deg", "Entry angle θ_f [deg]"},
        {"exit_angle_deg", "Exit angle θ_r [deg]"},
    }};
    for (const auto& [key, label] : kLabels) {
        if (name == key) return QString::fromUtf8(label);
    }
    return QString::fromStdString(name);
}

QString parameterLabel(const std::string& key) {
    const soil::SoilField* field = soil::findSoilField(key);
    return field ? QString::fromUtf8(field->symbol) : QString::fromStdString(key);
}

void checkIndices(std::size_t output, std::size_t outputs, std::size_t slip_angle,
                  std::size_t slip_angles) {
    if (output >= outputs || slip_angle >= slip_angles) {
        throw std::out_of_range("output " + std::to_string(output) + " of " +
                                std::to_string(outputs) + ", slip angle " +
                                std::to_string(slip_angle) + " of " + std::to_string(slip_angles));
    }
}

QCPBars* addBars(QCustomPlot& plot, const QString& name, const QColor& fill, double width) {
    auto* bars = new QCPBars(plot.xAxis, plot.yAxis);
    bars->setName(name);
    bars->setBrush(fill);
    bars->setPen(QPen(fill.darker(130), 0.8));
    bars->setWidth(width);
    return bars;
}

QCPErrorBars* addWhiskers(QCPBars* bars) {
    auto* whiskers = new QCPErrorBars(bars->keyAxis(), bars->valueAxis());
    whiskers->setDataPlottable(bars);
    whiskers->setPen(QPen(QColor(60, 60, 60), 1.0));
    whiskers->setWhiskerWidth(4);
    whiskers->removeFromLegend();
    return whiskers;
}

}  // namespace

QColor parameterColor(std::size_t k) {
    static const std::array<QColor, 8> kColors{
        QColor(31, 119, 180),  QColor(255, 127, 14), QColor(44, 160, 44),   QColor(214, 39, 40),
        QColor(148, 103, 189), QColor(140, 86, 75),  QColor(227, 119, 194), QColor(127, 127, 127)};
    return kColors[k % kColors.size()];
}

void plotGlobalIndices(QCustomPlot& plot, const analysis::GlobalSensitivityResult& result,
                       std::size_t output, std::size_t slip_angle, const QString& title) {
    const gsa::OperatingGrid& grid = result.grid();
    checkIndices(output, result.outputs().size(), slip_angle, grid.slip_angles_rad.size());
    const bool refused = result.status() == gsa::StudyStatus::kTooManyFailures;
    resetPlot(plot, refused ? title + "\n" + QString::fromStdString(result.message()) : title);
    const std::string name = gsa::outputName(result.outputs()[output]);
    const bool sobol = result.sobol.has_value();
    plot.xAxis->setLabel("Slip s");
    plot.yAxis->setLabel(
        sobol ? QString("Sobol' index of %1 (S1 solid, ST light)")
                    .arg(outputLabel(name).section(" [", 0, 0))
              : QString("Morris μ* (solid), σ (light) of %1").arg(outputLabel(name)));
    QSharedPointer<QCPAxisTickerText> ticker(new QCPAxisTickerText);
    plot.xAxis->setTicker(ticker);
    if (refused) {
        plot.replot();
        return;
    }
    const std::vector<std::string>& params = result.parameters();
    const std::size_t d = params.size(), slips = grid.slips.size();
    const double width = kGroupWidth / static_cast<double>(2 * d);
    const std::size_t points = grid.size();
    for (std::size_t k = 0; k < d; ++k) {
        const QColor color = parameterColor(k);
        QColor light = color;
        light.setAlpha(90);
        const QString symbol = parameterLabel(params[k]);
        QCPBars* main = addBars(plot, sobol ? "S1 " + symbol : "μ* " + symbol, color, width);
        QCPBars* second = addBars(plot, sobol ? "ST " + symbol : "σ " + symbol, light, width);
        QCPErrorBars* main_whiskers = addWhiskers(main);
        QCPErrorBars* second_whiskers = sobol ? addWhiskers(second) : nullptr;
        const auto i = static_cast<Eigen::Index>(k);
        for (std::size_t s = 0; s < slips; ++s) {
            const std::size_t point = slip_angle * slips + s;
            const auto c = static_cast<Eigen::Index>(output * points + point);
            const double centre = static_cast<double>(s + 1);
            const double left = centre - 0.5 * kGroupWidth + width * (2.0 * k + 0.5);
            if (sobol) {
                const gsa::SobolIndices& x = result.sobol->indices;
                main->addData(left, x.first_order(i, c));
                second->addData(left + width, x.total(i, c));
                main_whiskers->addData(x.first_order_conf(i, c));
                second_whiskers->addData(x.total_conf(i, c));
            } else {
                const gsa::MorrisIndices& x = result.morris->indices;
                main->addData(left, x.mu_star(i, c));
                second->addData(left + width, x.sigma(i, c));
                main_whiskers->addData(x.mu_star_conf(i, c));
            }
            if (k == 0) ticker->addTick(centre, QString("s = %1").arg(grid.slips[s]));
        }
    }
    // The legend under the axes (plot_legend.h): it covered the K and c bars inside them.
    plot.legend->setVisible(true);
    plot.rescaleAxes();
    plot.xAxis->setRange(0.5, static_cast<double>(slips) + 0.5);
    if (sobol) {
        // Indices live in [0, 1]; estimates and whiskers may stray a little outside it.
        const QCPRange r = plot.yAxis->range();
        plot.yAxis->setRange(std::min(0.0, r.lower) - 0.05, std::max(1.0, r.upper) + 0.05);
    } else {
        plot.yAxis->setRange(0.0, 1.1 * plot.yAxis->range().upper);
    }
    layOutLegend(plot);
    plot.replot();
}

void plotUncertaintyBands(QCustomPlot& plot, const analysis::UncertaintyBandResult& result,
                          std::size_t output, std::size_t slip_angle, const QString& title) {
    const gsa::BandResult& b = result.bands;
    checkIndices(output, b.outputs.size(), slip_angle, b.grid.slip_angles_rad.size());
    const bool refused = !b.usable();
    resetPlot(plot, refused ? title + "\n" + QString::fromStdString(b.message) : title);
    plot.xAxis->setTicker(QSharedPointer<QCPAxisTicker>(new QCPAxisTicker));
    const std::string name = gsa::outputName(b.outputs[output]);
    plot.xAxis->setLabel("Slip s");
    plot.yAxis->setLabel(outputLabel(name));
    if (refused) {
        plot.replot();
        return;
    }
    const std::size_t slips = b.grid.slips.size();
    const Eigen::MatrixXd& bands = b.bands[output];  // percentiles × points
    QVector<double> x;
    for (std::size_t s = 0; s < slips; ++s) x.push_back(b.grid.slips[s]);
    auto curve = [&](const Eigen::RowVectorXd& values) {
        QVector<double> y;
        for (std::size_t s = 0; s < slips; ++s)
            y.push_back(values(static_cast<Eigen::Index>(slip_angle * slips + s)));
        return y;
    };
    const Eigen::Index last = bands.rows() - 1;
    const QColor band(31, 119, 180);
    QCPGraph* low = plot.addGraph();
    low->setData(x, curve(bands.row(0)), true);
    low->setPen(QPen(band, 1.0));
    low->setName(QString("p%1 – p%2").arg(b.percentiles.front()).arg(b.percentiles.back()));
    QCPGraph* high = plot.addGraph();
    high->setData(x, curve(bands.row(last)), true);
    high->setPen(QPen(band, 1.0));
    QColor fill = band;
    fill.setAlpha(60);
    high->setBrush(fill);
    high->setChannelFillGraph(low);
    high->removeFromLegend();
    for (Eigen::Index q = 1; q < last; ++q) {
        QCPGraph* g = plot.addGraph();
        g->setData(x, curve(bands.row(q)), true);
        g->setPen(QPen(band, 1.0, Qt::DashLine));
        g->setName(QString("p%1").arg(b.percentiles[static_cast<std::size_t>(q)]));
    }
    QCPGraph* nominal = plot.addGraph();
    nominal->setData(x, curve(result.nominal.row(static_cast<Eigen::Index>(output))), true);
    nominal->setPen(QPen(QColor(214, 39, 40), 2.0));
    nominal->setName("nominal soil");
    plot.legend->setVisible(true);
    plot.rescaleAxes();
    plot.yAxis->scaleRange(1.1);
    layOutLegend(plot);
    plot.replot();
}

}  // namespace terra::ui
