#pragma once
/// @file cli_support.h
/// Shared pieces of the headless subcommands: the error types that map to exit codes, soil and
/// wheel resolution with flag overrides, list/range parsing and output writing.

#include <CLI/CLI.hpp>
#include <filesystem>
#include <optional>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/analysis/analysis.h"
#include "core/contact/bulldozing.h"
#include "core/contact/contact_parameters.h"
#include "core/contact/sinkage.h"
#include "core/io/parameters_json.h"

namespace terra::app {

/// Exit codes of the command line (docs/cli.md).
enum ExitCode : int { kSuccess = 0, kFailure = 1, kBadInput = 2 };

/// Bad user input: reported on stderr, exit code 2.
struct InputError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

/// An input file of a command: the flag that named it and its path.
struct NamedInput {
    std::string flag;  ///< "--input", "--experiments", "script"
    std::filesystem::path path;
};

/// Soil and wheel options shared by the subcommands, with the model flags that override the soil
/// file (Table 2.3 fixes θ_m = 15° and uses no j_max).
struct ModelOptions {
    std::string soil = "sandy-loam";
    std::string wheel = "A";
    std::vector<std::string> set;  ///< KEY=VALUE soil overrides in file units
    std::optional<double> a0, a1, jmax_m;
    bool no_jmax = false;
    std::optional<double> max_stress_angle_deg;
    std::optional<double> exit_angle_deg;
    std::optional<double> rut_ratio;
    std::string bulldozing = "bekker";
    std::string model = "full";

    void addTo(CLI::App& command, bool with_geometry = true);

    /// The resolved soil and wheel (presets or files, overrides applied, validated).
    soil::SoilParameters soilParameters(const io::PresetLocations& locations) const;
    wheel::WheelParameters wheelParameters(const io::PresetLocations& locations) const;

    contact::BulldozingModel bulldozingModel() const;
    contact::ContactModel contactModel() const;
    contact::ExitCondition exitCondition() const;
    std::optional<double> maxStressAngleRad() const;
    /// The exit condition, θ_m and bulldozing coefficients the flags choose.
    analysis::ModelChoices choices() const;
    /// The soil and wheel, with the conditions' defaults (core/analysis/conditions.h) and the
    /// contact model of --model.
    analysis::Inputs inputs(const io::PresetLocations& locations) const;
    /// --soil and --wheel as input files (for refuseInputAsOutput; a preset name that is no
    /// file is never equivalent to an output).
    std::vector<NamedInput> inputFiles() const;
};

/// Why `text` is not a plain decimal number for a flag, or "" when it is one. Refused: empty
/// text, hexadecimal ("0x0.8p0"), inf and nan, a number beyond a double, and a subnormal one
/// (nonzero, below 2.2e-308 in magnitude: the CSV and JSON readers refuse it too). `whole`: a
/// whole number in decimal digits (no fraction, no exponent; CLI11 alone would read "010" as
/// octal 8 and "0x10" as 16); `non_negative`: no minus sign (CLI11 alone reads "-1" into an
/// unsigned seed as 2^64 − 1).
std::string numberProblem(const std::string& text, bool whole = false, bool non_negative = false);

/// `value` from `text` when numberProblem accepts it; false otherwise.
bool parseStrictNumber(const std::string& text, double& value);

/// The checks every option of `app` and of its subcommands gets (docs/cli.md, "Strict values"):
/// a value may not be empty (`--out ''` is no path, `--slips ''` no list), and a numeric option
/// takes only what numberProblem accepts (whole and non-negative by the option's type). Call
/// once every subcommand is added.
void makeOptionsStrict(CLI::App& app);

/// Throws InputError when two KEY=VALUE items of `flag` (--set, --noise, --prior, --fix) name
/// the same key: the last one would silently win. Items without '=' are not keyed.
void refuseRepeatedKeys(const std::string& flag, const std::vector<std::string>& items);

/// "0:0.99:100" (first:last:count), "5,10,15" or "0.3": the values, or InputError naming `what`.
std::vector<double> parseValues(const std::string& text, const std::string& what);

/// Settings read from a JSON object built of flags: each issue's key renamed to its flag
/// ("passes" → "--passes", "depths_m[1]" → "--depths[1]"), for the commands whose flags are read by
/// their analysis's own settings reader (compaction, traction).
void nameFlags(std::vector<Issue>& issues,
               const std::vector<std::pair<std::string, std::string>>& keys_to_flags);

/// Throws InputError (exit 2) when `output`, a file the command is about to write (named by
/// `flag`), is one of `inputs`: the same file after resolving links and relative paths
/// (std::filesystem::equivalent), so that no command replaces the data it read. An output
/// that does not exist yet is never an input.
void refuseInputAsOutput(const std::string& flag, const std::filesystem::path& output,
                         const std::vector<NamedInput>& inputs);

/// Prints `lines` on stderr, one each after `prefix` ("warning: "): at most kMaxIssuesShown of
/// them, each cut to kMaxIssueChars characters, then "… and N more" (core/common/issue.h), so
/// that 20,000 bad rows skipped or warned about give a screenful, not megabytes.
void printLines(const std::vector<std::string>& lines, const std::string& prefix);

/// Writes `content` to `path` atomically, or to stdout when `path` is empty or "-".
void writeOutput(const std::string& path, const std::string& content);

/// Directory of the running executable (for finding resources/).
std::filesystem::path executableDirectory();

/// Prints a result's summary (analysis::Summary) for a person: a heading as "label: value
/// (detail)" (a trailing ':' when it has no value: its rows follow), a row indented as
/// "  label: value unit (detail)", a warning unindented as "label: value".
void printSummaryRow(std::ostream& out, const analysis::SummaryRow& row);
void printSummary(std::ostream& out, const analysis::Summary& summary);

/// Fixed-width number for human tables; never "-0.000" (a negative zero or a tiny negative value
/// that rounds to zero prints as "0.000").
std::string fixed(double value, int decimals);

/// `value` with a negative zero made +0, for JSON output (nlohmann writes −0.0 as "-0.0").
inline double plainZero(double value) { return value == 0.0 ? 0.0 : value; }

}  // namespace terra::app
