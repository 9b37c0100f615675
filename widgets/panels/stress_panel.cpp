#include "widgets/panels/stress_panel.h"

#include <qcustomplot.h>

#include <QComboBox>
#include <QDoubleSpinBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QVBoxLayout>

#include "core/contact/operating_fields.h"
#include "core/project/panels.h"
#include "core/project/saved_analyses.h"
#include "widgets/document/project_document.h"
#include "widgets/panels/summary_html.h"
#include "widgets/plots/figures.h"

namespace terra::ui {

StressPanel::StressPanel(ProjectDocument* document, QWidget* parent)
    : AnalysisPanel(document, "stresses", parent) {
    const analysis::StressSettings defaults;
    slip_ = new QDoubleSpinBox(this);
    slip_->setRange(-1.0, 1.0);
    slip_->setSingleStep(0.05);
    slip_->setDecimals(3);
    slip_->setValue(defaults.slip);
    slip_->setToolTip(QString::fromUtf8(contact::slipField().description));
    slip_angle_ = new QDoubleSpinBox(this);
    slip_angle_->setRange(-60.0, 60.0);
    slip_angle_->setSuffix(" °");
    slip_angle_->setValue(defaults.slip_angle_deg);
    slip_angle_->setToolTip(QString::fromUtf8(contact::slipAngleField().description));
    stress_ = new QComboBox(this);
    stress_->addItem("All stresses", "all");
    stress_->addItem("Normal stress σ", "sigma");
    stress_->addItem("Shear stress τ", "tau");
    stress_->addItem("Tangential shear τ_t", "tau_t");
    stress_->addItem("Lateral shear τ_l", "tau_l");
    info_ = new QLabel(this);
    info_->setObjectName("stresses.summary");
    info_->setTextFormat(Qt::RichText);
    info_->setWordWrap(true);
    readout_ = new QLabel(this);
    plot_ = new QCustomPlot(this);
    makeInteractive(plot_, readout_);

    auto* bar = new QHBoxLayout;
    bar->addWidget(new QLabel("Slip s:", this));
    bar->addWidget(slip_);
    bar->addWidget(new QLabel("Slip angle β:", this));
    bar->addWidget(slip_angle_);
    bar->addWidget(stress_);
    bar->addStretch(1);
    bar->addWidget(readout_);
    auto* layout = new QVBoxLayout(this);
    layout->addLayout(bar);
    layout->addWidget(plot_, 1);
    layout->addWidget(info_);

    for (QDoubleSpinBox* box : {slip_, slip_angle_}) {
        connect(box, &QDoubleSpinBox::valueChanged, this, [this] {
            storeSettings();
            scheduleUpdate();
        });
    }
    connect(stress_, &QComboBox::currentIndexChanged, this, [this] {
        storeSettings();
        redraw();
    });
    connect(this, &AnalysisPanel::failed, info_,
            [this](const QString& m) { info_->setText("<b>Error:</b> " + m.toHtmlEscaped()); });
    scheduleUpdate();
}

analysis::StressSettings StressPanel::current() const {
    analysis::StressSettings s = applied_;
    s.slip = slip_->value();
    s.slip_angle_deg = slip_angle_->value();
    s.stress = stress_->currentData().toString().toStdString();
    return s;
}

nlohmann::json StressPanel::settings() const {
    return project::toJson(project::StressPanelSettings{current()});
}

void StressPanel::applySettings(const nlohmann::json& json) {
    const auto settings =
        project::panelSettingsFromJson<project::StressPanelSettings>(withChanges(json));
    if (!settings) return;  // projects are checked when opened: only a program error lands here
    applied_ = settings->analysis;
    slip_->setValue(applied_.slip);
    slip_angle_->setValue(applied_.slip_angle_deg);
    const int i = stress_->findData(QString::fromStdString(applied_.stress));
    if (i >= 0) stress_->setCurrentIndex(i);
}

AnalysisPanel::Job StressPanel::makeJob() {
    const analysis::Inputs inputs = project::inputsOf(document_->project());
    const analysis::StressSettings settings = current();
    return [inputs, settings](const std::atomic<bool>& cancel) -> std::any {
        return analysis::computeStresses(inputs, settings, {&cancel});
    };
}

void StressPanel::present(const std::any& value) {
    result_ = std::any_cast<analysis::StressResult>(value);
    // The core summary (what `terrastudio stresses` prints) without its heading, which the plot's
    // title gives: θ_f and how it was found, θ_m, each stress's RMSE and MAE of the quadratic
    // approximation; a failed or cancelled run says so and why. The inputs and settings are the
    // panel's own: a result is only shown while they are those it was computed from (a change
    // computes again; a saved result is restored only for the same ones).
    const analysis::Summary summary =
        analysis::stressSummary(project::inputsOf(document_->project()), current(), result_);
    info_->setText(summaryParagraphHtml(
        std::span<const analysis::SummaryRow>(summary.begin() + 1, summary.end())));
    redraw();
}

void StressPanel::redraw() {
    const Project& p = document_->project();
    plotStresses(*plot_, result_, stress_->currentData().toString().toStdString(),
                 QString("%1, %2, W = %3 N, s = %4, β = %5°")
                     .arg(QString::fromStdString(p.soil.name), QString::fromStdString(p.wheel.name))
                     .arg(p.conditions.load_n)
                     .arg(slip_->value())
                     .arg(slip_angle_->value()));
}

nlohmann::json StressPanel::resultInputs() const {
    nlohmann::json inputs = AnalysisPanel::resultInputs();
    inputs["settings"].erase("stress");
    return inputs;
}

std::map<std::string, project::SavedResult> StressPanel::savedResults() const {
    return savedSection(project::kStressesVersion, project::savedJson(result_),
                        QString("%1 angles").arg(result_.table.rows.size()).toStdString(), false);
}

AnalysisPanel::Restored StressPanel::restoreResult(const std::string& section,
                                                   const project::SavedResult& saved) {
    return restoreSection(section, saved, project::kStressesVersion,
                          [](const nlohmann::json& json, const std::string& where) -> std::any {
                              return valueOrThrow(project::stressResultFromJson(json, where));
                          });
}

}  // namespace terra::ui
