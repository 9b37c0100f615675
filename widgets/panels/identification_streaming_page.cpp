#include "widgets/panels/identification_streaming_page.h"

#include <qcustomplot.h>

#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFileDialog>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QProgressBar>
#include <QPushButton>
#include <QSplitter>
#include <QTimer>
#include <QVBoxLayout>
#include <cmath>

#include "core/io/parameters_json.h"
#include "widgets/document/project_document.h"
#include "widgets/document/suggested_paths.h"
#include "widgets/editors/preset_names.h"
#include "widgets/plots/number_format.h"

namespace terra::ui {

IdentificationStreamingPage::IdentificationStreamingPage(ProjectDocument* document, QWidget* parent)
    : QWidget(parent), document_(document) {
    QWidget* page = this;
    source_ = new QComboBox(page);
    source_->addItem("Synthetic: project soil, then");
    source_->addItem("CSV file");
    source_->setToolTip(
        "A synthetic drive over a soil border (the true border is drawn as a grey dashed line), "
        "or a recorded CSV (slip, entry_angle_deg, Fx_N, Fz_N, My_Nm; time_s for pacing)");
    second_soil_ = new QComboBox(page);
    addPresetItems(second_soil_, studioPresetLocations(), "soils");
    if (const int i = second_soil_->findData("clayey-soil"); i >= 0)
        second_soil_->setCurrentIndex(i);
    second_soil_->setToolTip("The soil the synthetic drive crosses into");
    noise_ = new QDoubleSpinBox(page);
    noise_->setRange(0.0, 20.0);
    noise_->setSuffix(" % noise");
    noise_->setValue(analysis::StreamingSettings{}.noise_percent);
    noise_->setToolTip(
        "Synthetic noise σ as a percentage of each channel's largest value (Eq. 5.1)");
    file_ = new QLineEdit(page);
    file_->setPlaceholderText("CSV to play");
    browse_ = new QPushButton("Choose CSV…", page);
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
    status_ = new QLabel(page);
    status_->setWordWrap(true);
    status_->setTextInteractionFlags(Qt::TextSelectableByMouse);
    for (int i = 0; i < 2; ++i) plots_.push_back(new QCustomPlot(page));
    figures_ = std::make_unique<StreamingFigures>(plots_[0], plots_[1]);
    playback_ = new StreamingPlayback(this);
    replot_timer_ = new QTimer(this);
    replot_timer_->setSingleShot(true);
    replot_timer_->setInterval(40);

    // The source on two rows (one made the page scroll sideways at 1024×700): what is played,
    // then the CSV's file.
    auto* source_row = new QHBoxLayout;
    source_row->addWidget(new QLabel("Source:", page));
    source_row->addWidget(source_);
    source_row->addWidget(second_soil_);
    source_row->addWidget(noise_);
    source_row->addStretch(1);
    auto* file_row = new QHBoxLayout;
    file_row->addWidget(file_, 1);
    file_row->addWidget(browse_);
    file_row->addWidget(skip_bad_rows_);
    file_->setMinimumWidth(180);
    auto* play_row = new QHBoxLayout;
    play_row->addWidget(new QLabel("Speed:", page));
    play_row->addWidget(speed_);
    play_row->addWidget(play_);
    play_row->addWidget(pause_);
    play_row->addWidget(stop_);
    play_row->addWidget(position_, 1);
    auto* splitter = new QSplitter(page);
    splitter->addWidget(plots_[0]);
    splitter->addWidget(plots_[1]);
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
    layout->addWidget(status_);
    status_->setText(
        "Press Play: the samples are fed one at a time through the streaming estimator on the "
        "full model (moving horizon of 5 with an arrival cost; shaded: ±σ). A change of soil is "
        "an alarm of the CUSUM of normalised innovations (above h = ln 10⁶) confirmed by a "
        "likelihood-ratio refit; a change of load or slip alone is none.");

    connect(source_, &QComboBox::currentIndexChanged, this, [this] { updateControls(); });
    connect(browse_, &QPushButton::clicked, this, [this] {
        const QString path = QFileDialog::getOpenFileName(
            this, "Play identification data", startFolder(document_->filePath()), "CSV (*.csv)");
        if (!path.isEmpty()) setStreamSource(path);
    });
    connect(speed_, &QComboBox::currentIndexChanged, this, [this] {
        playback_->setSpeed(speed_->currentData().toDouble());
        updatePosition();
    });
    connect(play_, &QPushButton::clicked, this, &IdentificationStreamingPage::play);
    connect(pause_, &QPushButton::clicked, this, &IdentificationStreamingPage::pausePlayback);
    connect(stop_, &QPushButton::clicked, this, &IdentificationStreamingPage::stopPlayback);
    connect(replot_timer_, &QTimer::timeout, this, [this] {
        updatePosition();
        figures_->replot();
    });
    connect(playback_, &StreamingPlayback::sourceReady, this,
            [this](const StreamSource& source, std::size_t count) {
                count_ = count;
                border_ = source.true_border;
                description_ = QString::fromStdString(source.description);
                warnings_.clear();
                for (const auto& w : source.warnings) warnings_ << QString::fromStdString(w);
                truth_ = source.truth;
                hash_ = pending_hash_;
                stopped_ = false;
                resetFigures(count);
                figures_->replot();
                updatePosition();
            });
    connect(playback_, &StreamingPlayback::framesReady, this,
            &IdentificationStreamingPage::showFrames);
    connect(playback_, &StreamingPlayback::stateChanged, this,
            &IdentificationStreamingPage::playbackStateChanged);
    connect(playback_, &StreamingPlayback::failed, this, [this](const QString& message) {
        status_->setText("<b>Error:</b> " + message.toHtmlEscaped().replace("\n", "<br>"));
        // The data could not be read or played: say so where "preparing…" was.
        position_->setRange(0, 1);
        position_->setValue(0);
        position_->setFormat("failed: see the message below");
    });
    updateControls();
}

IdentificationStreamingPage::~IdentificationStreamingPage() {
    delete playback_;  // stops the run and joins its worker before the figures go
    playback_ = nullptr;
}

void IdentificationStreamingPage::setStreamSource(const QString& csv_path,
                                                  const QString& second_soil) {
    file_->setText(csv_path);
    source_->setCurrentIndex(csv_path.isEmpty() ? 0 : 1);
    if (const int i = second_soil_->findData(second_soil); i >= 0) second_soil_->setCurrentIndex(i);
    updateControls();
}

void IdentificationStreamingPage::setStreamSpeed(double speed) {
    int best = 0;
    for (int i = 0; i < speed_->count(); ++i) {
        if (std::abs(speed_->itemData(i).toDouble() - speed) <
            std::abs(speed_->itemData(best).toDouble() - speed))
            best = i;
    }
    speed_->setCurrentIndex(best);
}

bool IdentificationStreamingPage::canPlay() const { return play_->isEnabled(); }

void IdentificationStreamingPage::play() {
    if (playback_->state() == StreamingPlayback::State::kPaused) {
        playback_->resume();
        return;
    }
    const Project& project = document_->project();
    analysis::StreamingSettings settings = streamSettings();
    if (source_->currentIndex() == 1 && settings.csv.empty()) {
        status_->setText("<b>Error:</b> choose a CSV file to play");
        return;
    }
    const analysis::Inputs inputs = project::inputsOf(project);
    // Reading or synthesising runs on the worker, not on the GUI thread.
    StreamingPlayback::SourceFactory factory = [inputs, settings]() mutable {
        if (settings.csv.empty()) {
            auto soil = io::resolveSoil(studioPresetLocations(), settings.second_soil);
            if (!soil) throw std::invalid_argument("second soil: " + soil.message());
            settings.second = *soil;
        }
        return analysis::streamSource(inputs, settings);
    };
    // A running playback ends first (its "stopped" state is handled now, not after the new run's
    // figures were cleared).
    if (playback_->isActive()) playback_->stop();
    emit aboutToPlay();
    pending_hash_ = project::inputsHash(this->inputs());
    hash_.clear();  // nothing of a run is saved until its data are ready
    frames_.clear();
    count_ = 0;
    border_.reset();
    figures_->reset("Estimates: preparing the data…", 0, std::nullopt,
                    identification::StreamingEstimatorOptions{}.change_threshold);
    figures_->replot();
    position_->setRange(0, 1);
    position_->setValue(0);
    position_->setFormat("preparing…");
    status_->setText("Playing…");
    playback_->start(std::move(factory), project.wheel,
                     analysis::streamingOptions(inputs, settings),
                     speed_->currentData().toDouble());
}

analysis::StreamingSettings IdentificationStreamingPage::streamSettings() const {
    analysis::StreamingSettings settings;
    if (source_->currentIndex() == 1) {
        settings.csv = file_->text().trimmed().toStdString();
        settings.skip_bad_rows = skip_bad_rows_->isChecked();
    }
    settings.second_soil = second_soil_->currentData().toString().toStdString();
    settings.noise_percent = noise_->value();
    return settings;
}

void IdentificationStreamingPage::pausePlayback() { playback_->pause(); }

void IdentificationStreamingPage::stopPlayback() { playback_->stop(); }

void IdentificationStreamingPage::showFrames(const std::vector<StreamFrame>& frames) {
    frames_.insert(frames_.end(), frames.begin(), frames.end());
    figures_->append(frames);
    // Drawing is the GUI thread's only real work here: at most one replot per 40 ms however
    // fast the frames come.
    if (!replot_timer_->isActive()) replot_timer_->start();
}

QString IdentificationStreamingPage::status() const { return status_->text(); }

void IdentificationStreamingPage::updatePosition() {
    position_->setValue(static_cast<int>(frames_.size()));
    if (frames_.empty()) {
        position_text_->setText(count_ > 0 ? QString("%1 samples").arg(count_) : QString());
        return;
    }
    const StreamFrame& f = frames_.back();
    position_text_->setText(QString("sample %1 · t = %2 s · NIS %3 · CUSUM %4")
                                .arg(f.estimate.index)
                                .arg(f.time_s, 0, 'f', 2)
                                .arg(f.estimate.nis, 0, 'f', 1)
                                .arg(f.estimate.cusum, 0, 'f', 1));
}

void IdentificationStreamingPage::updateControls() {
    const bool csv = source_->currentIndex() == 1;
    second_soil_->setVisible(!csv);
    noise_->setVisible(!csv);
    file_->setVisible(csv);
    browse_->setVisible(csv);
    skip_bad_rows_->setVisible(csv);
    const auto state = playback_->state();
    const bool active = playback_->isActive();
    play_->setEnabled(state != StreamingPlayback::State::kPlaying);
    play_->setText(state == StreamingPlayback::State::kPaused ? "▶ Resume" : "▶ Play");
    pause_->setEnabled(state == StreamingPlayback::State::kPlaying);
    stop_->setEnabled(active);
    source_->setEnabled(!active);
    second_soil_->setEnabled(!active);
    noise_->setEnabled(!active);
    file_->setEnabled(!active);
    browse_->setEnabled(!active);
    skip_bad_rows_->setEnabled(!active);
}

void IdentificationStreamingPage::playbackStateChanged(StreamingPlayback::State state) {
    using State = StreamingPlayback::State;
    updateControls();
    if (state == State::kPlaying || state == State::kPaused) {
        if (state == State::kPaused)
            status_->setText("Paused: Resume goes on from the next sample.");
        else if (!frames_.empty())
            status_->setText("Playing…");
        return;
    }
    replot_timer_->stop();
    updatePosition();
    figures_->replot();
    if (state == State::kFailed || state == State::kIdle) {
        emit playbackEnded(state);
        return;
    }
    stopped_ = state != State::kFinished;
    figures_->setCompletion(stopped_ ? Completion::kCancelled : Completion::kComplete);
    figures_->replot();
    status_->setText(summary(state == State::kFinished));
    emit playbackEnded(state);
}

void IdentificationStreamingPage::clearResult() {
    stopPlayback();
    truth_.clear();
    border_.reset();
    count_ = 0;
    description_.clear();
    warnings_.clear();
    stopped_ = false;
    resetFigures(0);
    figures_->replot();
    hash_.clear();
    status_->setText("Not played yet: press Play.");
}

void IdentificationStreamingPage::resetFigures(std::size_t count) {
    frames_.clear();
    frames_.reserve(count);
    figures_->reset(truth_.empty() ? QString("Estimates") : QString("Estimates (dotted: truth)"),
                    count, border_, identification::StreamingEstimatorOptions{}.change_threshold);
    figures_->setTruth(truth_);
    position_->setRange(0, static_cast<int>(count));
    position_->setValue(0);
    position_->setFormat("%v / %m samples");
}

QString IdentificationStreamingPage::summary(bool finished) const {
    QStringList changes;
    for (std::size_t c : figures_->changePoints()) changes << QString::number(c);
    // A stopped playback is marked as every panel marks a cancelled run (completion.h).
    QString text = finished ? QString("Finished: %1 samples").arg(frames_.size())
                            : QString("<b>%1</b> — stopped after %2 of %3 samples")
                                  .arg(completionMark(Completion::kCancelled))
                                  .arg(frames_.size())
                                  .arg(count_);
    if (!description_.isEmpty()) text += QString(" (%1)").arg(description_.toHtmlEscaped());
    text += changes.isEmpty() ? QString("; no change of soil detected")
                              : QString("; change of soil at sample %1").arg(changes.join(", "));
    if (border_) text += QString(" (true border: %1)").arg(*border_);
    if (!frames_.empty() && frames_.back().estimate.estimated) {
        const auto& p = frames_.back().parameters;
        QStringList values;
        for (const char* key : {"phi_deg", "c_kPa", "K_m"}) {
            const analysis::IdentifiedField& f = *analysis::findIdentifiedField(key);
            const auto full = analysis::fullParameterOf(f);
            // Rounded to the std's second digit, as the batch fit's table (no "5.72e-18 ± 0.4").
            const double sd =
                frames_.back().estimate.std[static_cast<std::size_t>(*full)] / f.to_si;
            values << QString("%1 = %2 ± %3 %4")
                          .arg(QString::fromUtf8(f.symbol))
                          .arg(formatWithStd(f.userValue(p), sd))
                          .arg(formatStd(sd))
                          .arg(QString::fromStdString(f.displayUnit()));
        }
        text += ". Last estimate ± std: " + values.join(", ");
    }
    if (!warnings_.isEmpty()) {
        text += QString(". %1 warning(s): %2")
                    .arg(warnings_.size())
                    .arg(warnings_.mid(0, 3).join("; ").toHtmlEscaped());
    }
    return text;
}

void IdentificationStreamingPage::writeSettings(project::IdentificationPanelSettings& s) const {
    s.stream.csv = source_->currentIndex() == 1 ? file_->text().toStdString() : "";
    s.stream.second_soil = second_soil_->currentData().toString().toStdString();
    s.stream.noise_percent = noise_->value();
    s.stream_speed = speed_->currentData().toDouble();
    s.stream.skip_bad_rows = skip_bad_rows_->isChecked();
}

void IdentificationStreamingPage::applySettings(const project::IdentificationPanelSettings& s) {
    setStreamSource(QString::fromStdString(s.stream.csv),
                    QString::fromStdString(s.stream.second_soil));
    noise_->setValue(s.stream.noise_percent);
    setStreamSpeed(s.stream_speed);
    skip_bad_rows_->setChecked(s.stream.skip_bad_rows);
}

Table IdentificationStreamingPage::framesTable() const { return analysis::framesTable(frames_); }

nlohmann::json IdentificationStreamingPage::inputs() const {
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

std::optional<project::SavedResult> IdentificationStreamingPage::savedResult() const {
    // A playback that ended (finished or stopped), not one going on.
    if (playback_->isActive() || frames_.empty() || hash_.empty()) return std::nullopt;
    project::SavedResult saved;
    saved.inputs_hash = hash_;
    saved.version = project::kStreamingVersion;
    saved.partial = stopped_;
    saved.summary =
        QString("%1 of %2 samples played").arg(frames_.size()).arg(count_).toStdString();
    project::SavedStream stream;
    stream.frames = frames_;
    stream.sample_count = count_;
    stream.true_border = border_;
    stream.description = description_.toStdString();
    for (const QString& w : warnings_) stream.warnings.push_back(w.toStdString());
    stream.truth = truth_;
    stream.stopped = stopped_;
    saved.result = project::savedJson(stream);
    saved.tables.push_back({"frames", std::nullopt, analysis::framesTable(frames_)});
    return saved;
}

void IdentificationStreamingPage::showSaved(project::SavedStream stream, const std::string& hash) {
    count_ = stream.sample_count;
    border_ = stream.true_border;
    description_ = QString::fromStdString(stream.description);
    warnings_.clear();
    for (const std::string& w : stream.warnings) warnings_ << QString::fromStdString(w);
    truth_ = std::move(stream.truth);
    stopped_ = stream.stopped;
    hash_ = hash;
    resetFigures(count_);
    frames_ = std::move(stream.frames);
    figures_->append(frames_);
    figures_->setCompletion(stopped_ ? Completion::kCancelled : Completion::kComplete);
    figures_->replot();
    updatePosition();
    status_->setText("Saved with the project (not played again): " + summary(!stopped_));
}

}  // namespace terra::ui
