#pragma once
/// @file identification_figures.h
/// The streaming-identification figures (widgets/analyses/streaming_playback.h), drawn as the
/// samples arrive: the estimated parameters over sample index (φ and c, K_s and n₀, K) with
/// shaded ±σ bands (the estimator's posterior std), the CUSUM of the change test with its
/// threshold, and measured against predicted F_x, with the confirmed change points (and the true
/// border of synthetic data) as vertical lines.

#include <QString>
#include <cstddef>
#include <optional>
#include <vector>

#include "widgets/analyses/streaming_playback.h"

class QCustomPlot;
class QCPAxisRect;
class QCPGraph;
class QCPItemText;
class QCPTextElement;

#include "widgets/plots/completion.h"

namespace terra::ui {

class StreamingFigures {
public:
    /// Draws into two plots that it owns the content of (their layouts are replaced).
    StreamingFigures(QCustomPlot* estimates, QCustomPlot* detection);

    /// Empties both figures for a run of `sample_count` samples.
    void reset(const QString& title, std::size_t sample_count,
               std::optional<std::size_t> true_border, double threshold);
    /// Draws the parameters the data were made with (synthetic sources) as dotted steps.
    void setTruth(
        const std::vector<std::pair<std::size_t, identification::DecoupledParameters>>& truth);
    /// Adds frames (in order). Does not replot.
    void append(const std::vector<StreamFrame>& frames);
    /// Marks the estimates' title as every panel marks a stopped run ("… — CANCELLED (partial)",
    /// completion.h), or unmarks it. Does not replot.
    void setCompletion(Completion completion);
    /// The estimates figure's title as shown.
    QString title() const;
    /// Rescales the value axes to the data and replots both figures.
    void replot();

    std::size_t frameCount() const { return frames_; }
    /// Where each confirmed change began, and the sample that confirmed it.
    const std::vector<std::size_t>& changePoints() const { return changes_; }
    const std::vector<std::size_t>& confirmedAt() const { return confirmed_; }
    /// Graphs by name, for tests: "phi", "c", "Ks", "n0", "K", their bands "phi_lo", "phi_hi", …
    /// (estimate ∓ std), "score" (the CUSUM), "fx_measured", "fx_predicted", and the truth
    /// "phi_true", "c_true", "Ks_true", "n0_true", "K_true".
    QCPGraph* graph(const QString& name) const;

private:
    QCPAxisRect* addRect(QCustomPlot* plot, int row, const QString& left, const QString& right,
                         bool log);
    /// The labels it made (one per figure).
    std::vector<QCPItemText*> markVertical(std::size_t index, const QColor& color,
                                           Qt::PenStyle style, const QString& label,
                                           const QString& long_label = {});

    QCustomPlot* estimates_;
    QCustomPlot* detection_;
    std::vector<QCPAxisRect*> rects_;
    std::vector<std::pair<QString, QCPGraph*>> graphs_;
    QCPGraph* current_ = nullptr;  // the latest sample, highlighted
    QCPTextElement* current_label_ = nullptr;
    QString title_;  // as given to reset(), unmarked
    std::size_t frames_ = 0;
    std::size_t sample_count_ = 0;
    double threshold_ = 13.8155;
    std::vector<std::size_t> changes_;
    std::vector<std::size_t> confirmed_;
    // The true border (a synthetic source) and its labels: moved to mid-height when a change is
    // marked next to it, so that the two labels do not run into each other.
    std::optional<std::size_t> border_;
    std::vector<QCPItemText*> border_labels_;
};

}  // namespace terra::ui
