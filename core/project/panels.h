#pragma once
/// @file panels.h
/// What each studio panel saves in a .terra file's "panels" object: the settings of its
/// analysis and what it shows (a tab, a page). Read strictly like the rest of the file, so a
/// project never opens half-understood. The stresses, compaction, sensitivity and
/// identification panels store their analysis's own settings struct (the identification's, the
/// stresses', the sensitivity's and the compaction's read and written by their declared field
/// lists, core/common/declared_fields.h); the forces, global-sensitivity and rover panels a struct
/// of their controls (each on a declared field list too).

#include <cstdint>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/analysis/compaction.h"
#include "core/analysis/identification.h"
#include "core/analysis/sensitivity.h"
#include "core/analysis/streaming_identification.h"
#include "core/analysis/stresses.h"
#include "core/common/declared_fields.h"
#include "core/contact/operating_fields.h"
#include "core/io/json_reader.h"
#include "core/io/parameters_json.h"

namespace terra::project {

/// "forces": the tab shown ("Fx_N-vs-slip", … as the panel names its plots).
struct ForcesPanelSettings {
    std::string plot;

    template <typename Visitor>
    void visitFields(Visitor& v) {
        v(fields::text("plot", plot, "the tab shown"));
    }
};

/// "stresses": the analysis's settings (slip, slip angle, the stress shown, …), read and written
/// by their declared field list.
struct StressPanelSettings {
    analysis::StressSettings analysis;

    template <typename Visitor>
    void visitFields(Visitor& v) {
        v(fields::members(analysis));
    }
};

/// "compaction": the analysis's settings (slip, passes, profile, ν, width, map, …).
struct CompactionPanelSettings {
    analysis::CompactionSettings analysis;
};

/// "sensitivity": the analysis's settings (their declared field list) and the tab shown (Fx,
/// Fs, tornado).
struct SensitivityPanelSettings {
    analysis::SensitivitySettings analysis;
    std::string plot = "Fx";

    template <typename Visitor>
    void visitFields(Visitor& v) {
        v(fields::members(analysis));
        v(fields::choice("plot", plot,
                         {{"Fx", std::string("Fx")}, {"Fs", "Fs"}, {"tornado", "tornado"}},
                         "the tab shown"));
    }
};

/// The held-out choices of the identification panel: "hold out 20 %" (~1 in 5 samples
/// predicted) and 5 folds.
inline constexpr double kPanelHoldoutFraction = 0.2;
inline constexpr int kPanelFolds = 5;

/// "identification": the batch fit's settings (the analysis's own struct, read and written by
/// its field list: "csv", "noise_percent", "refine", "priors", "prior_soil", "loss",
/// "holdout", "folds", …) and what only the panel has (the streaming playback's, the wheel
/// chosen, the j_max mode). Projects written before the panel stored the struct (keys
/// "prior_items", a text of items, and "validation", none/holdout/folds) still open: both keys
/// are read, never written.
struct IdentificationPanelSettings {
    /// The fit's settings as the panel's controls show them. Its j_max is not used: the panel's
    /// `jmax` mode (with `jmax_mm`) says it, since "none" is no file value; nor its synthetic
    /// loads (`three_loads` makes them from the project's load at the fit).
    analysis::IdentificationSettings fit;
    bool three_loads = true;   ///< synthesise at ½W, W, 1½W (one load cannot separate c and φ)
    std::string page = "fit";  ///< fit or streaming
    /// The streaming playback's settings (the analysis's own struct): its data (csv; empty: a
    /// synthetic drive over a soil border), second soil, noise and bad rows, saved under the keys
    /// "stream_csv", "stream_second_soil", "stream_noise_percent", "stream_skip_bad_rows" with
    /// the ranges of StreamingSettings::visitFields. Its other keys are not the panel's.
    analysis::StreamingSettings stream;
    double stream_speed = 1.0;  ///< sample time per wall time; 0: as fast as possible
    /// The fit's wheel: "" the data's when they name one (a sidecar JSON beside the CSV), else
    /// the project's; "project"; or a wheel preset's name.
    std::string wheel;
    /// j_max of the fit: auto (the project soil's for synthetic data, none for a CSV), none,
    /// fixed (at jmax_mm) or fit (identified).
    std::string jmax = "auto";
    double jmax_mm = 20.0;

    template <typename Visitor>
    void visitFields(Visitor& v);
};

/// The old keys of IdentificationPanelSettings: "prior_items" ("phi_deg=30±5, c_kPa=2±1") and
/// "validation" (none, holdout, folds), read into the fit's settings.
void readOldPriorItems(io::ObjectReader& r, const char* key, analysis::IdentificationSettings& fit);
void readOldValidation(io::ObjectReader& r, const char* key, analysis::IdentificationSettings& fit);
/// "phi_deg=30±5, c_kPa=2±1" → its items.
std::vector<std::string> splitPriorItems(const std::string& text);

template <typename Visitor>
void IdentificationPanelSettings::visitFields(Visitor& v) {
    const auto never = [](const analysis::IdentificationSettings&) { return nlohmann::json(); };
    v(fields::members(fit));
    v(fields::custom("prior_items", fit, "string", "NAME=MEAN±STD items, comma-separated",
                     "(old form of priors)", readOldPriorItems, never));
    v(fields::custom("validation", fit, "name", "none, holdout, folds",
                     "(old form of holdout and folds)", readOldValidation, never));
    v(fields::flag("three_loads", three_loads, "synthesise at ½W, W, 1½W"));
    v(fields::choice("page", page, {{"fit", std::string("fit")}, {"streaming", "streaming"}},
                     "the page shown"));
    v(fields::text("stream_csv", stream.csv, "streaming: the data; empty: synthetic"));
    v(fields::text("stream_second_soil", stream.second_soil,
                   "streaming: the soil after the border"));
    v(fields::number("stream_noise_percent", stream.noise_percent,
                     analysis::kStreamingNoisePercentRange, "%", "streaming: synthetic noise"));
    v(fields::number("stream_speed", stream_speed, {0.0, 1000.0}, "",
                     "streaming: sample time per wall time; 0: as fast as possible"));
    v(fields::flag("stream_skip_bad_rows", stream.skip_bad_rows, "streaming: skip bad rows"));
    v(fields::text("wheel", wheel, "the fit's wheel: \"\", \"project\" or a preset"));
    v(fields::choice(
        "jmax", jmax,
        {{"auto", std::string("auto")}, {"none", "none"}, {"fixed", "fixed"}, {"fit", "fit"}},
        "j_max of the fit"));
    v(fields::number("jmax_mm", jmax_mm, {0.1, 1000.0}, "mm", "j_max held by \"fixed\""));
}

/// "global-sensitivity": the page shown, the study's method, grid and sample sizes (the ranges
/// of its parameter table are not saved: they start from docs/sensitivity.md's example), read
/// and written by its declared field list.
struct GlobalSensitivityPanelSettings {
    std::string page = "indices";  ///< indices or bands
    std::string method = "sobol";  ///< sobol or morris
    std::string output = "Fx_N";   ///< the output shown (gsa::outputNames())
    std::vector<double> slips{0.1, 0.3, 0.6};
    double slip_angle_deg = 0.0;
    int samples = 1024;      ///< Sobol' base samples or Morris trajectories
    int band_samples = 256;  ///< Monte Carlo samples of the bands
    std::uint64_t seed = 1;

    template <typename Visitor>
    void visitFields(Visitor& v);
};

/// The outputs a global-sensitivity panel may show, as names of its "output" choice.
const std::vector<fields::Name<std::string>>& globalSensitivityOutputNames();

template <typename Visitor>
void GlobalSensitivityPanelSettings::visitFields(Visitor& v) {
    v(fields::choice("page", page, {{"indices", std::string("indices")}, {"bands", "bands"}},
                     "the page shown"));
    v(fields::choice("method", method, {{"sobol", std::string("sobol")}, {"morris", "morris"}},
                     "Sobol' indices or Morris screening"));
    v(fields::Enum<std::string>{"output", &output, globalSensitivityOutputNames(),
                                "the output shown"});
    v(fields::numbers("slips", slips, contact::slipField().range, "", "the slips", 1, 1000));
    v(fields::number("slip_angle_deg", slip_angle_deg, contact::slipAngleField().range, "deg",
                     "the slip angle"));
    v(fields::integer("samples", samples, 2, 1 << 20,
                      "Sobol' base samples or Morris trajectories"));
    v(fields::integer("band_samples", band_samples, 2, 1 << 20,
                      "Monte Carlo samples of the bands"));
    v(fields::integer("seed", seed, 0, std::numeric_limits<std::uint64_t>::max(),
                      "the same seed gives the same numbers"));
}

/// "rover": the scenario chosen and the scenarios edited in the panel (name → scenario JSON).
struct RoverPanelSettings {
    std::string scenario;
    nlohmann::json edited = nlohmann::json::object();

    template <typename Visitor>
    void visitFields(Visitor& v);
};

/// "edited": an object of scenario objects by name, kept as JSON (each is checked as a scenario
/// by readPanelSettings when it is given the presets).
void readEditedScenarios(io::ObjectReader& r, const char* key, nlohmann::json& out);
inline nlohmann::json editedScenariosJson(const nlohmann::json& edited) { return edited; }

template <typename Visitor>
void RoverPanelSettings::visitFields(Visitor& v) {
    v(fields::text("scenario", scenario, "the scenario chosen: a preset's name or a file"));
    v(fields::custom("edited", edited, "object", "{name: scenario object}",
                     "the scenarios edited in the panel", readEditedScenarios,
                     editedScenariosJson));
}

void readPanelSettings(io::ObjectReader& r, ForcesPanelSettings& out);
void readPanelSettings(io::ObjectReader& r, StressPanelSettings& out);
/// A profile given by preset name is found in `locations` (else read as a path).
void readPanelSettings(io::ObjectReader& r, CompactionPanelSettings& out,
                       const io::PresetLocations* locations = nullptr);
void readPanelSettings(io::ObjectReader& r, SensitivityPanelSettings& out);
/// A parameter named by an old key in its priors or "fix" ("Ks=1500±500", issue 26) is read as
/// its new one and noted in `out.fit.key_warnings` (the panel shows the notes).
void readPanelSettings(io::ObjectReader& r, IdentificationPanelSettings& out);
void readPanelSettings(io::ObjectReader& r, GlobalSensitivityPanelSettings& out);
/// The edited scenarios are checked as scenarios when `locations` is given, their relative file
/// names read against `base_dir` (the project's folder).
void readPanelSettings(io::ObjectReader& r, RoverPanelSettings& out,
                       const io::PresetLocations* locations = nullptr,
                       const std::filesystem::path& base_dir = {});

nlohmann::json toJson(const ForcesPanelSettings& settings);
nlohmann::json toJson(const StressPanelSettings& settings);
nlohmann::json toJson(const CompactionPanelSettings& settings);
nlohmann::json toJson(const SensitivityPanelSettings& settings);
nlohmann::json toJson(const IdentificationPanelSettings& settings);
nlohmann::json toJson(const GlobalSensitivityPanelSettings& settings);
nlohmann::json toJson(const RoverPanelSettings& settings);

/// Checks a "panels" object: forces, stresses, compaction, sensitivity, identification, rover,
/// global-sensitivity (each optional); another panel name is an unknown key.
void readPanels(io::ObjectReader& panels, const io::PresetLocations* locations,
                const std::filesystem::path& base_dir = {});

/// One panel's settings from JSON (what the panel stored), every problem in the result.
template <typename Settings>
Result<Settings> panelSettingsFromJson(const nlohmann::json& json) {
    std::vector<Issue> issues;
    io::ObjectReader r(json, issues);
    Settings settings;
    readPanelSettings(r, settings);
    r.finish();
    if (!issues.empty()) return issues;
    return settings;
}

}  // namespace terra::project
