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

#include "core/common/units.h"
#include "core/io/parameters_json.h"
#include "widgets/document/project_document.h"
#include "widgets/plots/figures.h"

namespace terra::ui {
namespace {

const char* kChannels[] = {"Fx_N", "Fz_N", "My_Nm"};

// The project soil's value of each identified parameter (user units), for comparison.
std::vector<double> trueValues(const Project& p) {
    const auto& s = p.soil;
    const double ks = s.cohesive_modulus / p.wheel.width_m + s.frictional_modulus;
    return {s.max_stress_a0,
            s.max_stress_a1,
            ks / 1e3,
            s.sinkage_exponent,
            s.sinkage_exponent_slip,
            s.cohesion_pa / 1e3,
            units::radToDeg(s.friction_angle_rad),
            s.shear_modulus_m};
}

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
    noise_->setValue(2.0);
    noise_->setToolTip(
        "Synthetic noise σ as a percentage of each channel's largest value (Eq. 5.1)");
    refine_ = new QCheckBox("Refine (full model, std deviations)", this);
    refine_->setChecked(true);
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
    Table t;
    t.columns = {"sample", "time_s",        "estimated", "a0",  "a1",    "Ks_kPa",    "n0",
                 "n1",     "c_kPa",         "phi_deg",   "K_m", "score", "change_at", "window",
                 "Fx_N",   "Fx_predicted_N"};
    for (const StreamFrame& f : stream_frames_) {
        const auto& u = f.update;
        const auto& p = u.parameters;
        const double nan = std::nan("");
        const bool e = u.estimated;
        t.rows.push_back({static_cast<double>(u.index), f.time_s, e ? 1.0 : 0.0, e ? p.a0 : nan,
                          e ? p.a1 : nan, e ? p.pressure_modulus / 1e3 : nan, e ? p.n0 : nan,
                          e ? p.n1 : nan, e ? p.cohesion_pa / 1e3 : nan,
                          e ? units::radToDeg(p.friction_angle_rad) : nan,
                          e ? p.shear_modulus_m : nan, u.residual_score,
                          u.change_at ? static_cast<double>(*u.change_at) : nan,
                          static_cast<double>(u.window_size), f.fx_measured_n, f.fx_predicted_n});
    }
    return t;
}

nlohmann::json IdentificationPanel::settings() const {
    return {{"csv", file_->text().toStdString()},
            {"noise_percent", noise_->value()},
            {"refine", refine_->isChecked()},
            {"three_loads", three_loads_->isChecked()},
            {"page", pages_->currentIndex() == 1 ? "streaming" : "fit"},
            {"stream_csv", stream_source_->currentIndex() == 1 ? stream_file_->text().toStdString()
                                                               : std::string()},
            {"stream_second_soil", second_soil_->currentText().toStdString()},
            {"stream_noise_percent", stream_noise_->value()},
            {"stream_speed", speed_->currentData().toDouble()},
            {"stream_skip_bad_rows", skip_bad_rows_->isChecked()}};
}

void IdentificationPanel::applySettings(const nlohmann::json& s) {
    if (s.contains("csv")) file_->setText(QString::fromStdString(s["csv"].get<std::string>()));
    if (s.contains("noise_percent")) noise_->setValue(s["noise_percent"].get<double>());
    if (s.contains("refine")) refine_->setChecked(s["refine"].get<bool>());
    if (s.contains("three_loads")) three_loads_->setChecked(s["three_loads"].get<bool>());
    if (s.contains("page")) showPage(s["page"].get<std::string>() == "streaming" ? 1 : 0);
    if (s.contains("stream_csv") || s.contains("stream_second_soil")) {
        setStreamSource(QString::fromStdString(s.value("stream_csv", std::string())),
                        QString::fromStdString(s.value("stream_second_soil",
                                                       second_soil_->currentText().toStdString())));
    }
    if (s.contains("stream_noise_percent"))
        stream_noise_->setValue(s["stream_noise_percent"].get<double>());
    if (s.contains("stream_speed")) setStreamSpeed(s["stream_speed"].get<double>());
    if (s.contains("stream_skip_bad_rows"))
        skip_bad_rows_->setChecked(s["stream_skip_bad_rows"].get<bool>());
}

AnalysisPanel::Job IdentificationPanel::makeJob() {
    const AnalysisInputs inputs = AnalysisInputs::from(document_->project());
    IdentificationSettings settings;
    settings.csv = file_->text().trimmed().toStdString();
    settings.noise_relative = noise_->value() / 100.0;
    settings.refine = refine_->isChecked();
    if (three_loads_->isChecked()) {
        const double w = inputs.conditions.load_n;
        settings.loads_n = {0.5 * w, w, 1.5 * w};
    }
    return [inputs, settings](const std::atomic<bool>&) -> std::any {
        return computeIdentification(inputs, settings);
    };
}

void IdentificationPanel::present(const std::any& value) {
    result_ = std::any_cast<IdentificationResult>(value);
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
    const std::vector<double> truth = trueValues(document_->project());
    const bool synthetic = file_->text().isEmpty();
    parameters_->setRowCount(8);
    for (int i = 0; i < 8; ++i) {
        const std::string name = t.columns[static_cast<std::size_t>(i)];
        parameters_->setItem(i, 0, new QTableWidgetItem(QString::fromStdString(name)));
        parameters_->setItem(
            i, 1,
            new QTableWidgetItem(QString::number(t.rows[0][static_cast<std::size_t>(i)], 'g', 5)));
        QString std_text = "–";
        for (std::size_t c = 8; c < t.columns.size(); ++c) {
            if (t.columns[c] == name + "_std") std_text = QString::number(t.rows[0][c], 'g', 3);
        }
        parameters_->setItem(i, 2, new QTableWidgetItem(std_text));
        parameters_->setItem(
            i, 3,
            new QTableWidgetItem(
                synthetic ? QString::number(truth[static_cast<std::size_t>(i)], 'g', 5) : "–"));
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
    stream_noise_->setValue(1.0);
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
    StreamingPlayback::SourceFactory factory;
    const Project& project = document_->project();
    if (stream_source_->currentIndex() == 1) {
        const std::string path = stream_file_->text().trimmed().toStdString();
        if (path.empty()) {
            stream_status_->setText("<b>Error:</b> choose a CSV file to play");
            return;
        }
        const bool skip = skip_bad_rows_->isChecked();
        factory = [path, skip] {
            auto read = readStreamSource(path, skip);
            if (!read) throw std::invalid_argument(read.message());
            return *read;
        };
    } else {
        SoilBorderSpec spec;
        spec.first = project.soil;
        spec.wheel = project.wheel;
        spec.load_n = project.conditions.load_n;
        spec.noise_relative = stream_noise_->value() / 100.0;
        const std::string second = second_soil_->currentText().toStdString();
        factory = [spec, second]() mutable {
            auto soil = io::resolveSoil(presetLocations(), second);
            if (!soil) throw std::invalid_argument("second soil: " + soil.message());
            spec.second = *soil;
            return synthesiseSoilBorder(spec);
        };
    }
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
    playback_->start(std::move(factory), project.wheel, identification::StreamingOptions{},
                     speed_->currentData().toDouble());
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
        text += QString(
                    ". Last estimate (decoupled model, biased; refine a settled window for numbers "
                    "to report): "
                    "φ = %1°, c = %2 kPa, K = %3 mm")
                    .arg(units::radToDeg(p.friction_angle_rad), 0, 'f', 1)
                    .arg(p.cohesion_pa / 1e3, 0, 'f', 2)
                    .arg(p.shear_modulus_m * 1e3, 0, 'f', 1);
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
