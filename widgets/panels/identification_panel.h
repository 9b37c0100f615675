#pragma once
/// @file identification_panel.h
/// Identification panel (chapter 5, Figs. 5.1–5.6): synthesise data from the project's soil or
/// load a CSV, run the global identification on the full model (core/identification/identify.h
/// through core/analysis/identification.h, the same procedure as `terrastudio identify`) or the
/// decoupled fit alone, and see data against fitted curves for F_x, F_z and M_y with the
/// parameters ± std, prior against posterior, the held-out error, the ambiguity (both answers) and
/// the Newton decrement. A CSV's fit depends on the CSV and the panel's options only, never on the
/// project's soil; the panel says what the fit starts from. Runs on "Fit", off the GUI thread.
///
/// Its second page plays a data set back through the streaming estimator
/// (widgets/analyses/streaming_playback.h): a CSV, or a synthetic drive from the project's soil
/// onto a second soil, fed sample by sample on a worker at 0.1×, 1×, 10× or full speed, with pause
/// and stop; the estimates with ±σ bands, the CUSUM and the confirmed change points grow as it
/// plays. A CSV that cannot be read is reported with its line numbers.
///
/// A CSV chosen for the batch fit is previewed before Fit (data_preview.h, a "Data preview"
/// tab beside the parameters, in front until a fit is shown): its first rows as
/// the file has them, the columns found and ignored, the rows read and every bad row by line, and
/// the channels the fit will compare (core/analysis/data_preview.h, read on a worker as the fit
/// reads it), or why it cannot fit the file.
///
/// The panel is a thin composition: the batch fit page (identification_fit_page.h, whose fit
/// runs through this AnalysisPanel's worker), the streaming page
/// (identification_streaming_page.h) and the data preview inside the fit page; it keeps the
/// settings, the saved results and the studio's interface of both pages.
///
/// The fit's wheel is chosen and stated (issue 25, item 6): the data's wheel when a sidecar JSON
/// beside the CSV names one (core/io/experiment.h's metadata), else the project's, or a preset;
/// the line under the options says which wheel and why. j_max is auto (the project soil's for
/// synthetic data, none for a CSV), none, fixed or identified, and the report says whether the
/// residuals are noise (the adequacy check) and lists the distinct other minima only.

#include "core/analysis/identification.h"
#include "core/analysis/streaming_identification.h"
#include "core/project/panels.h"
#include "widgets/analyses/streaming_playback.h"
#include "widgets/panels/analysis_panel.h"
#include "widgets/plots/identification_figures.h"

class QTabWidget;

namespace terra::ui {

class IdentificationFitPage;
class IdentificationStreamingPage;

class IdentificationPanel : public AnalysisPanel {
    Q_OBJECT
public:
    explicit IdentificationPanel(ProjectDocument* document, QWidget* parent = nullptr);
    ~IdentificationPanel() override;  ///< stops the playback and waits for its worker

    const analysis::IdentificationResult& result() const;
    /// The batch fit's settings as the controls show them (core/analysis/identification.h).
    analysis::IdentificationSettings fitSettings() const;
    /// The streaming playback's settings as the controls show them (the second soil by name).
    analysis::StreamingSettings streamSettings() const;
    /// Uses this CSV as data (empty: synthesise from the project's soil).
    void setDataFile(const QString& path);
    /// The preview of the batch fit's CSV (plain text of its summary: rows, columns, bad rows by
    /// line, channels fitted; empty for synthetic data), and its first rows as cells. It is read
    /// on a worker: dataPreviewReading() is true until it is shown (dataPreviewShown()).
    QString dataPreview() const;
    QString dataPreviewCell(int row, int column) const;
    QString dataPreviewHeader(int column) const;
    bool dataPreviewReading() const;
    /// What the next fit starts from, as the panel shows it ("global search …", "prior: …").
    QString startDescription() const;
    /// The batch page's status line and its report (held-out error, ambiguity, the Newton decrement
    /// in words).
    QString fitStatus() const;
    QString fitReport() const;
    /// The global fit's options as a user sets them: prior soil ("" none), prior items,
    /// validation ("none", "holdout", "folds"), loss ("l2", "huber", "cauchy").
    void setFitOptions(const QString& prior_soil, const QString& prior_items,
                       const QString& validation, const QString& loss);
    /// The fit's wheel: "" (the data's when they name one, else the project's), "project" or a
    /// wheel preset's name.
    void setWheelChoice(const QString& choice);
    /// The wheel the next fit uses and the visible sentence that says which and why.
    wheel::WheelParameters chosenWheel() const;
    QString wheelDescription() const;
    /// The wheel the data name (a sidecar JSON beside the CSV), if any.
    const std::optional<wheel::WheelParameters>& dataWheel() const;
    /// The wheel of the fit on screen.
    const wheel::WheelParameters& fitWheel() const;
    /// j_max of the fit: "auto", "none", "fixed" (at jmax_mm) or "fit".
    void setShearLimit(const QString& mode, double jmax_mm = 20.0);
    /// The parameter table's text (row, column), for tests.
    QString parameterCell(int row, int column) const;
    /// The parameter table's header text of a column, for tests.
    QString parameterHeader(int column) const;
    /// The shown fit as a soil for the project: the identified a₀, a₁, K_s, n (n₀), n₁, c, φ, K
    /// on the wheel the fit used, with k_c : k_φ and γ of the project's soil (j_max too unless
    /// the fit held or identified one)
    /// (analysis::soilFromParameters: K_s = k_c/b + k_φ is the identified one on that wheel);
    /// named "<soil> (identified)" for synthetic data, "identified from <file>" for a CSV. Empty
    /// without a usable fit or when the result is not a valid soil.
    std::optional<soil::SoilParameters> identifiedSoil() const;
    /// "Apply identified soil to project": replaces the project's soil by identifiedSoil(), one
    /// undo step ("Apply identified soil (<source>)"). False when there is nothing to apply.
    bool applyIdentifiedSoil();
    std::vector<std::pair<QString, QCustomPlot*>> plots() const override;
    QCustomPlot* currentPlot() const override;
    /// The fit's data and curves, or on the streaming page one row per played sample.
    Table currentTable() const override;
    nlohmann::json settings() const override;
    void applySettings(const nlohmann::json& settings) override;
    /// The batch fit ("identification") and the last streaming playback that ended
    /// ("identification.streaming") on screen, for the project's results file; restoreResult
    /// shows each again, without fitting or playing, when its inputs are unchanged (the fit's:
    /// the soil, the fit's wheel, the conditions, the fit's options and the CSV's size and
    /// time; the playback's: the soil, wheel, load, its source and noise).
    std::map<std::string, project::SavedResult> savedResults() const override;
    Restored restoreResult(const std::string& section, const project::SavedResult& saved) override;

    // Streaming playback (the "Streaming playback" page).
    /// Shows the batch-fit page (0) or the streaming page (1).
    void showPage(int page);
    /// Fit on the batch page (as the button: priors checked first), Play on the streaming page.
    void requestRun() override;
    /// Plays the chosen source at the chosen speed (a running playback starts over; a paused
    /// one resumes).
    void play();
    void pausePlayback();
    void stopPlayback();
    /// The stream source: empty path = synthetic border from the project's soil onto `second_soil`.
    void setStreamSource(const QString& csv_path, const QString& second_soil = "clayey-soil");
    /// 0.1, 1, 10 or 0 (as fast as possible).
    void setStreamSpeed(double speed);
    const StreamingPlayback& playback() const;
    /// What the streaming figures hold (frames shown so far, change points found).
    const StreamingFigures& streamingFigures() const;
    /// The true border of the synthetic source being played (none for a CSV).
    std::optional<std::size_t> streamTrueBorder() const;
    std::size_t streamSampleCount() const;
    QString streamStatus() const;

protected:
    Job makeJob() override;
    void present(const std::any& result) override;
    nlohmann::json resultInputs() const override;
    void projectReplaced() override;

signals:
    /// The streaming playback ended: finished, stopped or failed (StreamingPlayback::State).
    void playbackEnded(terra::ui::StreamingPlayback::State state);
    /// The data preview of the batch fit's CSV is on screen (it is read on a worker).
    void dataPreviewShown();

private:
    /// What the controls show, as the project stores it (core/project/panels.h).
    project::IdentificationPanelSettings panelSettings() const;

    QTabWidget* pages_;
    IdentificationFitPage* fit_;
    IdentificationStreamingPage* streaming_;
    std::string fit_hash_;  // of the inputs of the fit on screen
};

}  // namespace terra::ui
