#include "widgets/panels/forces_panel.h"

#include <qcustomplot.h>

#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QTabWidget>
#include <QTimer>
#include <QtConcurrent/QtConcurrentRun>
#include <numbers>

#include "core/contact/contact_parameters.h"
#include "widgets/plots/sweep_plot.h"

namespace terra::ui {

ForcesPanel::ForcesPanel(io::PresetLocations locations, QWidget* parent)
    : QWidget(parent), locations_(std::move(locations)) {
    soil_ = new QComboBox(this);
    for (const std::string& name : io::presetNames(locations_, "soils")) soil_->addItem(QString::fromStdString(name));
    wheel_ = new QComboBox(this);
    for (const std::string& name : io::presetNames(locations_, "wheels")) wheel_->addItem(QString::fromStdString(name));
    load_ = new QDoubleSpinBox(this);
    load_->setRange(1.0, 5000.0);  // [N]; the model reports when there is no equilibrium
    load_->setDecimals(2);
    load_->setSuffix(" N");
    load_->setValue(58.86);  // Table 2.6: 6 kg
    model_ = new QComboBox(this);
    model_->addItem("full (numerical integration)", "full");
    model_->addItem("quadratic (closed form)", "quadratic");
    status_ = new QLabel(this);
    status_->setWordWrap(true);

    auto* form = new QFormLayout;
    form->addRow("Soil", soil_);
    form->addRow("Wheel", wheel_);
    form->addRow("Load W", load_);
    form->addRow("Model", model_);
    form->addRow(status_);
    auto* controls = new QWidget(this);
    controls->setLayout(form);
    controls->setMaximumWidth(320);

    tabs_ = new QTabWidget(this);
    for (const SweepQuantity& quantity : sweepQuantities()) {
        auto* plot = new QCustomPlot(tabs_);
        plot->setInteractions(QCP::iRangeDrag | QCP::iRangeZoom);
        plots_.push_back(plot);
        tabs_->addTab(plot, quantity.label.left(quantity.label.indexOf(" [")));
    }
    auto* layout = new QHBoxLayout(this);
    layout->addWidget(controls);
    layout->addWidget(tabs_, 1);

    debounce_ = new QTimer(this);
    debounce_->setSingleShot(true);
    debounce_->setInterval(30);  // [ms] coalesce a burst of edits into one sweep
    connect(debounce_, &QTimer::timeout, this, &ForcesPanel::startSweep);
    connect(&watcher_, &QFutureWatcher<Computation>::finished, this,
            [this] { showResult(watcher_.result()); });
    for (QComboBox* box : {soil_, wheel_, model_}) {
        connect(box, &QComboBox::currentIndexChanged, this, &ForcesPanel::scheduleUpdate);
    }
    connect(load_, &QDoubleSpinBox::valueChanged, this, &ForcesPanel::scheduleUpdate);
    selectPresets("sandy-loam", "A");
    scheduleUpdate();
}

bool ForcesPanel::selectPresets(const QString& soil, const QString& wheel) {
    const int s = soil_->findText(soil), w = wheel_->findText(wheel);
    if (s >= 0) soil_->setCurrentIndex(s);
    if (w >= 0) wheel_->setCurrentIndex(w);
    return s >= 0 && w >= 0;
}

void ForcesPanel::scheduleUpdate() {
    ++revision_;
    debounce_->start();
}

void ForcesPanel::startSweep() {
    if (watcher_.isRunning()) {  // the finished handler restarts with the newest inputs
        return;
    }
    const int revision = revision_;
    const std::string soil_name = soil_->currentText().toStdString();
    const std::string wheel_name = wheel_->currentText().toStdString();
    const double load = load_->value();
    const bool quadratic = model_->currentData().toString() == "quadratic";
    const io::PresetLocations locations = locations_;
    watcher_.setFuture(QtConcurrent::run([=]() {
        Computation out;
        out.revision = revision;
        const auto soil = io::resolveSoil(locations, soil_name);
        const auto wheel = io::resolveWheel(locations, wheel_name);
        if (!soil || !wheel) {
            out.error = QString::fromStdString(!soil ? soil.message() : wheel.message());
            return out;
        }
        analysis::SweepSpec spec;
        spec.slips = analysis::linspace(0.0, 0.99, 100);
        for (double beta : {5.0, 10.0, 15.0, 20.0, 25.0, 30.0}) {
            spec.slip_angles_rad.push_back(beta * std::numbers::pi / 180.0);
        }
        spec.load_n = load;
        spec.model = quadratic ? contact::ContactModel::kQuadratic : contact::ContactModel::kFull;
        try {
            out.result = analysis::sweepSlip(contact::makeContactParameters(*soil, *wheel), spec);
        } catch (const std::exception& e) {
            out.error = e.what();
        }
        return out;
    }));
}

void ForcesPanel::showResult(const Computation& computation) {
    if (computation.revision != revision_) {  // stale: inputs changed meanwhile
        startSweep();
        return;
    }
    if (!computation.error.isEmpty()) {
        status_->setText("<b>Error:</b> " + computation.error.toHtmlEscaped());
        return;
    }
    result_ = computation.result;
    const QString title = QString("%1, wheel %2, W = %3 N")
                              .arg(soil_->currentText(), wheel_->currentText())
                              .arg(load_->value());
    for (std::size_t i = 0; i < plots_.size(); ++i) {
        plotSweep(*plots_[i], result_.table, sweepQuantities()[i], title);
    }
    status_->setText(result_.warnings.empty()
                         ? QString("%1 points").arg(result_.table.rows.size())
                         : QString("%1 points; %2 without equilibrium (the wheel would sink to its axle)")
                               .arg(result_.table.rows.size())
                               .arg(result_.warnings.size()));
    emit sweepFinished();
}

}  // namespace terra::ui
