#include "widgets/panels/forces_panel.h"

#include <qcustomplot.h>

#include <QComboBox>
#include <QFileInfo>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QMenu>
#include <QPushButton>
#include <QTabWidget>
#include <QTableWidget>
#include <QToolButton>
#include <QVBoxLayout>
#include <algorithm>
#include <map>
#include <memory>
#include <set>
#include <stdexcept>

#include "core/project/panels.h"
#include "core/project/saved_analyses.h"
#include "widgets/document/project_document.h"
#include "widgets/editors/preset_names.h"
#include "widgets/panels/calibration_dialog.h"
#include "widgets/plots/figures.h"
#include "widgets/plots/reference_overlay.h"
#include "widgets/plots/sweep_plot.h"

namespace terra::ui {
namespace {

/// What one computation of the panel produces.
struct ForcesOutcome {
    analysis::ForcesResult sweep;
    analysis::SoilCurves soil;
    std::optional<analysis::ValidationResult> validation;  ///< with a test in the project
    std::vector<TestSweep> test_sweeps;
    std::shared_ptr<const io::Experiment> test;  ///< the test compared (drawn with its result)
    ForcesPanel::ReferenceCurves reference;      ///< the reference soil swept (name "": none)
};

/// The panel's quantities against slip: the sweep's six, then the sinkage.
const std::vector<SweepQuantity>& panelQuantities() {
    static const std::vector<SweepQuantity> quantities = [] {
        std::vector<SweepQuantity> all = sweepQuantities();
        all.push_back(sinkageQuantity());
        return all;
    }();
    return quantities;
}

/// The test's points predicted, and the model swept at each of its loads over its slip angles.
void compareWithTest(const analysis::Inputs& inputs, const io::Experiment& test,
                     const analysis::Control& control, ForcesOutcome& out) {
    analysis::ValidationSettings settings;
    settings.experiments = test.source;
    settings.data = test;
    settings.curves = false;  // the test_sweeps below are the panel's model lines
    out.validation = analysis::computeValidation(inputs, settings, control);
    std::map<double, std::set<double>> conditions;  // load → slip angles
    for (const io::ExperimentPoint& p : test.points) conditions[p.load_n].insert(p.slip_angle_deg);
    for (const auto& [load, angles] : conditions) {
        if (control.cancelled()) return;
        analysis::Inputs at_test = inputs;
        at_test.conditions.load_n = load;
        at_test.conditions.slip_angles_deg.assign(angles.begin(), angles.end());
        out.test_sweeps.push_back({load, analysis::computeForceSweep(at_test, {}, control).table});
    }
}

}  // namespace

ForcesPanel::ForcesPanel(ProjectDocument* document, QWidget* parent)
    : AnalysisPanel(document, "forces", parent) {
    model_ = new QComboBox(this);
    model_->addItem("Full model (numerical integration)", false);
    model_->addItem("Quadratic approximation (closed form)", true);
    status_ = new QLabel(this);
    // Its longest text ("444 points; 156 without equilibrium (the wheel would sink to its
    // axle)") wraps rather than widening the panel into a sideways scroll bar.
    status_->setWordWrap(true);
    status_->setMinimumWidth(60);
    status_->setSizePolicy(QSizePolicy::Ignored, QSizePolicy::Preferred);
    // The read-out on a line of its own under the plots, one text line high whether empty or
    // not: beside the Model box a long read-out was cut ("… F_x = -0.3902 N — [") and squeezed
    // the status into two lines, moving the tabs by 6 px with the mouse (a new user's audit).
    readout_ = new QLabel(this);
    readout_->setObjectName("forces.readout");
    readout_->setMinimumWidth(120);
    readout_->setMinimumHeight(readout_->fontMetrics().height());
    readout_->setSizePolicy(QSizePolicy::Ignored, QSizePolicy::Fixed);
    tabs_ = new QTabWidget(this);
    for (const SweepQuantity& quantity : panelQuantities()) {
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

    // A reference soil drawn dashed over the project's curves (a row of its own: fits 1024 px).
    compare_ = new QToolButton(this);
    compare_->setObjectName("forces.compare");
    compare_->setText("Compare with…");
    compare_->setToolTip(
        "Draw a reference soil dashed over the project's curves, swept with the project's wheel "
        "and conditions: the current soil pinned before you edit it, or a soil preset");
    compare_->setPopupMode(QToolButton::InstantPopup);
    compare_->setMenu(new QMenu(compare_));
    connect(compare_->menu(), &QMenu::aboutToShow, this, [this] { fillCompareMenu(); });
    fillCompareMenu();
    clear_compare_ = new QPushButton("Clear comparison", this);
    clear_compare_->setObjectName("forces.clear_comparison");
    clear_compare_->setToolTip("Remove the reference soil's curves");
    connect(clear_compare_, &QPushButton::clicked, this, [this] { clearComparison(); });
    compare_label_ = new QLabel(this);
    compare_label_->setMinimumWidth(1);  // a long soil name is clipped, never widens the panel
    auto* compare_bar = new QHBoxLayout;
    compare_bar->addWidget(compare_);
    compare_bar->addWidget(clear_compare_);
    compare_bar->addWidget(compare_label_, 1);
    updateCompareControls();

    // The measured test: what it is, its metrics, and its calibration (hidden without a test).
    test_box_ = new QGroupBox("Measured test", this);
    test_label_ = new QLabel(test_box_);
    test_label_->setWordWrap(true);
    test_label_->setTextInteractionFlags(Qt::TextSelectableByMouse);
    test_label_->setAlignment(Qt::AlignTop | Qt::AlignLeft);
    metrics_ = new QTableWidget(0, 5, test_box_);
    metrics_->setHorizontalHeaderLabels({"Channel", "Points", "RMSE", "MAE", "Max rel."});
    metrics_->horizontalHeaderItem(4)->setToolTip(
        "Largest relative error: max |predicted − measured| / |measured| over the points with a "
        "measured value ≠ 0");
    metrics_->verticalHeader()->hide();
    metrics_->setEditTriggers(QAbstractItemView::NoEditTriggers);
    metrics_->setFocusPolicy(Qt::NoFocus);
    metrics_->horizontalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
    metrics_->horizontalHeader()->setStretchLastSection(true);
    // Sized to its cells (showMetrics): no scroll bar takes a row's room.
    metrics_->setVerticalScrollBarPolicy(Qt::ScrollBarAlwaysOff);
    metrics_->setHorizontalScrollBarPolicy(Qt::ScrollBarAlwaysOff);
    metrics_->setToolTip(
        "The model at each measured point, θ_f solved from the measured load (docs/validation.md)");
    calibrate_ = new QPushButton("Calibrate to this test…", test_box_);
    calibrate_->setToolTip(
        "Fit the soil to the measurements, with the project's soil as the prior; see before and "
        "after, then apply it to the project (undoable)");
    auto* remove = new QPushButton("Remove test", test_box_);
    remove->setToolTip("Take the test out of the project (undoable)");
    // The test and its actions on the left, the metrics on the right: fits 1024 px screens.
    auto* buttons = new QHBoxLayout;
    buttons->addWidget(calibrate_);
    buttons->addWidget(remove);
    buttons->addStretch(1);
    auto* left = new QVBoxLayout;
    left->addWidget(test_label_);
    left->addLayout(buttons);
    left->addStretch(1);
    auto* test_layout = new QHBoxLayout(test_box_);
    test_layout->addLayout(left, 2);
    test_layout->addWidget(metrics_, 3);

    auto* layout = new QVBoxLayout(this);
    layout->addLayout(bar);
    layout->addLayout(compare_bar);
    layout->addWidget(tabs_, 1);
    layout->addWidget(readout_);
    layout->addWidget(test_box_);
    connect(calibrate_, &QPushButton::clicked, this, [this] {
        CalibrationDialog* dialog = openCalibration();
        if (dialog) dialog->show();
    });
    connect(remove, &QPushButton::clicked, this, [this] { document_->setExperiment({}); });
    connect(document_, &ProjectDocument::experimentChanged, this, [this] { updateTestBox(); });
    updateTestBox();

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
    for (std::size_t i = 0; i < panelQuantities().size(); ++i) {
        out.emplace_back(QString::fromStdString(panelQuantities()[i].column) + "-vs-slip",
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
    const Project& p = document_->project();
    Table shown, reference;
    if (currentPlot() == bulldozing_) {
        shown = soil_curves_.bulldozing;
        reference = shown_reference_.soil.bulldozing;
    } else if (currentPlot() == static_sinkage_) {
        shown = soil_curves_.static_sinkage;
        reference = shown_reference_.soil.static_sinkage;
    } else if (validation_ && shown_test_) {
        // With a test on the plots, its data go with them (the export writes what the figure
        // shows).
        shown = tableWithTest(result_.table, p.conditions.load_n, *shown_test_, test_sweeps_);
        reference = shown_reference_.sweep;
    } else {
        shown = result_.table;
        reference = shown_reference_.sweep;
    }
    if (shown_reference_.name.empty() || reference.rows.empty()) return shown;
    return tableWithReference(shown, p.soil.name, reference, shown_reference_.name,
                              p.conditions.load_n);
}

QCustomPlot* ForcesPanel::currentPlot() const {
    return plots_[static_cast<std::size_t>(tabs_->currentIndex())];
}

AnalysisPanel::Job ForcesPanel::makeJob() {
    const analysis::Inputs inputs = project::inputsOf(document_->project());
    std::shared_ptr<const io::Experiment> test;
    if (const io::Experiment* e = document_->experiment())
        test = std::make_shared<const io::Experiment>(*e);
    std::optional<Reference> reference = reference_;
    nlohmann::json key;
    std::optional<ReferenceCurves> cached;
    if (reference) {
        key = {{"name", reference->name},
               {"soil", io::toJson(reference->soil)},
               {"wheel", io::toJson(inputs.wheel)},
               {"conditions", analysis::toJson(inputs.conditions)}};
        if (cached_reference_.complete && cached_reference_.key == key) cached = cached_reference_;
    }
    return [inputs, test, reference, key, cached](const std::atomic<bool>& cancel) -> std::any {
        const analysis::Control control{&cancel};
        ForcesOutcome out;
        // ~1 ms, ~6 % of the sweep (sandy loam).
        out.soil = analysis::computeSoilCurves(inputs, {}, control);
        out.sweep = analysis::computeForceSweep(inputs, {}, control);
        // A test of a few points and one load adds one slip angle's sweep (~1/6 of the above).
        if (test) compareWithTest(inputs, *test, control, out);
        out.test = test;
        // The reference soil on the project's wheel and conditions: as long again as the sweep.
        if (cached) {
            out.reference = *cached;
        } else if (reference && !control.cancelled()) {
            out.reference.name = reference->name;
            out.reference.key = key;
            analysis::Inputs at_reference = inputs;
            at_reference.soil = reference->soil;
            try {
                out.reference.soil = analysis::computeSoilCurves(at_reference, {}, control);
                out.reference.sweep = analysis::computeForceSweep(at_reference, {}, control).table;
            } catch (const std::exception& e) {  // e.g. K_s ≤ 0 for this soil on another wheel
                out.reference.sweep = {};
                out.reference.soil = {};
                out.reference.error = e.what();
            }
            out.reference.complete = !control.cancelled();
        }
        return out;
    };
}

void ForcesPanel::present(const std::any& value) {
    auto outcome = std::any_cast<ForcesOutcome>(value);
    result_ = std::move(outcome.sweep);
    soil_curves_ = std::move(outcome.soil);
    validation_ = std::move(outcome.validation);
    test_sweeps_ = std::move(outcome.test_sweeps);
    // The test this result was computed with (an intermediate frame may be of an earlier one).
    shown_test_ = std::move(outcome.test);
    const Project& p = document_->project();
    const QString title =
        QString("%1, %2, W = %3 N%4")
            .arg(QString::fromStdString(p.soil.name), QString::fromStdString(p.wheel.name))
            .arg(p.conditions.load_n)
            .arg(p.conditions.quadratic ? " (quadratic model)" : "");
    const io::Experiment* test = validation_ ? shown_test_.get() : nullptr;
    shown_reference_ = std::move(outcome.reference);
    if (shown_reference_.complete) cached_reference_ = shown_reference_;
    const QString reference = QString::fromStdString(shown_reference_.name);
    for (std::size_t i = 0; i < panelQuantities().size(); ++i) {
        // With a reference the overlay refits and replots: the plot is drawn once.
        plotSweep(*plots_[i], result_.table, panelQuantities()[i], title,
                  shown_reference_.sweep.rows.empty());
        overlayReferenceSweep(*plots_[i], panelQuantities()[i], shown_reference_.sweep, reference);
        if (test)
            overlayExperiment(*plots_[i], panelQuantities()[i], *test, test_sweeps_, p.conditions);
    }
    showMetrics();
    const QString soil_title =
        QString("%1, %2 (r = %3 mm, b = %4 mm)")
            .arg(QString::fromStdString(p.soil.name), QString::fromStdString(p.wheel.name))
            .arg(p.wheel.radius_m * 1e3)
            .arg(p.wheel.width_m * 1e3);
    plotBulldozing(*bulldozing_, soil_curves_, soil_title);
    plotStaticSinkage(*static_sinkage_, soil_curves_, soil_title);
    overlayReferenceBulldozing(*bulldozing_, shown_reference_.soil, reference);
    overlayReferenceStaticSinkage(*static_sinkage_, shown_reference_.soil, reference);
    updateCompareControls();
    status_->setText(
        result_.warnings.empty()
            ? QString("%1 points").arg(result_.table.rows.size())
            : QString("%1 points; %2 without equilibrium (the wheel would sink to its axle)")
                  .arg(result_.table.rows.size())
                  .arg(result_.warnings.size()));
}

}  // namespace terra::ui

namespace terra::ui {

nlohmann::json ForcesPanel::resultInputs() const {
    const Project& p = document_->project();
    return {{"soil", io::toJson(p.soil)},
            {"wheel", io::toJson(p.wheel)},
            {"conditions", analysis::toJson(p.conditions)},
            {"test", project::fileStamp(p.experiment)}};
}

std::map<std::string, project::SavedResult> ForcesPanel::savedResults() const {
    project::SavedForces shown{result_, soil_curves_, validation_, {}};
    for (const TestSweep& s : test_sweeps_) shown.test_sweeps.push_back({s.load_n, s.table});
    std::map<std::string, project::SavedResult> out =
        savedSection(project::kForcesVersion, project::savedJson(shown),
                     QString("%1 points").arg(result_.table.rows.size()).toStdString(), false);
    if (calibration_) {
        if (std::optional<project::SavedResult> saved = calibration_->savedResult())
            out[name().toStdString() + ".calibration"] = std::move(*saved);
    }
    return out;
}

AnalysisPanel::Restored ForcesPanel::restoreResult(const std::string& section,
                                                   const project::SavedResult& saved) {
    if (section == name().toStdString()) {
        if (reference_)
            return {Restored::Kind::kInputsChanged, "a comparison soil is shown: computed again"};
        return restoreSection(
            section, saved, project::kForcesVersion,
            [this](const nlohmann::json& json, const std::string& where) -> std::any {
                project::SavedForces read = valueOrThrow(project::savedForcesFromJson(json, where));
                ForcesOutcome out;
                out.sweep = std::move(read.sweep);
                out.soil = std::move(read.soil);
                out.validation = std::move(read.validation);
                for (project::SavedTestSweep& s : read.test_sweeps)
                    out.test_sweeps.push_back({s.load_n, std::move(s.table)});
                if (out.validation) {
                    const io::Experiment* test = document_->experiment();
                    if (!test) throw std::invalid_argument("the project's test cannot be read");
                    out.test = std::make_shared<const io::Experiment>(*test);
                }
                return out;
            });
    }
    if (section != name().toStdString() + ".calibration")
        return unreadable("not a section of this panel");
    CalibrationDialog* dialog = openCalibration();
    if (!dialog) return inputsChanged();  // the project has no test now
    return dialog->restore(saved);
}

CalibrationDialog* ForcesPanel::openCalibration() {
    if (!document_->experiment()) return nullptr;
    if (!calibration_) {
        calibration_ = new CalibrationDialog(document_, this);
        calibration_->setObjectName("calibration_dialog");
    }
    return calibration_;
}

void ForcesPanel::updateTestBox() {
    const Project& p = document_->project();
    test_box_->setVisible(!p.experiment.empty());
    const io::Experiment* test = document_->experiment();
    calibrate_->setEnabled(test != nullptr);
    if (!test) {
        metrics_->setRowCount(0);
        validation_.reset();
        shown_test_.reset();
        test_label_->setText(p.experiment.empty()
                                 ? QString()
                                 : "<b>The test cannot be read:</b> " +
                                       document_->experimentError().toHtmlEscaped());
        return;
    }
    const QString file = QFileInfo(QString::fromStdString(test->source)).fileName();
    QString text = "<b>" + file.toHtmlEscaped() + "</b>";
    QString tip = QString::fromStdString(test->source);
    if (test->metadata) {
        const io::ExperimentMetadata& m = *test->metadata;
        if (!m.test.empty()) text += "<br>" + QString::fromStdString(m.test).toHtmlEscaped();
        for (const std::string* part : {&m.citation, &m.figures, &m.notes}) {
            if (!part->empty()) tip += "\n\n" + QString::fromStdString(*part);
        }
    }
    test_label_->setText(text);
    test_label_->setToolTip(tip);
}

void ForcesPanel::showMetrics() {
    metrics_->setRowCount(0);
    if (!validation_) return;
    const analysis::ValidationResult& v = *validation_;
    for (std::size_t c = 0; c < io::kExperimentChannelCount; ++c) {
        if (!v.before.metrics[c]) continue;
        const auto channel = static_cast<io::ExperimentChannel>(c);
        const analysis::ChannelMetrics& m = *v.before.metrics[c];
        const int row = metrics_->rowCount();
        metrics_->insertRow(row);
        auto* name = new QTableWidgetItem(channelLabel(channel));
        name->setToolTip(QString::fromUtf8(io::experimentChannels()[c].label));
        metrics_->setItem(row, 0, name);
        metrics_->setItem(row, 1, new QTableWidgetItem(QString::number(m.count)));
        metrics_->setItem(row, 2, new QTableWidgetItem(channelValue(channel, m.rmse)));
        metrics_->setItem(row, 3, new QTableWidgetItem(channelValue(channel, m.mae)));
        metrics_->setItem(row, 4, new QTableWidgetItem(relativeError(m.max_rel_error)));
    }
    // The notes (another wheel than the test's, points without equilibrium) under the test.
    QString text = test_label_->text().section("<br><i>", 0, 0);
    for (const std::string& note : v.notes)
        text += "<br><i>" + QString::fromStdString(note).toHtmlEscaped() + "</i>";
    test_label_->setText(text);
    // As tall as its rows (a test measures one to five channels), never taller than five.
    metrics_->resizeRowsToContents();
    int height = metrics_->horizontalHeader()->sizeHint().height() + 2 * metrics_->frameWidth();
    for (int row = 0; row < std::min(metrics_->rowCount(), 5); ++row)
        height += metrics_->rowHeight(row);
    metrics_->setFixedHeight(height);
    metrics_->resizeColumnsToContents();
    metrics_->setMinimumWidth(metrics_->horizontalHeader()->length() + 2 * metrics_->frameWidth());
}

}  // namespace terra::ui

namespace terra::ui {

void ForcesPanel::setPresetLocations(const io::PresetLocations& locations) {
    locations_ = locations;
    fillCompareMenu();
}

void ForcesPanel::pinReference() {
    const soil::SoilParameters& soil = document_->project().soil;
    compareWith(soil.name + " (before edit)", soil);
}

void ForcesPanel::compareWith(const std::string& name, const soil::SoilParameters& soil) {
    reference_ = Reference{name, soil};
    updateCompareControls();
    scheduleUpdate();
}

bool ForcesPanel::compareWithPreset(const std::string& preset, QString* error) {
    if (!locations_) {
        if (error) *error = "no preset directory";
        return false;
    }
    const Result<soil::SoilParameters> soil = io::resolveSoil(*locations_, preset);
    if (!soil) {
        if (error) *error = QString::fromStdString(soil.message());
        return false;
    }
    compareWith(soil->name, *soil);
    return true;
}

void ForcesPanel::clearComparison() {
    reference_.reset();
    updateCompareControls();
    scheduleUpdate();
}

QString ForcesPanel::referenceName() const {
    return reference_ ? QString::fromStdString(reference_->name) : QString();
}

void ForcesPanel::fillCompareMenu() {
    QMenu* menu = compare_->menu();
    menu->clear();
    QAction* pin = menu->addAction(QString("Current soil: pin \"%1\" as it is now")
                                       .arg(QString::fromStdString(document_->project().soil.name)),
                                   this, [this] { pinReference(); });
    pin->setObjectName("forces.compare_pin");
    pin->setToolTip("Keep the current curves, dashed, while you edit the soil");
    if (!locations_) return;
    menu->addSection("Soil preset");
    for (const std::string& preset : io::presetNames(*locations_, "soils")) {
        QAction* action =
            menu->addAction(presetDisplayName(*locations_, "soils", preset), this, [this, preset] {
                QString error;
                if (!compareWithPreset(preset, &error))
                    compare_label_->setText("<b>Cannot compare:</b> " + error.toHtmlEscaped());
            });
        action->setObjectName(QString::fromStdString("forces.compare_preset." + preset));
    }
}

void ForcesPanel::updateCompareControls() {
    clear_compare_->setEnabled(reference_.has_value());
    if (!reference_) {
        compare_label_->setText(
            "<i>No comparison: pin the current soil before editing it, or "
            "pick a preset</i>");
        return;
    }
    const QString name = QString::fromStdString(reference_->name).toHtmlEscaped();
    if (!shown_reference_.error.empty() && shown_reference_.name == reference_->name) {
        compare_label_->setText(
            QString("<b>%1</b> cannot be computed: %2")
                .arg(name, QString::fromStdString(shown_reference_.error).toHtmlEscaped()));
        return;
    }
    compare_label_->setText(QString("Dashed: <b>%1</b>").arg(name));
    compare_label_->setToolTip(
        "The reference soil, swept with the project's wheel, load and slip angles");
}

}  // namespace terra::ui
