#include "widgets/panels/identification_panel.h"

#include <qcustomplot.h>

#include <QTabWidget>
#include <QVBoxLayout>

#include "core/io/parameters_json.h"
#include "core/project/saved_identification.h"
#include "widgets/document/project_document.h"
#include "widgets/panels/data_preview.h"
#include "widgets/panels/identification_fit_options.h"
#include "widgets/panels/identification_fit_page.h"
#include "widgets/panels/identification_streaming_page.h"

namespace terra::ui {

IdentificationPanel::IdentificationPanel(ProjectDocument* document, QWidget* parent)
    : AnalysisPanel(document, "identification", parent) {
    setLive(false);
    fit_ = new IdentificationFitPage(document_, this);
    for (QCustomPlot* plot : fit_->plots()) makeInteractive(plot, fit_->readout());
    streaming_ = new IdentificationStreamingPage(document_, this);
    pages_ = new QTabWidget(this);
    pages_->setDocumentMode(true);
    pages_->addTab(fit_, "Batch fit");
    pages_->addTab(streaming_, "Streaming playback");
    auto* layout = new QVBoxLayout(this);
    layout->setContentsMargins(0, 0, 0, 0);
    layout->addWidget(pages_, 1);

    // The fit runs through this panel's worker (AnalysisPanel); the page shows its state.
    connect(fit_, &IdentificationFitPage::fitRequested, this, [this] {
        storeSettings();
        recompute();
    });
    connect(fit_, &IdentificationFitPage::cancelRequested, this, [this] { cancelRunning(); });
    connect(this, &AnalysisPanel::busyChanged, fit_, &IdentificationFitPage::setBusy);
    connect(this, &AnalysisPanel::failed, fit_, &IdentificationFitPage::showFailure);
    connect(&fit_->preview(), &DataPreviewWidget::previewShown, this,
            &IdentificationPanel::dataPreviewShown);
    connect(streaming_, &IdentificationStreamingPage::aboutToPlay, this,
            [this] { storeSettings(); });
    connect(streaming_, &IdentificationStreamingPage::playbackEnded, this,
            &IdentificationPanel::playbackEnded);
}

IdentificationPanel::~IdentificationPanel() {
    delete streaming_;  // stops the playback and joins its worker before the panel goes
    streaming_ = nullptr;
}

// --- The batch fit page --------------------------------------------------------------------------

const analysis::IdentificationResult& IdentificationPanel::result() const { return fit_->result(); }

analysis::IdentificationSettings IdentificationPanel::fitSettings() const {
    return fit_->fitSettings();
}

void IdentificationPanel::setDataFile(const QString& path) { fit_->setDataFile(path); }

QString IdentificationPanel::dataPreview() const { return fit_->dataPreview(); }

QString IdentificationPanel::dataPreviewCell(int row, int column) const {
    return fit_->preview().cell(row, column);
}

QString IdentificationPanel::dataPreviewHeader(int column) const {
    return fit_->preview().header(column);
}

bool IdentificationPanel::dataPreviewReading() const { return fit_->preview().isReading(); }

QString IdentificationPanel::startDescription() const { return fit_->options().startDescription(); }

QString IdentificationPanel::fitStatus() const { return fit_->fitStatus(); }

QString IdentificationPanel::fitReport() const { return fit_->fitReport(); }

void IdentificationPanel::setFitOptions(const QString& prior_soil, const QString& prior_items,
                                        const QString& validation, const QString& loss) {
    fit_->options().setFitOptions(prior_soil, prior_items, validation, loss);
}

void IdentificationPanel::setWheelChoice(const QString& choice) {
    fit_->options().setWheelChoice(choice);
}

wheel::WheelParameters IdentificationPanel::chosenWheel() const {
    return fit_->options().chosenWheel();
}

QString IdentificationPanel::wheelDescription() const { return fit_->options().wheelDescription(); }

const std::optional<wheel::WheelParameters>& IdentificationPanel::dataWheel() const {
    return fit_->options().dataWheel();
}

const wheel::WheelParameters& IdentificationPanel::fitWheel() const { return fit_->fitWheel(); }

void IdentificationPanel::setShearLimit(const QString& mode, double jmax_mm) {
    fit_->options().setShearLimit(mode, jmax_mm);
}

QString IdentificationPanel::parameterCell(int row, int column) const {
    return fit_->parameterCell(row, column);
}

QString IdentificationPanel::parameterHeader(int column) const {
    return fit_->parameterHeader(column);
}

std::optional<soil::SoilParameters> IdentificationPanel::identifiedSoil() const {
    return fit_->identifiedSoil();
}

bool IdentificationPanel::applyIdentifiedSoil() { return fit_->applyIdentifiedSoil(); }

AnalysisPanel::Job IdentificationPanel::makeJob() { return fit_->makeJob(); }

void IdentificationPanel::present(const std::any& value) {
    fit_hash_ = presentedInputsHash();
    fit_->present(value, [this](const QString& text) { return markedStatus(text); });
}

nlohmann::json IdentificationPanel::resultInputs() const {
    // The data file by its content, not its name: moving the project's folder keeps the result.
    nlohmann::json fit = settings();
    for (const char* other : {"csv", "page", "stream_csv", "stream_second_soil",
                              "stream_noise_percent", "stream_speed", "stream_skip_bad_rows"})
        fit.erase(other);
    const Project& p = document_->project();
    return {{"soil", io::toJson(p.soil)},
            {"wheel", io::toJson(fit_->options().chosenWheel())},
            {"conditions", analysis::toJson(p.conditions)},
            {"fit", fit},
            {"csv", project::fileStamp(fit_->dataFile().trimmed().toStdString())}};
}

void IdentificationPanel::projectReplaced() {
    fit_->clearResult();
    fit_hash_.clear();
    streaming_->clearResult();
    AnalysisPanel::projectReplaced();
}

// --- Both pages ----------------------------------------------------------------------------------

std::vector<std::pair<QString, QCustomPlot*>> IdentificationPanel::plots() const {
    return {{"identification-Fx", fit_->plots()[0]},
            {"identification-Fz", fit_->plots()[1]},
            {"identification-My", fit_->plots()[2]},
            {"identification-streaming-estimates", streaming_->plots()[0]},
            {"identification-streaming-detection", streaming_->plots()[1]}};
}

QCustomPlot* IdentificationPanel::currentPlot() const {
    if (pages_->currentIndex() == 1) return streaming_->plots()[0];
    return fit_->currentPlot();
}

Table IdentificationPanel::currentTable() const {
    if (pages_->currentIndex() == 0) return fit_->result().curves;
    return streaming_->framesTable();
}

project::IdentificationPanelSettings IdentificationPanel::panelSettings() const {
    project::IdentificationPanelSettings s;
    fit_->writeSettings(s);
    s.page = pages_->currentIndex() == 1 ? "streaming" : "fit";
    streaming_->writeSettings(s);
    return s;
}

nlohmann::json IdentificationPanel::settings() const { return project::toJson(panelSettings()); }

void IdentificationPanel::applySettings(const nlohmann::json& json) {
    const auto settings =
        project::panelSettingsFromJson<project::IdentificationPanelSettings>(withChanges(json));
    if (!settings) return;  // projects are checked when opened: only a program error lands here
    fit_->applySettings(*settings);
    showPage(settings->page == "streaming" ? 1 : 0);
    streaming_->applySettings(*settings);
}

std::map<std::string, project::SavedResult> IdentificationPanel::savedResults() const {
    std::map<std::string, project::SavedResult> out;
    const analysis::IdentificationResult& result = fit_->result();
    if (hasResult() && !fit_hash_.empty() && result.message.empty()) {
        project::SavedResult& saved = out[name().toStdString()];
        saved.inputs_hash = fit_hash_;
        saved.version = project::kIdentificationVersion;
        saved.partial = completion() != Completion::kComplete;
        saved.summary = QString("%1 samples, fitted in %2 ms")
                            .arg(result.data.samples.size())
                            .arg(result.fit_time_ms, 0, 'f', 0)
                            .toStdString();
        // The curves and parameters are tables of the result already: not written twice.
        saved.result = project::savedJson(result);
    }
    if (auto stream = streaming_->savedResult()) out[name().toStdString() + ".streaming"] = *stream;
    return out;
}

AnalysisPanel::Restored IdentificationPanel::restoreResult(const std::string& section,
                                                           const project::SavedResult& saved) {
    if (section == name().toStdString() + ".streaming") {
        if (saved.version != project::kStreamingVersion)
            return unreadable("saved in form version " + std::to_string(saved.version));
        if (saved.inputs_hash != project::inputsHash(streaming_->inputs())) return inputsChanged();
        if (streaming_->playback().isActive()) return unreadable("a playback is going on");
        Result<project::SavedStream> read = project::savedStreamFromJson(saved.result, section);
        if (!read) return unreadable(read.message());
        streaming_->showSaved(std::move(read).value(), saved.inputs_hash);
        return restoredShown();
    }
    if (section != name().toStdString()) return unreadable("not a section of this panel");
    if (saved.version != project::kIdentificationVersion)
        return unreadable("saved in form version " + std::to_string(saved.version));
    if (saved.inputs_hash != inputsHash()) return inputsChanged();
    Result<analysis::IdentificationResult> read =
        project::identificationResultFromJson(saved.result, section);
    if (!read) return unreadable(read.message());
    fit_->prepareSaved();
    showSaved(std::move(read).value(), saved.inputs_hash, saved.partial);
    fit_->setStatus(
        markedStatus(QString("Saved with the project (%1); not fitted again — Fit runs it again.")
                         .arg(QString::fromStdString(saved.summary).toHtmlEscaped())));
    return restoredShown();
}

void IdentificationPanel::showPage(int page) { pages_->setCurrentIndex(page == 1 ? 1 : 0); }

void IdentificationPanel::requestRun() {
    if (pages_->currentIndex() == 1) {
        if (streaming_->canPlay()) streaming_->play();
    } else {
        fit_->requestFit();
    }
}

// --- The streaming page --------------------------------------------------------------------------

analysis::StreamingSettings IdentificationPanel::streamSettings() const {
    return streaming_->streamSettings();
}

void IdentificationPanel::play() { streaming_->play(); }

void IdentificationPanel::pausePlayback() { streaming_->pausePlayback(); }

void IdentificationPanel::stopPlayback() { streaming_->stopPlayback(); }

void IdentificationPanel::setStreamSource(const QString& csv_path, const QString& second_soil) {
    streaming_->setStreamSource(csv_path, second_soil);
}

void IdentificationPanel::setStreamSpeed(double speed) { streaming_->setStreamSpeed(speed); }

const StreamingPlayback& IdentificationPanel::playback() const { return streaming_->playback(); }

const StreamingFigures& IdentificationPanel::streamingFigures() const {
    return streaming_->figures();
}

std::optional<std::size_t> IdentificationPanel::streamTrueBorder() const {
    return streaming_->trueBorder();
}

std::size_t IdentificationPanel::streamSampleCount() const { return streaming_->sampleCount(); }

QString IdentificationPanel::streamStatus() const { return streaming_->status(); }

}  // namespace terra::ui
