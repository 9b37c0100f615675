#include "widgets/panels/identification_fit_page.h"

#include <qcustomplot.h>

#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFile>
#include <QFileDialog>
#include <QFileInfo>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QLineEdit>
#include <QPushButton>
#include <QScrollArea>
#include <QScrollBar>
#include <QSignalBlocker>
#include <QSplitter>
#include <QStringList>
#include <QTabWidget>
#include <QTableWidget>
#include <QVBoxLayout>
#include <limits>

#include "core/analysis/validation.h"
#include "core/identification/parameters.h"
#include "core/io/experiment.h"
#include "core/io/parameters_json.h"
#include "widgets/document/project_document.h"
#include "widgets/document/suggested_paths.h"
#include "widgets/editors/preset_names.h"
#include "widgets/panels/data_preview.h"
#include "widgets/panels/identification_fit_options.h"
#include "widgets/panels/identification_report.h"
#include "widgets/plots/figures.h"
#include "widgets/plots/identification_figures.h"

namespace terra::ui {
namespace {

const char* kChannels[] = {"Fx_N", "Fz_N", "My_Nm"};
const char* kChannelSymbols[] = {"F_x [N]", "F_z [N]", "M_y [N·m]"};
const QString kIdentifiedSuffix = " (identified)";

}  // namespace

IdentificationFitPage::IdentificationFitPage(ProjectDocument* document, QWidget* parent)
    : QWidget(parent), document_(document) {
    file_ = new QLineEdit(this);
    file_->setPlaceholderText("synthesise from the project's soil (or choose a CSV)");
    file_->setMinimumWidth(180);  // the first row fits 700 px (1024×700, Compact layout)
    auto* browse = new QPushButton("Load CSV…", this);
    noise_ = new QDoubleSpinBox(this);
    noise_->setRange(0.0, 20.0);
    noise_->setSuffix(" %");
    noise_->setValue(project::IdentificationPanelSettings{}.fit.synthetic.noise_percent);
    noise_->setToolTip(
        "Synthetic noise σ as a percentage of each channel's largest value (Eq. 5.1)");
    refine_ = new QCheckBox("Full model (global search)", this);
    refine_->setToolTip(
        "On: the global identification on the full model (no start needed; std, priors, held-out "
        "error, ambiguity). Off: the thesis's decoupled three-step fit from fixed guesses");
    refine_->setChecked(project::IdentificationPanelSettings{}.fit.refine);
    three_loads_ = new QCheckBox("Synthesise at ½W, W, 1½W", this);
    three_loads_->setChecked(true);
    three_loads_->setToolTip(
        "One load cannot separate c and φ when the data are noisy (full_fit.h)");
    fit_ = new QPushButton("Fit", this);
    fit_->setObjectName("identification.fit");
    fit_->setDefault(true);
    cancel_fit_ = new QPushButton("Cancel", this);
    cancel_fit_->setObjectName("identification.cancel");
    cancel_fit_->setEnabled(false);
    cancel_fit_->setToolTip("Stops the fit: nothing is fitted, the soil is not changed");
    status_ = new QLabel(this);
    status_->setWordWrap(true);
    readout_ = new QLabel(this);
    tabs_ = new QTabWidget(this);
    for (const char* channel : kChannelSymbols) {
        auto* plot = new QCustomPlot(tabs_);
        plots_.push_back(plot);
        tabs_->addTab(plot, QString::fromUtf8(channel));
    }
    parameters_ = new QTableWidget(0, 6, this);
    parameters_->setObjectName("identification.parameters");
    parameters_->setHorizontalHeaderLabels(
        {"Parameter", "Identified", "± std", "Prior", "σ post/prior", "Truth"});
    parameters_->horizontalHeaderItem(4)->setToolTip(
        "Posterior std / prior std: near 1 the data do not see the parameter (the prior decides); "
        "≪ 1 the data determine it");
    parameters_->horizontalHeaderItem(5)->setToolTip(
        "The project soil the synthetic data were made from (none for a CSV)");
    options_ = new IdentificationFitOptions(document_, refine_, this);
    // The CSV before a fit: its first rows, what is read of it and what will be fitted.
    preview_ = new DataPreviewWidget(this);
    report_ = new QLabel(this);
    report_->setObjectName("identification.report");
    report_->setWordWrap(true);
    report_->setTextInteractionFlags(Qt::TextSelectableByMouse);
    report_->setAlignment(Qt::AlignTop | Qt::AlignLeft);
    // Columns as wide as their text, numbers on one line (they wrapped to "0.\n38273" in a
    // narrow side panel); a side panel narrower than the table scrolls it.
    parameters_->horizontalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
    parameters_->horizontalHeader()->setStretchLastSection(true);
    parameters_->setWordWrap(false);
    parameters_->verticalHeader()->hide();
    // Rows as tall as a line of text (the style's 30 px left room for 3 of 9 rows at 1024×700).
    parameters_->verticalHeader()->setMinimumSectionSize(fontMetrics().height() + 4);
    parameters_->verticalHeader()->setDefaultSectionSize(fontMetrics().height() + 4);
    parameters_->setEditTriggers(QAbstractItemView::NoEditTriggers);
    apply_ = new QPushButton("Apply identified soil to project", this);
    apply_->setObjectName("identification.apply");
    apply_->setToolTip(
        "Replace the project's soil by the identified parameters (a₀, a₁, K_s, n, n₁, c, φ, K); "
        "k_c : k_φ and γ stay the project soil's, and j_max unless the fit held or identified "
        "one. Edit ▸ Undo restores the soil");
    apply_->setEnabled(false);

    auto* bar = new QHBoxLayout;
    bar->addWidget(file_, 1);
    bar->addWidget(browse);
    bar->addWidget(new QLabel("Noise:", this));
    bar->addWidget(noise_);
    bar->addWidget(three_loads_);

    auto* start_row = new QHBoxLayout;
    start_row->addWidget(options_->startLabel(), 1);
    start_row->addWidget(fit_);
    start_row->addWidget(cancel_fit_);
    auto* side = new QWidget(this);
    auto* side_layout = new QVBoxLayout(side);
    side_layout->setContentsMargins(0, 0, 0, 0);
    // The CSV's preview and the fitted parameters share the room: the preview is in front
    // after a CSV is chosen, the parameters after a fit.
    side_tabs_ = new QTabWidget(side);
    side_tabs_->setObjectName("identification.side_tabs");
    side_tabs_->setDocumentMode(true);
    side_tabs_->addTab(parameters_, "Parameters");
    side_tabs_->addTab(preview_, "Data preview");
    side_tabs_->setTabVisible(1, false);
    side_layout->addWidget(side_tabs_, 2);
    side_layout->addWidget(apply_);
    // The report scrolls in what the table leaves: a long one (flags, adequacy) once took the
    // height of the table's rows.
    auto* report_area = new QScrollArea(side);
    report_area->setWidget(report_);
    report_area->setWidgetResizable(true);
    report_area->setFrameShape(QFrame::NoFrame);
    report_area->setHorizontalScrollBarPolicy(Qt::ScrollBarAlwaysOff);
    report_area->setMinimumHeight(2 * fontMetrics().lineSpacing());
    side_layout->addWidget(report_area, 1);
    auto* splitter = new QSplitter(this);
    splitter->addWidget(tabs_);
    splitter->addWidget(side);
    splitter->setStretchFactor(0, 3);
    splitter->setStretchFactor(1, 2);
    side->setMaximumWidth(560);
    auto* fit_layout = new QVBoxLayout(this);
    fit_layout->setContentsMargins(0, 0, 0, 0);
    fit_layout->addLayout(bar);
    fit_layout->addLayout(options_->methodRow());
    fit_layout->addLayout(options_->modelRow());
    fit_layout->addLayout(options_->priorRow());
    fit_layout->addLayout(start_row);
    fit_layout->addWidget(splitter, 1);
    auto* bottom = new QHBoxLayout;
    bottom->addWidget(status_, 1);
    bottom->addWidget(readout_);
    fit_layout->addLayout(bottom);

    connect(apply_, &QPushButton::clicked, this, [this] { applyIdentifiedSoil(); });
    connect(browse, &QPushButton::clicked, this, [this] {
        const QString path = QFileDialog::getOpenFileName(
            this, "Load identification data", startFolder(document_->filePath()), "CSV (*.csv)");
        if (!path.isEmpty()) setDataFile(path);
    });
    connect(fit_, &QPushButton::clicked, this, [this] {
        // Prior items are checked before anything runs; a bad one is named, nothing is fitted.
        if (const std::vector<Issue> issues = options_->priorIssues(); !issues.empty()) {
            status_->setText("<b>Error:</b> " +
                             QString::fromStdString(formatIssues(issues)).toHtmlEscaped());
            return;
        }
        emit fitRequested();
    });
    // After the options' own update (they connect first): the full model and the decoupled fit
    // read other columns.
    connect(refine_, &QCheckBox::toggled, this, [this] { updateDataPreview(); });
    connect(file_, &QLineEdit::textChanged, this, [this] {
        options_->setDataFile(file_->text());
        updateDataControls();
        updateDataPreview();
    });
    updateDataControls();
    connect(cancel_fit_, &QPushButton::clicked, this, [this] {
        status_->setText("Cancelling…");
        emit cancelRequested();
    });
}

QString IdentificationFitPage::fitStatus() const { return status_->text(); }

QString IdentificationFitPage::fitReport() const { return report_->text(); }

QString IdentificationFitPage::parameterCell(int row, int column) const {
    const QTableWidgetItem* item = parameters_->item(row, column);
    return item != nullptr ? item->text() : QString();
}

QString IdentificationFitPage::parameterHeader(int column) const {
    const QTableWidgetItem* item = parameters_->horizontalHeaderItem(column);
    return item != nullptr ? item->text() : QString();
}

std::optional<soil::SoilParameters> IdentificationFitPage::identifiedSoil() const {
    if (!result_.message.empty() || result_.parameters.rows.empty()) return std::nullopt;
    if (result_.report && !result_.report->usable()) return std::nullopt;
    const identification::DecoupledParameters& d = result_.identified;
    identification::ParameterVector p{};
    p[identification::kA0] = d.a0;
    p[identification::kA1] = d.a1;
    p[identification::kKs] = d.pressure_modulus;
    p[identification::kN] = d.n0;
    p[identification::kC] = d.cohesion_pa;
    p[identification::kPhi] = d.friction_angle_rad;
    p[identification::kK] = d.shear_modulus_m;
    p[identification::kJmax] = d.max_shear_deformation_m;
    const soil::SoilParameters& base = document_->project().soil;
    soil::SoilParameters soil;
    try {
        soil = analysis::soilFromParameters(base, fit_wheel_, p, d.n1);
    } catch (const std::invalid_argument&) {
        return std::nullopt;  // the project's soil has K_s ≤ 0 on that wheel: no k_c : k_φ
    }
    // j_max is the fit's when the fit identified it or held one the user chose.
    if (result_.report && fit_jmax_mode_ != "auto")
        soil.max_shear_deformation_m = d.max_shear_deformation_m;
    if (fit_source_ == "synthetic") {
        std::string name = base.name;
        const std::string suffix = kIdentifiedSuffix.toStdString();
        if (name.ends_with(suffix)) name.resize(name.size() - suffix.size());
        soil.name = name + suffix;
    } else {
        soil.name = "identified from " + fit_source_.toStdString();
    }
    soil.source = "identified by the studio's identification panel from " +
                  fit_source_.toStdString() + " on " + fit_wheel_.name;
    if (!soil::validate(soil).empty()) return std::nullopt;
    return soil;
}

bool IdentificationFitPage::applyIdentifiedSoil() {
    const std::optional<soil::SoilParameters> soil = identifiedSoil();
    if (!soil) return false;
    return document_->setSoil(*soil, "", QString("Apply identified soil (%1)").arg(fit_source_));
}

void IdentificationFitPage::updateDataControls() {
    // Noise and the three loads only apply to synthetic data.
    const bool synthetic = file_->text().trimmed().isEmpty();
    noise_->setEnabled(synthetic);
    three_loads_->setEnabled(synthetic);
}

void IdentificationFitPage::setDataFile(const QString& path) {
    file_->setText(path);
    if (!path.isEmpty()) document_->addDataSet(path.toStdString());
}

QString IdentificationFitPage::dataFile() const { return file_->text(); }

QString IdentificationFitPage::dataPreview() const {
    return side_tabs_->isTabVisible(1) ? preview_->text() : QString();
}

void IdentificationFitPage::updateDataPreview() {
    const QString path = file_->text().trimmed();
    if (path.isEmpty()) {
        preview_->clear();
        side_tabs_->setTabVisible(1, false);
        return;
    }
    side_tabs_->setTabVisible(1, true);
    side_tabs_->setCurrentIndex(1);
    // Read on a worker as the fit reads it (the full model and the decoupled fit read other
    // columns); shown when ready.
    preview_->preview(path, options_->fullModel());
}

void IdentificationFitPage::setStatus(const QString& html) { status_->setText(html); }

QCustomPlot* IdentificationFitPage::currentPlot() const {
    return plots_[static_cast<std::size_t>(tabs_->currentIndex())];
}

void IdentificationFitPage::writeSettings(project::IdentificationPanelSettings& s) const {
    analysis::IdentificationSettings& fit = s.fit;
    fit.csv = file_->text().toStdString();
    fit.synthetic.noise_percent = noise_->value();
    s.three_loads = three_loads_->isChecked();
    options_->writeSettings(s);
}

void IdentificationFitPage::applySettings(const project::IdentificationPanelSettings& s) {
    const analysis::IdentificationSettings& fit = s.fit;
    file_->setText(QString::fromStdString(fit.csv));
    noise_->setValue(fit.synthetic.noise_percent);
    three_loads_->setChecked(s.three_loads);
    options_->applySettings(s);
    // A parameter named by an old key in the saved priors ("Ks=…", issue 26): read as its new
    // one, noted as the command line notes it.
    if (!s.fit.key_warnings.empty()) {
        QStringList notes;
        for (const Issue& note : s.fit.key_warnings)
            notes << QString::fromStdString(note.where + ": " + note.message).toHtmlEscaped();
        status_->setText("<b>Warning:</b> the saved settings: " + notes.join("<br>"));
    }
}

analysis::IdentificationSettings IdentificationFitPage::fitSettings() const {
    project::IdentificationPanelSettings panel;
    writeSettings(panel);
    analysis::IdentificationSettings settings = panel.fit;
    settings.csv = file_->text().trimmed().toStdString();
    if (settings.refine) {
        if (panel.jmax == "none")
            settings.max_shear_deformation_m = std::numeric_limits<double>::infinity();
        if (panel.jmax == "fixed") settings.max_shear_deformation_m = panel.jmax_mm * 1e-3;
        settings.fit_max_shear_deformation = panel.jmax == "fit";
    } else {
        // The decoupled fit has none of the full model's options.
        const analysis::IdentificationSettings defaults;
        settings.prior_soil_name = defaults.prior_soil_name;
        settings.prior_items = defaults.prior_items;
        settings.holdout_fraction = defaults.holdout_fraction;
        settings.folds = defaults.folds;
        settings.loss = defaults.loss;
    }
    if (panel.three_loads && settings.csv.empty()) {
        const double w = document_->project().conditions.load_n;
        settings.synthetic.loads_n = {0.5 * w, w, 1.5 * w};
    }
    return settings;
}

std::function<std::any(const std::atomic<bool>&)> IdentificationFitPage::makeJob() {
    analysis::Inputs inputs = project::inputsOf(document_->project());
    // The wheel the panel states (synthetic data are made on it).
    inputs.wheel = options_->chosenWheel();
    pending_wheel_ = inputs.wheel;
    pending_jmax_mode_ = options_->jmaxMode();
    analysis::IdentificationSettings settings = fitSettings();
    return [inputs, settings](const std::atomic<bool>& cancel) mutable -> std::any {
        if (!settings.prior_soil_name.empty()) {  // read on the worker, not the GUI thread
            auto soil = io::resolveSoil(studioPresetLocations(), settings.prior_soil_name);
            if (!soil) throw std::invalid_argument("prior: " + soil.message());
            settings.prior_soil = *soil;
        }
        analysis::Control control{&cancel};
        control.threads = 0;  // one per core: the search's result does not depend on it
        return analysis::computeIdentification(inputs, settings, control);
    };
}

void IdentificationFitPage::prepareSaved() {
    // The fit's wheel and j_max mode are the ones the controls give now: the inputs hash the same.
    pending_wheel_ = options_->chosenWheel();
    pending_jmax_mode_ = options_->jmaxMode();
}

void IdentificationFitPage::requestFit() {
    if (fit_->isEnabled()) fit_->click();
}

void IdentificationFitPage::setBusy(bool busy) {
    fit_->setEnabled(!busy);
    cancel_fit_->setEnabled(busy);
    if (busy) status_->setText("Fitting…");
}

void IdentificationFitPage::showFailure(const QString& message) {
    fit_->setEnabled(true);
    cancel_fit_->setEnabled(false);
    status_->setText("<b>Error:</b> " + message.toHtmlEscaped());
}

void IdentificationFitPage::clearShown() {
    report_->clear();
    parameters_->setRowCount(0);
    fitTableToRows();
    for (QCustomPlot* plot : plots_) {
        plot->clearPlottables();
        // The title named the shown fit's samples and source: not over emptied axes.
        setPlotTitle(*plot, "No fit shown");
        plot->replot();
    }
}

void IdentificationFitPage::clearResult() {
    result_ = analysis::IdentificationResult{};
    apply_->setEnabled(false);
    clearShown();
    status_->setText("Not fitted yet: press Fit.");
}

void IdentificationFitPage::present(const std::any& value,
                                    const std::function<QString(const QString&)>& marked) {
    result_ = std::any_cast<analysis::IdentificationResult>(value);
    fit_wheel_ = pending_wheel_;
    fit_jmax_mode_ = pending_jmax_mode_;
    fit_source_ =
        file_->text().isEmpty() ? QString("synthetic") : QFileInfo(file_->text()).fileName();
    apply_->setEnabled(identifiedSoil().has_value());
    if (result_.message.empty()) side_tabs_->setCurrentIndex(0);  // the fit's parameters
    if (result_.cancelled) {
        // As every panel says it (completion.h): cancelled, and what there is of it — nothing.
        status_->setText(
            marked("Fit cancelled before it found a minimum: nothing fitted, "
                   "nothing to apply (Fit runs it again)."));
        // The previous fit's curves and table are not this one's: cleared, so that the plots,
        // the table and an export say the same.
        clearShown();
        return;
    }
    if (!result_.message.empty()) {
        status_->setText(
            "<b>Error:</b> " +
            QString::fromStdString(result_.message).toHtmlEscaped().replace("\n", "<br>"));
        report_->clear();
        return;
    }
    const QString source = file_->text().isEmpty()
                               ? QString("synthetic, %1 % noise").arg(noise_->value())
                               : QFileInfo(file_->text()).fileName();
    for (std::size_t i = 0; i < plots_.size(); ++i) {
        plotIdentification(*plots_[i], result_, kChannels[i],
                           QString("%1 samples (%2)").arg(result_.data.samples.size()).arg(source));
    }
    // The truth column is the project's soil only for data synthesised from it.
    std::optional<identification::DecoupledParameters> truth;
    if (file_->text().isEmpty())
        truth = identification::decoupledOf(document_->project().soil, fit_wheel_);
    fillParameterTable(*parameters_, result_, truth);
    fitTableToRows();
    report_->setText(identificationReport(result_));
    // The fit's warnings after its steps (a column not read, an old parameter key typed).
    QString status = identificationStatus(result_);
    for (const std::string& warning : result_.warnings)
        status += "<br><b>Warning:</b> " + QString::fromStdString(warning).toHtmlEscaped();
    status_->setText(status);
}

void IdentificationFitPage::fitTableToRows() {
    if (parameters_->rowCount() == 0) {
        parameters_->setMinimumHeight(0);
        return;
    }
    int height =
        parameters_->horizontalHeader()->sizeHint().height() + 2 * parameters_->frameWidth();
    for (int row = 0; row < parameters_->rowCount(); ++row) height += parameters_->rowHeight(row);
    // A side panel narrower than the columns shows a horizontal scroll bar under the rows.
    height += parameters_->horizontalScrollBar()->sizeHint().height();
    parameters_->setMinimumHeight(height);
}

}  // namespace terra::ui
