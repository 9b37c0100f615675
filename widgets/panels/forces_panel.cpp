#include "widgets/panels/forces_panel.h"

#include <qcustomplot.h>

#include <QComboBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QTabWidget>
#include <QVBoxLayout>

#include "widgets/analyses/analyses.h"
#include "widgets/document/project_document.h"
#include "widgets/plots/sweep_plot.h"

namespace terra::ui {

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
        tabs_->addTab(plot, quantity.label.left(quantity.label.indexOf(" [")));
    }
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
    for (std::size_t i = 0; i < plots_.size(); ++i) {
        out.emplace_back(QString::fromStdString(sweepQuantities()[i].column) + "-vs-slip", plots_[i]);
    }
    return out;
}

QCustomPlot* ForcesPanel::currentPlot() const { return plots_[static_cast<std::size_t>(tabs_->currentIndex())]; }

AnalysisPanel::Job ForcesPanel::makeJob() {
    const AnalysisInputs inputs = AnalysisInputs::from(document_->project());
    return [inputs](const std::atomic<bool>& cancel) -> std::any { return computeForceSweep(inputs, &cancel); };
}

void ForcesPanel::present(const std::any& value) {
    result_ = std::any_cast<analysis::SweepResult>(value);
    const Project& p = document_->project();
    const QString title = QString("%1, %2, W = %3 N%4")
                              .arg(QString::fromStdString(p.soil.name), QString::fromStdString(p.wheel.name))
                              .arg(p.conditions.load_n)
                              .arg(p.conditions.quadratic ? " (quadratic model)" : "");
    for (std::size_t i = 0; i < plots_.size(); ++i) {
        plotSweep(*plots_[i], result_.table, sweepQuantities()[i], title);
    }
    status_->setText(result_.warnings.empty()
                         ? QString("%1 points").arg(result_.table.rows.size())
                         : QString("%1 points; %2 without equilibrium (the wheel would sink to its axle)")
                               .arg(result_.table.rows.size())
                               .arg(result_.warnings.size()));
}

}  // namespace terra::ui
