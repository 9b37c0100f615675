#pragma once
/// @file results.h
/// The computed results a project shows, saved beside its .terra file so that reopening it shows
/// them without recomputing (issue 27). The sidecar `NAME.terra.results` (format
/// "terrastudio-results", version 2) holds, per section (a panel's result, or a part of it:
/// "global-sensitivity", "global-sensitivity.bands", "identification",
/// "identification.streaming", "rover", "forces", "forces.calibration", "stresses",
/// "compaction", "sensitivity"), the result in the section's own versioned JSON form (results.h
/// for the global study and the bands, saved_identification.h, saved_rover.h,
/// saved_validation.h, saved_analyses.h), the
/// tables it shows, whether it was partial, its status line, and a hash of the inputs that
/// produced it: a panel whose inputs still hash the same shows the saved result; one whose inputs
/// changed does not show it (it computes again, or waits for its button when heavy). A sidecar,
/// not a key of the .terra file, so that the project stays the version-1 file older studios
/// read, and a project without its results (deleted, not copied) still opens.
///
/// Reading is strict but contained: a file that is not JSON, not results or of a newer version is
/// refused as a whole (the project opens without results); a section that cannot be read is
/// listed in SavedResults::unreadable, with its name and what is wrong, and the others are
/// shown. Version 1 (the global study alone) reads as version 2.

#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/analysis/analysis.h"
#include "core/analysis/global_sensitivity.h"
#include "core/common/issue.h"

namespace terra::project {

inline constexpr const char* kResultsFormat = "terrastudio-results";
inline constexpr int kResultsVersion = 2;
/// Versions of the sections' `result` forms (SavedResult::version).
inline constexpr int kGlobalSensitivityVersion = 1;
inline constexpr int kUncertaintyBandsVersion = 1;

/// One section's result as saved.
struct SavedResult {
    std::string inputs_hash;  ///< inputsHash() of the inputs that produced it
    int version = 1;          ///< of the `result` form (kGlobalSensitivityVersion, …)
    bool partial = false;     ///< a cancelled run's (what it computed before it stopped)
    std::string summary;      ///< the panel's status line ("4608 model evaluations")
    nlohmann::json result;    ///< what the panel redraws from (its analysis's JSON form)
    std::vector<analysis::NamedTable> tables;  ///< the tables it shows, for reading and export

    bool operator==(const SavedResult& other) const;
};

/// Every saved result, by section name ("global-sensitivity", "identification.streaming").
struct SavedResults {
    std::map<std::string, SavedResult> panels;
    /// Sections of the file that could not be read ("p.terra.results: panels.rover" and why):
    /// not shown, the others are.
    std::vector<Issue> unreadable;
};

/// A 16-hex-digit hash (64-bit FNV-1a) of the inputs' compact JSON: the same inputs give the same
/// hash on every machine and run (nlohmann::json orders object keys).
std::string inputsHash(const nlohmann::json& inputs);

/// What a saved result's inputs hold of a data file: null for no file (an empty name), "missing"
/// for a file that cannot be read, else inputsHash of its bytes. The content, not the name or
/// the time stamp: moving or copying the project's folder keeps its results, an edited file
/// does not. The hash is remembered per file, size and modification time, so asking again
/// without a change reads nothing (thread-safe).
nlohmann::json fileStamp(const std::filesystem::path& path);

/// The sidecar of a project file: "field/p.terra" → "field/p.terra.results".
std::filesystem::path resultsPathFor(const std::filesystem::path& project_file);

nlohmann::json toJson(const SavedResults& results);
/// Results from JSON: an error (under `where`) for a file that is not results or of an unknown
/// version; a section that cannot be read goes to `unreadable`.
Result<SavedResults> savedResultsFromJson(const nlohmann::json& json, const std::string& where);
/// Reads a sidecar (strict JSON, then savedResultsFromJson).
Result<SavedResults> loadResults(const std::filesystem::path& path);
/// Writes a sidecar atomically (temporary file, then rename); an error message on failure. No
/// results: the sidecar is removed, so an old one cannot be shown for new inputs.
std::optional<std::string> saveResults(const std::filesystem::path& path,
                                       const SavedResults& results);

/// A global-sensitivity result in full (indices, intervals, samples used, grid) for a sidecar;
/// globalSensitivityResultFromJson reads it back to the same numbers.
nlohmann::json savedJson(const analysis::GlobalSensitivityResult& result);
/// The result savedJson wrote; every problem with its field path under `where`.
Result<analysis::GlobalSensitivityResult> globalSensitivityResultFromJson(
    const nlohmann::json& json, const std::string& where);

/// Uncertainty bands in full (percentile bands, mean, nominal curve, samples used, failures,
/// grid) for a sidecar; uncertaintyBandsFromJson reads them back to the same numbers.
nlohmann::json savedJson(const analysis::UncertaintyBandResult& result);
/// The bands savedJson wrote; every problem with its field path under `where`.
Result<analysis::UncertaintyBandResult> uncertaintyBandsFromJson(const nlohmann::json& json,
                                                                 const std::string& where);

}  // namespace terra::project
