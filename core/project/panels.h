#pragma once
/// @file panels.h
/// What each studio panel saves in a .terra file's "panels" object: the settings of its
/// analysis and what it shows (a tab, a page). Read strictly like the rest of the file, so a
/// project never opens half-understood. The stresses and compaction panels store their
/// analysis's own settings struct; the others a struct of their controls.

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/analysis/compaction.h"
#include "core/analysis/identification.h"
#include "core/analysis/sensitivity.h"
#include "core/analysis/streaming_identification.h"
#include "core/analysis/stresses.h"
#include "core/io/json_reader.h"
#include "core/io/parameters_json.h"

namespace terra::project {

/// "forces": the tab shown ("Fx_N-vs-slip", … as the panel names its plots).
struct ForcesPanelSettings {
    std::string plot;
};

/// "stresses": the analysis's settings (slip, slip angle, the stress shown, …).
struct StressPanelSettings {
    analysis::StressSettings analysis;
};

/// "compaction": the analysis's settings (slip, passes, profile, ν, width, map, …).
struct CompactionPanelSettings {
    analysis::CompactionSettings analysis;
};

/// "sensitivity": the analysis's settings and the tab shown (Fx, Fs, tornado).
struct SensitivityPanelSettings {
    analysis::SensitivitySettings analysis;
    std::string plot = "Fx";
};

/// "identification": the batch fit's settings and the streaming playback's, by their keys.
struct IdentificationPanelSettings {
    std::string csv;  ///< data of the batch fit; empty: synthetic
    double noise_percent = analysis::SyntheticSource{}.noise_percent;
    bool refine = analysis::IdentificationSettings{}.refine;
    bool three_loads = true;   ///< synthesise at ½W, W, 1½W (one load cannot separate c and φ)
    std::string page = "fit";  ///< fit or streaming
    std::string stream_csv;    ///< empty: a synthetic drive over a soil border
    std::string stream_second_soil = analysis::StreamingSettings{}.second_soil;
    double stream_noise_percent = analysis::StreamingSettings{}.noise_percent;
    double stream_speed = 1.0;  ///< sample time per wall time; 0: as fast as possible
    bool stream_skip_bad_rows = analysis::StreamingSettings{}.skip_bad_rows;
    // The global fit's options (core/analysis/identification.h).
    std::string prior_soil;           ///< soil preset the priors are centred on; empty: none
    std::string prior_items;          ///< "phi_deg=30±5, c_kPa=2±1" (parsePriorItem items)
    std::string validation = "none";  ///< none, holdout (20 % of the samples) or folds (5)
    std::string loss = "l2";          ///< l2, huber or cauchy
    /// The fit's wheel: "" the data's when they name one (a sidecar JSON beside the CSV), else
    /// the project's; "project"; or a wheel preset's name.
    std::string wheel;
    /// j_max of the fit: auto (the project soil's for synthetic data, none for a CSV), none,
    /// fixed (at jmax_mm) or fit (identified).
    std::string jmax = "auto";
    double jmax_mm = 20.0;
};

/// "global-sensitivity": the page shown, the study's method, grid and sample sizes (the ranges
/// of its parameter table are not saved: they start from docs/sensitivity.md's example).
struct GlobalSensitivityPanelSettings {
    std::string page = "indices";  ///< indices or bands
    std::string method = "sobol";  ///< sobol or morris
    std::string output = "Fx_N";   ///< the output shown (gsa::outputNames())
    std::vector<double> slips{0.1, 0.3, 0.6};
    double slip_angle_deg = 0.0;
    int samples = 1024;      ///< Sobol' base samples or Morris trajectories
    int band_samples = 256;  ///< Monte Carlo samples of the bands
    std::uint64_t seed = 1;
};

/// "rover": the scenario chosen and the scenarios edited in the panel (name → scenario JSON).
struct RoverPanelSettings {
    std::string scenario;
    nlohmann::json edited = nlohmann::json::object();
};

void readPanelSettings(io::ObjectReader& r, ForcesPanelSettings& out);
void readPanelSettings(io::ObjectReader& r, StressPanelSettings& out);
/// A profile given by preset name is found in `locations` (else read as a path).
void readPanelSettings(io::ObjectReader& r, CompactionPanelSettings& out,
                       const io::PresetLocations* locations = nullptr);
void readPanelSettings(io::ObjectReader& r, SensitivityPanelSettings& out);
void readPanelSettings(io::ObjectReader& r, IdentificationPanelSettings& out);
void readPanelSettings(io::ObjectReader& r, GlobalSensitivityPanelSettings& out);
/// The edited scenarios are checked as scenarios when `locations` is given.
void readPanelSettings(io::ObjectReader& r, RoverPanelSettings& out,
                       const io::PresetLocations* locations = nullptr);

nlohmann::json toJson(const ForcesPanelSettings& settings);
nlohmann::json toJson(const StressPanelSettings& settings);
nlohmann::json toJson(const CompactionPanelSettings& settings);
nlohmann::json toJson(const SensitivityPanelSettings& settings);
nlohmann::json toJson(const IdentificationPanelSettings& settings);
nlohmann::json toJson(const GlobalSensitivityPanelSettings& settings);
nlohmann::json toJson(const RoverPanelSettings& settings);

/// Checks a "panels" object: forces, stresses, compaction, sensitivity, identification, rover,
/// global-sensitivity (each optional); another panel name is an unknown key.
void readPanels(io::ObjectReader& panels, const io::PresetLocations* locations);

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
