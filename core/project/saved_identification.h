#pragma once
/// @file saved_identification.h
/// The identification's results in a project's results file (core/project/results.h): the batch
/// fit (data, curves, parameters, the global identification's report: estimate, uncertainty,
/// priors, held-out error, ambiguity, adequacy, steps) and the streaming playback's frames, each
/// read back to the same numbers, so that the identification panel draws them as it drew the
/// computed ones, "Apply identified soil" applies the same soil and the global study's
/// "identified soil's covariance" is the same covariance. Non-finite values survive (j_max = +inf:
/// no shear limit; NaN where a channel was not measured): result_json.h.

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/analysis/identification.h"
#include "core/analysis/streaming_identification.h"
#include "core/common/issue.h"
#include "core/project/result_json.h"

namespace terra::project {

/// Versions of the sections' forms (SavedResult::version).
inline constexpr int kIdentificationVersion = 1;
inline constexpr int kStreamingVersion = 1;

/// A batch identification in full for a results file.
nlohmann::json savedJson(const analysis::IdentificationResult& result);
/// The result savedJson wrote; every problem with its field path under `where`.
Result<analysis::IdentificationResult> identificationResultFromJson(const nlohmann::json& json,
                                                                    const std::string& where);

/// The global identification's report in full (estimate, uncertainty, priors, held-out error,
/// ambiguity, adequacy, steps): a part of savedJson(IdentificationResult), and of the
/// calibration's result (saved_validation.h). Throws std::invalid_argument (or nlohmann's type
/// error) for anything else.
nlohmann::json savedJson(const identification::IdentificationReport& report);
identification::IdentificationReport identificationReportFromJson(const nlohmann::json& json);

/// A streaming playback as shown: its frames, the change points and the source's sample count.
struct SavedStream {
    std::vector<analysis::StreamFrame> frames;
    std::size_t sample_count = 0;            ///< of the source (more than frames when stopped)
    std::optional<std::size_t> true_border;  ///< of a synthetic source
    std::string description;  ///< what was played ("sandy loam → clayey soil, …")
    std::vector<std::string> warnings;
    /// Synthetic data: the parameters each stretch was made with, from its first sample on.
    std::vector<std::pair<std::size_t, identification::DecoupledParameters>> truth;
    bool stopped = false;  ///< stopped before the end (the frames are the samples played)
};
nlohmann::json savedJson(const SavedStream& stream);
Result<SavedStream> savedStreamFromJson(const nlohmann::json& json, const std::string& where);

}  // namespace terra::project

namespace terra::project::saved {

/// A fit's report inside another saved result (the calibration's, saved_validation.cpp) is written
/// as savedJson(IdentificationReport) writes it: declared here, where every user sees it, and
/// defined once in saved_identification.cpp.
template <>
struct Value<identification::IdentificationReport> {
    static nlohmann::json write(const identification::IdentificationReport& report);
    static void read(const nlohmann::json& json, identification::IdentificationReport& report);
};

}  // namespace terra::project::saved
