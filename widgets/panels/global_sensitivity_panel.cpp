#include "widgets/panels/global_sensitivity_panel.h"

#include <qcustomplot.h>

#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QLineEdit>
#include <QProgressBar>
#include <QPushButton>
#include <QSpinBox>
#include <QStandardItemModel>
#include <QTabWidget>
#include <QTableWidget>
#include <QTimer>
#include <QVBoxLayout>
#include <sstream>

#include "core/io/csv.h"
#include "core/io/parameters_json.h"
#include "core/project/panels.h"
#include "core/soil/soil_parameters.h"
#include "widgets/document/project_document.h"
#include "widgets/plots/figures.h"
#include "widgets/plots/gsa_figures.h"

namespace terra::ui {
namespace {

// The rows of the parameter table: docs/sensitivity.md's example ranges ticked, the moduli
// unticked at ±20 % of the sandy loam.
struct Row {
    const char* key;
    bool varied;
    double low, high;
};
constexpr Row kRows[] = {{"phi_deg", true, 20.0, 35.0}, {"c_kPa", true, 0.0, 5.0},
                         {"K_m", true, 0.005, 0.04},    {"n", true, 0.5, 1.1},
                         {"kc", false, 4.24, 6.36},     {"kphi", false, 1212.0, 1818.0},
                         {"a0", false, 0.1, 0.3},       {"a1", false, 0.2, 0.4}};
constexpr int kLowColumn = 1, kHighColumn = 2;
constexpr int kPlotMinimumWidth = 200;  // [px], as before a study is drawn

struct Computed {
    std::optional<analysis::GlobalSensitivityResult> indices;
    std::optional<analysis::UncertaintyBandResult> bands;
};

QDoubleSpinBox* rangeBox(const soil::SoilField& field, double value, QWidget* parent) {
    auto* box = new QDoubleSpinBox(parent);
    box->setDecimals(4);
    box->setRange(field.range.low, field.range.high);
    box->setSingleStep((field.range.high - field.range.low) / 100.0);
    box->setValue(value);
    return box;
}

}  // namespace

GlobalSensitivityPanel::GlobalSensitivityPanel(ProjectDocument* document, QWidget* parent)
    : AnalysisPanel(document, "global-sensitivity", parent),
      fraction_(std::make_shared<std::atomic<double>>(0.0)) {
    setLive(false);  // a study takes seconds: it runs on "Compute"
    const project::GlobalSensitivityPanelSettings defaults;
    parameters_ = new QTableWidget(static_cast<int>(std::size(kRows)), 3, this);
    parameters_->setHorizontalHeaderLabels({"Parameter", "Low", "High"});
    parameters_->verticalHeader()->setVisible(false);
    parameters_->horizontalHeader()->setSectionResizeMode(QHeaderView::Stretch);
    for (int i = 0; i < static_cast<int>(std::size(kRows)); ++i) {
        const Row& row = kRows[i];
        const soil::SoilField& field = *soil::findSoilField(row.key);
        auto* item = new QTableWidgetItem(QString("%1 [%2]").arg(field.symbol, field.unit));
        item->setFlags(Qt::ItemIsEnabled | Qt::ItemIsUserCheckable);
        item->setCheckState(row.varied ? Qt::Checked : Qt::Unchecked);
        item->setData(Qt::UserRole, QString::fromUtf8(row.key));
        item->setToolTip(QString::fromUtf8(field.description));
        parameters_->setItem(i, 0, item);
        parameters_->setCellWidget(i, kLowColumn, rangeBox(field, row.low, parameters_));
        parameters_->setCellWidget(i, kHighColumn, rangeBox(field, row.high, parameters_));
    }
    // Never narrower than its spin boxes: at 1024×700 the stretched columns cut "1212.0000".
    int box = 0, label = 0;
    for (int i = 0; i < parameters_->rowCount(); ++i) {
        label = std::max(
            label, parameters_->fontMetrics().horizontalAdvance(parameters_->item(i, 0)->text()) +
                       40);  // and the check box
        for (int column : {kLowColumn, kHighColumn})
            box = std::max(box, parameters_->cellWidget(i, column)->minimumSizeHint().width());
    }
    parameters_->setMinimumWidth(label + 2 * box + 2 * parameters_->frameWidth() + 8);
    source_ = new QComboBox(this);
    source_->addItem("Ranges of the table");
    source_->addItem("Identified soil's covariance");
    // Disabled until an identification arrives (setIdentification).
    static_cast<QStandardItemModel*>(source_->model())->item(1)->setEnabled(false);
    method_ = new QComboBox(this);
    method_->addItem("Sobol' (S1, ST)", "sobol");
    method_->addItem("Morris (μ*, σ)", "morris");
    output_ = new QComboBox(this);
    // Shown by name, stored by key (the settings' and the CLI's `output`).
    const std::pair<const char*, const char*> outputs[] = {
        {"Drawbar pull F_x", "Fx_N"},           {"Side force F_s", "Fs_N"},
        {"Wheel torque M_y", "My_Nm"},          {"Sinkage h", "sinkage_m"},
        {"Entry angle θ_f", "entry_angle_deg"}, {"Vertical force F_z", "Fz_N"}};
    for (const auto& [shown, key] : outputs) output_->addItem(shown, key);
    slips_ = new QLineEdit("0.1,0.3,0.6", this);
    slip_angle_ = new QDoubleSpinBox(this);
    slip_angle_->setRange(-60.0, 60.0);
    slip_angle_->setSuffix(" °");
    samples_ = new QSpinBox(this);
    samples_->setRange(2, 1 << 20);
    samples_->setValue(defaults.samples);
    samples_->setToolTip("Sobol': base samples N (N (d + 2) runs per slip); Morris: trajectories");
    band_samples_ = new QSpinBox(this);
    band_samples_->setRange(2, 1 << 20);
    band_samples_->setValue(defaults.band_samples);
    seed_ = new QSpinBox(this);
    seed_->setRange(0, 1 << 30);
    seed_->setValue(1);
    compute_ = new QPushButton("Compute", this);
    cancel_ = new QPushButton("Cancel", this);
    cancel_->setEnabled(false);
    progress_ = new QProgressBar(this);
    trackProgress(progress_);
    status_ = new QLabel(this);
    status_->setWordWrap(true);
    readout_ = new QLabel(this);
    pages_ = new QTabWidget(this);
    indices_plot_ = new QCustomPlot(pages_);
    bands_plot_ = new QCustomPlot(pages_);
    for (QCustomPlot* plot : {indices_plot_, bands_plot_}) {
        makeInteractive(plot, readout_);
        // Its own minimum: a drawn study's legend and bar labels made the plot's hint ~600 px
        // and the panel's 1000 px, wider than a tiled row leaves it (View ▸ Layout ▸ Tile then
        // squeezed the panel beside it into a sideways scroll bar). The legend reflows instead.
        plot->setMinimumWidth(kPlotMinimumWidth);
    }
    pages_->addTab(indices_plot_, "Indices");
    pages_->addTab(bands_plot_, "Uncertainty bands");
    progress_timer_ = new QTimer(this);
    progress_timer_->setInterval(100);

    auto* form = new QFormLayout;
    form->addRow("Parameters from:", source_);
    form->addRow("Method:", method_);
    form->addRow("Slips:", slips_);
    form->addRow("Slip angle β:", slip_angle_);
    form->addRow("Samples (indices):", samples_);
    form->addRow("Samples (bands):", band_samples_);
    form->addRow("Seed:", seed_);
    form->addRow("Show:", output_);
    auto* buttons = new QHBoxLayout;
    buttons->addWidget(compute_);
    buttons->addWidget(cancel_);
    auto* side = new QVBoxLayout;
    side->addWidget(parameters_, 1);
    side->addLayout(form);
    side->addLayout(buttons);
    side->addWidget(progress_);
    auto* plots = new QVBoxLayout;
    plots->addWidget(pages_, 1);
    plots->addWidget(readout_);
    plots->addWidget(status_);
    auto* layout = new QHBoxLayout(this);
    layout->addLayout(side, 2);
    layout->addLayout(plots, 5);

    connect(compute_, &QPushButton::clicked, this, &GlobalSensitivityPanel::compute);
    connect(cancel_, &QPushButton::clicked, this, &AnalysisPanel::cancelRunning);
    connect(output_, &QComboBox::currentIndexChanged, this, [this] { redraw(); });
    for (QComboBox* box : {method_, output_})
        connect(box, &QComboBox::currentIndexChanged, this, [this] { storeSettings(); });
    connect(progress_timer_, &QTimer::timeout, this,
            [this] { progress_->setValue(static_cast<int>(100.0 * fraction_->load())); });
    connect(this, &AnalysisPanel::busyChanged, this, [this](bool busy) {
        compute_->setEnabled(!busy);
        cancel_->setEnabled(busy);
        if (busy) {
            fraction_->store(0.0);
            progress_timer_->start();
            status_->setText("Computing…");
        } else {
            progress_timer_->stop();
        }
    });
    connect(this, &AnalysisPanel::failed, this, [this](const QString& m) {
        progress_timer_->stop();
        compute_->setEnabled(true);
        cancel_->setEnabled(false);
        status_->setText("<b>Error:</b> " + m.toHtmlEscaped());
    });
    // The example study's indices once the panel is first shown, unless the study is heavy then
    // (startsByItself).
    scheduleUpdate();
}

std::size_t GlobalSensitivityPanel::plannedEvaluations() const {
    if (pages_->currentIndex() == 1) {
        const analysis::UncertaintyBandSettings s = bandSettings();
        return s.samples * static_cast<std::size_t>(s.slip_count) * s.study.slip_angles_deg.size();
    }
    const analysis::GlobalSensitivitySettings s = indexSettings();
    const std::size_t d =
        s.study.parameters.size() + (s.study.correlated ? s.study.correlated->keys.size() : 0);
    const std::size_t runs = s.method == analysis::GsaMethod::kMorris ? d + 1 : d + 2;
    return s.samples * runs * s.study.slips.size() * s.study.slip_angles_deg.size();
}

QString GlobalSensitivityPanel::statusText() const { return status_->text(); }

bool GlobalSensitivityPanel::startsByItself() {
    std::size_t evaluations = 0;
    try {
        evaluations = plannedEvaluations();
    } catch (const std::exception&) {
        return true;  // the computation reports what is wrong with the settings
    }
    if (evaluations <= kAutomaticEvaluations) return true;
    const bool bands = pages_->currentIndex() == 1;
    std::vector<QCustomPlot*> cleared;
    if (bands ? !bands_ : !indices_) cleared.push_back(currentPlot());
    showNotComputed(status_,
                    QString("Not computed: this study takes %L1 model evaluations — press "
                            "Compute to run it.")
                        .arg(evaluations),
                    cleared);
    return false;
}

void GlobalSensitivityPanel::projectReplaced() {
    indices_.reset();
    indices_hash_.clear();
    bands_.reset();
    bands_hash_.clear();
    // The identified soil of the project before is no source (the studio shares the opened
    // project's again when it shows its fit).
    setIdentification({}, identification::Uncertainty{});
    showNotComputed(status_, "Not computed yet: press Compute.", {indices_plot_, bands_plot_});
    AnalysisPanel::projectReplaced();
    scheduleUpdate();  // computes again when the study is light, else says "not computed"
}

void GlobalSensitivityPanel::showPage(int page) { pages_->setCurrentIndex(page); }

bool GlobalSensitivityPanel::setRange(const std::string& key, bool varied, double low,
                                      double high) {
    for (int i = 0; i < parameters_->rowCount(); ++i) {
        if (parameters_->item(i, 0)->data(Qt::UserRole).toString().toStdString() != key) continue;
        parameters_->item(i, 0)->setCheckState(varied ? Qt::Checked : Qt::Unchecked);
        static_cast<QDoubleSpinBox*>(parameters_->cellWidget(i, kLowColumn))->setValue(low);
        static_cast<QDoubleSpinBox*>(parameters_->cellWidget(i, kHighColumn))->setValue(high);
        return true;
    }
    return false;
}

void GlobalSensitivityPanel::setSlips(const QString& slips) { slips_->setText(slips); }
void GlobalSensitivityPanel::setSamples(int samples) {
    samples_->setValue(samples);
    band_samples_->setValue(samples);
}
void GlobalSensitivityPanel::setMethod(analysis::GsaMethod method) {
    method_->setCurrentIndex(method == analysis::GsaMethod::kMorris ? 1 : 0);
}

void GlobalSensitivityPanel::setIdentification(const identification::DecoupledParameters& p,
                                               const identification::Uncertainty& u) {
    identification_.reset();
    if (u.computed) identification_.emplace(p, u);
    static_cast<QStandardItemModel*>(source_->model())
        ->item(1)
        ->setEnabled(identification_.has_value());
    if (!identification_ && source_->currentIndex() == 1) source_->setCurrentIndex(0);
}

void GlobalSensitivityPanel::setSource(int source) { source_->setCurrentIndex(source); }

void GlobalSensitivityPanel::compute() { recompute(); }

void GlobalSensitivityPanel::requestRun() {
    if (compute_->isEnabled()) compute_->click();
}

analysis::Inputs GlobalSensitivityPanel::inputs() const {
    analysis::Inputs in = project::inputsOf(document_->project());
    if (source_->currentIndex() == 1 && identification_)
        in.soil = identification::soilOf(in.soil, in.wheel, identification_->first);
    return in;
}

analysis::StudyDefinition GlobalSensitivityPanel::definition() const {
    analysis::StudyDefinition d;
    d.parameters.clear();
    if (source_->currentIndex() == 1) {
        if (!identification_)
            throw std::invalid_argument(
                "no identified soil: run a fit in the identification panel");
        const analysis::Inputs in = project::inputsOf(document_->project());
        d.correlated = analysis::correlatedFromIdentification(
            identification_->first, identification_->second, in.soil, in.wheel);
    } else {
        for (int i = 0; i < parameters_->rowCount(); ++i) {
            if (parameters_->item(i, 0)->checkState() != Qt::Checked) continue;
            const double low =
                static_cast<QDoubleSpinBox*>(parameters_->cellWidget(i, kLowColumn))->value();
            const double high =
                static_cast<QDoubleSpinBox*>(parameters_->cellWidget(i, kHighColumn))->value();
            d.parameters.push_back(
                {parameters_->item(i, 0)->data(Qt::UserRole).toString().toStdString(),
                 gsa::Uniform{low, high}});
        }
    }
    d.outputs.clear();
    for (int i = 0; i < output_->count(); ++i)
        d.outputs.push_back(output_->itemData(i).toString().toStdString());
    d.slip_angles_deg = {slip_angle_->value()};
    d.load_n = document_->project().conditions.load_n;
    d.seed = static_cast<std::uint64_t>(seed_->value());
    return d;
}

analysis::GlobalSensitivitySettings GlobalSensitivityPanel::indexSettings() const {
    analysis::GlobalSensitivitySettings s;
    s.study = definition();
    s.study.slips.clear();
    std::stringstream stream(slips_->text().toStdString());
    for (std::string cell; std::getline(stream, cell, ',');) {
        double value = 0.0;
        if (!io::parseNumber(cell, value))
            throw std::invalid_argument("slips: " + io::quoteCell(cell) + " is not a number");
        s.study.slips.push_back(value);
    }
    s.method =
        method_->currentIndex() == 1 ? analysis::GsaMethod::kMorris : analysis::GsaMethod::kSobol;
    s.samples = static_cast<std::size_t>(samples_->value());
    return s;
}

analysis::UncertaintyBandSettings GlobalSensitivityPanel::bandSettings() const {
    analysis::UncertaintyBandSettings s;
    s.study = definition();
    s.study.slips.clear();  // 0 … the conditions' slip_max
    s.samples = static_cast<std::size_t>(band_samples_->value());
    return s;
}

AnalysisPanel::Job GlobalSensitivityPanel::makeJob() {
    const analysis::Inputs in = inputs();
    auto fraction = fraction_;
    auto progress = [fraction](double f) { fraction->store(f); };
    if (pages_->currentIndex() == 1) {
        const analysis::UncertaintyBandSettings s = bandSettings();
        pending_bands_hash_ = project::inputsHash(bandInputs());
        return [in, s, progress](const std::atomic<bool>& cancel) -> std::any {
            return Computed{std::nullopt,
                            analysis::computeUncertaintyBands(in, s, {&cancel, progress})};
        };
    }
    const analysis::GlobalSensitivitySettings s = indexSettings();
    return [in, s, progress](const std::atomic<bool>& cancel) -> std::any {
        return Computed{analysis::computeGlobalSensitivity(in, s, {&cancel, progress}),
                        std::nullopt};
    };
}

void GlobalSensitivityPanel::present(const std::any& value) {
    const auto& computed = std::any_cast<const Computed&>(value);
    // The study's own status (it knows whether it ran to the end), not the cancel flag alone.
    const gsa::StudyStatus status =
        computed.indices
            ? computed.indices->status()
            : (computed.bands ? computed.bands->bands.status : gsa::StudyStatus::kCompleted);
    setCompletion(status == gsa::StudyStatus::kCancelled ? Completion::kCancelled
                                                         : Completion::kComplete);
    progress_->setValue(static_cast<int>(100.0 * fraction_->load()));  // where it stopped
    if (computed.indices) {
        indices_ = computed.indices;
        indices_hash_ = presentedInputsHash();
    }
    if (computed.bands) {
        bands_ = computed.bands;
        bands_hash_ = pending_bands_hash_;
    }
    QString message;
    if (computed.indices) {
        message = QString("%1 model evaluations")
                      .arg(computed.indices->sobol ? computed.indices->sobol->evaluations
                                                   : computed.indices->morris->evaluations);
        if (!computed.indices->message().empty())
            message += "; " + QString::fromStdString(computed.indices->message());
    } else if (computed.bands) {
        message =
            QString("%1 samples")
                .arg(computed.bands->bands.used.empty() ? 0 : computed.bands->bands.used.front());
        if (!computed.bands->bands.message.empty())
            message += "; " + QString::fromStdString(computed.bands->bands.message);
    }
    status_->setText(markedStatus(message.toHtmlEscaped()));
    redraw();
}

void GlobalSensitivityPanel::redraw() {
    const std::size_t output = static_cast<std::size_t>(std::max(0, output_->currentIndex()));
    const Project& p = document_->project();
    const QString title =
        // Two lines: on one, a ~400 px plot (1024×700) cut the title at both ends.
        QString("%1, %2\nW = %3 N, β = %4°")
            .arg(QString::fromStdString(p.soil.name), QString::fromStdString(p.wheel.name))
            .arg(p.conditions.load_n)
            .arg(slip_angle_->value());
    // Each page's title says whether its own study was cancelled (the other page's may not be).
    auto marked = [&title](gsa::StudyStatus status) {
        return markedTitle(title, status == gsa::StudyStatus::kCancelled ? Completion::kCancelled
                                                                         : Completion::kComplete);
    };
    if (indices_ && output < indices_->outputs().size())
        plotGlobalIndices(*indices_plot_, *indices_, output, 0, marked(indices_->status()));
    if (bands_ && output < bands_->bands.outputs.size())
        plotUncertaintyBands(*bands_plot_, *bands_, output, 0, marked(bands_->bands.status));
}

std::vector<std::pair<QString, QCustomPlot*>> GlobalSensitivityPanel::plots() const {
    return {{"global-indices", indices_plot_}, {"uncertainty-bands", bands_plot_}};
}

QCustomPlot* GlobalSensitivityPanel::currentPlot() const {
    // By index: a plot shown in a dock of its own leaves a placeholder in its tab.
    return pages_->currentIndex() == 1 ? bands_plot_ : indices_plot_;
}

Table GlobalSensitivityPanel::currentTable() const {
    if (pages_->currentIndex() == 1) return bands_ ? bands_->table() : Table{};
    return indices_ ? indices_->table() : Table{};
}

nlohmann::json GlobalSensitivityPanel::settings() const {
    project::GlobalSensitivityPanelSettings s;
    s.page = pages_->currentIndex() == 1 ? "bands" : "indices";
    s.method = method_->currentData().toString().toStdString();
    s.output = output_->currentData().toString().toStdString();
    try {
        s.slips = indexSettings().study.slips;
    } catch (const std::exception&) {
        // Unreadable text is not saved: the defaults stand.
    }
    s.slip_angle_deg = slip_angle_->value();
    s.samples = samples_->value();
    s.band_samples = band_samples_->value();
    s.seed = static_cast<std::uint64_t>(seed_->value());
    return project::toJson(s);
}

void GlobalSensitivityPanel::applySettings(const nlohmann::json& json) {
    const auto settings =
        project::panelSettingsFromJson<project::GlobalSensitivityPanelSettings>(withChanges(json));
    if (!settings) return;  // projects are checked when opened
    pages_->setCurrentIndex(settings->page == "bands" ? 1 : 0);
    method_->setCurrentIndex(settings->method == "morris" ? 1 : 0);
    output_->setCurrentIndex(output_->findData(QString::fromStdString(settings->output)));
    QStringList slips;
    for (double s : settings->slips) slips << QString::number(s);
    slips_->setText(slips.join(","));
    slip_angle_->setValue(settings->slip_angle_deg);
    samples_->setValue(settings->samples);
    band_samples_->setValue(settings->band_samples);
    seed_->setValue(static_cast<int>(settings->seed));
}

nlohmann::json GlobalSensitivityPanel::resultInputs() const {
    const analysis::Inputs in = inputs();
    nlohmann::json varied = nlohmann::json::array();
    for (int i = 0; i < parameters_->rowCount(); ++i) {
        if (parameters_->item(i, 0)->checkState() != Qt::Checked) continue;
        varied.push_back(
            {parameters_->item(i, 0)->data(Qt::UserRole).toString().toStdString(),
             static_cast<QDoubleSpinBox*>(parameters_->cellWidget(i, kLowColumn))->value(),
             static_cast<QDoubleSpinBox*>(parameters_->cellWidget(i, kHighColumn))->value()});
    }
    nlohmann::json study = settings();
    for (const char* shown : {"page", "output", "band_samples"}) study.erase(shown);
    return {{"soil", io::toJson(in.soil)},
            {"wheel", io::toJson(in.wheel)},
            {"conditions", analysis::toJson(in.conditions)},
            {"source", source_->currentIndex()},
            {"varied", varied},
            {"study", study}};
}

nlohmann::json GlobalSensitivityPanel::bandInputs() const {
    nlohmann::json inputs = resultInputs();
    for (const char* indices_only : {"method", "samples"}) inputs["study"].erase(indices_only);
    inputs["study"]["band_samples"] = band_samples_->value();
    return inputs;
}

std::map<std::string, project::SavedResult> GlobalSensitivityPanel::savedResults() const {
    std::map<std::string, project::SavedResult> out;
    if (indices_ && !indices_hash_.empty()) {
        project::SavedResult& saved = out[name().toStdString()];
        saved.inputs_hash = indices_hash_;
        saved.version = project::kGlobalSensitivityVersion;
        saved.partial = indices_->status() == gsa::StudyStatus::kCancelled;
        saved.summary =
            QString("%1 model evaluations")
                .arg(indices_->sobol ? indices_->sobol->evaluations : indices_->morris->evaluations)
                .toStdString();
        saved.result = project::savedJson(*indices_);
        saved.tables.push_back({"indices", std::nullopt, indices_->table()});
    }
    if (bands_ && !bands_hash_.empty()) {
        project::SavedResult& saved = out[name().toStdString() + ".bands"];
        saved.inputs_hash = bands_hash_;
        saved.version = project::kUncertaintyBandsVersion;
        saved.partial = bands_->bands.status == gsa::StudyStatus::kCancelled;
        saved.summary = QString("%1 samples")
                            .arg(bands_->bands.used.empty() ? 0 : bands_->bands.used.front())
                            .toStdString();
        saved.result = project::savedJson(*bands_);
        saved.tables.push_back({"bands", std::nullopt, bands_->table()});
    }
    return out;
}

AnalysisPanel::Restored GlobalSensitivityPanel::restoreResult(const std::string& section,
                                                              const project::SavedResult& saved) {
    const bool bands = section == name().toStdString() + ".bands";
    if (!bands && section != name().toStdString()) return unreadable("not a section of this panel");
    if (saved.version !=
        (bands ? project::kUncertaintyBandsVersion : project::kGlobalSensitivityVersion))
        return unreadable("saved in form version " + std::to_string(saved.version));
    if (saved.inputs_hash != project::inputsHash(bands ? bandInputs() : resultInputs()))
        return inputsChanged();
    // After showSaved: marked as the saved result's completion ("CANCELLED (partial)").
    auto status = [this, &saved] {
        return markedStatus(
            QString("Saved with the project (%1); not recomputed — Compute runs it again.")
                .arg(QString::fromStdString(saved.summary).toHtmlEscaped()));
    };
    if (bands) {
        Result<analysis::UncertaintyBandResult> read =
            project::uncertaintyBandsFromJson(saved.result, section);
        if (!read) return unreadable(read.message());
        if (pages_->currentIndex() == 1) {
            // The page in view: shown as the panel's result (its first show computes nothing).
            showSaved(Computed{std::nullopt, std::move(read).value()}, inputsHash(), saved.partial);
            status_->setText(status());
        } else {
            bands_ = std::move(read).value();
            redraw();
        }
        bands_hash_ = saved.inputs_hash;
        return restoredShown();
    }
    Result<analysis::GlobalSensitivityResult> read =
        project::globalSensitivityResultFromJson(saved.result, section);
    if (!read) return unreadable(read.message());
    if (pages_->currentIndex() == 0) {
        showSaved(Computed{std::move(read).value(), std::nullopt}, saved.inputs_hash,
                  saved.partial);
        progress_->setValue(saved.partial ? 0 : 100);
        status_->setText(status());
    } else {
        indices_ = std::move(read).value();
        redraw();
    }
    indices_hash_ = saved.inputs_hash;
    return restoredShown();
}

}  // namespace terra::ui
