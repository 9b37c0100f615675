#include "widgets/panels/compaction_panel.h"

#include <qcustomplot.h>

#include <QComboBox>
#include <QDoubleSpinBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QPushButton>
#include <QSignalBlocker>
#include <QSpinBox>
#include <QTabWidget>
#include <QVBoxLayout>
#include <algorithm>
#include <cmath>

#include "core/contact/operating_fields.h"
#include "core/project/panels.h"
#include "core/project/saved_analyses.h"
#include "widgets/document/project_document.h"
#include "widgets/panels/summary_html.h"
#include "widgets/plots/compaction_figures.h"
#include "widgets/plots/figures.h"

namespace terra::ui {
namespace {

/// JSON equal up to rounding in the last digits (a profile read back from its JSON converts
/// Mg/m³ and hPa again).
bool nearlyEqual(const nlohmann::json& a, const nlohmann::json& b) {
    if (a.is_number() && b.is_number()) {
        const double x = a.get<double>(), y = b.get<double>();
        return std::abs(x - y) <= 1e-9 * std::max({1.0, std::abs(x), std::abs(y)});
    }
    if (a.type() != b.type() || a.size() != b.size()) return false;
    if (a.is_object()) {
        for (auto it = a.begin(); it != a.end(); ++it) {
            if (!b.contains(it.key()) || !nearlyEqual(*it, b[it.key()])) return false;
        }
        return true;
    }
    if (a.is_array()) {
        for (std::size_t i = 0; i < a.size(); ++i) {
            if (!nearlyEqual(a[i], b[i])) return false;
        }
        return true;
    }
    return a == b;
}

QWidget* page(QWidget* parent, QLayout* bar, QCustomPlot* plot) {
    auto* widget = new QWidget(parent);
    auto* layout = new QVBoxLayout(widget);
    layout->setContentsMargins(0, 0, 0, 0);
    if (bar) layout->addLayout(bar);
    layout->addWidget(plot, 1);
    return widget;
}

}  // namespace

CompactionPanel::CompactionPanel(ProjectDocument* document, io::PresetLocations locations,
                                 QWidget* parent)
    : AnalysisPanel(document, "compaction", parent), locations_(std::move(locations)) {
    const analysis::CompactionSettings defaults;
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
    passes_ = new QSpinBox(this);
    passes_->setObjectName("compaction.passes");
    passes_->setRange(1, kMaxPasses);
    passes_->setValue(defaults.passes);
    passes_->setToolTip("Wheels on the same track, each at the project's load and this slip");
    profile_ = new QComboBox(this);
    profile_->setObjectName("compaction.profile");
    profile_->addItem("none / soil's own");
    profiles_.emplace_back();
    for (const std::string& name : io::presetNames(locations_, "profiles")) {
        if (const auto read = io::resolveProfile(locations_, name)) {
            profile_->addItem(QString::fromStdString(name));
            profiles_.emplace_back(read.value());
        }
    }
    profile_->setToolTip(
        "Soil profile: layers with their precompression stress σ_pc (risk), ν and compression law "
        "(resources/profiles). \"none / soil's own\": the soil file's profile, else none: no "
        "σ_pc, no risk, no bulk density");
    concentration_ = new QComboBox(this);
    concentration_->addItem("per layer", QVariant());
    concentration_->addItem("3 (Boussinesq)", 3.0);
    concentration_->addItem("4 (hard, dry)", 4.0);
    concentration_->addItem("5 (moist)", 5.0);
    concentration_->addItem("6 (wet, soft)", 6.0);
    concentration_->setToolTip(
        "Concentration factor ν of Söhne's stress propagation: per layer takes each layer's ν "
        "(5 without a profile); a larger ν carries the stress deeper");
    width_ = new QComboBox(this);
    width_->addItem("uniform", static_cast<int>(compaction::WidthProfile::kUniform));
    width_->addItem("parabolic", static_cast<int>(compaction::WidthProfile::kParabolic));
    width_->setToolTip(
        "Contact stress across the wheel's width: uniform (rigid wheel) or "
        "parabolic (compliant tyre)");
    readout_ = new QLabel(this);
    summary_ = new QLabel(this);
    compute_ = new QPushButton("Compute", this);
    compute_->setToolTip("Run this compaction study (Ctrl+R)");
    compute_->hide();
    summary_->setObjectName("compaction.summary");
    summary_->setTextFormat(Qt::RichText);
    summary_->setWordWrap(true);

    tabs_ = new QTabWidget(this);
    profile_plot_ = new QCustomPlot(this);
    map_plot_ = new QCustomPlot(this);
    passes_plot_ = new QCustomPlot(this);
    for (QCustomPlot* plot : {profile_plot_, map_plot_, passes_plot_})
        makeInteractive(plot, readout_);
    shown_pass_ = new QComboBox(this);
    shown_pass_->addItem("envelope (all passes)");
    map_pass_ = new QSpinBox(this);
    map_pass_->setRange(1, defaults.passes);
    map_pass_->setToolTip("The pass whose stress field the map shows");
    auto* profile_bar = new QHBoxLayout;
    profile_bar->addWidget(new QLabel("Show:", this));
    profile_bar->addWidget(shown_pass_);
    profile_bar->addStretch(1);
    auto* map_bar = new QHBoxLayout;
    map_bar->addWidget(new QLabel("σ_z in the wheel's centre plane during pass", this));
    map_bar->addWidget(map_pass_);
    map_bar->addStretch(1);
    tabs_->addTab(page(tabs_, profile_bar, profile_plot_), "Depth profile");
    tabs_->addTab(page(tabs_, map_bar, map_plot_), "Stress map");
    tabs_->addTab(page(tabs_, nullptr, passes_plot_), "Passes");

    // Two rows: one needed ~900 px, more than a 1024 px screen leaves the panel.
    auto* bar = new QHBoxLayout;
    bar->addWidget(new QLabel("Slip s:", this));
    bar->addWidget(slip_);
    bar->addWidget(new QLabel("Slip angle β:", this));
    bar->addWidget(slip_angle_);
    bar->addWidget(new QLabel("Passes:", this));
    bar->addWidget(passes_);
    bar->addWidget(new QLabel("Width:", this));
    bar->addWidget(width_);
    bar->addStretch(1);
    auto* soil_bar = new QHBoxLayout;
    soil_bar->addWidget(new QLabel("Profile:", this));
    soil_bar->addWidget(profile_);
    soil_bar->addWidget(new QLabel("ν:", this));
    soil_bar->addWidget(concentration_);
    soil_bar->addStretch(1);
    soil_bar->addWidget(readout_);
    auto* layout = new QVBoxLayout(this);
    layout->addLayout(bar);
    layout->addLayout(soil_bar);
    layout->addWidget(tabs_, 1);
    auto* summary_bar = new QHBoxLayout;
    summary_bar->addWidget(summary_, 1);
    summary_bar->addWidget(compute_);
    layout->addLayout(summary_bar);

    for (QDoubleSpinBox* box : {slip_, slip_angle_})
        connect(box, &QDoubleSpinBox::valueChanged, this, &CompactionPanel::edited);
    for (QSpinBox* box : {passes_, map_pass_})
        connect(box, &QSpinBox::valueChanged, this, &CompactionPanel::edited);
    for (QComboBox* box : {profile_, concentration_, width_})
        connect(box, &QComboBox::currentIndexChanged, this, &CompactionPanel::edited);
    connect(shown_pass_, &QComboBox::currentIndexChanged, this, &CompactionPanel::drawProfile);
    connect(compute_, &QPushButton::clicked, this, &CompactionPanel::recompute);
    connect(this, &AnalysisPanel::failed, summary_,
            [this](const QString& m) { summary_->setText("<b>Error:</b> " + m.toHtmlEscaped()); });
    scheduleUpdate();
}

void CompactionPanel::edited() {
    map_pass_->setMaximum(passes_->value());
    storeSettings();
    scheduleUpdate();
}

analysis::CompactionSettings CompactionPanel::current() const {
    analysis::CompactionSettings s = applied_;
    s.slip = slip_->value();
    s.slip_angle_deg = slip_angle_->value();
    s.passes = passes_->value();
    const QVariant nu = concentration_->currentData();
    s.concentration = nu.isValid() ? std::optional<double>(nu.toDouble()) : std::nullopt;
    s.width = static_cast<compaction::WidthProfile>(width_->currentData().toInt());
    s.profile = profiles_[static_cast<std::size_t>(std::max(profile_->currentIndex(), 0))];
    s.map_x_points = kMapXPoints;
    s.map_z_points = kMapZPoints;
    s.map_pass = std::clamp(map_pass_->value(), 1, s.passes);
    return s;
}

nlohmann::json CompactionPanel::settings() const {
    return project::toJson(project::CompactionPanelSettings{current()});
}

void CompactionPanel::applySettings(const nlohmann::json& json) {
    nlohmann::json all = withChanges(json);
    if (json.is_object() && json.contains("depths_m")) {
        for (const char* key : {"concentration", "profile"}) {
            if (!json.contains(key)) all.erase(key);
        }
    }
    std::vector<Issue> issues;
    io::ObjectReader r(all, issues);
    project::CompactionPanelSettings read;
    project::readPanelSettings(r, read, &locations_);  // a profile may be a preset's name
    r.finish();
    if (!issues.empty()) return;  // projects are checked when opened: only a program error
    applied_ = read.analysis;
    {
        const QSignalBlocker b1(slip_), b2(slip_angle_), b3(passes_), b4(map_pass_), b5(width_);
        slip_->setValue(applied_.slip);
        slip_angle_->setValue(applied_.slip_angle_deg);
        passes_->setMaximum(std::max(kMaxPasses, applied_.passes));
        passes_->setValue(applied_.passes);
        map_pass_->setMaximum(applied_.passes);
        map_pass_->setValue(applied_.map_pass);
        width_->setCurrentIndex(width_->findData(static_cast<int>(applied_.width)));
        selectProfile(applied_.profile);
        selectConcentration(applied_.concentration);
    }
    edited();
}

void CompactionPanel::selectProfile(const std::optional<soil::SoilProfile>& profile) {
    const QSignalBlocker block(profile_);
    if (!profile) {
        profile_->setCurrentIndex(0);
        return;
    }
    const nlohmann::json wanted = io::toJson(*profile);
    for (std::size_t i = 1; i < profiles_.size(); ++i) {
        if (nearlyEqual(io::toJson(*profiles_[i]), wanted)) {
            profile_->setCurrentIndex(static_cast<int>(i));
            return;
        }
    }
    // Not a preset (edited, or from a file): kept as an item of its own.
    profile_->addItem(QString::fromStdString(profile->name) + " (project)");
    profiles_.push_back(profile);
    profile_->setCurrentIndex(profile_->count() - 1);
}

void CompactionPanel::selectConcentration(const std::optional<double>& nu) {
    const QSignalBlocker block(concentration_);
    int i = nu ? concentration_->findData(*nu) : 0;
    if (i < 0) {
        concentration_->addItem(QString::number(*nu), *nu);
        i = concentration_->count() - 1;
    }
    concentration_->setCurrentIndex(i);
}

int CompactionPanel::shownPass() const { return std::max(shown_pass_->currentIndex(), 0); }

void CompactionPanel::showPass(int pass) { shown_pass_->setCurrentIndex(pass); }

QString CompactionPanel::summary() const { return summary_->text(); }

QCustomPlot* CompactionPanel::currentPlot() const {
    const int tab = tabs_->currentIndex();
    return tab == 1 ? map_plot_ : tab == 2 ? passes_plot_ : profile_plot_;
}

Table CompactionPanel::currentTable() const {
    const int tab = tabs_->currentIndex();
    if (tab == 1) return shown_.result.map;
    analysis::CompactionResult shown;  // the profile on screen, in compactionOutcome's columns
    const int pass = shownPass();
    shown.envelope = pass == 0 || pass > static_cast<int>(shown_.result.passes.size())
                         ? shown_.result.envelope
                         : shown_.result.passes[static_cast<std::size_t>(pass - 1)].profile;
    shown.passes = shown_.result.passes;
    shown.profile = shown_.result.profile;
    const analysis::Outcome outcome = analysis::compactionOutcome(std::move(shown));
    return *outcome.table(tab == 2 ? "passes" : "profile");
}

AnalysisPanel::Job CompactionPanel::makeJob() {
    const analysis::Inputs inputs = project::inputsOf(document_->project());
    const analysis::CompactionSettings settings = current();
    return [inputs, settings](const std::atomic<bool>& cancel) -> std::any {
        return Shown{settings, analysis::computeCompaction(inputs, settings, {&cancel})};
    };
}

bool CompactionPanel::startsByItself() {
    const analysis::CompactionSettings s = current();
    const std::size_t work = static_cast<std::size_t>(s.passes) * s.depths_m.size();
    if (work <= static_cast<std::size_t>(kAutomaticPassDepths)) return true;
    std::vector<QCustomPlot*> cleared;
    if (!hasResult()) {
        for (const auto& [name, plot] : plots()) cleared.push_back(plot);
    }
    showNotComputed(summary_,
                    QString("Not computed: %1 passes at %2 depths is a long run — press Compute "
                            "(Ctrl+R) to run it.")
                        .arg(s.passes)
                        .arg(s.depths_m.size()),
                    cleared, compute_);
    return false;
}

void CompactionPanel::present(const std::any& value) {
    compute_->hide();
    shown_ = std::any_cast<Shown>(value);
    setCompletion(compactionCompletion(shown_.result));
    {
        const QSignalBlocker block(shown_pass_);
        const int keep = shown_pass_->currentIndex();
        shown_pass_->clear();
        shown_pass_->addItem("envelope (all passes)");
        for (const analysis::CompactionPass& p : shown_.result.passes)
            shown_pass_->addItem(QString("pass %1").arg(p.pass));
        shown_pass_->setCurrentIndex(keep < shown_pass_->count() ? std::max(keep, 0) : 0);
    }
    redraw();
    summary_->setText(summaryText());
}

QString CompactionPanel::baseTitle() const {
    const Project& p = document_->project();
    const analysis::CompactionSettings& s = shown_.settings;
    // Two lines: on one, with "envelope of 3 passes" after it, it was cut at both ends in a
    // tiled panel (1366×768) and at 1024×700.
    return QString("%1, %2, W = %3 N\ns = %4, β = %5°")
        .arg(QString::fromStdString(p.soil.name), QString::fromStdString(p.wheel.name))
        .arg(shown_.result.load_n)
        .arg(s.slip)
        .arg(s.slip_angle_deg);
}

void CompactionPanel::drawProfile() {
    const int pass = shownPass(), passes = shown_.settings.passes;
    const QString title = pass == 0
                              ? QString("%1: envelope of %2 %3")
                                    .arg(baseTitle())
                                    .arg(passes)
                                    .arg(passes == 1 ? "pass" : "passes")
                              : QString("%1: pass %2 of %3").arg(baseTitle()).arg(pass).arg(passes);
    plotCompactionProfile(*profile_plot_, shown_.result, pass,
                          compactionTitle(title, shown_.result));
}

void CompactionPanel::redraw() {
    const analysis::CompactionResult& r = shown_.result;
    drawProfile();
    plotCompactionMap(
        *map_plot_, r,
        compactionTitle(QString("%1: pass %2").arg(baseTitle()).arg(shown_.settings.map_pass), r));
    plotCompactionPasses(*passes_plot_, r, compactionTitle(baseTitle(), r));
}

QString CompactionPanel::summaryText() const {
    // The core summary (what `terrastudio compaction` prints) but its heading, which the plots'
    // titles give; a cancelled or failed run marked first.
    const analysis::Summary summary = analysis::compactionSummary(
        project::inputsOf(document_->project()), shown_.settings, shown_.result);
    const std::span<const analysis::SummaryRow> rows(summary.begin() + 1, summary.end());
    const QString status = shown_.result.ok() ? QString() : markedStatus(QString());
    return status.isEmpty() ? summaryHtml(rows) : status + "<br>" + summaryHtml(rows);
}

std::map<std::string, project::SavedResult> CompactionPanel::savedResults() const {
    // A long run cancelled is kept (marked partial): Compute runs it again.
    return savedSection(project::kCompactionVersion, project::savedJson(shown_.result),
                        QString("%1 passes").arg(shown_.result.passes.size()).toStdString(), true);
}

AnalysisPanel::Restored CompactionPanel::restoreResult(const std::string& section,
                                                       const project::SavedResult& saved) {
    return restoreSection(
        section, saved, project::kCompactionVersion,
        [this](const nlohmann::json& json, const std::string& where) -> std::any {
            // The settings it was computed with are the panel's: the inputs hash as now.
            return Shown{current(), valueOrThrow(project::compactionResultFromJson(json, where))};
        });
}

}  // namespace terra::ui
