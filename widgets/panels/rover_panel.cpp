#include "widgets/panels/rover_panel.h"

#include <qcustomplot.h>

#include <QCheckBox>
#include <QComboBox>
#include <QDialogButtonBox>
#include <QDoubleSpinBox>
#include <QFileInfo>
#include <QFontDatabase>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QPlainTextEdit>
#include <QPointer>
#include <QProgressBar>
#include <QPushButton>
#include <QSignalBlocker>
#include <QSlider>
#include <QTabWidget>
#include <QTableWidget>
#include <QTimer>
#include <QVBoxLayout>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>

#include "core/analysis/rover.h"
#include "core/io/atomic_file.h"
#include "core/io/json.h"
#include "core/project/panels.h"
#include "core/project/project.h"
#include "core/project/saved_rover.h"
#include "core/scenario/scenario_json.h"
#include "widgets/document/project_document.h"
#include "widgets/panels/summary_html.h"
#include "widgets/plots/field_layers.h"
#include "widgets/plots/figures.h"
#include "widgets/plots/rover_figures.h"

namespace terra::ui {
namespace {

namespace fs = std::filesystem;

/// The result of "Compare controllers": the chosen controller's run and the table.
struct Comparison {
    std::optional<analysis::RoverResult> shown;
    nlohmann::json table;
};

/// The file of a scenario: a preset's name, or the path of a scenario file of the project
/// (project::isScenarioFileName); empty when there is none.
fs::path presetFile(const io::PresetLocations& locations, const std::string& name) {
    std::error_code ec;
    if (project::isScenarioFileName(name))
        return fs::is_regular_file(name, ec) ? fs::path(name) : fs::path();
    for (const fs::path& dir : locations.directories) {
        const fs::path candidate = dir / "scenarios" / (name + ".json");
        if (fs::is_regular_file(candidate, ec)) return candidate;
    }
    return {};
}

}  // namespace

Result<scenario::Scenario> parseScenarioText(const QString& text, const std::string& name,
                                             const io::PresetLocations& locations) {
    const std::string where = "edited " + name;
    const Result<nlohmann::json> json = io::parseJson(text.toStdString(), where);
    if (!json) return json.issues();
    // Relative files (soils, robots) resolve against the preset's directory, as for the file.
    return scenario::scenarioFromJson(json.value(), where, locations,
                                      presetFile(locations, name).parent_path());
}

// ---------------------------------------------------------------------------------------------

ScenarioDialog::ScenarioDialog(const QString& name, const QString& text,
                               io::PresetLocations locations, QWidget* parent)
    : QDialog(parent), name_(name.toStdString()), locations_(std::move(locations)) {
    setWindowTitle("Edit scenario " + name);
    edit_ = new QPlainTextEdit(this);
    edit_->setFont(QFontDatabase::systemFont(QFontDatabase::FixedFont));
    edit_->setLineWrapMode(QPlainTextEdit::NoWrap);
    error_ = new QLabel(this);
    error_->setWordWrap(true);
    error_->setTextInteractionFlags(Qt::TextSelectableByMouse);
    buttons_ = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel, this);
    auto* layout = new QVBoxLayout(this);
    layout->addWidget(
        new QLabel("Scenario as JSON (format: docs/dynamics.md, \"Scenario\"):", this));
    layout->addWidget(edit_, 1);
    layout->addWidget(error_);
    layout->addWidget(buttons_);
    resize(720, 600);
    connect(buttons_, &QDialogButtonBox::accepted, this, &QDialog::accept);
    connect(buttons_, &QDialogButtonBox::rejected, this, &QDialog::reject);
    connect(edit_, &QPlainTextEdit::textChanged, this, &ScenarioDialog::validate);
    setText(text);
}

QString ScenarioDialog::text() const { return edit_->toPlainText(); }
void ScenarioDialog::setText(const QString& text) { edit_->setPlainText(text); }  // validates
QString ScenarioDialog::errorText() const { return valid_ ? QString() : error_->text(); }
bool ScenarioDialog::okEnabled() const {
    return buttons_->button(QDialogButtonBox::Ok)->isEnabled();
}

void ScenarioDialog::validate() {
    const auto parsed = parseScenarioText(edit_->toPlainText(), name_, locations_);
    valid_ = parsed.ok();
    buttons_->button(QDialogButtonBox::Ok)->setEnabled(valid_);
    if (valid_) {
        error_->setStyleSheet("color: palette(text);");
        error_->setText(QString("Valid: %1 s at %2 s steps on %3.")
                            .arg(parsed->duration_s)
                            .arg(parsed->time_step_s)
                            .arg(QString::fromStdString(parsed->terrain.base.name)));
    } else {
        error_->setStyleSheet("color: #c0392b;");
        error_->setText(QString::fromStdString(parsed.message()));
    }
}

// ---------------------------------------------------------------------------------------------

RoverPanel::RoverPanel(ProjectDocument* document, io::PresetLocations locations, QWidget* parent)
    : AnalysisPanel(document, "rover", parent), locations_(std::move(locations)) {
    setLive(false);  // scenarios use their own soils and robot; they run on request
    scenario_ = new QComboBox(this);
    for (const std::string& name : io::presetNames(locations_, "scenarios"))
        scenario_->addItem(QString::fromStdString(name));
    edit_ = new QPushButton("Edit…", this);
    edit_->setToolTip("Edit the scenario as JSON (kept in the project)");
    revert_ = new QPushButton("Revert", this);
    revert_->setToolTip("Drop the edit: back to the scenario file");
    edited_label_ = new QLabel(this);
    duration_ = new QDoubleSpinBox(this);
    duration_->setRange(0.01, 86400.0);
    duration_->setDecimals(2);
    duration_->setSuffix(" s");
    duration_->setToolTip("Simulated time (edits the scenario's duration_s)");
    duration_->setKeyboardTracking(false);
    controller_ = new QComboBox(this);
    controller_->setObjectName("rover.controller");
    for (const std::string& name : scenario::controllerNames())
        controller_->addItem(QString::fromStdString(name));
    controller_->setToolTip(
        "How the wheels are driven: the scenario's wheel speeds, or slip held at a fixed, "
        "optimal (streaming estimate) or oracle set-point (edits the scenario's controller; "
        "docs/traction.md)");
    slip_set_ = new QDoubleSpinBox(this);
    slip_set_->setObjectName("rover.slip");
    slip_set_->setRange(0.01, 0.95);
    slip_set_->setDecimals(3);
    slip_set_->setSingleStep(0.01);
    slip_set_->setToolTip("Slip set-point of fixed-slip; optimal's until its first soil estimate");
    slip_set_->setKeyboardTracking(false);
    traction_limited_ = new QCheckBox("Traction-limited", this);
    traction_limited_->setObjectName("rover.traction_limited");
    traction_limited_->setToolTip(
        "When the wheels stall with their slip above the set-point (a slope, a heavy implement), "
        "raise the set-point to the slip the robot needs, up to the drawbar-maximising slip, and "
        "drop back when the need falls (edits the scenario's controller; docs/traction.md §5)");
    robust_ = new QComboBox(this);
    robust_->setObjectName("rover.robust");
    for (const char* name : {"none", "expected", "quantile"}) robust_->addItem(name);
    robust_->setToolTip(
        "Optimal: plan s* of the soil estimate (none), or over its posterior the slip of the "
        "largest expected efficiency (expected) or of its largest lower quantile (quantile) "
        "(edits the scenario's controller; docs/traction.md §8)");
    quantile_ = new QDoubleSpinBox(this);
    quantile_->setObjectName("rover.quantile");
    const FieldInfo& quantile = scenario::robustQuantileField();
    quantile_->setRange(quantile.range.low, quantile.range.high);
    quantile_->setDecimals(2);
    quantile_->setSingleStep(0.05);
    quantile_->setToolTip(QString::fromUtf8(quantile.description));
    quantile_->setKeyboardTracking(false);
    identifier_ = new QComboBox(this);
    identifier_->setObjectName("rover.identifier");
    for (const char* name : {"decoupled", "full"}) identifier_->addItem(name);
    identifier_->setToolTip(
        "Optimal: the streaming soil estimator it plans on: the thesis's decoupled model on a "
        "sliding window, or the full wheel model's moving-horizon estimator (edits the "
        "scenario's controller; docs/traction.md §8)");
    run_ = new QPushButton("Run", this);
    compare_ = new QPushButton("Compare controllers", this);
    compare_->setObjectName("rover.compare");
    compare_->setToolTip(
        "Run the scenario under each controller (constant-speed, fixed-slip, optimal, oracle) and "
        "show the comparison table; the figures show the chosen controller's run "
        "(docs/traction.md §6)");
    cancel_ = new QPushButton("Cancel", this);
    cancel_->setEnabled(false);
    progress_ = new QProgressBar(this);
    trackProgress(progress_);
    status_ = new QLabel(this);
    status_->setObjectName("rover.summary");
    status_->setWordWrap(true);
    readout_ = new QLabel(this);
    tabs_ = new QTabWidget(this);

    // Top view with its scrubber first: where the robot is, on which soil.
    auto* view_page = new QWidget(tabs_);
    top_view_ = new QCustomPlot(view_page);
    makeInteractive(top_view_, readout_);
    scrubber_ = new QSlider(Qt::Horizontal, view_page);
    scrubber_->setRange(0, 0);
    scrubber_->setEnabled(false);
    scrubber_->setToolTip("Time: drag, or use the arrow keys to step through the run");
    time_ = new QLabel("t = – s", view_page);
    time_->setMinimumWidth(time_->fontMetrics().horizontalAdvance("t = 000.00 s, ψ = -000.00°"));
    play_ = new QPushButton("Play", view_page);
    play_->setCheckable(true);
    play_->setEnabled(false);
    player_ = new QTimer(this);
    player_->setInterval(40);
    layer_label_ = new QLabel("Layer:", view_page);
    layer_ = new QComboBox(view_page);
    layer_->setObjectName("rover.layer");
    layer_->setSizeAdjustPolicy(QComboBox::AdjustToContents);
    layer_->setToolTip(
        "The field map drawn under the track: the field's height and soil classes, or a map the "
        "run left (rut depth, passes, compaction risk, ...) as it was at the time shown "
        "(docs/user-guide.md, \"Field layers\")");
    layer_label_->setVisible(false);  // a field's: listLayers shows them
    layer_->setVisible(false);
    auto* scrub_bar = new QHBoxLayout;
    scrub_bar->addWidget(play_);
    scrub_bar->addWidget(scrubber_, 1);
    scrub_bar->addWidget(time_);
    scrub_bar->addWidget(layer_label_);
    scrub_bar->addWidget(layer_);
    auto* view_layout = new QVBoxLayout(view_page);
    view_layout->setContentsMargins(0, 0, 0, 0);
    view_layout->addWidget(top_view_, 1);
    view_layout->addLayout(scrub_bar);
    tabs_->addTab(view_page, "Top view");
    for (const RoverFigure& figure : roverFigures()) {
        auto* plot = new QCustomPlot(tabs_);
        makeInteractive(plot, readout_);
        plots_.push_back(plot);
        tabs_->addTab(plot, figure.tab);
        if (!figure.thesis.isEmpty())
            tabs_->setTabToolTip(tabs_->count() - 1, "Thesis " + figure.thesis);
    }
    // The comparison of the controllers, after the figures.
    comparison_table_ = new QTableWidget(tabs_);
    comparison_table_->setObjectName("rover.comparison");
    comparison_table_->setEditTriggers(QAbstractItemView::NoEditTriggers);
    comparison_table_->verticalHeader()->setVisible(false);
    tabs_->addTab(comparison_table_, "Comparison");
    tabs_->setTabToolTip(tabs_->count() - 1,
                         "The controllers compared on this scenario (Compare controllers)");
    drawn_.assign(plots_.size(), true);  // nothing to draw yet
    connect(tabs_, &QTabWidget::currentChanged, this, [this](int index) {
        if (index <= 0 || static_cast<std::size_t>(index) > plots_.size()) return;
        const auto i = static_cast<std::size_t>(index - 1);
        if (drawn_[i]) {
            plots_[i]->replot(QCustomPlot::rpQueuedReplot);  // its cursor may have moved
        } else {
            drawFigure(i);
        }
    });

    // Rows: what runs, how the wheels are driven, then running it. One row needed ~1000 px, more
    // than a 1024 px screen leaves the panel.
    auto* bar = new QHBoxLayout;
    bar->addWidget(new QLabel("Scenario:", this));
    bar->addWidget(scenario_, 1);
    bar->addWidget(edit_);
    bar->addWidget(revert_);
    bar->addWidget(edited_label_);
    bar->addWidget(new QLabel("Duration:", this));
    bar->addWidget(duration_);
    // How the wheels are driven, on a row of its own (on the first one the panel no longer fits
    // 1024 px: tests/app/main_window_test.cpp).
    auto* control_bar = new QHBoxLayout;
    control_bar->addWidget(new QLabel("Controller:", this));
    control_bar->addWidget(controller_);
    control_bar->addWidget(new QLabel("Slip set-point:", this));
    control_bar->addWidget(slip_set_);
    control_bar->addWidget(traction_limited_);
    control_bar->addStretch(1);
    // The optimal controller's set-point and soil estimator, on a row of their own (beside the
    // controller the panel no longer fits 1024 px).
    auto* optimal_bar = new QHBoxLayout;
    optimal_bar->addWidget(new QLabel("Optimal: robust", this));
    optimal_bar->addWidget(robust_);
    optimal_bar->addWidget(new QLabel("quantile", this));
    optimal_bar->addWidget(quantile_);
    optimal_bar->addWidget(new QLabel("estimator", this));
    optimal_bar->addWidget(identifier_);
    optimal_bar->addStretch(1);
    auto* run_bar = new QHBoxLayout;
    run_bar->addWidget(run_);
    run_bar->addWidget(compare_);
    run_bar->addWidget(cancel_);
    run_bar->addWidget(progress_, 1);
    run_bar->addWidget(readout_, 1);
    auto* layout = new QVBoxLayout(this);
    layout->addLayout(bar);
    layout->addLayout(control_bar);
    layout->addLayout(optimal_bar);
    layout->addLayout(run_bar);
    layout->addWidget(tabs_, 1);
    layout->addWidget(status_);

    listScenarioFiles();
    connect(document_, &ProjectDocument::scenariosChanged, this, &RoverPanel::listScenarioFiles);
    connect(scenario_, &QComboBox::currentIndexChanged, this, [this] {
        showScenarioState();
        storeSettings();
    });
    connect(edit_, &QPushButton::clicked, this, &RoverPanel::editScenario);
    connect(revert_, &QPushButton::clicked, this, &RoverPanel::revertScenario);
    connect(duration_, &QDoubleSpinBox::valueChanged, this, [this](double seconds) {
        nlohmann::json json = currentJson();
        if (!json.is_object() || json.value("duration_s", -1.0) == seconds) return;
        json["duration_s"] = seconds;
        QString error;
        if (!setScenarioText(QString::fromStdString(json.dump(2)), &error))
            status_->setText("<b>Error:</b> " + error.toHtmlEscaped());
    });
    connect(controller_, &QComboBox::currentTextChanged, this,
            [this](const QString& type) { setControllerValue("type", type.toStdString()); });
    connect(slip_set_, &QDoubleSpinBox::valueChanged, this,
            [this](double slip) { setControllerValue("slip", slip); });
    connect(traction_limited_, &QCheckBox::toggled, this,
            [this](bool on) { setControllerValue("traction_limited", on); });
    connect(robust_, &QComboBox::currentTextChanged, this,
            [this](const QString& robust) { setControllerValue("robust", robust.toStdString()); });
    connect(quantile_, &QDoubleSpinBox::valueChanged, this,
            [this](double q) { setControllerValue("quantile", q); });
    connect(identifier_, &QComboBox::currentTextChanged, this,
            [this](const QString& name) { setControllerValue("identifier", name.toStdString()); });
    connect(scrubber_, &QSlider::valueChanged, this, &RoverPanel::scrubTo);
    connect(layer_, &QComboBox::currentIndexChanged, this, [this] {
        const QString key = layerKey();
        layer_choice_ = key.isEmpty() ? "none" : key.toStdString();
        drawLayer();
    });
    connect(play_, &QPushButton::toggled, this, [this](bool on) {
        if (on && scrubber_->value() >= scrubber_->maximum()) scrubber_->setValue(0);
        on ? player_->start() : player_->stop();
    });
    connect(player_, &QTimer::timeout, this, [this] {
        // About 10 s of simulated time per second of playback, at least one row per tick.
        const int step = std::max(1, (scrubber_->maximum() + 1) / 150);
        if (scrubber_->value() >= scrubber_->maximum()) {
            play_->setChecked(false);
            return;
        }
        scrubber_->setValue(std::min(scrubber_->maximum(), scrubber_->value() + step));
    });
    connect(run_, &QPushButton::clicked, this, [this] {
        storeSettings();
        compare_next_ = false;
        recompute();
    });
    connect(compare_, &QPushButton::clicked, this, [this] {
        storeSettings();
        compare_next_ = true;
        recompute();
    });
    connect(cancel_, &QPushButton::clicked, this, [this] {
        status_->setText("Cancelling…");
        cancelRunning();
    });
    connect(this, &AnalysisPanel::busyChanged, this, [this](bool busy) {
        run_->setEnabled(!busy);
        compare_->setEnabled(!busy);
        cancel_->setEnabled(busy);
        edit_->setEnabled(!busy);
        if (busy) {
            status_->setText("Running…");
            // The plots of the previous run are not this run's: say so in their titles (they
            // used to keep "… completed" while the new run went on).
            if (!title_.isEmpty()) {
                retitle(QString("%1 — previous run; running %2…")
                            .arg(QString::fromStdString(shown_name_), scenario_->currentText()));
            }
        }
    });
    connect(this, &AnalysisPanel::failed, this, [this](const QString& m) {
        run_->setEnabled(true);
        compare_->setEnabled(true);
        cancel_->setEnabled(false);
        edit_->setEnabled(true);
        status_->setText("<b>Error:</b> " + m.toHtmlEscaped());
    });
    showScenarioState();
}

void RoverPanel::requestRun() {
    if (run_->isEnabled()) run_->click();
}

void RoverPanel::requestComparison() {
    if (compare_->isEnabled()) compare_->click();
}

void RoverPanel::drawFigure(std::size_t i) const {
    if (i >= plots_.size() || drawn_[i]) return;
    plotRoverFigure(*plots_[i], result_.series, roverFigures()[i].key, title_);
    setRoverTimeCursor(*plots_[i], result_.series, roverFigures()[i].key,
                       static_cast<std::size_t>(scrubber_->value()));
    plots_[i]->replot(QCustomPlot::rpQueuedReplot);
    drawn_[i] = true;
}

void RoverPanel::plotShownOutside(QCustomPlot* plot) {
    AnalysisPanel::plotShownOutside(plot);
    for (std::size_t i = 0; i < plots_.size(); ++i) {
        if (plots_[i] == plot) drawFigure(i);
    }
}

std::vector<std::pair<QString, QCustomPlot*>> RoverPanel::plots() const {
    std::vector<std::pair<QString, QCustomPlot*>> out;
    for (std::size_t i = 0; i < plots_.size(); ++i) {
        drawFigure(i);  // exports and tests see every figure of the current run
        out.emplace_back(QString::fromStdString("rover-" + roverFigures()[i].key), plots_[i]);
    }
    out.emplace_back("rover-top-view", top_view_);
    return out;
}

QCustomPlot* RoverPanel::currentPlot() const {
    const int i = tabs_->currentIndex();
    if (i <= 0 || static_cast<std::size_t>(i) > plots_.size()) return top_view_;
    drawFigure(static_cast<std::size_t>(i - 1));
    return plots_[static_cast<std::size_t>(i - 1)];
}

std::string RoverPanel::nameAt(int index) const {
    // A scenario file's item holds its path; a preset's is its name.
    const QVariant path = scenario_->itemData(index);
    return (path.isValid() ? path.toString() : scenario_->itemText(index)).toStdString();
}

std::string RoverPanel::currentName() const { return nameAt(scenario_->currentIndex()); }

int RoverPanel::scenarioIndex(const std::string& name) const {
    for (int i = 0; i < scenario_->count(); ++i) {
        if (nameAt(i) == name) return i;
    }
    return -1;
}

void RoverPanel::listScenarioFiles() {
    const std::string current = currentName();
    const QSignalBlocker block(scenario_);
    for (int i = scenario_->count() - 1; i >= 0; --i) {
        if (scenario_->itemData(i).isValid()) scenario_->removeItem(i);
    }
    for (const std::string& path : document_->project().scenarios) {
        const QString file = QString::fromStdString(path);
        scenario_->addItem(QFileInfo(file).fileName(), file);
        scenario_->setItemData(scenario_->count() - 1, file, Qt::ToolTipRole);
    }
    const int i = scenarioIndex(current);
    if (i >= 0) {
        scenario_->setCurrentIndex(i);
        return;
    }
    // The file shown was removed (Add scenario undone): back to the first preset.
    scenario_->setCurrentIndex(0);
    showScenarioState();
    storeSettings();
}

bool RoverPanel::chooseScenario(const QString& name) {
    const int i = scenarioIndex(name.toStdString());
    if (i < 0) return false;
    scenario_->setCurrentIndex(i);
    return true;
}

bool RoverPanel::useRobotFile(const QString& path, QString* error) {
    nlohmann::json json = currentJson();
    if (!json.is_object()) {
        if (error) *error = "the current scenario cannot be read";
        return false;
    }
    json["robot"] = QFileInfo(path).absoluteFilePath().toStdString();
    return setScenarioText(QString::fromStdString(json.dump(2)), error);
}

nlohmann::json RoverPanel::settings() const {
    return project::toJson(project::RoverPanelSettings{currentName(), edits_});
}

void RoverPanel::applySettings(const nlohmann::json& json) {
    const auto settings =
        project::panelSettingsFromJson<project::RoverPanelSettings>(withChanges(json));
    if (!settings) return;  // projects are checked when opened: only a program error lands here
    edits_ = settings->edited;
    const int i = scenarioIndex(settings->scenario);
    if (i >= 0) scenario_->setCurrentIndex(i);
    showScenarioState();
}

nlohmann::json RoverPanel::currentJson() const {
    const std::string name = currentName();
    if (edits_.contains(name)) return edits_[name];
    const fs::path file = presetFile(locations_, name);
    if (file.empty()) return nullptr;
    const Result<nlohmann::json> json = io::readJsonFile(file);
    return json ? json.value() : nlohmann::json();
}

QString RoverPanel::scenarioText() const {
    const std::string name = currentName();
    if (!edits_.contains(name)) {
        std::string text;
        const fs::path file = presetFile(locations_, name);
        if (!file.empty() && !io::readFile(file, text))
            return QString::fromStdString(text);  // as written
    }
    const nlohmann::json json = currentJson();
    return json.is_null() ? QString() : QString::fromStdString(json.dump(2));
}

bool RoverPanel::isEdited() const { return edits_.contains(currentName()); }

bool RoverPanel::setScenarioText(const QString& text, QString* error) {
    const auto parsed = parseScenarioText(text, currentName(), locations_);
    if (!parsed) {
        if (error) *error = QString::fromStdString(parsed.message());
        return false;
    }
    storeEdit(io::parseJson(text.toStdString(), {}).value());
    return true;
}

void RoverPanel::storeEdit(const nlohmann::json& json) {
    edits_[currentName()] = json;
    storeSettings();  // into the project: saved with it
    showScenarioState();
}

void RoverPanel::setControllerValue(const std::string& key, const nlohmann::json& value) {
    nlohmann::json json = currentJson();
    if (!json.is_object()) return;
    nlohmann::json controller = json.value("controller", nlohmann::json::object());
    if (!controller.is_object()) return;  // the reader names the problem at Run
    if (controller.value(key, nlohmann::json()) == value) return;
    // The default (constant speed) of a scenario without a controller stays without one.
    if (key == "type" && value == "constant-speed" && !json.contains("controller")) return;
    controller[key] = value;
    if (!controller.contains("type")) controller["type"] = controller_->currentText().toStdString();
    json["controller"] = controller;
    QString error;
    if (!setScenarioText(QString::fromStdString(json.dump(2)), &error))
        status_->setText("<b>Error:</b> " + error.toHtmlEscaped());
}

void RoverPanel::revertScenario() {
    edits_.erase(currentName());
    storeSettings();
    showScenarioState();
}

void RoverPanel::showScenarioState() {
    const bool edited = isEdited();
    edited_label_->setText(edited ? "<i>edited</i>" : QString());
    revert_->setEnabled(edited);
    const nlohmann::json json = currentJson();
    const QSignalBlocker block(duration_);
    if (json.is_object() && json.contains("duration_s") && json["duration_s"].is_number()) {
        duration_->setValue(json["duration_s"].get<double>());
    }
    {
        const QSignalBlocker block_type(controller_);
        const QSignalBlocker block_slip(slip_set_);
        const QSignalBlocker block_limited(traction_limited_);
        const QSignalBlocker block_robust(robust_);
        const QSignalBlocker block_quantile(quantile_);
        const QSignalBlocker block_identifier(identifier_);
        const scenario::ControllerSpec defaults;
        std::string type = scenario::controllerName(defaults.type);
        double slip = defaults.slip;
        bool limited = defaults.traction_limited;
        std::string robust = scenario::robustSlipName(defaults.robust);
        double quantile = defaults.quantile;
        std::string identifier = scenario::soilIdentifierName(defaults.identifier);
        if (json.is_object() && json.contains("controller") && json["controller"].is_object()) {
            const nlohmann::json& c = json["controller"];
            if (c.contains("type") && c["type"].is_string()) type = c["type"].get<std::string>();
            if (c.contains("slip") && c["slip"].is_number()) slip = c["slip"].get<double>();
            if (c.contains("traction_limited") && c["traction_limited"].is_boolean())
                limited = c["traction_limited"].get<bool>();
            if (c.contains("robust") && c["robust"].is_string())
                robust = c["robust"].get<std::string>();
            if (c.contains("quantile") && c["quantile"].is_number())
                quantile = c["quantile"].get<double>();
            if (c.contains("identifier") && c["identifier"].is_string())
                identifier = c["identifier"].get<std::string>();
        }
        controller_->setCurrentText(QString::fromStdString(type));
        slip_set_->setValue(slip);
        slip_set_->setEnabled(type == "fixed-slip" || type == "optimal");
        traction_limited_->setChecked(limited);
        traction_limited_->setEnabled(type != "constant-speed");
        robust_->setCurrentText(QString::fromStdString(robust));
        quantile_->setValue(quantile);
        identifier_->setCurrentText(QString::fromStdString(identifier));
        robust_->setEnabled(type == "optimal");
        quantile_->setEnabled(type == "optimal" && robust == "quantile");
        identifier_->setEnabled(type == "optimal");
    }
    previewScenario();
}

namespace {

/// "sandy loam; patches: clay, wet sand" — the soils a scenario drives on.
QString soilsOf(const scenario::Scenario& scenario) {
    if (scenario.field) {
        // "the field Sloped field with a wet hollow (field: sandy loam; wet hollow: lean clay)".
        QStringList classes;
        for (const auto& [code, soil] : scenario.field->legend) {
            const auto label = scenario.field_labels.find(code);
            const QString name = QString::fromStdString(soil.name);
            classes << (label != scenario.field_labels.end() && !label->second.empty() &&
                                label->second != soil.name
                            ? QString::fromStdString(label->second) + ": " + name
                            : name);
        }
        const QString field = QString::fromStdString(scenario.field->name);
        return (field.isEmpty() ? QString("a field") : "the field " + field) +
               (classes.isEmpty() ? QString() : " (" + classes.join("; ") + ")");
    }
    QString text = QString::fromStdString(scenario.terrain.base.name);
    QStringList patches;
    for (const dynamics::SoilPatch& patch : scenario.terrain.patches)
        patches << QString::fromStdString(patch.soil.name);
    patches.removeDuplicates();
    if (!patches.isEmpty()) text += "; patches: " + patches.join(", ");
    return text;
}

}  // namespace

void RoverPanel::retitle(const QString& title) {
    title_ = title;
    for (QCustomPlot* plot : plots_) setPlotTitle(*plot, title_);  // undrawn ones take title_
    setPlotTitle(*top_view_, title_);
}

void RoverPanel::previewScenario() {
    if (isBusy()) return;
    const std::string name = currentName();
    const QString shown = QString::fromStdString(name) + (isEdited() ? " (edited)" : "");
    if (!result_.series.rows.empty()) {
        // A run is on screen: every tab keeps showing it (the top view too, so that an export of
        // any tab is that run), titled with its own status, and says when the scenario chosen
        // since (another one, an edit, a revert) is not the one it ran.
        const QString run_title = roverTitle(shown_name_, result_.status);
        if (currentJson() == shown_json_) {
            retitle(run_title);
            status_->setText(summaryText());
            return;
        }
        retitle(QString("%1; now %2: press Run").arg(run_title, shown));
        status_->setText(QString("Shown: the run of %1 — %2. The scenario is now %3: press Run "
                                 "to run it.")
                             .arg(QString::fromStdString(shown_name_).toHtmlEscaped(),
                                  completion() == Completion::kComplete
                                      ? QString("completed")
                                      : "<b>" + completionMark(completion()) + "</b>",
                                  shown.toHtmlEscaped()));
        return;
    }
    auto loaded = isEdited() ? parseScenarioText(QString::fromStdString(edits_[name].dump()), name,
                                                 locations_)
                             : scenario::resolveScenario(locations_, name);
    if (!loaded) return;  // Run says what is wrong
    plotRoverTopView(*top_view_, *loaded, Table{}, 0, shown + " — not run yet: soils and start");
    preview_ = std::move(loaded).value();
    previewing_ = true;
    listLayers(preview_, nullptr);
    status_->setText(QString("Runs on the scenario's own soils (not the project's): %1. Press Run.")
                         .arg(soilsOf(preview_).toHtmlEscaped()));
}

void RoverPanel::projectReplaced() {
    result_ = scenario::RunResult{};
    shown_ = scenario::Scenario{};
    shown_name_.clear();
    shown_json_ = nullptr;
    comparison_ = nlohmann::json::array();
    title_.clear();
    showComparison();
    // The time scrubber of no run: empty, stopped, "t = – s".
    play_->setChecked(false);
    play_->setEnabled(false);
    {
        const QSignalBlocker block(scrubber_);
        scrubber_->setRange(0, 0);
        scrubber_->setValue(0);
    }
    scrubber_->setEnabled(false);
    time_->setText(timeLabel());
    for (std::size_t i = 0; i < plots_.size(); ++i) {
        plots_[i]->clearPlottables();
        plots_[i]->replot();
        drawn_[i] = false;
    }
    AnalysisPanel::projectReplaced();
    previewScenario();  // the top view: the scenario's soils and start, "not run yet"
    if (isBusy()) {
        // A discarded run still ending: the preview once it has (previewScenario waits for it).
        auto connection = std::make_shared<QMetaObject::Connection>();
        *connection =
            connect(this, &AnalysisPanel::busyChanged, this, [this, connection](bool busy) {
                if (busy) return;
                disconnect(*connection);
                if (result_.series.rows.empty()) previewScenario();
            });
    }
}

void RoverPanel::editScenario() {
    ScenarioDialog dialog(scenario_->currentText(), scenarioText(), locations_, this);
    if (dialog.exec() != QDialog::Accepted) return;
    QString error;
    if (!setScenarioText(dialog.text(), &error))
        status_->setText("<b>Error:</b> " + error.toHtmlEscaped());
}

AnalysisPanel::Job RoverPanel::makeJob() {
    const std::string name = currentName();
    auto loaded = isEdited() ? parseScenarioText(QString::fromStdString(edits_[name].dump()), name,
                                                 locations_)
                             : scenario::resolveScenario(locations_, name);
    if (!loaded) throw std::invalid_argument(loaded.message());
    pending_name_ = name + (isEdited() ? " (edited)" : "");
    pending_json_ = currentJson();
    analysis::RoverSettings settings;
    settings.scenario = name;
    settings.loaded = *loaded;
    QPointer<QProgressBar> bar = progress_;
    auto progress = [bar](double fraction) {
        QMetaObject::invokeMethod(
            bar,
            [bar, fraction] {
                if (bar) bar->setValue(static_cast<int>(fraction * 100.0));
            },
            Qt::QueuedConnection);
    };
    if (!std::exchange(compare_next_, false)) {
        return [settings, progress](const std::atomic<bool>& cancel) -> std::any {
            analysis::Control control{&cancel};
            control.progress = progress;
            // The scenario travels with its result: the top view needs its robot and soils.
            return analysis::runRover(settings, control);
        };
    }
    // Every controller in turn, each a quarter of the bar; a cancelled run ends the comparison
    // with the runs so far (the cancelled one marked "not completed").
    return [settings, progress](const std::atomic<bool>& cancel) -> std::any {
        Comparison out;
        const scenario::ControllerType chosen = settings.loaded->controller.type;
        const std::vector<analysis::ControllerRun> runs = analysis::compareControllers(
            settings, analysis::Control{&cancel, progress},
            [&](const std::string& name, analysis::RoverResult& result) {
                if (scenario::controllerFromName(name) == chosen || !out.shown)
                    out.shown = std::move(result);
            });
        out.table = analysis::controllerComparison(runs);
        return out;
    };
}

void RoverPanel::present(const std::any& value) {
    analysis::RoverResult result;
    const auto* compared = std::any_cast<Comparison>(&value);
    if (compared) {
        result = *compared->shown;
        comparison_ = compared->table;
        showComparison();
    } else {
        result = std::any_cast<analysis::RoverResult>(value);
    }
    shown_ = std::move(result.scenario);
    result_ = std::move(result.run);
    shown_name_ = pending_name_;
    shown_json_ = pending_json_;
    setCompletion(roverCompletion(result_.status));
    title_ = roverTitle(shown_name_, result_.status);
    const Table& t = result_.series;
    drawn_.assign(plots_.size(), false);
    const int last = static_cast<int>(t.rows.size()) - 1;
    plotRoverTopView(*top_view_, shown_, t, static_cast<std::size_t>(std::max(last, 0)), title_);
    {
        const QSignalBlocker block(scrubber_);
        scrubber_->setRange(0, std::max(last, 0));
        scrubber_->setPageStep(std::max(1, last / 60));  // Page Up/Down: 1/60 of the run
        scrubber_->setValue(std::max(last, 0));
    }
    previewing_ = false;
    preview_ = {};
    listLayers(shown_, result_.maps ? &*result_.maps : nullptr);
    scrubber_->setEnabled(last > 0);
    play_->setEnabled(last > 0);
    time_->setText(timeLabel());
    // After the scrubber is at the last row: the figure's time cursor starts there.
    if (tabs_->currentIndex() > 0) drawFigure(static_cast<std::size_t>(tabs_->currentIndex() - 1));
    for (std::size_t i = 0; i < plots_.size(); ++i) {
        if (plots_[i]->isVisible()) drawFigure(i);  // one in a dock of its own (plot_docking.h)
    }
    if (t.rows.size() < 2) {
        status_->setText("No output: " + QString::fromStdString(result_.message));
        return;
    }
    if (compared) {
        status_->setText(
            QString("Compared the %1 controllers (Comparison tab); the figures show %2 "
                    "— ")
                .arg(comparison_.size())
                .arg(scenario::controllerName(shown_.controller.type)) +
            summaryText());
        return;
    }
    status_->setText(summaryText());
}

void RoverPanel::showComparison() {
    struct ColumnSpec {
        const char* key;
        const char* header;
        int decimals;
        double scale;
    };
    static const ColumnSpec kColumns[] = {
        {"distance_m", "distance\n[m]", 3, 1.0},
        {"energy_per_m_J", "energy\n[J/m]", 2, 1.0},
        {"energy_per_drawbar_work", "energy /\ndrawbar work", 2, 1.0},
        {"mean_efficiency", "mean η", 4, 1.0},
        {"mean_drawbar_N", "drawbar\n[N]", 3, 1.0},
        {"drawbar_vs_oracle", "drawbar /\noracle's", 3, 1.0},
        {"slip_tracking_rms", "slip\nRMS", 4, 1.0},
        {"settling_time_s", "settling\n[s]", 2, 1.0},
        {"settling_band_time_s", "settling in\nband [s]", 2, 1.0},
        {"rut_depth_m", "rut\n[mm]", 2, 1e3},
    };
    QStringList headers{"controller"};
    for (const ColumnSpec& c : kColumns) headers << QString::fromUtf8(c.header);
    comparison_table_->clear();
    comparison_table_->setColumnCount(static_cast<int>(headers.size()));
    comparison_table_->setHorizontalHeaderLabels(headers);
    comparison_table_->setRowCount(static_cast<int>(comparison_.size()));
    int r = 0;
    for (const nlohmann::json& row : comparison_) {
        QString name = QString::fromStdString(row.value("controller", std::string()));
        if (row.value("status", std::string()) != "completed") name += " (not completed)";
        comparison_table_->setItem(r, 0, new QTableWidgetItem(name));
        int c = 1;
        for (const ColumnSpec& spec : kColumns) {
            const nlohmann::json& v = row[spec.key];
            // Not defined (no set-point, no border, no oracle run): a dash, never "nan".
            auto* item = new QTableWidgetItem(
                v.is_number() ? QString::number(v.get<double>() * spec.scale, 'f', spec.decimals)
                              : QString("–"));
            item->setTextAlignment(Qt::AlignRight | Qt::AlignVCenter);
            comparison_table_->setItem(r, c++, item);
        }
        ++r;
    }
    comparison_table_->resizeColumnsToContents();
    comparison_table_->resizeRowsToContents();
}

Table RoverPanel::comparisonAsTable() const {
    Table t;
    t.label_column = "controller";
    t.columns = {"distance_m",        "energy_per_m_J",  "energy_per_drawbar_work",
                 "mean_efficiency",   "mean_drawbar_N",  "drawbar_vs_oracle",
                 "slip_tracking_rms", "settling_time_s", "settling_band_time_s",
                 "rut_depth_m"};
    for (const nlohmann::json& row : comparison_) {
        t.labels.push_back(row.value("controller", std::string()));
        std::vector<double> values;
        for (const std::string& key : t.columns) {
            const nlohmann::json& v = row[key];
            values.push_back(v.is_number() ? v.get<double>() : std::nan(""));
        }
        t.rows.push_back(std::move(values));
    }
    return t;
}

bool RoverPanel::showTab(const QString& label) {
    for (int i = 0; i < tabs_->count(); ++i) {
        if (tabs_->tabText(i) == label) {
            tabs_->setCurrentIndex(i);
            return true;
        }
    }
    return false;
}

Table RoverPanel::currentTable() const {
    return tabs_->currentWidget() == comparison_table_ ? comparisonAsTable() : result_.series;
}

QString RoverPanel::summaryText() const {
    // The core summary (what `terrastudio simulate` prints: the simulated time, the final pose,
    // the distance, each wheel's mean slip, the motor energy; a field run's cells, deepest rut and
    // largest compaction risk; a mission's time, progress and path error; the status and the
    // energy balance's warning), in its words and digits, after the soils it ran on.
    const analysis::Summary summary = analysis::roverSummary(result_, shown_);
    const QString on = "on " + soilsOf(shown_).toHtmlEscaped();
    return (completion() == Completion::kComplete ? "Completed " + on : markedStatus(on)) + "<br>" +
           summaryParagraphHtml(summary);
}

QString RoverPanel::timeLabel() const {
    const Table& t = result_.series;
    const auto row = static_cast<std::size_t>(scrubber_->value());
    if (row >= t.rows.size()) return "t = – s";
    const RoverPose pose = roverPoseAt(t, row);
    return QString("t = %1 s, ψ = %2°")
        .arg(pose.t_s, 0, 'f', 2)
        .arg(pose.yaw_rad * 180.0 / 3.14159265358979, 0, 'f', 2);
}

void RoverPanel::scrubTo(int row) {
    if (row < 0 || static_cast<std::size_t>(row) >= result_.series.rows.size()) return;
    if (scrubber_->value() != row) {
        scrubber_->setValue(row);  // comes back here through valueChanged
        return;
    }
    scrubLayer();  // before the pose, which replots
    setRoverTopViewPose(*top_view_, shown_.robot, result_.series, static_cast<std::size_t>(row));
    time_->setText(timeLabel());
    // The time plots' cursors follow; only the plot in view is redrawn now (the others when their
    // tab is shown, see the constructor), so that dragging stays smooth.
    for (std::size_t i = 0; i < plots_.size(); ++i) {
        if (!drawn_[i]) continue;
        setRoverTimeCursor(*plots_[i], result_.series, roverFigures()[i].key,
                           static_cast<std::size_t>(row));
        if (plots_[i]->isVisible()) plots_[i]->replot(QCustomPlot::rpQueuedReplot);
    }
}

// --- Field layers (core/scenario/map_layers.h, widgets/plots/field_layers.h) -------------------

const scenario::Scenario& RoverPanel::layerScenario() const {
    return previewing_ ? preview_ : shown_;
}

const scenario::FieldMaps* RoverPanel::layerMaps() const {
    return !previewing_ && result_.maps ? &*result_.maps : nullptr;
}

QString RoverPanel::layerKey() const { return layer_->currentData().toString(); }

bool RoverPanel::chooseLayer(const QString& key) {
    const int i = layer_->findData(key.isEmpty() ? QString("none") : key);
    if (i < 0) return false;
    layer_->setCurrentIndex(i);
    return true;
}

void RoverPanel::listLayers(const scenario::Scenario& scenario, const scenario::FieldMaps* maps) {
    const QSignalBlocker block(layer_);
    layers_ = scenario::mapLayers(scenario, maps);
    // A map without cells (a saved run from before that map existed) has nothing to draw.
    layers_.erase(std::remove_if(layers_.begin(), layers_.end(),
                                 [&](const scenario::MapLayer& layer) {
                                     const field::Raster* r =
                                         scenario::layerRaster(scenario, maps, layer.key);
                                     return r == nullptr || r->values.empty();
                                 }),
                  layers_.end());
    layer_->clear();
    layer_->addItem("none", QString("none"));
    for (const scenario::MapLayer& layer : layers_)
        layer_->addItem(QString::fromStdString(layer.label), QString::fromStdString(layer.key));
    int chosen = layer_->findData(QString::fromStdString(layer_choice_));
    for (const char* fallback : {"rut_depth_m", "soil_classes", "height"}) {
        if (chosen < 0) chosen = layer_->findData(QString(fallback));
    }
    layer_->setCurrentIndex(std::max(chosen, 0));
    layer_label_->setVisible(!layers_.empty());
    layer_->setVisible(!layers_.empty());
    drawLayer();
}

void RoverPanel::drawLayer() {
    const int i = layer_->currentIndex() - 1;
    if (i < 0 || static_cast<std::size_t>(i) >= layers_.size()) {
        if (topViewLayer(*top_view_) == nullptr) return;
        const int width = top_view_->axisRect()->width();
        removeTopViewLayer(*top_view_);
        refitTopView(width);
        return;
    }
    const scenario::MapLayer& layer = layers_[static_cast<std::size_t>(i)];
    const scenario::Scenario& s = layerScenario();
    const scenario::FieldMaps* maps = layerMaps();
    if (layer.timed) {
        // The driven area: where the run's maps can differ from untouched soil, and what a saved
        // run keeps of them.
        layer_box_ = scenario::drivenArea(s, previewing_ ? Table{} : result_.series);
    } else {
        // The field's own maps under everything in view, a view's width beyond each side so that
        // a little panning does not show their edge.
        const QCPRange x = top_view_->xAxis->range(), y = top_view_->yAxis->range();
        layer_box_ = {x.lower - x.size(), y.lower - y.size(), x.upper + x.size(),
                      y.upper + y.size()};
    }
    const int width = top_view_->axisRect()->width();
    const field::Raster final_view = scenario::layerView(s, maps, layer, layer_box_);
    layer_display_ = layerDisplay(layer, final_view);
    const bool scrubbed = layer.timed && !previewing_ && !result_.series.rows.empty();
    drawTopViewLayer(
        *top_view_, layer, layer_display_,
        scrubbed ? scenario::layerView(s, maps, layer, layer_box_, scrubTime()) : final_view);
    refitTopView(width);
}

void RoverPanel::refitTopView(int width_before) {
    top_view_->replot();  // lays out the axes with or without the layer's colour scale
    if (top_view_->axisRect()->width() == width_before) return;  // the user's zoom stays
    // A colour scale took width from the axes (or gave it back): the driven area again, with
    // equal scales on x and y.
    const auto [x0, y0, x1, y1] =
        scenario::drivenArea(layerScenario(), previewing_ ? Table{} : result_.series);
    fitEqualScales(*top_view_, x0, y0, x1, y1);
    top_view_->replot();
}

void RoverPanel::scrubLayer() {
    const int i = layer_->currentIndex() - 1;
    if (i < 0 || static_cast<std::size_t>(i) >= layers_.size() || previewing_) return;
    const scenario::MapLayer& layer = layers_[static_cast<std::size_t>(i)];
    if (!layer.timed) return;
    updateTopViewLayer(
        *top_view_, layer_display_,
        scenario::layerView(layerScenario(), layerMaps(), layer, layer_box_, scrubTime()));
}

double RoverPanel::scrubTime() const {
    const Table& t = result_.series;
    const auto row = static_cast<std::size_t>(scrubber_->value());
    if (row >= t.rows.size()) return std::numeric_limits<double>::infinity();
    return t.rows[row][t.column("t_s")];
}

// --- Saved with the project (core/project/saved_rover.h) ---------------------------------------

nlohmann::json RoverPanel::resultInputs() const { return {{"scenario", currentJson()}}; }

std::map<std::string, project::SavedResult> RoverPanel::savedResults() const {
    if (!hasResult() || isBusy() || result_.series.rows.empty() || shown_json_.is_null()) return {};
    project::SavedResult saved;
    saved.inputs_hash = project::inputsHash({{"scenario", shown_json_}});
    saved.version = project::kRoverVersion;
    saved.partial = result_.status != scenario::RunResult::Status::kCompleted;
    saved.summary = QString("%1, %2 s simulated")
                        .arg(QString::fromStdString(shown_name_))
                        .arg(result_.summary.duration_s, 0, 'f', 2)
                        .toStdString();
    // The series is in the result already (a table): not written twice (a long run is megabytes).
    project::SavedRoverRun run{result_, shown_name_, shown_json_};
    if (run.run.maps) {
        // A field run's maps over the driven area, the part the top view draws them on: the
        // rest of the field is untouched soil (and a 2,500 × 1,000 raster would be megabytes).
        const std::array<double, 4> box = scenario::drivenArea(shown_, result_.series);
        const scenario::CellWindow window =
            scenario::windowOver(run.run.maps->rut_depth_m, box[0], box[1], box[2], box[3]);
        run.run.maps = scenario::cropMaps(*run.run.maps, window);
    }
    saved.result = project::savedJson(run);
    return {{name().toStdString(), std::move(saved)}};
}

AnalysisPanel::Restored RoverPanel::restoreResult(const std::string& section,
                                                  const project::SavedResult& saved) {
    if (section != name().toStdString()) return unreadable("not a section of this panel");
    if (saved.version != project::kRoverVersion)
        return unreadable("saved in form version " + std::to_string(saved.version));
    if (saved.inputs_hash != inputsHash()) return inputsChanged();
    Result<project::SavedRoverRun> read = project::savedRoverRunFromJson(saved.result, section);
    if (!read) return unreadable(read.message());
    project::SavedRoverRun run = std::move(read).value();
    // The scenario as it ran, for the top view's robot and soils (no simulation: a parse).
    auto scenario =
        parseScenarioText(QString::fromStdString(run.scenario.dump()), currentName(), locations_);
    if (!scenario) return unreadable("its scenario: " + scenario.message());
    pending_name_ = run.scenario_name;
    pending_json_ = run.scenario;
    showSaved(analysis::RoverResult{std::move(scenario).value(), std::move(run.run)},
              saved.inputs_hash, saved.partial);
    status_->setText("Saved with the project (not run again). " + status_->text());
    return restoredShown();
}

}  // namespace terra::ui
