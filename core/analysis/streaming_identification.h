#pragma once
/// @file streaming_identification.h
/// Streaming identification of a data set on the full model (core/identification/
/// streaming_estimator.h: moving horizon with an arrival cost, CUSUM on normalised innovations
/// confirmed by a likelihood-ratio test): the samples fed one at a time, each giving a frame — the
/// estimate with its std, the normalised innovation and the CUSUM, a confirmed change of soil, and
/// F_x measured against F_x predicted by the estimate before the sample. The data are a CSV
/// or a synthetic drive over a soil border. The studio's streaming playback (which paces the same
/// frames in time, widgets/analyses/streaming_playback.h), `terrastudio identify --stream` and a
/// script's "streaming" analysis.

#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/analysis/analysis.h"
#include "core/common/declared_fields.h"
#include "core/common/issue.h"
#include "core/common/range.h"
#include "core/contact/operating_fields.h"
#include "core/identification/data_set.h"
#include "core/identification/decoupled_fit.h"
#include "core/identification/streaming_estimator.h"
#include "core/soil/soil_parameters.h"

namespace terra::analysis {

struct AnalysisType;
struct ReadContext;

/// A data set to play and, when it was synthesised, where its soil changes.
struct StreamSource {
    identification::DataSet data;
    std::optional<std::size_t> true_border;  ///< index of the first sample of the second soil
    std::string description;                 ///< "sandy loam → clayey soil, 1 % noise", "log.csv"
    std::vector<std::string> warnings;       ///< rows skipped, points the soil could not carry
    /// Synthetic data: the parameters each stretch was made with, from its first sample on (for
    /// drawing the truth beside the estimates; K_s = k_c/b + k_φ).
    std::vector<std::pair<std::size_t, identification::DecoupledParameters>> truth;
};

/// A synthetic drive over a soil border: the slip sweep of the first soil, then of the second,
/// each in a scrambled but fixed order (a robot's slip wanders; a monotone sweep is not what a
/// streaming identifier sees), with Gaussian noise (Eq. 5.1). Samples are 10 ms apart (100 Hz).
struct SoilBorderSpec {
    soil::SoilParameters first;
    soil::SoilParameters second;
    wheel::WheelParameters wheel;
    double load_n = contact::kDefaultLoadN;  ///< W [N]
    double noise_relative = 0.01;            ///< σ per channel as a fraction of its largest value
    std::uint64_t seed = 1;                  ///< the second soil uses seed + 1
    int samples_per_soil = 101;              ///< slips 0.05 … 0.9
    double sample_period_s = 0.01;           ///< time between samples [s]
};
/// Throws std::invalid_argument for an invalid soil, wheel, load or noise.
StreamSource synthesiseSoilBorder(const SoilBorderSpec& spec);

/// Reads a CSV for playback (data_set.h columns, as the full model reads them: an entry angle or a
/// load). Bad rows either stop the read, every one listed with its line number, or are skipped and
/// listed in `warnings`.
Result<StreamSource> readStreamSource(const std::string& path, bool skip_bad_rows);

/// The range of the synthetic noise [%] and of the moving horizon [samples].
inline constexpr Range kStreamingNoisePercentRange{0.0, 100.0};
inline constexpr int kMaxStreamingWindow = 1000;  ///< beyond it a refit costs less

struct StreamingSettings {
    std::string csv;             ///< data file; empty: a synthetic drive over a soil border
    bool skip_bad_rows = false;  ///< false: a bad row stops the read, every bad row listed
    /// Synthetic: the soil after the border (a preset or a file); the first is the inputs'.
    std::string second_soil = "clayey-soil";
    std::optional<soil::SoilParameters> second;  ///< that soil, resolved (by the reader or caller)
    double noise_percent = 1.0;  ///< synthetic: σ as % of each channel's largest value
    std::uint64_t seed = 1;      ///< synthetic: noise seed
    /// The estimator's options (window, change test, the model of its fits); `columns` is set
    /// from the data when played. Its file keys: "window", "load_N" and "jmax_m".
    identification::StreamingEstimatorOptions options;

    /// Its file keys, one line each (core/common/declared_fields.h): the reader, toJson, the
    /// command line's flags and compute's checks are made from them. The resolved second soil
    /// and the estimator's other options are not file keys.
    template <typename Visitor>
    void visitFields(Visitor& v);
};

/// "window": a whole number in [1, kMaxStreamingWindow] into the estimator's std::size_t.
void readStreamingWindow(io::ObjectReader& r, const char* key, std::size_t& out);
inline nlohmann::json streamingWindowJson(const std::size_t& window) { return window; }

template <typename Visitor>
void StreamingSettings::visitFields(Visitor& v) {
    v(fields::flag("skip_bad_rows", skip_bad_rows,
                   "true: bad rows of the CSV are skipped (listed); false: they stop the read"));
    v(fields::path("csv", csv,
                   "data set CSV (full-model columns), read at once; empty: a synthetic drive "
                   "over a soil border"));
    v(fields::text("second_soil", second_soil,
                   "synthetic: the soil after the border (preset or JSON file)"));
    v(fields::number("noise_percent", noise_percent, kStreamingNoisePercentRange, "%",
                     "synthetic: noise σ as % of each channel's largest value"));
    v(fields::integer("seed", seed, 0, std::numeric_limits<std::uint64_t>::max() - 1,
                      "synthetic: noise seed (the second soil uses seed + 1)"));
    v(fields::custom("window", options.window, "whole number", "[1, 1000]",
                     "samples of the moving horizon", readStreamingWindow, streamingWindowJson));
    v(fields::field(contact::loadField(), options.fit.load_n));
    // The model's shear-deformation limit held at a value (+inf: none), as identification's.
    v(fields::field(*soil::findSoilField("jmax_m"), options.fit.max_shear_deformation_m,
                    std::numeric_limits<double>::infinity()));
}

/// The keys of StreamingSettings::visitFields, read strictly (io::readFields), then what a field
/// list cannot say: "csv" is read at once (relative to the context's directory; a bad file is a
/// problem of the settings) and "second_soil" is resolved through the context's presets (when no
/// CSV is given, the default too).
void readStreamingSettings(io::ObjectReader& r, const ReadContext& context, StreamingSettings& out);
/// The settings' file keys (io::fieldsToJson): what readStreamingSettings reads back.
nlohmann::json toJson(const StreamingSettings& settings);

/// The data the settings name: the CSV, or the drive from the inputs' soil onto the second soil
/// at the conditions' load. Throws std::invalid_argument when it cannot be read or made.
StreamSource streamSource(const Inputs& inputs, const StreamingSettings& settings);

/// What the studio shows of one sample.
struct StreamFrame {
    identification::StreamEstimate estimate;  ///< the estimator's state after the sample
    /// The estimate in the field table's terms (identified_parameters.h; n₀ = n, n₁ = 0).
    identification::DecoupledParameters parameters;
    double time_s = 0.0;         ///< the sample's time (its time_s, or index × 10 ms)
    double fx_measured_n = 0.0;  ///< F_x of the sample [N] (NaN when not measured)
    /// F_x the estimate *before* this sample predicts for it (full model) [N]; NaN while there is
    /// no estimate.
    double fx_predicted_n = 0.0;
};

/// The times the samples are played at: the data's own when every sample has one and they
/// never go back, else 10 ms apart.
std::vector<double> sampleTimes(const identification::DataSet& data);

/// One streaming run, sample by sample (the playback paces the calls; computeStreaming does not).
class StreamingRun {
public:
    /// `options.columns` says which channels the samples carry.
    StreamingRun(const wheel::WheelParameters& wheel,
                 const identification::StreamingEstimatorOptions& options);
    /// The frame of one more sample, played at `time_s`.
    StreamFrame push(const identification::Sample& sample, double time_s);

private:
    wheel::WheelParameters wheel_;
    identification::StreamingEstimatorOptions options_;
    identification::StreamingEstimator estimator_;
    std::optional<identification::ParameterVector> estimate_;  // before the next sample
};

/// One row per frame: sample, time_s, estimated, the identified fields and their *_std (NaN
/// while there is no estimate; n1 has no std), nis, cusum, used, change_at (NaN when none), Fx_N,
/// Fx_predicted_N.
Table framesTable(const std::vector<StreamFrame>& frames);

struct StreamingResult {
    StreamSource source;  ///< without its samples (they are the frames')
    std::vector<StreamFrame> frames;
    std::vector<std::size_t> changes;  ///< samples where a confirmed change of soil began
    std::size_t sample_count = 0;      ///< of the source (more than the frames when cancelled)
    bool cancelled = false;
};

/// Plays a source's samples as fast as they compute, on `wheel`. Throws std::invalid_argument
/// for a source without samples.
StreamingResult playStreaming(StreamSource source, const wheel::WheelParameters& wheel,
                              identification::StreamingEstimatorOptions options,
                              const Control& control = {});
/// The estimator's options for these inputs and settings: a synthetic drive's model takes the
/// inputs' soil's j_max (the data were made with it); a CSV's never depends on the inputs' soil.
identification::StreamingEstimatorOptions streamingOptions(const Inputs& inputs,
                                                           const StreamingSettings& settings);
/// The settings' source (streamSource), played. Throws std::invalid_argument when the data
/// cannot be read or made.
StreamingResult computeStreaming(const Inputs& inputs, const StreamingSettings& settings = {},
                                 const Control& control = {});
/// Table "frames"; notes: the source's warnings and the changes found.
Outcome streamingOutcome(StreamingResult result);

AnalysisType streamingType();

}  // namespace terra::analysis
