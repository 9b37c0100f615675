#pragma once
/// @file identification_streaming_page.h
/// The identification panel's "Streaming playback" page (identification_panel.h): a data set
/// played back through the streaming estimator (widgets/analyses/streaming_playback.h) — a CSV,
/// or a synthetic drive from the project's soil onto a second soil — fed sample by sample on a
/// worker at 0.1×, 1×, 10× or full speed, with pause and stop; the estimates with ±σ bands, the
/// CUSUM and the confirmed change points grow as it plays. A CSV that cannot be read is reported
/// with its line numbers.

#include <QStringList>
#include <QWidget>
#include <memory>
#include <optional>

#include "core/analysis/streaming_identification.h"
#include "core/project/panels.h"
#include "core/project/results.h"
#include "core/project/saved_identification.h"
#include "widgets/analyses/streaming_playback.h"
#include "widgets/plots/identification_figures.h"

class QCheckBox;
class QComboBox;
class QCustomPlot;
class QDoubleSpinBox;
class QLabel;
class QLineEdit;
class QProgressBar;
class QPushButton;
class QTimer;

namespace terra::ui {

class ProjectDocument;

class IdentificationStreamingPage : public QWidget {
    Q_OBJECT
public:
    explicit IdentificationStreamingPage(ProjectDocument* document, QWidget* parent = nullptr);
    ~IdentificationStreamingPage() override;  ///< stops the playback and waits for its worker

    /// The playback's settings as the controls show them (the second soil by name).
    analysis::StreamingSettings streamSettings() const;
    /// The controls' part of the panel's saved settings, and setting them from it.
    void writeSettings(project::IdentificationPanelSettings& s) const;
    void applySettings(const project::IdentificationPanelSettings& s);
    /// Plays the chosen source at the chosen speed (a running playback starts over; a paused
    /// one resumes).
    void play();
    /// Whether Play can be pressed now (the studio's Ctrl+R).
    bool canPlay() const;
    void pausePlayback();
    void stopPlayback();
    /// The stream source: empty path = synthetic border from the project's soil onto `second_soil`.
    void setStreamSource(const QString& csv_path, const QString& second_soil = "clayey-soil");
    /// 0.1, 1, 10 or 0 (as fast as possible).
    void setStreamSpeed(double speed);
    const StreamingPlayback& playback() const { return *playback_; }
    const StreamingFigures& figures() const { return *figures_; }
    /// The estimates (0) and detection (1) plots.
    const std::vector<QCustomPlot*>& plots() const { return plots_; }
    /// One row per played sample of the run on screen.
    Table framesTable() const;
    std::optional<std::size_t> trueBorder() const { return border_; }
    std::size_t sampleCount() const { return count_; }
    QString status() const;

    /// What the playback's result depends on (not its speed), hashed for the results file.
    nlohmann::json inputs() const;
    /// The last playback that ended (finished or stopped), for the project's results file; none
    /// while one goes on or before any.
    std::optional<project::SavedResult> savedResult() const;
    /// Shows a saved playback whose inputs hash `hash`, without playing it again.
    void showSaved(project::SavedStream stream, const std::string& hash);
    /// No playback on screen (another project was opened): stopped, its figures emptied.
    void clearResult();

signals:
    /// Play starts a new run (the panel stores its settings).
    void aboutToPlay();
    /// The playback ended: finished, stopped or failed (StreamingPlayback::State).
    void playbackEnded(terra::ui::StreamingPlayback::State state);

private:
    void showFrames(const std::vector<StreamFrame>& frames);
    void playbackStateChanged(StreamingPlayback::State state);
    void updateControls();
    void updatePosition();
    /// The status line once a playback ended (finished or stopped).
    QString summary(bool finished) const;
    /// Starts the figures over for a source of `count` samples.
    void resetFigures(std::size_t count);

    ProjectDocument* document_;
    QComboBox* source_;
    QComboBox* second_soil_;
    QDoubleSpinBox* noise_;
    QLineEdit* file_;
    QPushButton* browse_;
    QCheckBox* skip_bad_rows_;
    QComboBox* speed_;
    QPushButton* play_;
    QPushButton* pause_;
    QPushButton* stop_;
    QProgressBar* position_;
    QLabel* position_text_;
    QLabel* status_;
    std::vector<QCustomPlot*> plots_;
    std::unique_ptr<StreamingFigures> figures_;
    StreamingPlayback* playback_;
    QTimer* replot_timer_;  // coalesces replots while frames arrive (at most ~25 per second)
    std::optional<std::size_t> border_;
    std::size_t count_ = 0;
    std::vector<StreamFrame> frames_;  // of the run on screen
    QString description_;
    QStringList warnings_;
    std::vector<std::pair<std::size_t, identification::DecoupledParameters>> truth_;
    bool stopped_ = false;      // the playback on screen was stopped before its end
    std::string hash_;          // of the inputs of the playback on screen
    std::string pending_hash_;  // of the playback being started (play())
};

}  // namespace terra::ui
