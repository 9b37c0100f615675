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
#include "core/common/declared_fields.h"
#include "core/compaction/footprint.h"
#include "core/compaction/passes.h"
#include "core/compaction/track_memory.h"
#include "core/contact/operating_fields.h"
#include "core/io/parameters_json.h"
#include "core/soil/soil_profile.h"

namespace terra::analysis {

/// The measure compared with σ_pc (risk, and the stress of the compression law when N is derived
/// from σ_pc).
enum class RiskStress {
    kVertical,  ///< σ_z: like for like with σ_pc from uniaxial tests (the default)
    kMajor,     ///< σ₁: the major principal stress
};

/// The limits of the compaction's settings (their field list's ranges).
inline constexpr Range kCompactionDepthRange{0.0, 10.0, true};    ///< a depth [m]
inline constexpr Range kCompactionConcentrationRange{2.5, 12.0};  ///< ν: 3 Boussinesq … 6 soft
inline constexpr int kMaxCompactionPasses = 1000;
inline constexpr int kMaxCompactionMapPoints = 1000;  ///< per axis
inline constexpr std::size_t kMaxCompactionDepths = 2000;

/// "reload_k0_kPa_m" and "reload_Au_kPa_m2": the reload law's k₀ [kPa/m in the file, Pa/m in
/// the member] and A_u [kPa/m², Pa/m²].
const FieldInfo& reloadK0Field();
const FieldInfo& reloadAuField();

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

    /// Its file keys, one line each (core/common/declared_fields.h): the reader, toJson and
    /// compute's checks are made from them, the model choices among them.
    template <typename Visitor>
    void visitFields(Visitor& v);
};

/// "profile": an object read at once; a preset name or a path is left to
/// readCompactionSettings (it needs the preset locations and the file's directory).
void readProfileKey(io::ObjectReader& r, const char* key, std::optional<soil::SoilProfile>& out);
nlohmann::json writeProfileKey(const std::optional<soil::SoilProfile>& profile);
/// "map_points" [x, z] and "map_pass": written only with a map (map_x_points > 0).
void readMapPoints(io::ObjectReader& r, const char* key, CompactionSettings& out);
nlohmann::json writeMapPoints(const CompactionSettings& settings);
void readMapPass(io::ObjectReader& r, const char* key, CompactionSettings& out);
nlohmann::json writeMapPass(const CompactionSettings& settings);

template <typename Visitor>
void CompactionSettings::visitFields(Visitor& v) {
    const FieldInfo& s = contact::slipField();
    v(fields::number(s.key, slip, s.range, "", "slip s of every pass"));
    v(fields::number("slip_angle_deg", slip_angle_deg, contact::slipAngleField().range, "deg",
                     "slip angle β"));
    v(fields::number("concentration", concentration, kCompactionConcentrationRange, "",
                     "concentration factor ν for every depth; absent: each layer's, else 5"));
    v(fields::numbers("depths_m", depths_m, kCompactionDepthRange, "m",
                      "depths of the profile below the untouched surface, ascending", 1,
                      kMaxCompactionDepths));
    v(fields::integer("passes", passes, 1, kMaxCompactionPasses,
                      "wheels on the same track, each at the same load and slip"));
    v(fields::choice("width", width,
                     {{"uniform", compaction::WidthProfile::kUniform},
                      {"parabolic", compaction::WidthProfile::kParabolic}},
                     "the stress across the width"));
    v(fields::choice("risk_stress", risk_stress,
                     {{"sigma_z", RiskStress::kVertical}, {"sigma_1", RiskStress::kMajor}},
                     "the stress compared with sigma_pc"));
    v(fields::field(reloadK0Field(), reload.k0_pa_m));
    v(fields::field(reloadAuField(), reload.au_pa_m2));
    v(fields::flag("shear_memory", reload.shear_memory,
                   "carry the shear deformation of earlier passes"));
    v(fields::custom("profile", profile, "object or name", "a profile object, a preset or a path",
                     "the soil profile; absent: the soil's own, or none", readProfileKey,
                     writeProfileKey));
    v(fields::custom("map_points", *this, "2 whole numbers", "[2, 1000] each, or [0, 0]",
                     "the x-z map of stress: points along x and z (absent: no map)", readMapPoints,
                     writeMapPoints));
    v(fields::custom("map_pass", *this, "whole number", "[1, passes]",
                     "the pass the map shows (with map_points)", readMapPass, writeMapPass));
    v(fields::members(model));
}

/// The keys of CompactionSettings::visitFields read strictly (io::readFields), then what a
/// list cannot say: a "profile" given by preset name or path (found in `locations`, else read
/// as a path relative to `base_dir`) and compactionRuleIssues.
void readCompactionSettings(io::ObjectReader& r, CompactionSettings& out,
                            const io::PresetLocations* locations = nullptr,
                            const std::filesystem::path& base_dir = {});
/// The rule between values the reader checks too: at least one depth, depths increasing.
std::vector<Issue> compactionRuleIssues(const CompactionSettings& settings);
/// What computeCompaction checks beside the reader, as it always has (a panel merges a
/// partial object into its state, so a map pass beyond the passes it is about to set must read):
/// a reload stiffness k₀ + A_u z > 0, a map of at least 2 × 2 points showing a pass that exists.
std::vector<Issue> compactionRunIssues(const CompactionSettings& settings);
/// The settings' file keys (io::fieldsToJson), the model choices among them.
nlohmann::json toJson(const CompactionSettings& settings);

using compaction::kDefaultConcentration;  ///< ν: Söhne's "normal" soil

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
    /// kCancelled: stopped by the cancel flag; kFailed: a pass found no equilibrium (`message`);
    /// else kCompleted; the passes before are kept in both. Invalid inputs or settings throw
    /// (computeCompaction), so never kInvalidInput.
    Outcome::Status status() const {
        return cancelled ? Outcome::Status::kCancelled
               : ok()    ? Outcome::Status::kCompleted
                         : Outcome::Status::kFailed;
    }
};

/// Throws std::invalid_argument for invalid inputs or settings (each named).
CompactionResult computeCompaction(const Inputs& inputs, const CompactionSettings& settings = {},
                                   const Control& control = {});

/// The JSON of `terrastudio compaction --json` (docs/cli.md): "profile", "red_to_depth_m",
/// "passes" and the inputs that made them; "status" (statusName(result.status())), "notes",
/// and "message" when there is one.
nlohmann::json toJson(const CompactionResult& result);

/// A layer's bulk density shown as "unchanged" when it moved less than this [Mg/m³] (the last
/// digit the summary shows; below the yield point a layer keeps its density, compaction.md K3).
inline constexpr double kDensityShownMg_m3 = 5e-4;

/// The result for a person, as `terrastudio compaction` prints it above its tables and the
/// compaction panel shows it: a heading with the soil, the wheel, the load W, s, β, ν and the
/// passes; why it stopped (cancelled or failed, the passes before kept); the profile (or none:
/// no σ_pc, no risk); the rut and the sinkage of the last pass [mm]; the red zone's depth [m]
/// (a warning) or none; each layer's bulk density after the last pass [Mg/m³] (and before it,
/// when it changed); the
/// notes as warnings. Each number's `json` points at it in toJson(result) (the rut's and the
/// sinkage's `number` in m).
Summary compactionSummary(const Inputs& inputs, const CompactionSettings& settings,
                          const CompactionResult& result);

/// Tables "profile" (the envelope), "passes" and "map"; the document "compaction".
Outcome compactionOutcome(CompactionResult result);

struct AnalysisType;
/// The registry's entry (registry.cpp lists it).
AnalysisType compactionType();

}  // namespace terra::analysis
