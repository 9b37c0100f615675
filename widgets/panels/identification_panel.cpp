#include "widgets/panels/identification_panel.h"

#include <qcustomplot.h>

#include <QCheckBox>
#include <QComboBox>
#include <QCoreApplication>
#include <QDoubleSpinBox>
#include <QFileDialog>
#include <QFileInfo>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QLineEdit>
#include <QProgressBar>
#include <QPushButton>
#include <QSplitter>
#include <QTabWidget>
#include <QTableWidget>
#include <QTimer>
#include <QVBoxLayout>
#include <cmath>

#include "core/io/parameters_json.h"
#include "core/project/panels.h"
#include "widgets/document/project_document.h"
#include "widgets/plots/figures.h"

namespace terra::ui {
namespace {

const char* kChannels[] = {"Fx_N", "Fz_N", "My_Nm"};

}  // namespace

IdentificationPanel::IdentificationPanel(ProjectDocument* document, QWidget* parent)
    : AnalysisPanel(document, "identification", parent) {
    setLive(false);
    file_ = new QLineEdit(this);
    file_->setPlaceholderText("synthesise from the project's soil (or choose a CSV)");
    file_->setMinimumWidth(220);
    auto* browse = new QPushButton("Load CSV…", this);
    noise_ = new QDoubleSpinBox(this);
    noise_->setRange(0.0, 20.0);
    noise_->setSuffix(" %");
    noise_->setValue(project::IdentificationPanelSettings{}.noise_percent);
    noise_->setToolTip(
        "Synthetic noise σ as a percentage of each channel's largest value (Eq. 5.1)");
    refine_ = new QCheckBox("Refine (full model, std deviations)", this);
    refine_->setChecked(project::IdentificationPanelSettings{}.refine);
    three_loads_ = new QCheckBox("Synthesise at ½W, W, 1½W", this);
    three_loads_->setChecked(true);
    three_loads_->setToolTip(
        "One load cannot separate c and φ when the data are noisy (full_fit.h)");
    fit_ = new QPushButton("Fit", this);
    fit_->setDefault(true);
    status_ = new QLabel(this);
    status_->setWordWrap(true);
    readout_ = new QLabel(this);
    tabs_ = new QTabWidget(this);
    for (const char* channel : kChannels) {
        auto* plot = new QCustomPlot(tabs_);
        makeInteractive(plot, readout_);
        plots_.push_back(plot);
        tabs_->addTab(plot, channel);
    }
    parameters_ = new QTableWidget(0, 4, this);
    parameters_->setHorizontalHeaderLabels({"Parameter", "Identified", "± std", "Project soil"});
    parameters_->horizontalHeader()->setSectionResizeMode(QHeaderView::Stretch);
    parameters_->verticalHeader()->hide();
    parameters_->setEditTriggers(QAbstractItemView::NoEditTriggers);

    auto* fit_page = new QWidget(this);
    auto* bar = new QHBoxLayout;
    bar->addWidget(file_, 1);
    bar->addWidget(browse);
    bar->addWidget(new QLabel("Noise:", this));
    bar->addWidget(noise_);
    bar->addWidget(three_loads_);
    bar->addWidget(refine_);
    bar->addWidget(fit_);
    auto* splitter = new QSplitter(this);
    splitter->addWidget(tabs_);
    splitter->addWidget(parameters_);
    splitter->setStretchFactor(0, 3);
    splitter->setStretchFactor(1, 1);
    parameters_->setMaximumWidth(460);
    auto* fit_layout = new QVBoxLayout(fit_page);
    fit_layout->setContentsMargins(0, 0, 0, 0);
    fit_layout->addLayout(bar);
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

    connect(browse, &QPushButton::clicked, this, [this] {
        const QString path =
            QFileDialog::getOpenFileName(this, "Load identification data", {}, "CSV (*.csv)");
        if (!path.isEmpty()) setDataFile(path);
    });
    connect(fit_, &QPushButton::clicked, this, [this] {
        storeSettings();
        recompute();
    });
    connect(this, &AnalysisPanel::busyChanged, this, [this](bool busy) {
        fit_->setEnabled(!busy);
        if (busy) status_->setText("Fitting…");
    });
    connect(this, &AnalysisPanel::failed, this, [this](const QString& m) {
        fit_->setEnabled(true);
        status_->setText("<b>Error:</b> " + m.toHtmlEscaped());
    });
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

nlohmann::json IdentificationPanel::settings() const {
    project::IdentificationPanelSettings s;
    s.csv = file_->text().toStdString();
    s.noise_percent = noise_->value();
    s.refine = refine_->isChecked();
    s.three_loads = three_loads_->isChecked();
    s.page = pages_->currentIndex() == 1 ? "streaming" : "fit";
    s.stream_csv = stream_source_->currentIndex() == 1 ? stream_file_->text().toStdString() : "";
    s.stream_second_soil = second_soil_->currentText().toStdString();
    s.stream_noise_percent = stream_noise_->value();
    s.stream_speed = speed_->currentData().toDouble();
    s.stream_skip_bad_rows = skip_bad_rows_->isChecked();
    return project::toJson(s);
}

void IdentificationPanel::applySettings(const nlohmann::json& json) {
    const auto settings =
        project::panelSettingsFromJson<project::IdentificationPanelSettings>(withChanges(json));
    if (!settings) return;  // projects are checked when opened: only a program error lands here
    const project::IdentificationPanelSettings& s = *settings;
    file_->setText(QString::fromStdString(s.csv));
    noise_->setValue(s.noise_percent);
    refine_->setChecked(s.refine);
    three_loads_->setChecked(s.three_loads);
    showPage(s.page == "streaming" ? 1 : 0);
    setStreamSource(QString::fromStdString(s.stream_csv),
                    QString::fromStdString(s.stream_second_soil));
    stream_noise_->setValue(s.stream_noise_percent);
    setStreamSpeed(s.stream_speed);
    skip_bad_rows_->setChecked(s.stream_skip_bad_rows);
}

analysis::IdentificationSettings IdentificationPanel::fitSettings() const {
    analysis::IdentificationSettings settings;
    settings.csv = file_->text().trimmed().toStdString();
    settings.synthetic.noise_percent = noise_->value();
    settings.refine = refine_->isChecked();
    if (three_loads_->isChecked()) {
        const double w = document_->project().conditions.load_n;
        settings.synthetic.loads_n = {0.5 * w, w, 1.5 * w};
    }
    return settings;
}

AnalysisPanel::Job IdentificationPanel::makeJob() {
    const analysis::Inputs inputs = project::inputsOf(document_->project());
    const analysis::IdentificationSettings settings = fitSettings();
    return [inputs, settings](const std::atomic<bool>& cancel) -> std::any {
        return analysis::computeIdentification(inputs, settings, {&cancel});
    };
}

void IdentificationPanel::present(const std::any& value) {
    result_ = std::any_cast<analysis::IdentificationResult>(value);
    if (!result_.message.empty()) {
        status_->setText("<b>Error:</b> " +
                         QString::fromStdString(result_.message).toHtmlEscaped());
        return;
    }
    const QString source = file_->text().isEmpty()
                               ? QString("synthetic, %1 % noise").arg(noise_->value())
                               : QFileInfo(file_->text()).fileName();
    for (std::size_t i = 0; i < plots_.size(); ++i) {
        plotIdentification(*plots_[i], result_, kChannels[i],
                           QString("Identification: %1 samples (%2)")
                               .arg(result_.data.samples.size())
                               .arg(source));
    }
    const Table& t = result_.parameters;
    const Project& project = document_->project();
    const auto truth = analysis::identifiedOf(project.soil, project.wheel);
    const bool synthetic = file_->text().isEmpty();
    const auto fields = analysis::identifiedFields();
    parameters_->setRowCount(static_cast<int>(fields.size()));
    for (std::size_t i = 0; i < fields.size(); ++i) {
        const analysis::IdentifiedField& field = fields[i];
        const int row = static_cast<int>(i);
        auto* name = new QTableWidgetItem(QString::fromStdString(field.symbolWithUnit()));
        name->setToolTip(QString::fromUtf8(field.description));
        parameters_->setItem(row, 0, name);
        parameters_->setItem(row, 1, new QTableWidgetItem(QString::number(t.rows[0][i], 'g', 5)));
        QString std_text = "–";
        for (std::size_t c = fields.size(); c < t.columns.size(); ++c) {
            if (t.columns[c] == std::string(field.key) + "_std")
                std_text = QString::number(t.rows[0][c], 'g', 3);
        }
        parameters_->setItem(row, 2, new QTableWidgetItem(std_text));
        parameters_->setItem(
            row, 3,
            new QTableWidgetItem(synthetic ? QString::number(field.userValue(truth), 'g', 5)
                                           : "–"));
    }
    QStringList steps;
    for (const auto& step : result_.fit.steps) {
        steps << QString("%1: Σr² = %2")
                     .arg(QString::fromStdString(step.name))
                     .arg(step.squared_residual_norm, 0, 'g', 4);
    }
    if (result_.refined) {
        steps << QString("refined: Σr² = %1 (%2)")
                     .arg(result_.refined->report.squared_residual_norm, 0, 'g', 4)
                     .arg(QString::fromStdString(result_.refined->report.termination).left(40));
        for (const auto& flag : result_.refined->uncertainty.flags)
            steps << QString::fromStdString(flag);
    }
    status_->setText(QString("Fit in %1 ms. ").arg(result_.fit_time_ms, 0, 'f', 0) +
                     steps.join(";  "));
}

// --- Streaming playback -------------------------------------------------------------------------

namespace {

io::PresetLocations presetLocations() {
    return io::PresetLocations::standard(QCoreApplication::applicationDirPath().toStdString());
}

}  // namespace

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
    for (const std::string& name : io::presetNames(presetLocations(), "soils")) {
        second_soil_->addItem(QString::fromStdString(name));
    }
    if (const int i = second_soil_->findText("clayey-soil"); i >= 0)
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
    position_text_->setMinimumWidth(260);
    stream_status_ = new QLabel(page);
    stream_status_->setWordWrap(true);
    stream_status_->setTextInteractionFlags(Qt::TextSelectableByMouse);
    for (int i = 0; i < 2; ++i) stream_plots_.push_back(new QCustomPlot(page));
    stream_figures_ = std::make_unique<StreamingFigures>(stream_plots_[0], stream_plots_[1]);
    playback_ = new StreamingPlayback(this);
    replot_timer_ = new QTimer(this);
    replot_timer_->setSingleShot(true);
    replot_timer_->setInterval(40);

    auto* source_row = new QHBoxLayout;
    source_row->addWidget(new QLabel("Source:", page));
    source_row->addWidget(stream_source_);
    source_row->addWidget(second_soil_);
    source_row->addWidget(stream_noise_);
    source_row->addWidget(stream_file_, 1);
    source_row->addWidget(stream_browse_);
    source_row->addWidget(skip_bad_rows_);
    source_row->addStretch(1);
    auto* play_row = new QHBoxLayout;
    play_row->addWidget(new QLabel("Speed:", page));
    play_row->addWidget(speed_);
    play_row->addWidget(play_);
    play_row->addWidget(pause_);
    play_row->addWidget(stop_);
    play_row->addWidget(position_, 1);
    play_row->addWidget(position_text_);
    auto* splitter = new QSplitter(page);
    splitter->addWidget(stream_plots_[0]);
    splitter->addWidget(stream_plots_[1]);
    splitter->setStretchFactor(0, 1);
    splitter->setStretchFactor(1, 1);
    splitter->setSizes({600, 600});  // half and half (a QCustomPlot has no size hint to share by)
    auto* layout = new QVBoxLayout(page);
    layout->setContentsMargins(0, 0, 0, 0);
    layout->addLayout(source_row);
    layout->addLayout(play_row);
    layout->addWidget(splitter, 1);
    layout->addWidget(stream_status_);
    stream_status_->setText(
        "Press Play: the samples are fed one at a time through the streaming identifier "
        "(sliding window of 60, change of soil when the residual score stays above 8).");

    connect(stream_source_, &QComboBox::currentIndexChanged, this,
            [this] { updateStreamControls(); });
    connect(stream_browse_, &QPushButton::clicked, this, [this] {
        const QString path =
            QFileDialog::getOpenFileName(this, "Play identification data", {}, "CSV (*.csv)");
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
                stream_frames_.clear();
                stream_frames_.reserve(count);
                stream_figures_->reset(source.truth.empty() ? QString("Estimates")
                                                            : QString("Estimates (dotted: truth)"),
                                       count, stream_border_,
                                       identification::StreamingOptions{}.threshold);
                stream_figures_->setTruth(source.truth);
                position_->setRange(0, static_cast<int>(count));
                position_->setValue(0);
                position_->setFormat("%v / %m samples");
                stream_figures_->replot();
                updatePosition();
            });
    connect(playback_, &StreamingPlayback::framesReady, this, &IdentificationPanel::showFrames);
    connect(playback_, &StreamingPlayback::stateChanged, this,
            &IdentificationPanel::playbackStateChanged);
    connect(playback_, &StreamingPlayback::failed, this, [this](const QString& message) {
        stream_status_->setText("<b>Error:</b> " + message.toHtmlEscaped().replace("\n", "<br>"));
    });
    updateStreamControls();
}

void IdentificationPanel::showPage(int page) { pages_->setCurrentIndex(page == 1 ? 1 : 0); }

void IdentificationPanel::setStreamSource(const QString& csv_path, const QString& second_soil) {
    stream_file_->setText(csv_path);
    stream_source_->setCurrentIndex(csv_path.isEmpty() ? 0 : 1);
    if (const int i = second_soil_->findText(second_soil); i >= 0) second_soil_->setCurrentIndex(i);
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
    stream_frames_.clear();
    stream_count_ = 0;
    stream_border_.reset();
    stream_figures_->reset("Estimates: preparing the data…", 0, std::nullopt,
                           identification::StreamingOptions{}.threshold);
    stream_figures_->replot();
    position_->setRange(0, 1);
    position_->setValue(0);
    position_->setFormat("preparing…");
    stream_status_->setText("Playing…");
    playback_->start(std::move(factory), project.wheel, settings.options,
                     speed_->currentData().toDouble());
}

analysis::StreamingSettings IdentificationPanel::streamSettings() const {
    analysis::StreamingSettings settings;
    if (stream_source_->currentIndex() == 1) {
        settings.csv = stream_file_->text().trimmed().toStdString();
        settings.skip_bad_rows = skip_bad_rows_->isChecked();
    }
    settings.second_soil = second_soil_->currentText().toStdString();
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
    position_text_->setText(QString("sample %1 · t = %2 s · window %3 · score %4")
                                .arg(f.update.index)
                                .arg(f.time_s, 0, 'f', 2)
                                .arg(f.update.window_size)
                                .arg(f.update.residual_score, 0, 'f', 1));
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
    QStringList changes;
    for (std::size_t c : stream_figures_->changePoints()) changes << QString::number(c);
    QString text = state == State::kFinished
                       ? QString("Finished: %1 samples").arg(stream_frames_.size())
                       : QString("Stopped after %1 of %2 samples")
                             .arg(stream_frames_.size())
                             .arg(stream_count_);
    if (!stream_description_.isEmpty())
        text += QString(" (%1)").arg(stream_description_.toHtmlEscaped());
    text += changes.isEmpty() ? QString("; no change of soil detected")
                              : QString("; change of soil at sample %1").arg(changes.join(", "));
    if (stream_border_) text += QString(" (true border: %1)").arg(*stream_border_);
    if (!stream_frames_.empty() && stream_frames_.back().update.estimated) {
        const auto& p = stream_frames_.back().update.parameters;
        QStringList values;
        for (const char* key : {"phi_deg", "c_kPa", "K_m"}) {
            const analysis::IdentifiedField& f = *analysis::findIdentifiedField(key);
            values << QString("%1 = %2 %3")
                          .arg(QString::fromUtf8(f.symbol))
                          .arg(f.userValue(p), 0, 'g', 3)
                          .arg(QString::fromStdString(f.displayUnit()));
        }
        text +=
            ". Last estimate (decoupled model, biased; refine a settled window for numbers "
            "to report): " +
            values.join(", ");
    }
    if (!stream_warnings_.isEmpty()) {
        text += QString(". %1 warning(s): %2")
                    .arg(stream_warnings_.size())
                    .arg(stream_warnings_.mid(0, 3).join("; ").toHtmlEscaped());
    }
    stream_status_->setText(text);
    emit playbackEnded(state);
}

}  // namespace terra::ui
