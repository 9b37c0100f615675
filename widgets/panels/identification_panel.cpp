#include "widgets/panels/identification_panel.h"

#include <qcustomplot.h>

#include <QCheckBox>
#include <QDoubleSpinBox>
#include <QFileDialog>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QLineEdit>
#include <QPushButton>
#include <QSplitter>
#include <QTabWidget>
#include <QTableWidget>
#include <QVBoxLayout>

#include "core/common/units.h"
#include "widgets/document/project_document.h"
#include "widgets/plots/figures.h"

namespace terra::ui {
namespace {

const char* kChannels[] = {"Fx_N", "Fz_N", "My_Nm"};

// The project soil's value of each identified parameter (user units), for comparison.
std::vector<double> trueValues(const Project& p) {
    const auto& s = p.soil;
    const double ks = s.cohesive_modulus / p.wheel.width_m + s.frictional_modulus;
    return {s.max_stress_a0, s.max_stress_a1, ks / 1e3, s.sinkage_exponent, s.sinkage_exponent_slip,
            s.cohesion_pa / 1e3, units::radToDeg(s.friction_angle_rad), s.shear_modulus_m};
}

}  // namespace

IdentificationPanel::IdentificationPanel(ProjectDocument* document, QWidget* parent)
    : AnalysisPanel(document, "identification", parent) {
    setLive(false);
    file_ = new QLineEdit(this);
    file_->setPlaceholderText("synthesise from the project's soil (or choose a CSV)");
    file_->setMinimumWidth(220);
    auto* browse = new QPushButton("Load CSV…", this);
    noise_ = new QDoubleSpinBox(this);
    noise_->setRange(0.0, 20.0);
    noise_->setSuffix(" %");
    noise_->setValue(2.0);
    noise_->setToolTip("Synthetic noise σ as a percentage of each channel's largest value (Eq. 5.1)");
    refine_ = new QCheckBox("Refine (full model, std deviations)", this);
    refine_->setChecked(true);
    three_loads_ = new QCheckBox("Synthesise at ½W, W, 1½W", this);
    three_loads_->setChecked(true);
    three_loads_->setToolTip("One load cannot separate c and φ when the data are noisy (full_fit.h)");
    fit_ = new QPushButton("Fit", this);
    fit_->setDefault(true);
    status_ = new QLabel(this);
    status_->setWordWrap(true);
    readout_ = new QLabel(this);
    tabs_ = new QTabWidget(this);
    for (const char* channel : kChannels) {
        auto* plot = new QCustomPlot(tabs_);
        makeInteractive(plot, readout_);
        plots_.push_back(plot);
        tabs_->addTab(plot, channel);
    }
    parameters_ = new QTableWidget(0, 4, this);
    parameters_->setHorizontalHeaderLabels({"Parameter", "Identified", "± std", "Project soil"});
    parameters_->horizontalHeader()->setSectionResizeMode(QHeaderView::Stretch);
    parameters_->verticalHeader()->hide();
    parameters_->setEditTriggers(QAbstractItemView::NoEditTriggers);

    auto* bar = new QHBoxLayout;
    bar->addWidget(file_, 1);
    bar->addWidget(browse);
    bar->addWidget(new QLabel("Noise:", this));
    bar->addWidget(noise_);
    bar->addWidget(three_loads_);
    bar->addWidget(refine_);
    bar->addWidget(fit_);
    auto* splitter = new QSplitter(this);
    splitter->addWidget(tabs_);
    splitter->addWidget(parameters_);
    splitter->setStretchFactor(0, 3);
    splitter->setStretchFactor(1, 1);
    parameters_->setMaximumWidth(460);
    auto* layout = new QVBoxLayout(this);
    layout->addLayout(bar);
    layout->addWidget(splitter, 1);
    auto* bottom = new QHBoxLayout;
    bottom->addWidget(status_, 1);
    bottom->addWidget(readout_);
    layout->addLayout(bottom);

    connect(browse, &QPushButton::clicked, this, [this] {
        const QString path = QFileDialog::getOpenFileName(this, "Load identification data", {}, "CSV (*.csv)");
        if (!path.isEmpty()) setDataFile(path);
    });
    connect(fit_, &QPushButton::clicked, this, [this] {
        storeSettings();
        recompute();
    });
    connect(this, &AnalysisPanel::busyChanged, this, [this](bool busy) {
        fit_->setEnabled(!busy);
        if (busy) status_->setText("Fitting…");
    });
    connect(this, &AnalysisPanel::failed, this, [this](const QString& m) {
        fit_->setEnabled(true);
        status_->setText("<b>Error:</b> " + m.toHtmlEscaped());
    });
}

void IdentificationPanel::setDataFile(const QString& path) {
    file_->setText(path);
    if (!path.isEmpty()) document_->addDataSet(path.toStdString());
}

std::vector<std::pair<QString, QCustomPlot*>> IdentificationPanel::plots() const {
    return {{"identification-Fx", plots_[0]}, {"identification-Fz", plots_[1]}, {"identification-My", plots_[2]}};
}

QCustomPlot* IdentificationPanel::currentPlot() const { return plots_[static_cast<std::size_t>(tabs_->currentIndex())]; }

nlohmann::json IdentificationPanel::settings() const {
    return {{"csv", file_->text().toStdString()},
            {"noise_percent", noise_->value()},
            {"refine", refine_->isChecked()},
            {"three_loads", three_loads_->isChecked()}};
}

void IdentificationPanel::applySettings(const nlohmann::json& s) {
    if (s.contains("csv")) file_->setText(QString::fromStdString(s["csv"].get<std::string>()));
    if (s.contains("noise_percent")) noise_->setValue(s["noise_percent"].get<double>());
    if (s.contains("refine")) refine_->setChecked(s["refine"].get<bool>());
    if (s.contains("three_loads")) three_loads_->setChecked(s["three_loads"].get<bool>());
}

AnalysisPanel::Job IdentificationPanel::makeJob() {
    const AnalysisInputs inputs = AnalysisInputs::from(document_->project());
    IdentificationSettings settings;
    settings.csv = file_->text().trimmed().toStdString();
    settings.noise_relative = noise_->value() / 100.0;
    settings.refine = refine_->isChecked();
    if (three_loads_->isChecked()) {
        const double w = inputs.conditions.load_n;
        settings.loads_n = {0.5 * w, w, 1.5 * w};
    }
    return [inputs, settings](const std::atomic<bool>&) -> std::any { return computeIdentification(inputs, settings); };
}

void IdentificationPanel::present(const std::any& value) {
    result_ = std::any_cast<IdentificationResult>(value);
    if (!result_.message.empty()) {
        status_->setText("<b>Error:</b> " + QString::fromStdString(result_.message).toHtmlEscaped());
        return;
    }
    const QString source = file_->text().isEmpty() ? QString("synthetic, %1 % noise").arg(noise_->value())
                                                   : QFileInfo(file_->text()).fileName();
    for (std::size_t i = 0; i < plots_.size(); ++i) {
        plotIdentification(*plots_[i], result_, kChannels[i],
                           QString("Identification: %1 samples (%2)").arg(result_.data.samples.size()).arg(source));
    }
    const Table& t = result_.parameters;
    const std::vector<double> truth = trueValues(document_->project());
    const bool synthetic = file_->text().isEmpty();
    parameters_->setRowCount(8);
    for (int i = 0; i < 8; ++i) {
        const std::string name = t.columns[static_cast<std::size_t>(i)];
        parameters_->setItem(i, 0, new QTableWidgetItem(QString::fromStdString(name)));
        parameters_->setItem(i, 1, new QTableWidgetItem(QString::number(t.rows[0][static_cast<std::size_t>(i)], 'g', 5)));
        QString std_text = "–";
        for (std::size_t c = 8; c < t.columns.size(); ++c) {
            if (t.columns[c] == name + "_std") std_text = QString::number(t.rows[0][c], 'g', 3);
        }
        parameters_->setItem(i, 2, new QTableWidgetItem(std_text));
        parameters_->setItem(i, 3, new QTableWidgetItem(synthetic ? QString::number(truth[static_cast<std::size_t>(i)], 'g', 5) : "–"));
    }
    QStringList steps;
    for (const auto& step : result_.fit.steps) {
        steps << QString("%1: Σr² = %2").arg(QString::fromStdString(step.name)).arg(step.squared_residual_norm, 0, 'g', 4);
    }
    if (result_.refined) {
        steps << QString("refined: Σr² = %1 (%2)")
                     .arg(result_.refined->report.squared_residual_norm, 0, 'g', 4)
                     .arg(QString::fromStdString(result_.refined->report.termination).left(40));
        for (const auto& flag : result_.refined->uncertainty.flags) steps << QString::fromStdString(flag);
    }
    status_->setText(QString("Fit in %1 ms. ").arg(result_.fit_time_ms, 0, 'f', 0) + steps.join(";  "));
}

}  // namespace terra::ui
