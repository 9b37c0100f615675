#include "widgets/panels/forces_panel.h"

#include <qcustomplot.h>

#include <QComboBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QTabWidget>
#include <QVBoxLayout>
#include <algorithm>

#include "core/project/panels.h"
#include "widgets/document/project_document.h"
#include "widgets/plots/figures.h"
#include "widgets/plots/sweep_plot.h"

namespace terra::ui {
namespace {

/// What one computation of the panel produces.
struct ForcesOutcome {
    analysis::ForcesResult sweep;
    analysis::SoilCurves soil;
};

}  // namespace

ForcesPanel::ForcesPanel(ProjectDocument* document, QWidget* parent)
    : AnalysisPanel(document, "forces", parent) {
    model_ = new QComboBox(this);
    model_->addItem("Full model (numerical integration)", false);
    model_->addItem("Quadratic approximation (closed form)", true);
    status_ = new QLabel(this);
    readout_ = new QLabel(this);
    readout_->setMinimumWidth(260);
    tabs_ = new QTabWidget(this);
    for (const SweepQuantity& quantity : sweepQuantities()) {
        auto* plot = new QCustomPlot(tabs_);
        makeInteractive(plot, readout_);
        plots_.push_back(plot);
        // Short tab names (eight tabs fit the panel); the full label is the tooltip.
        const QString label = quantity.label.left(quantity.label.indexOf(" ["));
        tabs_->addTab(plot, label.section(' ', 0, -2));
        tabs_->setTabToolTip(tabs_->count() - 1, label);
    }
    bulldozing_ = new QCustomPlot(tabs_);
    static_sinkage_ = new QCustomPlot(tabs_);
    makeInteractive(bulldozing_, readout_);
    makeInteractive(static_sinkage_, readout_);
    plots_.push_back(bulldozing_);
    plots_.push_back(static_sinkage_);
    tabs_->addTab(bulldozing_, "Bulldozing");
    tabs_->setTabToolTip(tabs_->count() - 1,
                         "Bulldozing resistance F_b against sinkage h (Fig. 2.15)");
    tabs_->addTab(static_sinkage_, "Static sinkage");
    tabs_->setTabToolTip(tabs_->count() - 1, "Static sinkage h_s against load W (Fig. 2.6)");
    auto* bar = new QHBoxLayout;
    bar->addWidget(new QLabel("Model:", this));
    bar->addWidget(model_);
    bar->addWidget(status_, 1);
    bar->addWidget(readout_);
    auto* layout = new QVBoxLayout(this);
    layout->addLayout(bar);
    layout->addWidget(tabs_, 1);

    connect(model_, &QComboBox::currentIndexChanged, this,
            [this] { document_->setQuadraticModel(model_->currentData().toBool()); });
    connect(document_, &ProjectDocument::conditionsChanged, this, [this] {
        const QSignalBlocker block(model_);
        model_->setCurrentIndex(document_->project().conditions.quadratic ? 1 : 0);
    });
    connect(this, &AnalysisPanel::failed, status_,
            [this](const QString& m) { status_->setText("<b>Error:</b> " + m.toHtmlEscaped()); });
    scheduleUpdate();
}

std::vector<std::pair<QString, QCustomPlot*>> ForcesPanel::plots() const {
    std::vector<std::pair<QString, QCustomPlot*>> out;
    for (std::size_t i = 0; i < sweepQuantities().size(); ++i) {
        out.emplace_back(QString::fromStdString(sweepQuantities()[i].column) + "-vs-slip",
                         plots_[i]);
    }
    out.emplace_back("Fb-vs-sinkage", bulldozing_);
    out.emplace_back("static-sinkage-vs-load", static_sinkage_);
    return out;
}

nlohmann::json ForcesPanel::settings() const {
    const auto all = plots();
    project::ForcesPanelSettings s;
    s.plot = all[static_cast<std::size_t>(std::max(tabs_->currentIndex(), 0))].first.toStdString();
    return project::toJson(s);
}

void ForcesPanel::applySettings(const nlohmann::json& json) {
    const auto settings =
        project::panelSettingsFromJson<project::ForcesPanelSettings>(withChanges(json));
    if (!settings) return;  // projects are checked when opened: only a program error lands here
    const QString wanted = QString::fromStdString(settings->plot);
    const auto all = plots();
    for (std::size_t i = 0; i < all.size(); ++i) {
        if (all[i].first == wanted) tabs_->setCurrentIndex(static_cast<int>(i));
    }
}

Table ForcesPanel::currentTable() const {
    if (currentPlot() == bulldozing_) return soil_curves_.bulldozing;
    if (currentPlot() == static_sinkage_) return soil_curves_.static_sinkage;
    return result_.table;
}

QCustomPlot* ForcesPanel::currentPlot() const {
    return plots_[static_cast<std::size_t>(tabs_->currentIndex())];
}

AnalysisPanel::Job ForcesPanel::makeJob() {
    const analysis::Inputs inputs = project::inputsOf(document_->project());
    return [inputs](const std::atomic<bool>& cancel) -> std::any {
        const analysis::Control control{&cancel};
        ForcesOutcome out;
        // ~1 ms, ~6 % of the sweep (sandy loam).
        out.soil = analysis::computeSoilCurves(inputs, {}, control);
        out.sweep = analysis::computeForceSweep(inputs, {}, control);
        return out;
    };
}

void ForcesPanel::present(const std::any& value) {
    auto outcome = std::any_cast<ForcesOutcome>(value);
    result_ = std::move(outcome.sweep);
    soil_curves_ = std::move(outcome.soil);
    const Project& p = document_->project();
    const QString title =
        QString("%1, %2, W = %3 N%4")
            .arg(QString::fromStdString(p.soil.name), QString::fromStdString(p.wheel.name))
            .arg(p.conditions.load_n)
            .arg(p.conditions.quadratic ? " (quadratic model)" : "");
    for (std::size_t i = 0; i < sweepQuantities().size(); ++i) {
        plotSweep(*plots_[i], result_.table, sweepQuantities()[i], title);
    }
    const QString soil_title =
        QString("%1, %2 (r = %3 mm, b = %4 mm)")
            .arg(QString::fromStdString(p.soil.name), QString::fromStdString(p.wheel.name))
            .arg(p.wheel.radius_m * 1e3)
            .arg(p.wheel.width_m * 1e3);
    plotBulldozing(*bulldozing_, soil_curves_, soil_title);
    plotStaticSinkage(*static_sinkage_, soil_curves_, soil_title);
    status_->setText(
        result_.warnings.empty()
            ? QString("%1 points").arg(result_.table.rows.size())
            : QString("%1 points; %2 without equilibrium (the wheel would sink to its axle)")
                  .arg(result_.table.rows.size())
                  .arg(result_.warnings.size()));
}

}  // namespace terra::ui
