#pragma once
/// @file script.h
/// Run scripts (`terrastudio run SCRIPT.json`, docs/user-guide.md "Scripted runs"): a list of
/// analyses of the registry (core/analysis/registry.h) on a soil, a wheel and operating
/// conditions, with the figures to draw and the expectations to check. A script is read and
/// checked whole before anything runs: every problem is reported with its field path
/// (`script.json: analyses[2].slip_count: 1e+308 is outside the allowed range [2, 10000]`),
/// unknown keys with the nearest known one. The expectations, the Markdown report and the
/// manifest are here too; the application only draws the figures and writes the files.

#include <any>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/analysis/analysis.h"
#include "core/analysis/registry.h"
#include "core/common/issue.h"
#include "core/common/table.h"
#include "core/io/parameters_json.h"

namespace terra::project {

/// One expectation: the value of `column` in the row nearest to `at` (one column after the
/// other) lies in [min, max].
struct Expectation {
    std::string table;   ///< a table of the analysis; empty: its main table
    std::string column;  ///< a column of that table ("Fx_N")
    std::vector<std::pair<std::string, double>> at;
    double min = -std::numeric_limits<double>::infinity();
    double max = std::numeric_limits<double>::infinity();
    std::string why;  ///< what the expectation checks, for the reader of the script
};

/// What an expectation found.
struct ExpectationOutcome {
    std::string text;  ///< "Fx_N at slip = 0.3, slip_angle_deg = 5: 36.2 in [30, 40]"
    bool passed = false;
};

/// Checks one expectation against a table (a missing column or an empty table fails it).
ExpectationOutcome check(const Expectation& expectation, const Table& table);
/// Checks each expectation against the table it names of an analysis's outcome.
std::vector<ExpectationOutcome> evaluate(const std::vector<Expectation>& expectations,
                                         const analysis::Outcome& outcome);

/// The image formats the runner writes.
const std::vector<std::string>& imageFormats();

/// How the figures are written.
struct ExportSettings {
    int width = 1200;  ///< [px] (PDF: points)
    int height = 800;  ///< [px]
    int dpi = 96;
    std::vector<std::string> formats{"png"};
};

/// One analysis of a script, resolved and checked.
struct ScriptAnalysis {
    std::string name;                              ///< file names start with it; unique
    const analysis::AnalysisType* type = nullptr;  ///< from the registry
    std::optional<std::string> title;              ///< the figures' title instead of the default
    analysis::Inputs inputs;  ///< the script's soil (with "set"), wheel and conditions, or its own
    std::any settings;        ///< the type's settings (type->read)
    std::vector<analysis::FigureSpec> figures;  ///< to draw, in this order
    std::vector<Expectation> expectations;
};

struct Script {
    std::string title = "TerraStudio run";
    ExportSettings export_settings;
    std::vector<ScriptAnalysis> analyses;
    nlohmann::json source;  ///< the script as read (for the manifest)
};

/// A script from JSON; `where` (the file) prefixes every issue; relative files are looked for
/// in `base_dir`.
Result<Script> scriptFromJson(const nlohmann::json& json, const std::string& where,
                              const io::PresetLocations& locations,
                              const std::filesystem::path& base_dir);
/// Reads a script file (strict JSON, then scriptFromJson).
Result<Script> loadScript(const std::filesystem::path& path, const io::PresetLocations& locations);

/// What one analysis of a run produced and found.
struct RunRecord {
    std::string name, type;
    std::vector<std::string> images;  ///< file names, in the output directory
    std::vector<std::string> data;
    std::vector<ExpectationOutcome> outcomes;
    std::string error;  ///< non-empty: the analysis failed
    std::vector<std::string> notes;
    double seconds = 0.0;
};

/// Failed expectations plus failed analyses.
int failureCount(const std::vector<RunRecord>& records);

/// report.md: the failures first, then per analysis its expectations, images, data and notes;
/// `cancelled` (non-empty: the run was stopped by a signal) is said at the top.
std::string reportMarkdown(const Script& script, const std::string& script_path,
                           const std::vector<RunRecord>& records,
                           const std::string& cancelled = {});
/// manifest.json: the tool, the script and its inputs, every output and outcome (and
/// "cancelled": true with the note when the run was stopped).
nlohmann::json manifest(const Script& script, const std::string& script_path,
                        const std::vector<RunRecord>& records, const std::string& tool,
                        const std::string& cancelled = {});

}  // namespace terra::project
