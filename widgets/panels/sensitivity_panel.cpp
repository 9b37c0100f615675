#include "widgets/panels/sensitivity_panel.h"

#include <qcustomplot.h>

#include <QComboBox>
#include <QDoubleSpinBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QTabWidget>
#include <QVBoxLayout>
#include <algorithm>
#include <array>

#include "core/project/panels.h"
#include "core/project/saved_analyses.h"
#include "core/soil/soil_parameters.h"
#include "widgets/document/project_document.h"
#include "widgets/plots/figures.h"

namespace terra::ui {

SensitivityPanel::SensitivityPanel(ProjectDocument* document, QWidget* parent)
    : AnalysisPanel(document, "sensitivity", parent) {
    parameter_ = new QComboBox(this);
    for (const auto& p : analysis::thesisSensitivityParameters()) {
        const soil::SoilField* field = soil::findSoilField(p.key);
        QStringList values;
        for (double v : p.values) values << QString::number(v);
        parameter_->addItem(QString("%1 [%2]: %3")
                                .arg(field ? field->symbol : p.key.c_str(),
                                     field ? field->unit : "", values.join(", ")),
                            QString::fromStdString(p.key));
    }
    const analysis::SensitivitySettings defaults;
    parameter_->setCurrentIndex(parameter_->findData(QString::fromStdString(defaults.parameter)));
    slip_angle_ = new QDoubleSpinBox(this);
    slip_angle_->setRange(-60.0, 60.0);
    slip_angle_->setSuffix(" °");
    slip_angle_->setValue(defaults.slip_angles_deg.front());
    tornado_slip_ = new QDoubleSpinBox(this);
    tornado_slip_->setRange(0.0, 1.0);
    tornado_slip_->setSingleStep(0.05);
    tornado_slip_->setValue(defaults.tornado_slip);
    status_ = new QLabel(this);
    readout_ = new QLabel(this);
    tabs_ = new QTabWidget(this);
    fx_ = new QCustomPlot(tabs_);
    fs_ = new QCustomPlot(tabs_);
    tornado_ = new QCustomPlot(tabs_);
    // Keys that do not change with the parameter (the plots() names do): a plot in a dock of its
    // own comes back by this name (plot_docking.h).
    fx_->setObjectName("sensitivity-Fx");
    fs_->setObjectName("sensitivity-Fs");
    tornado_->setObjectName("tornado");
    for (QCustomPlot* plot : {fx_, fs_, tornado_}) makeInteractive(plot, readout_);
    tabs_->addTab(fx_, "Drawbar pull F_x");
    tabs_->addTab(fs_, "Side force F_s");
    tabs_->addTab(tornado_, "Tornado (all parameters)");

    auto* bar = new QHBoxLayout;
    bar->addWidget(new QLabel("Parameter:", this));
    bar->addWidget(parameter_);
    bar->addWidget(new QLabel("β:", this));
    bar->addWidget(slip_angle_);
    bar->addWidget(new QLabel("Tornado at s =", this));
    bar->addWidget(tornado_slip_);
    bar->addStretch(1);
    // The read-out under the plots, beside the status: in the controls' row it made the panel
    // 755 px wide, wider than a 1024×700 window leaves it.
    auto* bottom = new QHBoxLayout;
    bottom->addWidget(status_, 1);
    bottom->addWidget(readout_);
    auto* layout = new QVBoxLayout(this);
    layout->addLayout(bar);
    layout->addWidget(tabs_, 1);
    layout->addLayout(bottom);

    auto changed = [this] {
        storeSettings();
        scheduleUpdate();
    };
    connect(parameter_, &QComboBox::currentIndexChanged, this, changed);
    connect(slip_angle_, &QDoubleSpinBox::valueChanged, this, changed);
    connect(tornado_slip_, &QDoubleSpinBox::valueChanged, this, changed);
    connect(this, &AnalysisPanel::failed, status_,
            [this](const QString& m) { status_->setText("<b>Error:</b> " + m.toHtmlEscaped()); });
    connect(this, &AnalysisPanel::busyChanged, status_, [this](bool busy) {
        if (busy) status_->setText("Computing…");
    });
    scheduleUpdate();
}

std::vector<std::pair<QString, QCustomPlot*>> SensitivityPanel::plots() const {
    const QString key = QString::fromStdString(shown_.parameter);
    return {{"sensitivity-" + key + "-Fx", fx_},
            {"sensitivity-" + key + "-Fs", fs_},
            {"tornado", tornado_}};
}

QCustomPlot* SensitivityPanel::currentPlot() const {
    // By index: a plot shown in a dock of its own leaves a placeholder in its tab.
    const std::array<QCustomPlot*, 3> in_tab_order{fx_, fs_, tornado_};
    return in_tab_order[static_cast<std::size_t>(std::clamp(tabs_->currentIndex(), 0, 2))];
}

Table SensitivityPanel::currentTable() const {
    return currentPlot() == tornado_ ? result_.tornado : result_.family.table;
}

nlohmann::json SensitivityPanel::settings() const {
    static const char* const kPlots[] = {"Fx", "Fs", "tornado"};
    project::SensitivityPanelSettings s;
    s.analysis = applied_;
    s.analysis.parameter = parameter_->currentData().toString().toStdString();
    s.analysis.slip_angles_deg = {slip_angle_->value()};
    s.analysis.tornado_slip = tornado_slip_->value();
    s.plot = kPlots[std::clamp(tabs_->currentIndex(), 0, 2)];
    return project::toJson(s);
}

void SensitivityPanel::applySettings(const nlohmann::json& json) {
    const auto settings =
        project::panelSettingsFromJson<project::SensitivityPanelSettings>(withChanges(json));
    if (!settings) return;  // projects are checked when opened: only a program error lands here
    applied_ = settings->analysis;
    const int i = parameter_->findData(QString::fromStdString(applied_.parameter));
    if (i >= 0) parameter_->setCurrentIndex(i);
    slip_angle_->setValue(applied_.slip_angles_deg.front());
    tornado_slip_->setValue(applied_.tornado_slip);
    const std::string& plot = settings->plot;
    tabs_->setCurrentIndex(plot == "tornado" ? 2 : plot == "Fs" ? 1 : 0);
}

analysis::SensitivitySettings SensitivityPanel::current() const {
    analysis::SensitivitySettings settings = applied_;
    settings.parameter = parameter_->currentData().toString().toStdString();
    settings.slip_angles_deg = {slip_angle_->value()};
    settings.tornado_slip = tornado_slip_->value();
    return settings;
}

AnalysisPanel::Job SensitivityPanel::makeJob() {
    const analysis::Inputs inputs = project::inputsOf(document_->project());
    const analysis::SensitivitySettings settings = current();
    shown_ = settings;
    return [inputs, settings](const std::atomic<bool>& cancel) -> std::any {
        return analysis::computeSensitivity(inputs, settings, {&cancel});
    };
}

void SensitivityPanel::present(const std::any& value) {
    result_ = std::any_cast<analysis::SensitivityResult>(value);
    const Project& p = document_->project();
    const QString title =
        QString("%1, %2, W = %3 N, β = %4°")
            .arg(QString::fromStdString(p.soil.name), QString::fromStdString(p.wheel.name))
            .arg(p.conditions.load_n)
            .arg(shown_.slip_angles_deg.front());
    plotSensitivityFamily(*fx_, result_, shown_.parameter, "Fx_N", title);
    plotSensitivityFamily(*fs_, result_, shown_.parameter, "Fs_N", title);
    plotTornado(*tornado_, result_, shown_.tornado_slip, title);
    status_->setText(QString("%1 points; %2 without equilibrium")
                         .arg(result_.family.table.rows.size())
                         .arg(result_.family.warnings.size()));
}

nlohmann::json SensitivityPanel::resultInputs() const {
    nlohmann::json inputs = AnalysisPanel::resultInputs();
    inputs["settings"].erase("plot");
    return inputs;
}

std::map<std::string, project::SavedResult> SensitivityPanel::savedResults() const {
    return savedSection(project::kSensitivityVersion, project::savedJson(result_),
                        QString("%1 points").arg(result_.family.table.rows.size()).toStdString(),
                        false);
}

AnalysisPanel::Restored SensitivityPanel::restoreResult(const std::string& section,
                                                        const project::SavedResult& saved) {
    const analysis::SensitivitySettings before = shown_;
    shown_ = current();  // what the saved study was of, when it is shown: the inputs hash as now
    const Restored restored =
        restoreSection(section, saved, project::kSensitivityVersion,
                       [](const nlohmann::json& json, const std::string& where) -> std::any {
                           return valueOrThrow(project::sensitivityResultFromJson(json, where));
                       });
    if (!restored.shown()) shown_ = before;
    return restored;
}

}  // namespace terra::ui
