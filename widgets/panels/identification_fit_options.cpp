#include "widgets/panels/identification_fit_options.h"

#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFile>
#include <QFileInfo>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QSignalBlocker>

#include "core/analysis/identification.h"
#include "core/io/experiment.h"
#include "core/io/parameters_json.h"
#include "widgets/document/project_document.h"
#include "widgets/editors/preset_names.h"

namespace terra::ui {
namespace {

QString wheelNumber(double value) { return QString::number(value, 'g', 4); }

}  // namespace

IdentificationFitOptions::IdentificationFitOptions(ProjectDocument* document, QCheckBox* full_model,
                                                   QWidget* page)
    : QObject(page), document_(document), refine_(full_model) {
    prior_soil_ = new QComboBox(page);
    prior_soil_->addItem("none", QString());
    addPresetItems(prior_soil_, studioPresetLocations(),
                   "soils");  // "sandy loam", data "sandy-loam"
    prior_soil_->setToolTip(
        "Gaussian priors centred on a soil preset: ±0.1 a₀, a₁; ±50 % K_s, c (at least 1 kPa), K; "
        "±0.2 n; ±5° φ (docs/identification.md, Priors)");
    prior_items_ = new QLineEdit(page);
    prior_items_->setPlaceholderText("e.g. phi_deg=30±5, c_kPa=2±1");
    prior_items_->setToolTip(
        "Priors per parameter, mean±std (or +-) in a0, a1, Ks [kPa/m^n], n, c_kPa, phi_deg, K_m; "
        "on top of the soil prior");
    validation_ = new QComboBox(page);
    validation_->addItem("no held-out", "none");
    validation_->addItem("hold-out 20%", "holdout");
    validation_->addItem("5-fold", "folds");
    validation_->setToolTip(
        "Predict samples the fit did not use: the held-out RMS against the noise level");
    loss_ = new QComboBox(page);
    loss_->addItem("least squares", "l2");
    loss_->addItem("Huber loss", "huber");
    loss_->addItem("Cauchy loss", "cauchy");
    loss_->setToolTip(
        "The loss of the fit: least squares, or a robust loss (Huber, Cauchy) that limits the pull "
        "of outliers");
    wheel_ = new QComboBox(page);
    wheel_->setObjectName("identification.wheel");
    wheel_->setToolTip(
        "The wheel the model is fitted with (its r and b enter every force): the data's when a "
        "sidecar JSON beside the CSV names one, else the project's, or a preset");
    wheel_->setSizeAdjustPolicy(QComboBox::AdjustToMinimumContentsLengthWithIcon);
    wheel_->setMinimumContentsLength(14);
    wheel_note_ = new QLabel(page);
    wheel_note_->setObjectName("identification.wheel_note");
    wheel_note_->setWordWrap(true);
    jmax_mode_ = new QComboBox(page);
    jmax_mode_->setObjectName("identification.jmax");
    jmax_mode_->addItem("j_max: auto", "auto");
    jmax_mode_->addItem("j_max: none", "none");
    jmax_mode_->addItem("j_max: fixed", "fixed");
    jmax_mode_->addItem("j_max: fit", "fit");
    jmax_mode_->setToolTip(
        "The shear limit j_max of the model (Eq. 2.16): auto (the project soil's for synthetic "
        "data, none for a CSV), none, fixed at the value beside, or identified as an eighth "
        "parameter (with a prior of 20 ± 20 mm when the data do not determine it)");
    jmax_value_ = new QDoubleSpinBox(page);
    jmax_value_->setObjectName("identification.jmax_value");
    jmax_value_->setRange(0.1, 1000.0);
    jmax_value_->setDecimals(1);
    jmax_value_->setSuffix(" mm");
    jmax_value_->setValue(project::IdentificationPanelSettings{}.jmax_mm);
    jmax_value_->setToolTip("j_max held by 'j_max: fixed' [mm]");
    start_ = new QLabel(page);
    start_->setWordWrap(true);
    // The fit's options on two rows, so that no row forces a wide window and the prior's text
    // keeps room to be read (one row squeezed it to ~30 px at 1024×700): the method, validation
    // and loss; then the prior.
    method_row_ = new QHBoxLayout;
    method_row_->addWidget(refine_);
    method_row_->addWidget(validation_);
    method_row_->addWidget(loss_);
    method_row_->addStretch(1);
    prior_row_ = new QHBoxLayout;
    prior_row_->addWidget(new QLabel("Prior:", page));
    prior_row_->addWidget(prior_soil_);
    prior_row_->addWidget(prior_items_, 1);
    prior_items_->setMinimumWidth(180);  // "phi_deg=30±5, c_kPa=2±1" readable
    for (QComboBox* combo : {prior_soil_, validation_}) {
        combo->setSizeAdjustPolicy(QComboBox::AdjustToMinimumContentsLengthWithIcon);
        combo->setMinimumContentsLength(12);  // the longest item ("clayey-soil", "hold-out 20%")
    }
    // The wheel and j_max on a row of their own, with the sentence that says which wheel.
    model_row_ = new QHBoxLayout;
    model_row_->addWidget(new QLabel("Wheel:", page));
    model_row_->addWidget(wheel_);
    model_row_->addWidget(jmax_mode_);
    model_row_->addWidget(jmax_value_);
    model_row_->addWidget(wheel_note_, 1);

    for (QComboBox* combo : {prior_soil_, validation_, loss_, wheel_, jmax_mode_}) {
        connect(combo, &QComboBox::currentIndexChanged, this, [this] { updateControls(); });
    }
    connect(document_, &ProjectDocument::wheelChanged, this, [this] { updateWheelChoices(); });
    connect(prior_items_, &QLineEdit::textChanged, this, [this] { updateControls(); });
    connect(refine_, &QCheckBox::toggled, this, [this] { updateControls(); });
    updateWheelChoices();
}

bool IdentificationFitOptions::fullModel() const { return refine_->isChecked(); }

void IdentificationFitOptions::setDataFile(const QString& csv) {
    csv_ = csv.trimmed();
    updateWheelChoices();
}

void IdentificationFitOptions::writeSettings(project::IdentificationPanelSettings& s) const {
    analysis::IdentificationSettings& fit = s.fit;
    fit.refine = refine_->isChecked();
    fit.prior_soil_name = prior_soil_->currentData().toString().toStdString();
    fit.prior_items = project::splitPriorItems(prior_items_->text().toStdString());
    const QString validation = validation_->currentData().toString();
    if (validation == "holdout") fit.holdout_fraction = project::kPanelHoldoutFraction;
    if (validation == "folds") fit.folds = project::kPanelFolds;
    fit.loss = analysis::lossFromName(loss_->currentData().toString().toStdString())
                   .value_or(identification::Loss::kSquared);
    s.wheel = wheel_->currentData().toString().toStdString();
    s.jmax = jmax_mode_->currentData().toString().toStdString();
    s.jmax_mm = jmax_value_->value();
}

void IdentificationFitOptions::applySettings(const project::IdentificationPanelSettings& s) {
    const analysis::IdentificationSettings& fit = s.fit;
    refine_->setChecked(fit.refine);
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

QString IdentificationFitOptions::jmaxMode() const {
    return refine_->isChecked() ? jmax_mode_->currentData().toString() : QString("auto");
}

std::vector<Issue> IdentificationFitOptions::priorIssues() const {
    std::vector<Issue> issues;
    if (!refine_->isChecked()) return issues;
    identification::Priors scratch;
    for (const std::string& item : project::splitPriorItems(prior_items_->text().toStdString())) {
        const auto bad = identification::parsePriorItem(item, scratch);
        issues.insert(issues.end(), bad.begin(), bad.end());
    }
    return issues;
}

void IdentificationFitOptions::updateControls() {
    const bool global = refine_->isChecked();
    for (QWidget* w :
         std::initializer_list<QWidget*>{prior_soil_, prior_items_, validation_, loss_})
        w->setEnabled(global);
    jmax_mode_->setEnabled(global);
    jmax_value_->setEnabled(global && jmax_mode_->currentData().toString() == "fixed");
    start_->setText(startDescription());
    wheel_note_->setText(wheelDescription());
}

QString IdentificationFitOptions::startDescription() const {
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
    text += csv_.isEmpty() ? QString("; data synthesised from the project's soil")
                           : QString("; the project's soil is not used");
    return text;
}

void IdentificationFitOptions::setFitOptions(const QString& prior_soil, const QString& prior_items,
                                             const QString& validation, const QString& loss) {
    const int soil = prior_soil_->findData(prior_soil);
    prior_soil_->setCurrentIndex(prior_soil.isEmpty() || soil < 0 ? 0 : soil);
    prior_items_->setText(prior_items);
    if (const int i = validation_->findData(validation); i >= 0) validation_->setCurrentIndex(i);
    if (const int i = loss_->findData(loss); i >= 0) loss_->setCurrentIndex(i);
    updateControls();
}

void IdentificationFitOptions::updateWheelChoices() {
    // The data's wheel: named by a sidecar JSON beside the CSV (core/io/experiment.h's
    // metadata, "wheel"); a sidecar that is not one names none.
    data_wheel_.reset();
    data_wheel_source_.clear();
    if (!csv_.isEmpty()) {
        const QFileInfo info(csv_);
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
        addPresetItems(wheel_, studioPresetLocations(), "wheels");
        const int index = wheel_->findData(previous);
        wheel_->setCurrentIndex(index >= 0 ? index : 0);
    }
    updateControls();
}

void IdentificationFitOptions::setWheelChoice(const QString& choice) {
    const int index = wheel_->findData(choice);
    wheel_->setCurrentIndex(index >= 0 ? index : 0);
    updateControls();
}

wheel::WheelParameters IdentificationFitOptions::chosenWheel() const {
    const QString choice = wheel_->currentData().toString();
    if (choice.isEmpty() && data_wheel_) return *data_wheel_;
    if (choice.isEmpty() || choice == "project") return document_->project().wheel;
    const Result<wheel::WheelParameters> preset =
        io::resolveWheel(studioPresetLocations(), choice.toStdString());
    return preset ? preset.value() : document_->project().wheel;
}

QString IdentificationFitOptions::wheelDescription() const {
    const wheel::WheelParameters w = chosenWheel();
    QString text = QString("Fitting with %1 (r = %2 m, b = %3 m)")
                       .arg(QString::fromStdString(w.name))
                       .arg(wheelNumber(w.radius_m))
                       .arg(wheelNumber(w.width_m));
    const QString choice = wheel_->currentData().toString();
    const bool synthetic = csv_.isEmpty();
    if (choice.isEmpty() && data_wheel_) {
        text += QString(": the data's wheel (%1)").arg(data_wheel_source_);
    } else if (choice.isEmpty()) {
        text += synthetic ? QString(": the project's wheel, the synthetic data's")
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

void IdentificationFitOptions::setShearLimit(const QString& mode, double jmax_mm) {
    if (const int i = jmax_mode_->findData(mode); i >= 0) jmax_mode_->setCurrentIndex(i);
    jmax_value_->setValue(jmax_mm);
    updateControls();
}

}  // namespace terra::ui
