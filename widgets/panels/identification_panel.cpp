#include "widgets/panels/identification_panel.h"

#include <qcustomplot.h>

#include <QCheckBox>
#include <QComboBox>
#include <QCoreApplication>
#include <QDoubleSpinBox>
#include <QFile>
#include <QFileDialog>
#include <QFileInfo>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QLineEdit>
#include <QProgressBar>
#include <QPushButton>
#include <QSignalBlocker>
#include <QSplitter>
#include <QTabWidget>
#include <QTableWidget>
#include <QTimer>
#include <QVBoxLayout>
#include <cmath>
#include <limits>
#include <set>

#include "core/analysis/validation.h"
#include "core/identification/data_set.h"
#include "core/identification/observation_model.h"
#include "core/identification/parameters.h"
#include "core/io/experiment.h"
#include "core/io/parameters_json.h"
#include "core/project/panels.h"
#include "core/project/saved_identification.h"
#include "widgets/document/project_document.h"
#include "widgets/document/suggested_paths.h"
#include "widgets/editors/preset_names.h"
#include "widgets/plots/figures.h"
#include "widgets/plots/number_format.h"

namespace terra::ui {
namespace {

const char* kChannels[] = {"Fx_N", "Fz_N", "My_Nm"};
const char* kChannelSymbols[] = {"F_x [N]", "F_z [N]", "M_y [N·m]"};

io::PresetLocations presetLocations() {
    return io::PresetLocations::standard(QCoreApplication::applicationDirPath().toStdString());
}

QString number(double value, int digits = 4) { return QString::number(value, 'g', digits); }

/// The size of a field's values: what rounding noise is measured against (formatNumber).
double scaleOf(const FieldInfo& field) {
    const double high = std::max(std::abs(field.range.low), std::abs(field.range.high));
    return std::isfinite(high) ? high : 1.0;
}

// Channel names of the data files ("Fx_N") in a text for a person: their symbols, as the tabs
// and the other panels show them.
QString withSymbols(QString text) {
    const std::pair<const char*, const char*> symbols[] = {
        {"Fx_N", "F_x"}, {"Fz_N", "F_z"}, {"My_Nm", "M_y"}, {"sinkage_m", "h"}};
    for (const auto& [name, symbol] : symbols)
        text.replace(QString::fromUtf8(name), QString::fromUtf8(symbol));
    return text;
}

const QString kIdentifiedSuffix = " (identified)";

// The columns data_set.h reads; others are ignored.
const std::set<QString> kKnownColumns = {"slip", "entry_angle_deg", "entry_angle_rad", "Fx_N",
                                         "Fz_N", "My_Nm",           "slip_angle_deg",  "Fy_N",
                                         "W_N",  "sinkage_m",       "time_s"};
constexpr int kPreviewRows = 5;  // data rows of the file shown before a fit

// One CSV line's cells (the data files have no quoted fields; a quote is shown as it is).
QStringList csvCells(const QString& line) {
    QStringList cells = line.split(',');
    for (QString& cell : cells) cell = cell.trimmed();
    return cells;
}

}  // namespace

IdentificationPanel::IdentificationPanel(ProjectDocument* document, QWidget* parent)
    : AnalysisPanel(document, "identification", parent) {
    setLive(false);
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
        makeInteractive(plot, readout_);
        plots_.push_back(plot);
        tabs_->addTab(plot, QString::fromUtf8(channel));
    }
    parameters_ = new QTableWidget(0, 6, this);
    parameters_->setHorizontalHeaderLabels(
        {"Parameter", "Identified", "± std", "Prior", "σ post/prior", "Truth"});
    parameters_->horizontalHeaderItem(4)->setToolTip(
        "Posterior std / prior std: near 1 the data do not see the parameter (the prior decides); "
        "≪ 1 the data determine it");
    parameters_->horizontalHeaderItem(5)->setToolTip(
        "The project soil the synthetic data were made from (none for a CSV)");
    prior_soil_ = new QComboBox(this);
    prior_soil_->addItem("none", QString());
    addPresetItems(prior_soil_, presetLocations(), "soils");  // "sandy loam", data "sandy-loam"
    prior_soil_->setToolTip(
        "Gaussian priors centred on a soil preset: ±0.1 a₀, a₁; ±50 % K_s, c (at least 1 kPa), K; "
        "±0.2 n; ±5° φ (docs/identification.md, Priors)");
    prior_items_ = new QLineEdit(this);
    prior_items_->setPlaceholderText("e.g. phi_deg=30±5, c_kPa=2±1");
    prior_items_->setToolTip(
        "Priors per parameter, mean±std (or +-) in a0, a1, Ks [kPa/m^n], n, c_kPa, phi_deg, K_m; "
        "on top of the soil prior");
    validation_ = new QComboBox(this);
    validation_->addItem("no held-out", "none");
    validation_->addItem("hold-out 20%", "holdout");
    validation_->addItem("5-fold", "folds");
    validation_->setToolTip(
        "Predict samples the fit did not use: the held-out RMS against the noise level");
    loss_ = new QComboBox(this);
    loss_->addItem("least squares", "l2");
    loss_->addItem("Huber loss", "huber");
    loss_->addItem("Cauchy loss", "cauchy");
    loss_->setToolTip(
        "The loss of the fit: least squares, or a robust loss (Huber, Cauchy) that limits the pull "
        "of outliers");
    wheel_ = new QComboBox(this);
    wheel_->setObjectName("identification.wheel");
    wheel_->setToolTip(
        "The wheel the model is fitted with (its r and b enter every force): the data's when a "
        "sidecar JSON beside the CSV names one, else the project's, or a preset");
    wheel_->setSizeAdjustPolicy(QComboBox::AdjustToMinimumContentsLengthWithIcon);
    wheel_->setMinimumContentsLength(14);
    wheel_note_ = new QLabel(this);
    wheel_note_->setObjectName("identification.wheel_note");
    wheel_note_->setWordWrap(true);
    jmax_mode_ = new QComboBox(this);
    jmax_mode_->setObjectName("identification.jmax");
    jmax_mode_->addItem("j_max: auto", "auto");
    jmax_mode_->addItem("j_max: none", "none");
    jmax_mode_->addItem("j_max: fixed", "fixed");
    jmax_mode_->addItem("j_max: fit", "fit");
    jmax_mode_->setToolTip(
        "The shear limit j_max of the model (Eq. 2.16): auto (the project soil's for synthetic "
        "data, none for a CSV), none, fixed at the value beside, or identified as an eighth "
        "parameter (with a prior of 20 ± 20 mm when the data do not determine it)");
    jmax_value_ = new QDoubleSpinBox(this);
    jmax_value_->setObjectName("identification.jmax_value");
    jmax_value_->setRange(0.1, 1000.0);
    jmax_value_->setDecimals(1);
    jmax_value_->setSuffix(" mm");
    jmax_value_->setValue(project::IdentificationPanelSettings{}.jmax_mm);
    jmax_value_->setToolTip("j_max held by 'j_max: fixed' [mm]");
    start_ = new QLabel(this);
    start_->setWordWrap(true);
    // The CSV before a fit: its first rows, what is read of it and what will be fitted.
    preview_box_ = new QGroupBox(this);
    preview_box_->setFlat(true);
    preview_ = new QLabel(preview_box_);
    preview_->setWordWrap(true);
    preview_->setTextInteractionFlags(Qt::TextSelectableByMouse);
    preview_rows_ = new QTableWidget(0, 0, preview_box_);
    preview_rows_->verticalHeader()->setDefaultSectionSize(20);
    preview_rows_->setEditTriggers(QAbstractItemView::NoEditTriggers);
    preview_rows_->setWordWrap(false);
    preview_rows_->horizontalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
    // The header, five rows and a horizontal scroll bar.
    preview_rows_->setMaximumHeight(26 + 20 * kPreviewRows + 22);
    preview_rows_->setToolTip("The first rows of the file as it has them (line numbers at left)");
    auto* preview_layout = new QVBoxLayout(preview_box_);
    preview_layout->addWidget(preview_);
    preview_layout->addWidget(preview_rows_);
    report_ = new QLabel(this);
    report_->setWordWrap(true);
    report_->setTextInteractionFlags(Qt::TextSelectableByMouse);
    report_->setAlignment(Qt::AlignTop | Qt::AlignLeft);
    // Columns as wide as their text, numbers on one line (they wrapped to "0.\n38273" in a
    // narrow side panel); a side panel narrower than the table scrolls it.
    parameters_->horizontalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
    parameters_->horizontalHeader()->setStretchLastSection(true);
    parameters_->setWordWrap(false);
    parameters_->verticalHeader()->hide();
    parameters_->setEditTriggers(QAbstractItemView::NoEditTriggers);
    apply_ = new QPushButton("Apply identified soil to project", this);
    apply_->setToolTip(
        "Replace the project's soil by the identified parameters (a₀, a₁, K_s, n, n₁, c, φ, K); "
        "k_c : k_φ and γ stay the project soil's, and j_max unless the fit held or identified "
        "one. Edit ▸ Undo restores the soil");
    apply_->setEnabled(false);

    auto* fit_page = new QWidget(this);
    auto* bar = new QHBoxLayout;
    bar->addWidget(file_, 1);
    bar->addWidget(browse);
    bar->addWidget(new QLabel("Noise:", this));
    bar->addWidget(noise_);
    bar->addWidget(three_loads_);
    // The fit's options on two rows, so that no row forces a wide window and the prior's text
    // keeps room to be read (one row squeezed it to ~30 px at 1024×700): the method, validation
    // and loss; then the prior.
    auto* options = new QHBoxLayout;
    options->addWidget(refine_);
    options->addWidget(validation_);
    options->addWidget(loss_);
    options->addStretch(1);
    auto* prior_row = new QHBoxLayout;
    prior_row->addWidget(new QLabel("Prior:", this));
    prior_row->addWidget(prior_soil_);
    prior_row->addWidget(prior_items_, 1);
    prior_items_->setMinimumWidth(180);  // "phi_deg=30±5, c_kPa=2±1" readable
    for (QComboBox* combo : {prior_soil_, validation_}) {
        combo->setSizeAdjustPolicy(QComboBox::AdjustToMinimumContentsLengthWithIcon);
        combo->setMinimumContentsLength(12);  // the longest item ("clayey-soil", "hold-out 20%")
    }
    // The wheel and j_max on a row of their own, with the sentence that says which wheel.
    auto* model_row = new QHBoxLayout;
    model_row->addWidget(new QLabel("Wheel:", this));
    model_row->addWidget(wheel_);
    model_row->addWidget(jmax_mode_);
    model_row->addWidget(jmax_value_);
    model_row->addWidget(wheel_note_, 1);
    auto* start_row = new QHBoxLayout;
    start_row->addWidget(start_, 1);
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
    side_tabs_->addTab(preview_box_, "Data preview");
    side_tabs_->setTabVisible(1, false);
    side_layout->addWidget(side_tabs_, 2);
    side_layout->addWidget(apply_);
    side_layout->addWidget(report_, 1);
    auto* splitter = new QSplitter(this);
    splitter->addWidget(tabs_);
    splitter->addWidget(side);
    splitter->setStretchFactor(0, 3);
    splitter->setStretchFactor(1, 2);
    side->setMaximumWidth(560);
    auto* fit_layout = new QVBoxLayout(fit_page);
    fit_layout->setContentsMargins(0, 0, 0, 0);
    fit_layout->addLayout(bar);
    fit_layout->addLayout(options);
    fit_layout->addLayout(model_row);
    fit_layout->addLayout(prior_row);
    fit_layout->addLayout(start_row);
    fit_layout->addWidget(splitter, 1);
    auto* bottom = new QHBoxLayout;
    bottom->addWidget(status_, 1);
    bottom->addWidget(readout_);
    fit_layout->addLayout(bottom);

    auto* stream_page = new QWidget(this);
    buildStreamingPage(stream_page);
    pages_ = new QTabWidget(this);
    pages_->setDocumentMode(true);
    pages_->addTab(fit_page, "Batch fit");
    pages_->addTab(stream_page, "Streaming playback");
    auto* layout = new QVBoxLayout(this);
    layout->setContentsMargins(0, 0, 0, 0);
    layout->addWidget(pages_, 1);

    connect(apply_, &QPushButton::clicked, this, [this] { applyIdentifiedSoil(); });
    connect(browse, &QPushButton::clicked, this, [this] {
        const QString path = QFileDialog::getOpenFileName(
            this, "Load identification data", startFolder(document_->filePath()), "CSV (*.csv)");
        if (!path.isEmpty()) setDataFile(path);
    });
    connect(fit_, &QPushButton::clicked, this, [this] {
        // Prior items are checked before anything runs; a bad one is named, nothing is fitted.
        if (refine_->isChecked()) {
            std::vector<Issue> issues;
            identification::Priors scratch;
            for (const std::string& item :
                 project::splitPriorItems(prior_items_->text().toStdString())) {
                const auto bad = identification::parsePriorItem(item, scratch);
                issues.insert(issues.end(), bad.begin(), bad.end());
            }
            if (!issues.empty()) {
                status_->setText("<b>Error:</b> " +
                                 QString::fromStdString(formatIssues(issues)).toHtmlEscaped());
                return;
            }
        }
        storeSettings();
        recompute();
    });
    for (QComboBox* combo : {prior_soil_, validation_, loss_, wheel_, jmax_mode_}) {
        connect(combo, &QComboBox::currentIndexChanged, this, [this] { updateFitControls(); });
    }
    connect(document_, &ProjectDocument::wheelChanged, this, [this] { updateWheelChoices(); });
    connect(prior_items_, &QLineEdit::textChanged, this, [this] { updateFitControls(); });
    connect(refine_, &QCheckBox::toggled, this, [this] {
        updateFitControls();
        updateDataPreview();  // the full model and the decoupled fit read other columns
    });
    connect(file_, &QLineEdit::textChanged, this, [this] {
        updateWheelChoices();
        updateDataPreview();
    });
    updateWheelChoices();
    connect(cancel_fit_, &QPushButton::clicked, this, [this] {
        status_->setText("Cancelling…");
        cancelRunning();
    });
    connect(this, &AnalysisPanel::busyChanged, this, [this](bool busy) {
        fit_->setEnabled(!busy);
        cancel_fit_->setEnabled(busy);
        if (busy) status_->setText("Fitting…");
    });
    connect(this, &AnalysisPanel::failed, this, [this](const QString& m) {
        fit_->setEnabled(true);
        cancel_fit_->setEnabled(false);
        status_->setText("<b>Error:</b> " + m.toHtmlEscaped());
    });
}

QString IdentificationPanel::startDescription() const {
    if (!refine_->isChecked()) {
        return "Starts from: the thesis's fixed guesses (decoupled three-step fit; no search)";
    }
    QString text = QString("Starts from: global search (%1 design points, and no start needed)")
                       .arg(identification::IdentifyOptions{}.design_points);
    QStringList prior;
    if (prior_soil_->currentIndex() > 0) prior << prior_soil_->currentText() + " preset";
    for (const std::string& item : project::splitPriorItems(prior_items_->text().toStdString()))
        prior << QString::fromStdString(item);
    text += prior.isEmpty() ? QString("; no prior") : "; prior: " + prior.join(" + ");
    text += file_->text().trimmed().isEmpty()
                ? QString("; data synthesised from the project's soil")
                : QString("; the project's soil is not used");
    return text;
}

QString IdentificationPanel::fitStatus() const { return status_->text(); }

QString IdentificationPanel::fitReport() const { return report_->text(); }

void IdentificationPanel::setFitOptions(const QString& prior_soil, const QString& prior_items,
                                        const QString& validation, const QString& loss) {
    const int soil = prior_soil_->findData(prior_soil);
    prior_soil_->setCurrentIndex(prior_soil.isEmpty() || soil < 0 ? 0 : soil);
    prior_items_->setText(prior_items);
    if (const int i = validation_->findData(validation); i >= 0) validation_->setCurrentIndex(i);
    if (const int i = loss_->findData(loss); i >= 0) loss_->setCurrentIndex(i);
    updateFitControls();
}

QString IdentificationPanel::parameterCell(int row, int column) const {
    const QTableWidgetItem* item = parameters_->item(row, column);
    return item != nullptr ? item->text() : QString();
}

QString IdentificationPanel::parameterHeader(int column) const {
    const QTableWidgetItem* item = parameters_->horizontalHeaderItem(column);
    return item != nullptr ? item->text() : QString();
}

std::optional<soil::SoilParameters> IdentificationPanel::identifiedSoil() const {
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

bool IdentificationPanel::applyIdentifiedSoil() {
    const std::optional<soil::SoilParameters> soil = identifiedSoil();
    if (!soil) return false;
    return document_->setSoil(*soil, "", QString("Apply identified soil (%1)").arg(fit_source_));
}

void IdentificationPanel::updateFitControls() {
    const bool global = refine_->isChecked();
    for (QWidget* w :
         std::initializer_list<QWidget*>{prior_soil_, prior_items_, validation_, loss_})
        w->setEnabled(global);
    // Noise and the three loads only apply to synthetic data.
    const bool synthetic = file_->text().trimmed().isEmpty();
    noise_->setEnabled(synthetic);
    three_loads_->setEnabled(synthetic);
    jmax_mode_->setEnabled(global);
    jmax_value_->setEnabled(global && jmax_mode_->currentData().toString() == "fixed");
    start_->setText(startDescription());
    wheel_note_->setText(wheelDescription());
}

void IdentificationPanel::updateWheelChoices() {
    // The data's wheel: named by a sidecar JSON beside the CSV (core/io/experiment.h's
    // metadata, "wheel"); a sidecar that is not one names none.
    data_wheel_.reset();
    data_wheel_source_.clear();
    const QString csv = file_->text().trimmed();
    if (!csv.isEmpty()) {
        const QFileInfo info(csv);
        const QString sidecar = info.absolutePath() + "/" + info.completeBaseName() + ".json";
        QFile file(sidecar);
        if (file.open(QIODevice::ReadOnly)) {
            const Result<io::ExperimentMetadata> metadata =
                io::parseExperimentMetadata(file.readAll().toStdString(), sidecar.toStdString());
            if (metadata && metadata.value().wheel) {
                data_wheel_ = metadata.value().wheel;
                data_wheel_source_ = QFileInfo(sidecar).fileName();
            }
        }
    }
    const QString previous = wheel_->currentData().toString();
    {
        const QSignalBlocker block(wheel_);
        wheel_->clear();
        const QString project = QString::fromStdString(document_->project().wheel.name);
        wheel_->addItem(data_wheel_
                            ? QString("data's: %1").arg(QString::fromStdString(data_wheel_->name))
                            : QString("project's: %1").arg(project),
                        QString());
        wheel_->addItem(QString("project's: %1").arg(project), "project");
        addPresetItems(wheel_, presetLocations(), "wheels");
        const int index = wheel_->findData(previous);
        wheel_->setCurrentIndex(index >= 0 ? index : 0);
    }
    updateFitControls();
}

void IdentificationPanel::setWheelChoice(const QString& choice) {
    const int index = wheel_->findData(choice);
    wheel_->setCurrentIndex(index >= 0 ? index : 0);
    updateFitControls();
}

wheel::WheelParameters IdentificationPanel::chosenWheel() const {
    const QString choice = wheel_->currentData().toString();
    if (choice.isEmpty() && data_wheel_) return *data_wheel_;
    if (choice.isEmpty() || choice == "project") return document_->project().wheel;
    const Result<wheel::WheelParameters> preset =
        io::resolveWheel(presetLocations(), choice.toStdString());
    return preset ? preset.value() : document_->project().wheel;
}

QString IdentificationPanel::wheelDescription() const {
    const wheel::WheelParameters w = chosenWheel();
    QString text = QString("Fitting with %1 (r = %2 m, b = %3 m)")
                       .arg(QString::fromStdString(w.name))
                       .arg(number(w.radius_m))
                       .arg(number(w.width_m));
    const QString choice = wheel_->currentData().toString();
    const bool synthetic = file_->text().trimmed().isEmpty();
    if (choice.isEmpty() && data_wheel_) {
        text += QString(": the data's wheel (%1)").arg(data_wheel_source_);
    } else if (choice.isEmpty()) {
        text += synthetic ? QString(": the project's wheel (the synthetic data are made with it)")
                          : QString(": the project's wheel (the data name no wheel)");
    } else if (choice == "project") {
        text += ": the project's wheel, chosen";
        if (data_wheel_) {
            text += QString(" — <b>not the data's</b> (%1)")
                        .arg(QString::fromStdString(data_wheel_->name).toHtmlEscaped());
        }
    } else {
        text += ": a preset, chosen";
        if (data_wheel_) {
            text += QString(" — <b>not the data's</b> (%1)")
                        .arg(QString::fromStdString(data_wheel_->name).toHtmlEscaped());
        }
    }
    return text + ".";
}

void IdentificationPanel::setShearLimit(const QString& mode, double jmax_mm) {
    if (const int i = jmax_mode_->findData(mode); i >= 0) jmax_mode_->setCurrentIndex(i);
    jmax_value_->setValue(jmax_mm);
    updateFitControls();
}

void IdentificationPanel::setDataFile(const QString& path) {
    file_->setText(path);
    if (!path.isEmpty()) document_->addDataSet(path.toStdString());
}

std::vector<std::pair<QString, QCustomPlot*>> IdentificationPanel::plots() const {
    return {{"identification-Fx", plots_[0]},
            {"identification-Fz", plots_[1]},
            {"identification-My", plots_[2]},
            {"identification-streaming-estimates", stream_plots_[0]},
            {"identification-streaming-detection", stream_plots_[1]}};
}

QCustomPlot* IdentificationPanel::currentPlot() const {
    if (pages_->currentIndex() == 1) return stream_plots_[0];
    return plots_[static_cast<std::size_t>(tabs_->currentIndex())];
}

Table IdentificationPanel::currentTable() const {
    if (pages_->currentIndex() == 0) return result_.curves;
    return analysis::framesTable(stream_frames_);
}

project::IdentificationPanelSettings IdentificationPanel::panelSettings() const {
    project::IdentificationPanelSettings s;
    analysis::IdentificationSettings& fit = s.fit;
    fit.csv = file_->text().toStdString();
    fit.synthetic.noise_percent = noise_->value();
    fit.refine = refine_->isChecked();
    fit.prior_soil_name = prior_soil_->currentData().toString().toStdString();
    fit.prior_items = project::splitPriorItems(prior_items_->text().toStdString());
    const QString validation = validation_->currentData().toString();
    if (validation == "holdout") fit.holdout_fraction = project::kPanelHoldoutFraction;
    if (validation == "folds") fit.folds = project::kPanelFolds;
    fit.loss = analysis::lossFromName(loss_->currentData().toString().toStdString())
                   .value_or(identification::Loss::kSquared);
    s.three_loads = three_loads_->isChecked();
    s.page = pages_->currentIndex() == 1 ? "streaming" : "fit";
    s.stream_csv = stream_source_->currentIndex() == 1 ? stream_file_->text().toStdString() : "";
    s.stream_second_soil = second_soil_->currentData().toString().toStdString();
    s.stream_noise_percent = stream_noise_->value();
    s.stream_speed = speed_->currentData().toDouble();
    s.stream_skip_bad_rows = skip_bad_rows_->isChecked();
    s.wheel = wheel_->currentData().toString().toStdString();
    s.jmax = jmax_mode_->currentData().toString().toStdString();
    s.jmax_mm = jmax_value_->value();
    return s;
}

nlohmann::json IdentificationPanel::settings() const { return project::toJson(panelSettings()); }

void IdentificationPanel::applySettings(const nlohmann::json& json) {
    const auto settings =
        project::panelSettingsFromJson<project::IdentificationPanelSettings>(withChanges(json));
    if (!settings) return;  // projects are checked when opened: only a program error lands here
    const project::IdentificationPanelSettings& s = *settings;
    const analysis::IdentificationSettings& fit = s.fit;
    file_->setText(QString::fromStdString(fit.csv));
    noise_->setValue(fit.synthetic.noise_percent);
    refine_->setChecked(fit.refine);
    three_loads_->setChecked(s.three_loads);
    showPage(s.page == "streaming" ? 1 : 0);
    setStreamSource(QString::fromStdString(s.stream_csv),
                    QString::fromStdString(s.stream_second_soil));
    stream_noise_->setValue(s.stream_noise_percent);
    setStreamSpeed(s.stream_speed);
    skip_bad_rows_->setChecked(s.stream_skip_bad_rows);
    QStringList items;
    for (const std::string& item : fit.prior_items) items << QString::fromStdString(item);
    const QString validation = fit.folds > 0                ? "folds"
                               : fit.holdout_fraction > 0.0 ? "holdout"
                                                            : "none";
    setFitOptions(QString::fromStdString(fit.prior_soil_name), items.join(", "), validation,
                  analysis::lossName(fit.loss));
    setWheelChoice(QString::fromStdString(s.wheel));
    setShearLimit(QString::fromStdString(s.jmax), s.jmax_mm);
}

analysis::IdentificationSettings IdentificationPanel::fitSettings() const {
    const project::IdentificationPanelSettings panel = panelSettings();
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

AnalysisPanel::Job IdentificationPanel::makeJob() {
    analysis::Inputs inputs = project::inputsOf(document_->project());
    inputs.wheel = chosenWheel();  // the wheel the panel states (synthetic data are made on it)
    pending_wheel_ = inputs.wheel;
    pending_jmax_mode_ = refine_->isChecked() ? jmax_mode_->currentData().toString() : "auto";
    analysis::IdentificationSettings settings = fitSettings();
    return [inputs, settings](const std::atomic<bool>& cancel) mutable -> std::any {
        if (!settings.prior_soil_name.empty()) {  // read on the worker, not the GUI thread
            auto soil = io::resolveSoil(presetLocations(), settings.prior_soil_name);
            if (!soil) throw std::invalid_argument("prior: " + soil.message());
            settings.prior_soil = *soil;
        }
        return analysis::computeIdentification(inputs, settings, {&cancel});
    };
}

void IdentificationPanel::present(const std::any& value) {
    result_ = std::any_cast<analysis::IdentificationResult>(value);
    fit_hash_ = presentedInputsHash();
    fit_wheel_ = pending_wheel_;
    fit_jmax_mode_ = pending_jmax_mode_;
    fit_source_ =
        file_->text().isEmpty() ? QString("synthetic") : QFileInfo(file_->text()).fileName();
    apply_->setEnabled(identifiedSoil().has_value());
    if (result_.message.empty()) side_tabs_->setCurrentIndex(0);  // the fit's parameters
    if (result_.cancelled) {
        // As every panel says it (completion.h): cancelled, and what there is of it — nothing.
        status_->setText(
            markedStatus("Fit cancelled before it found a minimum: nothing fitted, "
                         "nothing to apply (Fit runs it again)."));
        report_->clear();
        // The previous fit's curves and table are not this one's: cleared, so that the plots,
        // the table and an export say the same.
        parameters_->setRowCount(0);
        for (QCustomPlot* plot : plots_) {
            plot->clearPlottables();
            plot->replot();
        }
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
    const Table& t = result_.parameters;
    const Project& project = document_->project();
    // The truth column is the project's soil only for data synthesised from it.
    const bool synthetic = file_->text().isEmpty();
    const auto truth = identification::decoupledOf(project.soil, fit_wheel_);
    const identification::IdentificationReport* report =
        result_.report ? &*result_.report : nullptr;
    const auto fields = analysis::identifiedFields();
    parameters_->setRowCount(static_cast<int>(fields.size()));
    for (std::size_t i = 0; i < fields.size(); ++i) {
        const analysis::IdentifiedField& field = fields[i];
        const int row = static_cast<int>(i);
        auto* name = new QTableWidgetItem(QString::fromStdString(field.symbolWithUnit()));
        name->setToolTip(QString::fromUtf8(field.description));
        parameters_->setItem(row, 0, name);
        // The value to the digits its std supports; without one, to 5 digits with rounding
        // noise as 0 (a c at its bound of 0 read "-1.25e-18").
        double sd = 0.0;
        for (std::size_t c = fields.size(); c < t.columns.size(); ++c) {
            if (t.columns[c] == std::string(field.key) + "_std") sd = t.rows[0][c];
        }
        const double value = t.rows[0][i];
        parameters_->setItem(
            row, 1,
            new QTableWidgetItem(std::isinf(value) ? QString("none")  // j_max: no limit
                                 : sd > 0.0        ? formatWithStd(value, sd)
                                                   : formatNumber(value, scaleOf(field), 5)));
        parameters_->setItem(row, 2, new QTableWidgetItem(formatStd(sd)));
        QString prior = "–", ratio = "–";
        if (const auto full = analysis::fullParameterOf(field); report && full) {
            const identification::PriorComparison& c =
                report->prior[static_cast<std::size_t>(*full)];
            if (c.active) {
                // As the user gave it ("12 ± 2"), rounding noise of the unit conversion dropped.
                prior = formatNumber(c.prior_mean / field.to_si, scaleOf(field)) + " ± " +
                        formatNumber(c.prior_std / field.to_si);
                ratio = QString::number(c.std_ratio, 'f', 2);
            }
        }
        parameters_->setItem(row, 3, new QTableWidgetItem(prior));
        parameters_->setItem(row, 4, new QTableWidgetItem(ratio));
        parameters_->setItem(
            row, 5,
            new QTableWidgetItem(!synthetic ? QString("–")
                                 : std::isinf(field.userValue(truth))
                                     ? QString("none")
                                     : formatNumber(field.userValue(truth), scaleOf(field), 5)));
    }
    QStringList lines;
    lines << QString::fromStdString(result_.start_description).toHtmlEscaped();
    if (report) {
        lines << QString("Data: %1.")
                     .arg(withSymbols(QString::fromStdString(report->setup.description)));
        // The Newton decrement gᵀH⁻¹g in a user's words: what one more step would still gain in
        // χ², against the change of 1 that is one σ (the gradient norm stays in the JSON report).
        if (report->newton_decrement < 0.1)
            lines << QString(
                "At a minimum: one more step would lower χ² by less than 0.1 (a "
                "change of 1 is one σ).");
        else
            lines << QString(
                         "Not clearly at a minimum: one more step would still lower χ² by "
                         "%1 (a change of 1 is one σ); fit again, or fix or give priors to "
                         "the parameters the data do not determine.")
                         .arg(number(report->newton_decrement, 2));
        if (report->holdout.computed) {
            QStringList channels;
            for (int c = 0; c < identification::kChannelCount; ++c) {
                const auto k = static_cast<std::size_t>(c);
                if (!report->holdout.channels[k]) continue;
                channels << QString("%1 %2 (%3 σ)")
                                .arg(withSymbols(identification::channelNames()[k]))
                                .arg(number(report->holdout.rms[k], 3))
                                .arg(QString::number(report->holdout.rms_over_noise[k], 'f', 2));
            }
            lines << QString(
                         "Held-out RMS (%1 samples, %2 fold(s)): %3. ≈ 1 σ: the model "
                         "predicts new samples to the noise.")
                         .arg(report->holdout.samples)
                         .arg(report->holdout.folds)
                         .arg(channels.join(", "));
        } else {
            lines << QString("Held-out error: not computed (choose hold out or 5-fold).");
        }
        auto answer = [&fields](const identification::ParameterVector& p) {
            QStringList values;
            for (const char* key : {"phi_deg", "c_kPa", "Ks_kPa", "n0", "K_m"}) {
                const analysis::IdentifiedField& f = *analysis::findIdentifiedField(key);
                const auto full = analysis::fullParameterOf(f);
                values << QString("%1 = %2")
                              .arg(QString::fromUtf8(f.symbol))
                              .arg(formatNumber(p[static_cast<std::size_t>(*full)] / f.to_si,
                                                scaleOf(f)));
            }
            (void)fields;
            return values.join(", ");
        };
        if (report->ambiguity.empty()) {
            lines << QString("Ambiguity: none (no other minimum within Δχ² = %1).")
                         .arg(number(report->ambiguity_delta_chi2, 3));
        } else {
            lines << QString(
                         "<b>Ambiguous</b>: %1 other minimum(s) within Δχ² = %2 — the data "
                         "cannot choose. Best: %3.")
                         .arg(report->ambiguity.size())
                         .arg(number(report->ambiguity_delta_chi2, 3))
                         .arg(answer(report->parameters));
            for (const identification::Minimum& m : report->ambiguity) {
                lines << QString("Other (Δχ² = %1): %2.")
                             .arg(number(m.delta_chi2, 3))
                             .arg(answer(m.parameters));
            }
        }
        if (report->adequacy.flag) {
            lines
                << QString(
                       "<b>Systematic misfit</b> (adequacy p = %1): the residuals follow slip, so "
                       "the estimate is biased and its std too small (the note below says "
                       "where; a shear limit? try j_max: fit).")
                       .arg(number(report->adequacy.p, 2));
        } else {
            lines << QString("Adequacy: the residuals look like noise (smallest p = %1).")
                         .arg(number(report->adequacy.p, 2));
        }
        for (const auto& flag : report->uncertainty.flags)
            lines << QString::fromStdString(flag).toHtmlEscaped();
    }
    report_->setText(lines.join("<br>"));
    QStringList steps;
    for (const auto& step : result_.steps()) {
        steps << QString("%1: Σr² = %2")
                     .arg(QString::fromStdString(step.name))
                     .arg(step.squared_residual_norm, 0, 'g', 4);
    }
    status_->setText(QString("Fit in %1 ms. ").arg(result_.fit_time_ms, 0, 'f', 0) +
                     steps.join(";  "));
}

nlohmann::json IdentificationPanel::resultInputs() const {
    // The data file by its content, not its name: moving the project's folder keeps the result.
    nlohmann::json fit = settings();
    for (const char* other : {"csv", "page", "stream_csv", "stream_second_soil",
                              "stream_noise_percent", "stream_speed", "stream_skip_bad_rows"})
        fit.erase(other);
    const Project& p = document_->project();
    return {{"soil", io::toJson(p.soil)},
            {"wheel", io::toJson(chosenWheel())},
            {"conditions", analysis::toJson(p.conditions)},
            {"fit", fit},
            {"csv", project::fileStamp(file_->text().trimmed().toStdString())}};
}

nlohmann::json IdentificationPanel::streamInputs() const {
    const Project& p = document_->project();
    const analysis::StreamingSettings s = streamSettings();
    return {{"soil", io::toJson(p.soil)},
            {"wheel", io::toJson(p.wheel)},
            {"conditions", analysis::toJson(p.conditions)},
            {"skip_bad_rows", s.skip_bad_rows},
            {"second_soil", s.second_soil},
            {"noise_percent", s.noise_percent},
            {"csv_stamp", project::fileStamp(s.csv)}};
}

std::map<std::string, project::SavedResult> IdentificationPanel::savedResults() const {
    std::map<std::string, project::SavedResult> out;
    if (hasResult() && !fit_hash_.empty() && result_.message.empty()) {
        project::SavedResult& saved = out[name().toStdString()];
        saved.inputs_hash = fit_hash_;
        saved.version = project::kIdentificationVersion;
        saved.partial = completion() != Completion::kComplete;
        saved.summary = QString("%1 samples, fitted in %2 ms")
                            .arg(result_.data.samples.size())
                            .arg(result_.fit_time_ms, 0, 'f', 0)
                            .toStdString();
        // The curves and parameters are tables of the result already: not written twice.
        saved.result = project::savedJson(result_);
    }
    // A playback that ended (finished or stopped), not one going on.
    if (!playback_->isActive() && !stream_frames_.empty() && !stream_hash_.empty()) {
        project::SavedResult& saved = out[name().toStdString() + ".streaming"];
        saved.inputs_hash = stream_hash_;
        saved.version = project::kStreamingVersion;
        saved.partial = stream_stopped_;
        saved.summary = QString("%1 of %2 samples played")
                            .arg(stream_frames_.size())
                            .arg(stream_count_)
                            .toStdString();
        project::SavedStream stream;
        stream.frames = stream_frames_;
        stream.sample_count = stream_count_;
        stream.true_border = stream_border_;
        stream.description = stream_description_.toStdString();
        for (const QString& w : stream_warnings_) stream.warnings.push_back(w.toStdString());
        stream.truth = stream_truth_;
        stream.stopped = stream_stopped_;
        saved.result = project::savedJson(stream);
        saved.tables.push_back({"frames", std::nullopt, analysis::framesTable(stream_frames_)});
    }
    return out;
}

AnalysisPanel::Restored IdentificationPanel::restoreResult(const std::string& section,
                                                           const project::SavedResult& saved) {
    if (section == name().toStdString() + ".streaming") {
        if (saved.version != project::kStreamingVersion)
            return unreadable("saved in form version " + std::to_string(saved.version));
        if (saved.inputs_hash != project::inputsHash(streamInputs())) return inputsChanged();
        if (playback_->isActive()) return unreadable("a playback is going on");
        Result<project::SavedStream> read = project::savedStreamFromJson(saved.result, section);
        if (!read) return unreadable(read.message());
        project::SavedStream stream = std::move(read).value();
        stream_count_ = stream.sample_count;
        stream_border_ = stream.true_border;
        stream_description_ = QString::fromStdString(stream.description);
        stream_warnings_.clear();
        for (const std::string& w : stream.warnings) stream_warnings_ << QString::fromStdString(w);
        stream_truth_ = std::move(stream.truth);
        stream_stopped_ = stream.stopped;
        stream_hash_ = saved.inputs_hash;
        resetStreamFigures(stream_count_);
        stream_frames_ = std::move(stream.frames);
        stream_figures_->append(stream_frames_);
        stream_figures_->setCompletion(stream_stopped_ ? Completion::kCancelled
                                                       : Completion::kComplete);
        stream_figures_->replot();
        updatePosition();
        stream_status_->setText("Saved with the project (not played again): " +
                                streamSummary(!stream_stopped_));
        return restoredShown();
    }
    if (section != name().toStdString()) return unreadable("not a section of this panel");
    if (saved.version != project::kIdentificationVersion)
        return unreadable("saved in form version " + std::to_string(saved.version));
    if (saved.inputs_hash != inputsHash()) return inputsChanged();
    Result<analysis::IdentificationResult> read =
        project::identificationResultFromJson(saved.result, section);
    if (!read) return unreadable(read.message());
    // The fit's wheel and j_max mode are the ones the controls give now: the inputs hash the same.
    pending_wheel_ = chosenWheel();
    pending_jmax_mode_ = refine_->isChecked() ? jmax_mode_->currentData().toString() : "auto";
    showSaved(std::move(read).value(), saved.inputs_hash, saved.partial);
    status_->setText(
        markedStatus(QString("Saved with the project (%1); not fitted again — Fit runs it again.")
                         .arg(QString::fromStdString(saved.summary).toHtmlEscaped())));
    return restoredShown();
}

// --- Streaming playback -------------------------------------------------------------------------

IdentificationPanel::~IdentificationPanel() {
    delete playback_;  // stops the run and joins its worker before the figures go
    playback_ = nullptr;
}

void IdentificationPanel::buildStreamingPage(QWidget* page) {
    stream_source_ = new QComboBox(page);
    stream_source_->addItem("Synthetic: project soil, then");
    stream_source_->addItem("CSV file");
    stream_source_->setToolTip(
        "A synthetic drive over a soil border (the true border is drawn as a grey dashed line), "
        "or a recorded CSV (slip, entry_angle_deg, Fx_N, Fz_N, My_Nm; time_s for pacing)");
    second_soil_ = new QComboBox(page);
    addPresetItems(second_soil_, presetLocations(), "soils");
    if (const int i = second_soil_->findData("clayey-soil"); i >= 0)
        second_soil_->setCurrentIndex(i);
    second_soil_->setToolTip("The soil the synthetic drive crosses into");
    stream_noise_ = new QDoubleSpinBox(page);
    stream_noise_->setRange(0.0, 20.0);
    stream_noise_->setSuffix(" % noise");
    stream_noise_->setValue(project::IdentificationPanelSettings{}.stream_noise_percent);
    stream_noise_->setToolTip(
        "Synthetic noise σ as a percentage of each channel's largest value (Eq. 5.1)");
    stream_file_ = new QLineEdit(page);
    stream_file_->setPlaceholderText("CSV to play");
    stream_browse_ = new QPushButton("Choose CSV…", page);
    skip_bad_rows_ = new QCheckBox("Skip bad rows", page);
    skip_bad_rows_->setToolTip(
        "Off: a bad row stops the playback before it starts, with its line number");
    speed_ = new QComboBox(page);
    speed_->addItem("0.1×", 0.1);
    speed_->addItem("1× (real time)", 1.0);
    speed_->addItem("10×", 10.0);
    speed_->addItem("max", 0.0);
    speed_->setCurrentIndex(1);
    speed_->setToolTip(
        "Sample time per wall time (samples' time_s, else 100 Hz); max: as fast as the identifier "
        "runs");
    play_ = new QPushButton("▶ Play", page);
    pause_ = new QPushButton("❚❚ Pause", page);
    stop_ = new QPushButton("■ Stop", page);
    position_ = new QProgressBar(page);
    position_->setRange(0, 1);
    position_->setValue(0);
    position_->setFormat("no run yet");
    position_text_ = new QLabel(page);
    stream_status_ = new QLabel(page);
    stream_status_->setWordWrap(true);
    stream_status_->setTextInteractionFlags(Qt::TextSelectableByMouse);
    for (int i = 0; i < 2; ++i) stream_plots_.push_back(new QCustomPlot(page));
    stream_figures_ = std::make_unique<StreamingFigures>(stream_plots_[0], stream_plots_[1]);
    playback_ = new StreamingPlayback(this);
    replot_timer_ = new QTimer(this);
    replot_timer_->setSingleShot(true);
    replot_timer_->setInterval(40);

    // The source on two rows (one made the page scroll sideways at 1024×700): what is played,
    // then the CSV's file.
    auto* source_row = new QHBoxLayout;
    source_row->addWidget(new QLabel("Source:", page));
    source_row->addWidget(stream_source_);
    source_row->addWidget(second_soil_);
    source_row->addWidget(stream_noise_);
    source_row->addStretch(1);
    auto* file_row = new QHBoxLayout;
    file_row->addWidget(stream_file_, 1);
    file_row->addWidget(stream_browse_);
    file_row->addWidget(skip_bad_rows_);
    stream_file_->setMinimumWidth(180);
    auto* play_row = new QHBoxLayout;
    play_row->addWidget(new QLabel("Speed:", page));
    play_row->addWidget(speed_);
    play_row->addWidget(play_);
    play_row->addWidget(pause_);
    play_row->addWidget(stop_);
    play_row->addWidget(position_, 1);
    auto* splitter = new QSplitter(page);
    splitter->addWidget(stream_plots_[0]);
    splitter->addWidget(stream_plots_[1]);
    splitter->setStretchFactor(0, 1);
    splitter->setStretchFactor(1, 1);
    splitter->setSizes({600, 600});  // half and half (a QCustomPlot has no size hint to share by)
    auto* layout = new QVBoxLayout(page);
    layout->setContentsMargins(0, 0, 0, 0);
    layout->addLayout(source_row);
    layout->addLayout(file_row);
    layout->addLayout(play_row);
    // On a line of its own: beside the controls it made the page 786 px wide (1024 px screens).
    layout->addWidget(position_text_);
    layout->addWidget(splitter, 1);
    layout->addWidget(stream_status_);
    stream_status_->setText(
        "Press Play: the samples are fed one at a time through the streaming estimator on the "
        "full model (moving horizon of 5 with an arrival cost; shaded: ±σ). A change of soil is "
        "an alarm of the CUSUM of normalised innovations (above h = ln 10⁶) confirmed by a "
        "likelihood-ratio refit; a change of load or slip alone is none.");

    connect(stream_source_, &QComboBox::currentIndexChanged, this,
            [this] { updateStreamControls(); });
    connect(stream_browse_, &QPushButton::clicked, this, [this] {
        const QString path = QFileDialog::getOpenFileName(
            this, "Play identification data", startFolder(document_->filePath()), "CSV (*.csv)");
        if (!path.isEmpty()) setStreamSource(path);
    });
    connect(speed_, &QComboBox::currentIndexChanged, this, [this] {
        playback_->setSpeed(speed_->currentData().toDouble());
        updatePosition();
    });
    connect(play_, &QPushButton::clicked, this, &IdentificationPanel::play);
    connect(pause_, &QPushButton::clicked, this, &IdentificationPanel::pausePlayback);
    connect(stop_, &QPushButton::clicked, this, &IdentificationPanel::stopPlayback);
    connect(replot_timer_, &QTimer::timeout, this, [this] {
        updatePosition();
        stream_figures_->replot();
    });
    connect(playback_, &StreamingPlayback::sourceReady, this,
            [this](const StreamSource& source, std::size_t count) {
                stream_count_ = count;
                stream_border_ = source.true_border;
                stream_description_ = QString::fromStdString(source.description);
                stream_warnings_.clear();
                for (const auto& w : source.warnings) stream_warnings_ << QString::fromStdString(w);
                stream_truth_ = source.truth;
                stream_hash_ = pending_stream_hash_;
                stream_stopped_ = false;
                resetStreamFigures(count);
                stream_figures_->replot();
                updatePosition();
            });
    connect(playback_, &StreamingPlayback::framesReady, this, &IdentificationPanel::showFrames);
    connect(playback_, &StreamingPlayback::stateChanged, this,
            &IdentificationPanel::playbackStateChanged);
    connect(playback_, &StreamingPlayback::failed, this, [this](const QString& message) {
        stream_status_->setText("<b>Error:</b> " + message.toHtmlEscaped().replace("\n", "<br>"));
        // The data could not be read or played: say so where "preparing…" was.
        position_->setRange(0, 1);
        position_->setValue(0);
        position_->setFormat("failed: see the message below");
    });
    updateStreamControls();
}

void IdentificationPanel::showPage(int page) { pages_->setCurrentIndex(page == 1 ? 1 : 0); }

void IdentificationPanel::setStreamSource(const QString& csv_path, const QString& second_soil) {
    stream_file_->setText(csv_path);
    stream_source_->setCurrentIndex(csv_path.isEmpty() ? 0 : 1);
    if (const int i = second_soil_->findData(second_soil); i >= 0) second_soil_->setCurrentIndex(i);
    updateStreamControls();
}

void IdentificationPanel::setStreamSpeed(double speed) {
    int best = 0;
    for (int i = 0; i < speed_->count(); ++i) {
        if (std::abs(speed_->itemData(i).toDouble() - speed) <
            std::abs(speed_->itemData(best).toDouble() - speed))
            best = i;
    }
    speed_->setCurrentIndex(best);
}

void IdentificationPanel::requestRun() {
    if (pages_->currentIndex() == 1) {
        if (play_->isEnabled()) play();
    } else if (fit_->isEnabled()) {
        fit_->click();
    }
}

void IdentificationPanel::play() {
    if (playback_->state() == StreamingPlayback::State::kPaused) {
        playback_->resume();
        return;
    }
    const Project& project = document_->project();
    analysis::StreamingSettings settings = streamSettings();
    if (stream_source_->currentIndex() == 1 && settings.csv.empty()) {
        stream_status_->setText("<b>Error:</b> choose a CSV file to play");
        return;
    }
    const analysis::Inputs inputs = project::inputsOf(project);
    // Reading or synthesising runs on the worker, not on the GUI thread.
    StreamingPlayback::SourceFactory factory = [inputs, settings]() mutable {
        if (settings.csv.empty()) {
            auto soil = io::resolveSoil(presetLocations(), settings.second_soil);
            if (!soil) throw std::invalid_argument("second soil: " + soil.message());
            settings.second = *soil;
        }
        return analysis::streamSource(inputs, settings);
    };
    // A running playback ends first (its "stopped" state is handled now, not after the new run's
    // figures were cleared).
    if (playback_->isActive()) playback_->stop();
    storeSettings();
    pending_stream_hash_ = project::inputsHash(streamInputs());
    stream_hash_.clear();  // nothing of a run is saved until its data are ready
    stream_frames_.clear();
    stream_count_ = 0;
    stream_border_.reset();
    stream_figures_->reset("Estimates: preparing the data…", 0, std::nullopt,
                           identification::StreamingEstimatorOptions{}.change_threshold);
    stream_figures_->replot();
    position_->setRange(0, 1);
    position_->setValue(0);
    position_->setFormat("preparing…");
    stream_status_->setText("Playing…");
    playback_->start(std::move(factory), project.wheel,
                     analysis::streamingOptions(inputs, settings),
                     speed_->currentData().toDouble());
}

analysis::StreamingSettings IdentificationPanel::streamSettings() const {
    analysis::StreamingSettings settings;
    if (stream_source_->currentIndex() == 1) {
        settings.csv = stream_file_->text().trimmed().toStdString();
        settings.skip_bad_rows = skip_bad_rows_->isChecked();
    }
    settings.second_soil = second_soil_->currentData().toString().toStdString();
    settings.noise_percent = stream_noise_->value();
    return settings;
}

void IdentificationPanel::pausePlayback() { playback_->pause(); }

void IdentificationPanel::stopPlayback() { playback_->stop(); }

void IdentificationPanel::showFrames(const std::vector<StreamFrame>& frames) {
    stream_frames_.insert(stream_frames_.end(), frames.begin(), frames.end());
    stream_figures_->append(frames);
    // Drawing is the GUI thread's only real work here: at most one replot per 40 ms however
    // fast the frames come.
    if (!replot_timer_->isActive()) replot_timer_->start();
}

QString IdentificationPanel::streamStatus() const { return stream_status_->text(); }

void IdentificationPanel::updatePosition() {
    position_->setValue(static_cast<int>(stream_frames_.size()));
    if (stream_frames_.empty()) {
        position_text_->setText(stream_count_ > 0 ? QString("%1 samples").arg(stream_count_)
                                                  : QString());
        return;
    }
    const StreamFrame& f = stream_frames_.back();
    position_text_->setText(QString("sample %1 · t = %2 s · NIS %3 · CUSUM %4")
                                .arg(f.estimate.index)
                                .arg(f.time_s, 0, 'f', 2)
                                .arg(f.estimate.nis, 0, 'f', 1)
                                .arg(f.estimate.cusum, 0, 'f', 1));
}

void IdentificationPanel::updateStreamControls() {
    const bool csv = stream_source_->currentIndex() == 1;
    second_soil_->setVisible(!csv);
    stream_noise_->setVisible(!csv);
    stream_file_->setVisible(csv);
    stream_browse_->setVisible(csv);
    skip_bad_rows_->setVisible(csv);
    const auto state = playback_->state();
    const bool active = playback_->isActive();
    play_->setEnabled(state != StreamingPlayback::State::kPlaying);
    play_->setText(state == StreamingPlayback::State::kPaused ? "▶ Resume" : "▶ Play");
    pause_->setEnabled(state == StreamingPlayback::State::kPlaying);
    stop_->setEnabled(active);
    stream_source_->setEnabled(!active);
    second_soil_->setEnabled(!active);
    stream_noise_->setEnabled(!active);
    stream_file_->setEnabled(!active);
    stream_browse_->setEnabled(!active);
    skip_bad_rows_->setEnabled(!active);
}

void IdentificationPanel::playbackStateChanged(StreamingPlayback::State state) {
    using State = StreamingPlayback::State;
    updateStreamControls();
    if (state == State::kPlaying || state == State::kPaused) {
        if (state == State::kPaused)
            stream_status_->setText("Paused: Resume goes on from the next sample.");
        else if (!stream_frames_.empty())
            stream_status_->setText("Playing…");
        return;
    }
    replot_timer_->stop();
    updatePosition();
    stream_figures_->replot();
    if (state == State::kFailed || state == State::kIdle) {
        emit playbackEnded(state);
        return;
    }
    stream_stopped_ = state != State::kFinished;
    stream_figures_->setCompletion(stream_stopped_ ? Completion::kCancelled
                                                   : Completion::kComplete);
    stream_figures_->replot();
    stream_status_->setText(streamSummary(state == State::kFinished));
    emit playbackEnded(state);
}

void IdentificationPanel::resetStreamFigures(std::size_t count) {
    stream_frames_.clear();
    stream_frames_.reserve(count);
    stream_figures_->reset(
        stream_truth_.empty() ? QString("Estimates") : QString("Estimates (dotted: truth)"), count,
        stream_border_, identification::StreamingEstimatorOptions{}.change_threshold);
    stream_figures_->setTruth(stream_truth_);
    position_->setRange(0, static_cast<int>(count));
    position_->setValue(0);
    position_->setFormat("%v / %m samples");
}

QString IdentificationPanel::streamSummary(bool finished) const {
    QStringList changes;
    for (std::size_t c : stream_figures_->changePoints()) changes << QString::number(c);
    // A stopped playback is marked as every panel marks a cancelled run (completion.h).
    QString text = finished ? QString("Finished: %1 samples").arg(stream_frames_.size())
                            : QString("<b>%1</b> — stopped after %2 of %3 samples")
                                  .arg(completionMark(Completion::kCancelled))
                                  .arg(stream_frames_.size())
                                  .arg(stream_count_);
    if (!stream_description_.isEmpty())
        text += QString(" (%1)").arg(stream_description_.toHtmlEscaped());
    text += changes.isEmpty() ? QString("; no change of soil detected")
                              : QString("; change of soil at sample %1").arg(changes.join(", "));
    if (stream_border_) text += QString(" (true border: %1)").arg(*stream_border_);
    if (!stream_frames_.empty() && stream_frames_.back().estimate.estimated) {
        const auto& p = stream_frames_.back().parameters;
        QStringList values;
        for (const char* key : {"phi_deg", "c_kPa", "K_m"}) {
            const analysis::IdentifiedField& f = *analysis::findIdentifiedField(key);
            const auto full = analysis::fullParameterOf(f);
            // Rounded to the std's second digit, as the batch fit's table (no "5.72e-18 ± 0.4").
            const double sd =
                stream_frames_.back().estimate.std[static_cast<std::size_t>(*full)] / f.to_si;
            values << QString("%1 = %2 ± %3 %4")
                          .arg(QString::fromUtf8(f.symbol))
                          .arg(formatWithStd(f.userValue(p), sd))
                          .arg(formatStd(sd))
                          .arg(QString::fromStdString(f.displayUnit()));
        }
        text += ". Last estimate ± std: " + values.join(", ");
    }
    if (!stream_warnings_.isEmpty()) {
        text += QString(". %1 warning(s): %2")
                    .arg(stream_warnings_.size())
                    .arg(stream_warnings_.mid(0, 3).join("; ").toHtmlEscaped());
    }
    return text;
}

}  // namespace terra::ui

namespace terra::ui {

QString IdentificationPanel::dataPreview() const {
    return side_tabs_->isTabVisible(1) ? preview_->text() : QString();
}

QString IdentificationPanel::dataPreviewCell(int row, int column) const {
    const QTableWidgetItem* item = preview_rows_->item(row, column);
    return item != nullptr ? item->text() : QString();
}

QString IdentificationPanel::dataPreviewHeader(int column) const {
    const QTableWidgetItem* item = preview_rows_->horizontalHeaderItem(column);
    return item != nullptr ? item->text() : QString();
}

void IdentificationPanel::updateDataPreview() {
    const QString path = file_->text().trimmed();
    preview_rows_->clear();
    preview_rows_->setRowCount(0);
    preview_rows_->setColumnCount(0);
    if (path.isEmpty()) {
        side_tabs_->setTabVisible(1, false);
        return;
    }
    side_tabs_->setTabVisible(1, true);
    side_tabs_->setCurrentIndex(1);
    preview_box_->setTitle(QFileInfo(path).fileName());
    QFile file(path);
    if (!QFileInfo(path).isFile() || !file.open(QIODevice::ReadOnly | QIODevice::Text)) {
        preview_->setText("No such file: " + path);
        return;
    }
    // The first rows as the file has them, with their line numbers.
    QStringList header;
    int line_number = 0;
    while (!file.atEnd() && preview_rows_->rowCount() < kPreviewRows) {
        const QString line = QString::fromUtf8(file.readLine()).trimmed();
        ++line_number;
        if (line_number == 1) {
            header = csvCells(line);
            preview_rows_->setColumnCount(static_cast<int>(header.size()));
            preview_rows_->setHorizontalHeaderLabels(header);
            continue;
        }
        if (line.isEmpty()) continue;
        const int row = preview_rows_->rowCount();
        preview_rows_->insertRow(row);
        preview_rows_->setVerticalHeaderItem(row,
                                             new QTableWidgetItem(QString::number(line_number)));
        const QStringList cells = csvCells(line);
        for (int c = 0; c < std::min<int>(static_cast<int>(cells.size()), header.size()); ++c)
            preview_rows_->setItem(row, c, new QTableWidgetItem(cells[c]));
    }
    QStringList known, ignored;
    for (const QString& column : header)
        (kKnownColumns.contains(column) ? known : ignored) << column;
    QStringList lines;
    lines << "Columns: " +
                 (known.isEmpty() ? QString("none of the data columns") : known.join(", ")) +
                 (ignored.isEmpty() ? QString() : " (ignored: " + ignored.join(", ") + ")");
    // Read as the fit reads it (the same columns needed), every bad row listed: the fit itself
    // refuses a file with bad rows.
    const bool full_model = refine_->isChecked();
    const auto needs = full_model ? identification::ColumnNeeds::kFullModel
                                  : identification::ColumnNeeds::kDecoupled;
    auto read =
        identification::readDataSet(path.toStdString(), identification::BadRows::kSkip, needs);
    if (!read) {
        lines << "Cannot be fitted: " + withSymbols(QString::fromStdString(read.message()));
        preview_->setText(lines.join("\n"));
        return;
    }
    const std::size_t good = read->data.samples.size(), bad = read->skipped.size();
    lines << QString("Rows: %1 read%2").arg(good).arg(bad ? QString(", %1 bad").arg(bad) : "");
    for (const Issue& issue : read->skipped) {
        const QString where = QString::fromStdString(issue.where);
        const QString line = where.section(':', -1);  // "data.csv:6" → "6"
        lines << QString("  line %1: %2").arg(line, QString::fromStdString(issue.message));
    }
    if (bad > 0) lines << "Fit refuses the file until the bad rows are fixed or removed.";
    if (full_model) {
        const auto setup =
            identification::setupModel(read->data, identification::DataSource::kAuto, std::nullopt,
                                       std::numeric_limits<double>::infinity());
        if (!setup) {
            lines << "Cannot be fitted: " + withSymbols(QString::fromStdString(setup.message()));
        } else {
            QStringList fitted;
            for (int c = 0; c < identification::kChannelCount; ++c) {
                if (setup->channels[static_cast<std::size_t>(c)])
                    fitted << withSymbols(QString::fromUtf8(identification::channelNames()[c]));
            }
            lines << QString("Fits: %1 (%2)")
                         .arg(fitted.join(", "),
                              setup->source == identification::DataSource::kEntryAngle
                                  ? "entry angle measured"
                                  : "entry angle solved from the load");
        }
    } else {
        lines << "Fits: " + withSymbols("Fx_N, Fz_N, My_Nm") +
                     " (decoupled fit: entry angle measured)";
    }
    preview_->setText(lines.join("\n"));
}

}  // namespace terra::ui
