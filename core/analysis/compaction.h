#pragma once
/// @file compaction.h
/// What a wheel does to the soil below it (docs/compaction.md): the stress at depth under the
/// wheel's own contact stresses (Söhne/Fröhlich propagation), the compaction risk against the
/// profile's precompression stress (Terranimo's bands), the bulk density after each pass
/// (O'Sullivan's compression law) and repeated passes on one track (Wong's unload–reload law).
/// `terrastudio compaction`, a script's "compaction", Python's ts.compaction and the studio's
/// compaction panel all call computeCompaction.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/analysis/analysis.h"
#include "core/compaction/footprint.h"
#include "core/compaction/passes.h"
#include "core/compaction/track_memory.h"
#include "core/io/parameters_json.h"
#include "core/soil/soil_profile.h"

namespace terra::analysis {

/// The measure compared with σ_pc (risk, and the stress of the compression law when N is derived
/// from σ_pc).
enum class RiskStress {
    kVertical,  ///< σ_z: like for like with σ_pc from uniaxial tests (the default)
    kMajor,     ///< σ₁: the major principal stress
};

struct CompactionSettings {
    double slip = 0.1;            ///< s [-] of every pass
    double slip_angle_deg = 0.0;  ///< β [deg]
    /// ν for every depth; empty: each layer's own ν, else kDefaultConcentration.
    std::optional<double> concentration;
    /// Depths of the profile [m] below the untouched surface, ascending (default 0.1 … 1.0).
    std::vector<double> depths_m = defaultDepths();
    int passes = 1;  ///< wheels on the same track, each at the same load and slip
    compaction::WidthProfile width = compaction::WidthProfile::kUniform;
    RiskStress risk_stress = RiskStress::kVertical;
    compaction::ReloadLaw reload;  ///< Wong / SCM unload–reload law of the repeated passes
    /// The profile; empty: the soil's own (SoilParameters::profile), or none (no σ_pc, no risk).
    std::optional<soil::SoilProfile> profile;
    /// The x–z map of stress under the wheel: points along x and along z (0: no map).
    int map_x_points = 0;
    int map_z_points = 0;
    int map_pass = 1;  ///< which pass the map shows
    ModelChoices model;

    static std::vector<double> defaultDepths();
};

using compaction::kDefaultConcentration;  ///< ν: Söhne's "normal" soil

/// Reads "slip", "slip_angle_deg", "concentration", "depths_m", "passes", "width" (uniform,
/// parabolic), "risk_stress" (sigma_z, sigma_1), "reload_k0_kPa_m", "reload_Au_kPa_m2",
/// "shear_memory", "profile" (an object, a preset name or a path, relative to `base_dir`),
/// "map_points" ([x, z]), "map_pass" and the model choices.
void readCompactionSettings(io::ObjectReader& r, CompactionSettings& out,
                            const io::PresetLocations* locations = nullptr,
                            const std::filesystem::path& base_dir = {});
nlohmann::json toJson(const CompactionSettings& settings);

using compaction::Risk;
using compaction::riskName;
using compaction::riskOf;

/// One depth of a profile: the largest values it sees during a pass (or over all passes).
struct DepthValues {
    double depth_m = 0.0;
    compaction::StressMeasures max;           ///< [Pa]
    std::optional<double> precompression_pa;  ///< σ_pc at this depth before the pass
    std::optional<Risk> risk;
};

/// One wheel on the track.
struct CompactionPass {
    int pass = 1;
    double entry_angle_deg = 0.0;      ///< θ_f on the rut's surface
    double sinkage_m = 0.0;            ///< rim depth below the untouched surface (z_p + h)
    double sinkage_increment_m = 0.0;  ///< over the previous pass's deepest sinkage
    double rut_depth_m = 0.0;          ///< the rut after this pass (elastic rebound taken off)
    contact::WheelForces<double> forces;
    std::vector<DepthValues> profile;
    std::optional<double> red_to_depth_m;    ///< deepest red [m]; 0: no red; empty: no profile
    std::vector<double> bulk_density_kg_m3;  ///< per layer, after the pass
    std::vector<double> precompression_pa;   ///< per layer, after the pass
};

struct CompactionResult {
    std::vector<CompactionPass> passes;
    /// Each depth's largest values over all passes; σ_pc of the untouched profile; the worst
    /// risk any pass gave.
    std::vector<DepthValues> envelope;
    std::optional<double> red_to_depth_m;      ///< deepest red over all passes
    std::optional<soil::SoilProfile> profile;  ///< the profile used (untouched)
    Table map;  ///< x_m, z_m, sigma_z_kPa, p_kPa, sigma_1_kPa (map_pass); empty without a map
    double load_n = 0.0;
    double concentration_used = kDefaultConcentration;  ///< when one ν applies to every depth
    std::string message;  ///< non-empty: a pass found no equilibrium (the passes before are kept)
    /// Stopped by the cancel flag (`message` says after how many passes): the field callers
    /// test, never the message's words.
    bool cancelled = false;
    std::vector<std::string> notes;

    bool ok() const { return message.empty(); }
};

/// Throws std::invalid_argument for invalid inputs or settings (each named).
CompactionResult computeCompaction(const Inputs& inputs, const CompactionSettings& settings = {},
                                   const Control& control = {});

/// The JSON of `terrastudio compaction --json` (docs/cli.md): "profile", "red_to_depth_m",
/// "passes" and the inputs that made them.
nlohmann::json toJson(const CompactionResult& result);

/// Tables "profile" (the envelope), "passes" and "map"; the document "compaction".
Outcome compactionOutcome(CompactionResult result);

struct AnalysisType;
/// The registry's entry (registry.cpp lists it).
AnalysisType compactionType();

}  // namespace terra::analysis
