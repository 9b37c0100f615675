#include "widgets/panels/calibration_dialog.h"

#include <QCheckBox>
#include <QDialogButtonBox>
#include <QDoubleSpinBox>
#include <QFileInfo>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QLineEdit>
#include <QProgressBar>
#include <QPushButton>
#include <QTableWidget>
#include <QVBoxLayout>

#include "core/identification/parameters.h"
#include "core/io/parameters_json.h"
#include "core/project/project.h"
#include "core/project/saved_validation.h"
#include "widgets/document/project_document.h"
#include "widgets/panels/summary_html.h"
#include "widgets/plots/completion.h"

namespace terra::ui {
namespace {

namespace id = identification;

const QString kSuffix = " (calibrated)";

QDoubleSpinBox* noiseBox(QWidget* parent, const QString& unit, double max, const QString& tip) {
    auto* box = new QDoubleSpinBox(parent);
    box->setRange(0.0, max);
    box->setDecimals(3);
    box->setSingleStep(0.1);
    box->setSuffix(" " + unit);
    box->setSpecialValueText("estimated");
    box->setToolTip(tip + "; 0: estimated from the residuals (docs/validation.md)");
    return box;
}

QTableWidgetItem* cell(const QString& text, const QString& tip = {}) {
    auto* item = new QTableWidgetItem(text);
    if (!tip.isEmpty()) item->setToolTip(tip);
    return item;
}

void setupTable(QTableWidget* table, const QStringList& headers) {
    table->setColumnCount(static_cast<int>(headers.size()));
    table->setHorizontalHeaderLabels(headers);
    table->verticalHeader()->hide();
    table->setEditTriggers(QAbstractItemView::NoEditTriggers);
    table->setFocusPolicy(Qt::NoFocus);  // read-only: no current-cell frame
    table->horizontalHeader()->setSectionResizeMode(QHeaderView::Stretch);
    table->horizontalHeader()->setSectionResizeMode(0, QHeaderView::ResizeToContents);
}

/// Whether a row of the validation summary is one the dialog's tables show: a metric (the
/// metrics table) or a calibrated parameter (the parameter table).
bool tableRow(const analysis::SummaryRow& row) {
    for (const char* table : {"/metrics", "/calibration/metrics", "/calibration/held_out",
                              "/calibration/parameters/"}) {
        if (row.json.starts_with(table)) return true;
    }
    return false;
}

/// The summary's row of a calibrated parameter (its JSON key), or nullptr.
const analysis::SummaryRow* parameterRow(const analysis::Summary& summary, const std::string& key) {
    const std::string at = "/calibration/parameters/" + key + "/value";
    for (const analysis::SummaryRow& row : summary) {
        if (row.json == at) return &row;
    }
    return nullptr;
}

}  // namespace

CalibrationDialog::CalibrationDialog(ProjectDocument* document, QWidget* parent)
    : QDialog(parent), document_(document) {
    setWindowTitle("Calibrate to this test");
    intro_ = new QLabel(this);
    intro_->setWordWrap(true);
    fx_noise_ = noiseBox(this, "N", 1e3, "Noise std of the measured drawbar pull F_x");
    my_noise_ = noiseBox(this, "N·m", 1e3, "Noise std of the measured torque M_y");
    sinkage_noise_ = noiseBox(this, "mm", 100.0, "Noise std of the measured sinkage h");
    fit_n1_ = new QCheckBox("Fit n₁ too (slip-sinkage N = n + n₁ s)", this);
    fit_n1_->setToolTip(
        "Profiles χ² over n₁ (docs/model.md, Slip-sinkage): about forty fits instead of one");
    fit_slips_ = new QLineEdit(this);
    fit_slips_->setObjectName("fit_slips");
    fit_slips_->setPlaceholderText("every point");
    fit_slips_->setToolTip(
        "Calibrate on the points at these slips only (comma separated, each a slip of the test); "
        "the others are held out and predicted: their errors say how well the calibrated soil "
        "predicts what it was not fitted to (docs/validation.md)");
    run_ = new QPushButton("Calibrate", this);
    run_->setDefault(true);
    cancel_ = new QPushButton("Cancel", this);
    progress_ = new QProgressBar(this);
    progress_->setRange(0, 100);
    progress_->setValue(0);
    status_ = new QLabel(this);
    status_->setTextFormat(Qt::RichText);  // an unescaped "<=" made Qt show the "<br>" as text
    status_->setWordWrap(true);
    status_->setTextInteractionFlags(Qt::TextSelectableByMouse);
    metrics_ = new QTableWidget(0, 3, this);
    setupTable(metrics_, {"Metric", "Given soil", "Calibrated"});
    parameters_ = new QTableWidget(0, 4, this);
    setupTable(parameters_, {"Parameter", "Calibrated", "± std", "Prior (given soil)"});
    parameters_->horizontalHeaderItem(2)->setToolTip(
        "From the fit's covariance (Laplace approximation); as large as the value: the test does "
        "not determine the parameter, the prior does");
    apply_ = new QPushButton("Apply calibrated soil to project", this);
    apply_->setToolTip(
        "Replaces the project's soil by the calibrated one (Edit ▸ Undo restores it)");
    auto* close = new QDialogButtonBox(QDialogButtonBox::Close, this);

    auto* options = new QHBoxLayout;
    options->addWidget(new QLabel("Noise σ:", this));
    for (auto [label, box] : {std::pair{"F_x", fx_noise_}, std::pair{"M_y", my_noise_},
                              std::pair{"h", sinkage_noise_}}) {
        options->addSpacing(8);
        options->addWidget(new QLabel(label, this));
        options->addWidget(box);
    }
    options->addSpacing(16);
    options->addWidget(fit_n1_);
    options->addStretch(1);
    auto* slips = new QHBoxLayout;
    slips->addWidget(new QLabel("Fit on slips:", this));
    slips->addWidget(fit_slips_, 1);
    auto* run_bar = new QHBoxLayout;
    run_bar->addWidget(run_);
    run_bar->addWidget(cancel_);
    run_bar->addWidget(progress_, 1);
    auto* tables = new QHBoxLayout;
    tables->addWidget(metrics_, 1);
    tables->addWidget(parameters_, 1);
    auto* bottom = new QHBoxLayout;
    bottom->addWidget(apply_);
    bottom->addStretch(1);
    bottom->addWidget(close);
    auto* layout = new QVBoxLayout(this);
    layout->addWidget(intro_);
    layout->addLayout(options);
    layout->addLayout(slips);
    layout->addLayout(run_bar);
    layout->addWidget(status_);
    layout->addLayout(tables, 1);
    layout->addLayout(bottom);
    resize(820, 460);

    connect(run_, &QPushButton::clicked, this, [this] { start(); });
    connect(cancel_, &QPushButton::clicked, this, [this] { cancel(); });
    connect(apply_, &QPushButton::clicked, this, [this] { apply(); });
    connect(close, &QDialogButtonBox::rejected, this, &QDialog::reject);
    connect(&runner_, &AnalysisRunner::finished, this, &CalibrationDialog::finished);
    connect(&runner_, &AnalysisRunner::progressed, this,
            [this](double fraction) { progress_->setValue(static_cast<int>(fraction * 100.0)); });
    // Another soil, wheel or test makes the result one of an earlier project.
    connect(document_, &ProjectDocument::changed, this, [this] { updateButtons(); });
    updateButtons();
}

CalibrationDialog::~CalibrationDialog() = default;  // the runner cancels the fit and waits

QString CalibrationDialog::fitSlipsProblem() const {
    const QString text = fit_slips_->text().trimmed();
    if (text.isEmpty()) return {};
    for (const QString& part : text.split(',')) {
        bool ok = false;
        part.trimmed().toDouble(&ok);
        if (!ok)
            return QString(
                       "Fit on slips: '%1' is not a number; give slips of the test, comma "
                       "separated, or nothing for every point")
                .arg(part.trimmed().left(40));
    }
    return {};
}

void CalibrationDialog::setFitSlips(const QString& slips) { fit_slips_->setText(slips); }

std::optional<analysis::ValidationSettings> CalibrationDialog::settings() const {
    if (!fitSlipsProblem().isEmpty()) return std::nullopt;
    analysis::ValidationSettings s;
    const QString slips = fit_slips_->text().trimmed();
    if (!slips.isEmpty()) {
        for (const QString& part : slips.split(',')) s.fit_slips.push_back(part.toDouble());
    }
    if (const io::Experiment* test = document_->experiment()) {
        s.experiments = test->source;
        s.data = *test;
    }
    s.calibrate = true;
    s.curves = false;  // the dialog shows metrics and parameters, no figure
    s.noise[io::kExpFx] = fx_noise_->value();
    s.noise[io::kExpMy] = my_noise_->value();
    s.noise[io::kExpSinkage] = sinkage_noise_->value() / 1e3;
    s.fit_n1 = fit_n1_->isChecked();
    return s;
}

void CalibrationDialog::setOptions(double fx_noise_n, double my_noise_nm, double sinkage_noise_mm,
                                   bool fit_n1) {
    fx_noise_->setValue(fx_noise_n);
    my_noise_->setValue(my_noise_nm);
    sinkage_noise_->setValue(sinkage_noise_mm);
    fit_n1_->setChecked(fit_n1);
}

bool CalibrationDialog::start() {
    if (isRunning() || !document_->experiment()) return false;
    const std::optional<analysis::ValidationSettings> typed = settings();
    if (!typed) {
        status_->setText("<b>Error:</b> " + fitSlipsProblem().toHtmlEscaped());
        return false;
    }
    const analysis::Inputs inputs = project::inputsOf(document_->project());
    const analysis::ValidationSettings s = *typed;
    started_revision_ = document_->revision();
    started_settings_ = controlSettings();
    applied_ = false;
    status_shows_result_ = false;
    progress_->setValue(0);
    progress_->setFormat("%p %");
    status_->setText("Calibrating…");
    runner_.start([inputs, s](const analysis::Control& control) -> std::any {
        return analysis::computeValidation(inputs, s, control);
    });
    updateButtons();
    return true;
}

void CalibrationDialog::cancel() {
    if (!isRunning()) return;
    runner_.cancel();
    status_->setText("Cancelling…");
}

void CalibrationDialog::finished(const AnalysisRunner::Outcome& out) {
    if (out.cancelled) {
        progress_->setFormat("%p % (cancelled)");
        // Marked as every panel marks a cancelled run (completion.h).
        status_->setText("<b>" + completionMark(Completion::kCancelled) +
                         "</b> — calibration cancelled: nothing calibrated, nothing to apply.");
    } else if (!out.error.isEmpty()) {
        status_->setText("<b>Error:</b> " + out.error.toHtmlEscaped());
    } else {
        result_ = std::any_cast<analysis::ValidationResult>(out.value);
        result_revision_ = started_revision_;
        result_settings_ = started_settings_;
        progress_->setValue(100);
        showResult();
    }
    updateButtons();
    emit calibrationFinished();
}

void CalibrationDialog::showResult() {
    const analysis::ValidationResult& r = *result_;
    const analysis::Calibration& cal = *r.calibration;
    const bool usable = cal.report.usable() && cal.after;
    // The core summary (what `validate` prints) but the rows the tables below show.
    const analysis::Summary summary = analysis::validationSummary(r);
    analysis::Summary rows;
    for (const analysis::SummaryRow& row : summary) {
        if (!tableRow(row)) rows.push_back(row);
    }
    status_->setText(summaryHtml(rows));
    status_shows_result_ = true;

    // The metrics as the core lays them out and formats them (validationMetricsTable: the
    // numbers `validate` prints), a column per set of points.
    const analysis::MetricsTable table = analysis::validationMetricsTable(r);
    const bool held_out = table.columns.size() == 4;
    QStringList headers{"Metric", "Given soil", "Calibrated"};
    if (held_out)
        headers << "Held out\ngiven"
                << "Held out\ncalibrated";
    metrics_->setRowCount(0);
    setupTable(metrics_, headers);
    if (held_out) {
        metrics_->horizontalHeaderItem(3)->setToolTip(
            "The points the calibration did not use, with the given soil");
        metrics_->horizontalHeaderItem(4)->setToolTip(
            "The points the calibration did not use, predicted by the calibrated soil");
    }
    for (const analysis::MetricsTable::Row& row : table.rows) {
        const int at = metrics_->rowCount();
        metrics_->insertRow(at);
        metrics_->setItem(at, 0, cell(QString::fromStdString(row.label)));
        for (std::size_t col = 0; col < row.cells.size(); ++col) {
            metrics_->setItem(at, static_cast<int>(col) + 1,
                              cell(QString::fromStdString(analysis::cellText(row.cells[col]))));
        }
    }
    parameters_->setRowCount(0);
    if (!usable) return;
    // The parameters as the summary gives them: the value to its std's place, the std, the prior
    // (its detail: "prior 31.9", then ", ended at its bound").
    const auto addParameter = [this](const QString& label, const QString& key,
                                     const analysis::SummaryRow& row) {
        const auto [value, sd] = valueAndStd(row);
        const QString detail = QString::fromStdString(row.detail);
        const bool at_bound = detail.contains(", ended at its bound");
        const int at = parameters_->rowCount();
        parameters_->insertRow(at);
        parameters_->setItem(at, 0, cell(label, key));
        parameters_->setItem(at, 1, cell(value + (at_bound ? " (at bound)" : "")));
        parameters_->setItem(at, 2, cell(sd.isEmpty() ? QString::fromUtf8("–") : sd));
        parameters_->setItem(at, 3, cell(detail.section(", ", 0, 0).remove(0, 6)));
    };
    for (int k = 0; k < id::kJmax; ++k) {  // j_max is held at the soil's, not calibrated
        const id::ParameterField& field = id::fieldOf(static_cast<id::FullParameter>(k));
        const std::string key = id::oldKeyOf(field);
        if (const analysis::SummaryRow* row = parameterRow(summary, key))
            addParameter(QString::fromStdString(field.symbolWithUnit()),
                         QString::fromStdString(key), *row);
    }
    if (const analysis::SummaryRow* row = parameterRow(summary, "n1")) {
        analysis::SummaryRow n1 = *row;
        n1.detail = "prior 0";  // the thesis model's n₁
        addParameter("n₁", "n1", n1);
    }
}

bool CalibrationDialog::canApply() const {
    return !isRunning() && result_ && result_->calibration &&
           result_->calibration->report.usable() && result_revision_ == document_->revision();
}

void CalibrationDialog::updateButtons() {
    const bool running = isRunning();
    run_->setEnabled(!running && document_->experiment() != nullptr);
    cancel_->setEnabled(running);
    // The noise of a channel the test does not measure does not apply.
    const io::Experiment* measured = document_->experiment();
    const std::pair<QWidget*, io::ExperimentChannel> noises[] = {
        {fx_noise_, io::kExpFx}, {my_noise_, io::kExpMy}, {sinkage_noise_, io::kExpSinkage}};
    for (const auto& [box, channel] : noises)
        box->setEnabled(!running && measured && measured->measures(channel));
    fit_n1_->setEnabled(!running);
    fit_slips_->setEnabled(!running);
    apply_->setEnabled(canApply());
    if (result_ && status_shows_result_ && !running && !applied_ &&
        result_revision_ != document_->revision()) {
        status_shows_result_ = false;  // said once
        status_->setText(
            "The project changed since this calibration: run it again to apply it.<br>" +
            status_->text());
    }
    const io::Experiment* test = document_->experiment();
    intro_->setText(
        test ? QString("Fits the project's soil (%1) to the test %2 on the project's wheel (%3), "
                       "with the soil as the prior and first start.")
                   .arg(QString::fromStdString(document_->project().soil.name).toHtmlEscaped(),
                        QFileInfo(QString::fromStdString(test->source)).fileName().toHtmlEscaped(),
                        QString::fromStdString(document_->project().wheel.name).toHtmlEscaped())
             : QString("The project has no measured test (File ▸ Load Experiment…)."));
}

bool CalibrationDialog::apply() {
    if (!canApply()) return false;
    soil::SoilParameters soil = result_->calibration->soil;
    // Calibrating a calibrated soil again: one suffix, not two.
    const std::string suffix = kSuffix.toStdString();
    std::string base = document_->project().soil.name;
    if (base.ends_with(suffix)) base.resize(base.size() - suffix.size());
    soil.name = base + suffix;
    const QString test = QFileInfo(QString::fromStdString(result_->source)).fileName();
    applied_ = true;
    const bool applied = document_->setSoil(soil, "", QString("Calibrate soil to %1").arg(test));
    applied_ = applied;
    if (applied)
        status_->setText("Applied: the project's soil is now " +
                         QString::fromStdString(soil.name).toHtmlEscaped() +
                         " (Edit ▸ Undo restores the previous one).");
    updateButtons();
    return applied;
}

nlohmann::json CalibrationDialog::controlSettings() const {
    return {{"noise_Fx_N", fx_noise_->value()},
            {"noise_My_Nm", my_noise_->value()},
            {"noise_sinkage_mm", sinkage_noise_->value()},
            {"fit_n1", fit_n1_->isChecked()},
            {"fit_slips", fit_slips_->text().trimmed().toStdString()}};
}

nlohmann::json CalibrationDialog::calibrationInputs(const soil::SoilParameters& given,
                                                    const nlohmann::json& settings) const {
    const io::Experiment* test = document_->experiment();
    return {{"soil", io::toJson(given)},
            {"wheel", io::toJson(document_->project().wheel)},
            {"test", test ? project::fileStamp(test->source) : nlohmann::json()},
            {"settings", settings}};
}

std::optional<project::SavedResult> CalibrationDialog::savedResult() const {
    if (isRunning() || !result_ || !result_->calibration) return std::nullopt;
    project::SavedResult saved;
    saved.version = project::kCalibrationVersion;
    saved.inputs_hash =
        project::inputsHash(calibrationInputs(result_->before.soil, result_settings_));
    saved.summary = "calibrated to " +
                    QFileInfo(QString::fromStdString(result_->source)).fileName().toStdString();
    saved.result = {{"calibration", project::savedJson(*result_)}, {"settings", result_settings_}};
    return saved;
}

namespace {

/// A soil's JSON without its name: "sandy loam (calibrated)" is the calibrated soil applied.
nlohmann::json unnamed(soil::SoilParameters soil) {
    soil.name.clear();
    return io::toJson(soil);
}

}  // namespace

AnalysisPanel::Restored CalibrationDialog::restore(const project::SavedResult& saved) {
    using Kind = AnalysisPanel::Restored::Kind;
    const auto refuse = [](Kind kind, const std::string& why) {
        return AnalysisPanel::Restored{kind, why};
    };
    if (isRunning()) return refuse(Kind::kUnreadable, "a calibration is running");
    if (saved.version != project::kCalibrationVersion)
        return refuse(Kind::kUnreadable, "saved in form version " + std::to_string(saved.version));
    if (!saved.result.is_object() || !saved.result.contains("calibration") ||
        !saved.result.contains("settings") || !saved.result["settings"].is_object())
        return refuse(Kind::kUnreadable, "no calibration or settings");
    Result<analysis::ValidationResult> read =
        project::validationResultFromJson(saved.result["calibration"], "calibration");
    if (!read) return refuse(Kind::kUnreadable, read.message());
    if (!read->calibration) return refuse(Kind::kUnreadable, "not a calibration");
    const nlohmann::json& settings = saved.result["settings"];
    if (saved.inputs_hash != project::inputsHash(calibrationInputs(read->before.soil, settings)))
        return refuse(Kind::kInputsChanged, "its wheel, test or settings changed");
    const nlohmann::json soil = unnamed(document_->project().soil);
    const bool given = soil == unnamed(read->before.soil);
    const bool applied = soil == unnamed(read->calibration->soil);
    if (!given && !applied)
        return refuse(Kind::kInputsChanged,
                      "the project's soil is neither its given nor its calibrated soil");
    try {
        fx_noise_->setValue(settings.at("noise_Fx_N").get<double>());
        my_noise_->setValue(settings.at("noise_My_Nm").get<double>());
        sinkage_noise_->setValue(settings.at("noise_sinkage_mm").get<double>());
        fit_n1_->setChecked(settings.at("fit_n1").get<bool>());
        fit_slips_->setText(QString::fromStdString(settings.at("fit_slips").get<std::string>()));
    } catch (const std::exception& e) {
        return refuse(Kind::kUnreadable, std::string("settings: ") + e.what());
    }
    result_ = std::move(read).value();
    result_settings_ = settings;
    // Applicable while the project keeps the given soil; applied already otherwise.
    applied_ = applied && !given;
    result_revision_ = applied_ ? -1 : document_->revision();
    progress_->setValue(100);
    showResult();
    status_->setText("Saved with the project; not calibrated again (Calibrate runs it again).<br>" +
                     status_->text());
    if (applied_)
        status_->setText("Applied: the project's soil is this calibration's.<br>" +
                         status_->text());
    status_shows_result_ = !applied_;
    updateButtons();
    return {Kind::kShown, {}};
}

QString CalibrationDialog::statusText() const { return status_->text(); }

}  // namespace terra::ui
