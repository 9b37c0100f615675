#pragma once
/// @file analysis.h
/// The shape every analysis of the product has (docs/architecture.md, "Analysis services"): a
/// settings struct with its defaults, a reader of those settings from JSON that reports every
/// problem with its field path, and a compute function (inputs, settings, control) → a typed
/// result, viewed uniformly as an Outcome (named tables, notes, status) by the script runner,
/// the reports and the Python module. The command line, the scripts and the studio's panels all
/// call the same compute function; nothing else assembles an analysis.

#include <any>
#include <atomic>
#include <functional>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/analysis/conditions.h"
#include "core/common/declared_fields.h"
#include "core/common/issue.h"
#include "core/common/table.h"
#include "core/contact/bulldozing.h"
#include "core/contact/contact_parameters.h"
#include "core/contact/sinkage.h"
#include "core/io/json_reader.h"
#include "core/soil/soil_parameters.h"
#include "core/wheel/wheel_parameters.h"

namespace terra::analysis {

/// What an analysis of a project reads: the soil, the wheel and the operating conditions.
struct Inputs {
    soil::SoilParameters soil;
    wheel::WheelParameters wheel;
    OperatingConditions conditions;

    /// The soil on the wheel as the contact model sees it; throws std::invalid_argument when the
    /// soil or the wheel is invalid or K_s = k_c/b + k_φ ≤ 0.
    contact::ContactParameters<double> contact() const;
};

/// Every problem of the inputs: soil, wheel, conditions and the pair (K_s > 0).
std::vector<Issue> validate(const Inputs& inputs);

/// Progress and cancellation of a running analysis (the studio's workers, the CLI's Ctrl-C).
struct Control {
    Control(const std::atomic<bool>* cancel_flag = nullptr,  // NOLINT(google-explicit-constructor)
            std::function<void(double)> on_progress = {})
        : cancel(cancel_flag), progress(std::move(on_progress)) {}

    const std::atomic<bool>* cancel;       ///< set: stop early, keep what was computed
    std::function<void(double)> progress;  ///< fraction done in [0, 1]; may be empty
    /// Threads the analysis may use, the caller's included (1: none started; 0: one per
    /// hardware thread, at most 8). The identification's global search uses them
    /// (IdentifyOptions::threads); the result is the same whatever the count.
    int threads = 1;

    bool cancelled() const { return cancel != nullptr && cancel->load(std::memory_order_relaxed); }
    void report(double fraction) const {
        if (progress) progress(fraction);
    }
};

/// Contact-model choices beyond the soil and the wheel (the command line's model flags; the
/// thesis's defaults: θ_r = 0, θ_m from Eq. 2.18, Bekker's bulldozing coefficients).
struct ModelChoices {
    contact::ExitCondition exit;                 ///< θ_r or rut ratio λ (Eq. 2.12)
    std::optional<double> max_stress_angle_rad;  ///< fixed θ_m; empty: Eq. 2.18
    contact::BulldozingModel bulldozing = contact::BulldozingModel::kBekker;  ///< Eq. 2.27

    /// Its file keys, one line each (core/common/declared_fields.h): "exit_angle_deg" or
    /// "rut_ratio" (not both), "max_stress_angle_deg" and "bulldozing". A settings struct that
    /// holds the choices lists them with `fields::members(model)`.
    template <typename Visitor>
    void visitFields(Visitor& v);
};

// The custom kinds of ModelChoices' list: what no kind says. The angles are converted as the
// command line always has (read: units::degToRad; written: roundSignificant(radToDeg)), bit for
// bit; θ_r and λ are one member under two keys; "bulldozing" is written only when not Bekker's.

/// "exit_angle_deg" [deg] → a θ_r exit condition; also reports the rule between the two keys
/// of the exit condition (exitConditionRule), so that every reader of the list checks it.
void readExitAngle(io::ObjectReader& r, const char* key, contact::ExitCondition& out);
/// θ_r in degrees when the condition is an angle other than 0 (the default); else null.
nlohmann::json exitAngleJson(const contact::ExitCondition& exit);
/// "rut_ratio" λ → a rut-ratio exit condition.
void readRutRatio(io::ObjectReader& r, const char* key, contact::ExitCondition& out);
/// λ when the condition is a rut ratio; else null.
nlohmann::json rutRatioJson(const contact::ExitCondition& exit);
/// "max_stress_angle_deg" [deg] → θ_m [rad].
void readMaxStressAngle(io::ObjectReader& r, const char* key, std::optional<double>& out_rad);
nlohmann::json maxStressAngleJson(const std::optional<double>& rad);
/// "bulldozing": bekker or hegedus.
void readBulldozing(io::ObjectReader& r, const char* key, contact::BulldozingModel& out);
nlohmann::json bulldozingJson(const contact::BulldozingModel& model);
/// The rule between the keys of the exit condition that a list cannot say: θ_r or λ, not both
/// ("give exit_angle_deg or rut_ratio, not both", at "rut_ratio").
void exitConditionRule(io::ObjectReader& r);

template <typename Visitor>
void ModelChoices::visitFields(Visitor& v) {
    v(fields::custom("exit_angle_deg", exit, "number", "[-90, 0] deg",
                     "exit angle θ_r (≤ 0); not with rut_ratio", readExitAngle, exitAngleJson));
    v(fields::custom("rut_ratio", exit, "number", "[0, 1]",
                     "rut ratio λ = h_r/h_f giving θ_r (Eq. 2.12); not with exit_angle_deg",
                     readRutRatio, rutRatioJson));
    v(fields::custom("max_stress_angle_deg", max_stress_angle_rad, "number", "[-90, 90] deg",
                     "fixed θ_m instead of Eq. 2.18; absent: Eq. 2.18", readMaxStressAngle,
                     maxStressAngleJson));
    v(fields::custom("bulldozing", bulldozing, "name", "bekker, hegedus",
                     "side-wall pressure coefficients (Eq. 2.27)", readBulldozing, bulldozingJson));
}

/// The keys of ModelChoices::visitFields (io::readFields); absent keys keep the defaults. Other
/// code calls it for a struct that does not list the choices itself.
void readModelChoices(io::ObjectReader& r, ModelChoices& out);
/// The non-default choices as JSON (io::fieldsToJson), merged into `out`.
void writeModelChoices(const ModelChoices& choices, nlohmann::json& out);

/// One table of a result.
struct NamedTable {
    std::string name;  ///< what a script's expectation calls it ("sweep", "errors")
    /// The CSV file is NAME + suffix + ".csv" ("", "-errors"); empty: not written as CSV.
    std::optional<std::string> file_suffix;
    Table table;
};

/// One line of a result's plain summary (what `terrastudio CMD` prints without --json, what a
/// panel formats): a label, the value as a person reads it (rounded, "± std" where there is
/// one), its unit, a detail said after it ("prior 0.4"), and how it stands out. `json` points at
/// what the row shows in the result's toJson (an RFC 6901 pointer; "" when the JSON does not
/// hold it, a heading's: the object its rows come from); `number` is that value when it is a
/// number, as the JSON holds it (its unit: m where the row shows mm, a fraction where it shows
/// %), NaN otherwise.
struct SummaryRow {
    enum class Emphasis {
        kNormal,
        kHeading,  ///< a section's title: its rows follow
        kWarning,  ///< a failure, a flag or a note that a reader must not miss
    };
    std::string label;
    std::string value;
    std::string unit;
    std::string detail;
    Emphasis emphasis = Emphasis::kNormal;
    std::string json;
    double number = std::numeric_limits<double>::quiet_NaN();
};
using Summary = std::vector<SummaryRow>;

/// A result seen uniformly: its tables, notes and status, and the typed result for the figures.
struct Outcome {
    /// Completed; stopped by the cancel flag (what was computed so far); failed (no result, see
    /// message); or invalid input (the data or settings cannot be used, see message).
    enum class Status { kCompleted, kCancelled, kFailed, kInvalidInput };
    Status status = Status::kCompleted;
    std::string message;             ///< why it failed or stopped early
    std::vector<NamedTable> tables;  ///< the main table first
    std::vector<std::string> notes;  ///< warnings and solver reports
    std::vector<std::pair<std::string, nlohmann::json>> documents;  ///< file suffix → JSON output
    std::any result;  ///< the typed result (ForcesResult, StressResult, …), for the figures

    /// The table of that name ("" or absent: the main table), or nullptr.
    const Table* table(std::string_view name = {}) const;
};

/// A status as the results' JSON and Python's run() spell it: "completed", "cancelled",
/// "failed", "invalid input".
const char* statusName(Outcome::Status status);

}  // namespace terra::analysis
