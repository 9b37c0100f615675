#include "widgets/panels/rover_panel.h"

#include <qcustomplot.h>

#include <QComboBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QPointer>
#include <QProgressBar>
#include <QPushButton>
#include <QTabWidget>
#include <QVBoxLayout>

#include "core/scenario/scenario_json.h"
#include "widgets/plots/figures.h"
#include "widgets/plots/sweep_plot.h"

namespace terra::ui {
namespace {

const char* kWheels[] = {"FL", "FR", "RL", "RR"};
const QColor kWheelColors[] = {QColor(31, 119, 180), QColor(214, 39, 40), QColor(44, 160, 44), QColor(255, 127, 14)};

QVector<double> column(const Table& t, const std::string& name) {
    const auto v = t.values(name);
    return QVector<double>(v.begin(), v.end());
}

void lines(QCustomPlot& plot, const Table& t, const std::vector<std::pair<std::string, QString>>& series,
           const QString& y_label, const QString& title) {
    resetPlot(plot, title);
    plot.xAxis->setLabel("Time t [s]");
    plot.yAxis->setLabel(y_label);
    const QVector<double> time = column(t, "t_s");
    int i = 0;
    for (const auto& [name, label] : series) {
        QCPGraph* g = plot.addGraph();
        g->setData(time, column(t, name), true);
        g->setName(label);
        g->setPen(QPen(kWheelColors[i++ % 4], 1.6));
    }
    plot.legend->setVisible(series.size() > 1);
    plot.rescaleAxes();
    plot.yAxis->scaleRange(1.1, plot.yAxis->range().center());
    placeLegend(plot);
    plot.replot();
}

}  // namespace

RoverPanel::RoverPanel(ProjectDocument* document, io::PresetLocations locations, QWidget* parent)
    : AnalysisPanel(document, "rover", parent), locations_(std::move(locations)) {
    setLive(false);  // scenarios use their own soils and robot; they run on request
    scenario_ = new QComboBox(this);
    for (const std::string& name : io::presetNames(locations_, "scenarios")) scenario_->addItem(QString::fromStdString(name));
    run_ = new QPushButton("Run", this);
    cancel_ = new QPushButton("Cancel", this);
    cancel_->setEnabled(false);
    progress_ = new QProgressBar(this);
    progress_->setRange(0, 100);
    status_ = new QLabel(this);
    status_->setWordWrap(true);
    readout_ = new QLabel(this);
    tabs_ = new QTabWidget(this);
    for (const char* name : {"Path", "Yaw", "Velocities", "Slip", "Drawbar pull", "Sinkage"}) {
        auto* plot = new QCustomPlot(tabs_);
        makeInteractive(plot, readout_);
        plots_.push_back(plot);
        tabs_->addTab(plot, name);
    }
    auto* bar = new QHBoxLayout;
    bar->addWidget(new QLabel("Scenario:", this));
    bar->addWidget(scenario_);
    bar->addWidget(run_);
    bar->addWidget(cancel_);
    bar->addWidget(progress_, 1);
    bar->addWidget(readout_);
    auto* layout = new QVBoxLayout(this);
    layout->addLayout(bar);
    layout->addWidget(tabs_, 1);
    layout->addWidget(status_);

    connect(run_, &QPushButton::clicked, this, [this] {
        storeSettings();
        recompute();
    });
    connect(cancel_, &QPushButton::clicked, this, &AnalysisPanel::cancelRunning);
    connect(this, &AnalysisPanel::busyChanged, this, [this](bool busy) {
        run_->setEnabled(!busy);
        cancel_->setEnabled(busy);
        if (busy) {
            progress_->setValue(0);
            status_->setText("Running…");
        }
    });
    connect(this, &AnalysisPanel::failed, this, [this](const QString& m) {
        run_->setEnabled(true);
        cancel_->setEnabled(false);
        status_->setText("<b>Error:</b> " + m.toHtmlEscaped());
    });
}

std::vector<std::pair<QString, QCustomPlot*>> RoverPanel::plots() const {
    std::vector<std::pair<QString, QCustomPlot*>> out;
    for (int i = 0; i < tabs_->count(); ++i) {
        out.emplace_back("rover-" + tabs_->tabText(i).toLower().replace(' ', '-'), plots_[static_cast<std::size_t>(i)]);
    }
    return out;
}

QCustomPlot* RoverPanel::currentPlot() const { return plots_[static_cast<std::size_t>(tabs_->currentIndex())]; }

nlohmann::json RoverPanel::settings() const { return {{"scenario", scenario_->currentText().toStdString()}}; }

void RoverPanel::applySettings(const nlohmann::json& s) {
    if (s.contains("scenario")) {
        const int i = scenario_->findText(QString::fromStdString(s["scenario"].get<std::string>()));
        if (i >= 0) scenario_->setCurrentIndex(i);
    }
}

AnalysisPanel::Job RoverPanel::makeJob() {
    auto loaded = scenario::resolveScenario(locations_, scenario_->currentText().toStdString());
    if (!loaded) throw std::invalid_argument(loaded.message());
    const scenario::Scenario scenario = *loaded;
    QPointer<QProgressBar> bar = progress_;
    return [scenario, bar](const std::atomic<bool>& cancel) -> std::any {
        scenario::RunOptions options;
        options.cancel = &cancel;
        options.progress = [bar](double fraction) {
            QMetaObject::invokeMethod(bar, [bar, fraction] {
                if (bar) bar->setValue(static_cast<int>(fraction * 100.0));
            }, Qt::QueuedConnection);
        };
        return scenario::runScenario(scenario, options);
    };
}

void RoverPanel::present(const std::any& value) {
    result_ = std::any_cast<scenario::RunResult>(value);
    progress_->setValue(100);
    const QString name = scenario_->currentText();
    const char* status[] = {"completed", "CANCELLED (partial)", "DIVERGED (partial)"};
    const QString title = QString("%1 — %2").arg(name, status[static_cast<int>(result_.status)]);
    const Table& t = result_.series;
    if (t.rows.size() < 2) {
        status_->setText("No output: " + QString::fromStdString(result_.message));
        return;
    }
    // Path: top-down view of the centre of mass (x forward, y left), equal scales.
    QCustomPlot& path = *plots_[0];
    resetPlot(path, title);
    auto* curve = new QCPCurve(path.xAxis, path.yAxis);
    curve->setData(column(t, "x_m"), column(t, "y_m"));
    curve->setPen(QPen(kWheelColors[0], 2.0));
    curve->setName("centre of mass");
    path.xAxis->setLabel("x [m]");
    path.yAxis->setLabel("y [m]");
    path.rescaleAxes();
    path.xAxis->scaleRange(1.1, path.xAxis->range().center());
    path.yAxis->setScaleRatio(path.xAxis, 1.0);
    path.replot();
    lines(*plots_[1], t, {{"yaw_deg", "yaw"}}, "Yaw ψ [deg]", title);
    lines(*plots_[2], t, {{"forward_m_s", "forward"}, {"lateral_m_s", "lateral"}}, "Velocity [m/s]", title);
    std::vector<std::pair<std::string, QString>> slip, fx, sinkage;
    for (const char* w : kWheels) {
        slip.emplace_back(std::string(w) + "_slip", w);
        fx.emplace_back(std::string(w) + "_Fx_N", w);
        sinkage.emplace_back(std::string(w) + "_sinkage_m", w);
    }
    lines(*plots_[3], t, slip, "Slip ratio s [-]", title);
    lines(*plots_[4], t, fx, "Drawbar pull F_x [N]", title);
    lines(*plots_[5], t, sinkage, "Sinkage h [m]", title);
    const auto& s = result_.summary;
    status_->setText(QString("%1: %2 s simulated, final pose x = %3 m, y = %4 m, yaw = %5°, distance %6 m, "
                             "motor energy %7 J%8")
                         .arg(status[static_cast<int>(result_.status)])
                         .arg(s.duration_s, 0, 'f', 2)
                         .arg(s.x_m, 0, 'f', 3)
                         .arg(s.y_m, 0, 'f', 3)
                         .arg(s.yaw_rad * 180.0 / 3.14159265358979, 0, 'f', 2)
                         .arg(s.distance_m, 0, 'f', 3)
                         .arg(s.energy_j, 0, 'f', 1)
                         .arg(result_.message.empty() ? QString() : ". " + QString::fromStdString(result_.message)));
}

}  // namespace terra::ui
