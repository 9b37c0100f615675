#pragma once
/// @file results.h
/// The computed results a project shows, saved beside its .terra file so that reopening it shows
/// them without recomputing (issue 27). The sidecar `NAME.terra.results` (format
/// "terrastudio-results", version 1) holds, per panel, the result in the panel's own JSON form,
/// the tables it shows, whether it was partial, its status line, and a hash of the inputs that
/// produced it: a panel whose inputs still hash the same shows the saved result; one whose inputs
/// changed computes again (or waits for Compute, when heavy). A sidecar, not a key of the .terra
/// file, so that the project stays the version-1 file older studios read, and a project without
/// its results (deleted, not copied) still opens.

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
inline constexpr int kResultsVersion = 1;

/// One panel's result as saved.
struct SavedResult {
    std::string inputs_hash;  ///< inputsHash() of the inputs that produced it
    bool partial = false;     ///< a cancelled run's (what it computed before it stopped)
    std::string summary;      ///< the panel's status line ("4608 model evaluations")
    nlohmann::json result;    ///< what the panel redraws from (its analysis's JSON form)
    std::vector<analysis::NamedTable> tables;  ///< the tables it shows, for reading and export

    bool operator==(const SavedResult& other) const;
};

/// Every saved result, by panel name ("global-sensitivity").
struct SavedResults {
    std::map<std::string, SavedResult> panels;
};

/// A 16-hex-digit hash (64-bit FNV-1a) of the inputs' compact JSON: the same inputs give the same
/// hash on every machine and run (nlohmann::json orders object keys).
std::string inputsHash(const nlohmann::json& inputs);

/// The sidecar of a project file: "field/p.terra" → "field/p.terra.results".
std::filesystem::path resultsPathFor(const std::filesystem::path& project_file);

nlohmann::json toJson(const SavedResults& results);
/// Results from JSON; every problem with its field path under `where`.
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

}  // namespace terra::project
