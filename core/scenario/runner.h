#pragma once
/// @file runner.h
/// Runs a scenario at its fixed step: progress callback, cancel flag, a time series, a summary,
/// and (optionally) the streaming identification of one wheel's noisy samples. Cancelled or
/// diverged runs keep what was computed, marked as such.

#include <array>
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/common/table.h"
#include "core/dynamics/rover.h"
#include "core/field/raster.h"
#include "core/scenario/scenario.h"

namespace terra::scenario {

/// Relative energy-balance error above which a run is flagged (summary "warning").
inline constexpr double kEnergyBalanceTolerance = 0.01;

struct RunOptions {
    /// Called about every 1 % of the duration with the fraction done (0..1).
    std::function<void(double)> progress;
    /// Polled every step; when it becomes true the run stops and keeps what it has.
    const std::atomic<bool>* cancel = nullptr;
    /// s* for the optimal and oracle controllers (analysis::runRover passes computeTraction).
    /// Those controllers refuse to run without it.
    SlipPlanner slip_planner;
};

/// What a run produced, summed up (the summary JSON of docs/dynamics.md).
struct Summary {
    double duration_s = 0.0;                     ///< simulated time actually run [s]
    double x_m = 0.0, y_m = 0.0, yaw_rad = 0.0;  ///< final pose (centre of mass)
    double distance_m = 0.0;  ///< path length of the centre of mass on the ground [m]
    std::array<double, dynamics::kWheelCount> mean_slip{};  ///< time average of s per wheel
    /// The joint motors' work: drive ∫ Σ τ ω dt plus steering ∫ Σ τ δ̇ dt [J].
    double energy_j = 0.0;
    double dissipated_j = 0.0;                                ///< work into the soil [J]
    double kinetic_change_j = 0.0, potential_change_j = 0.0;  ///< [J]
    /// (energy − dissipated − ΔE_kinetic − ΔE_potential) / energy: 1e-5…4e-4 at a good step; above
    /// kEnergyBalanceTolerance the step is too large for the contact's stiffness
    /// (docs/dynamics.md). When the motors' work is not positive, over the largest of |energy|,
    /// |dissipated| and |ΔE_kinetic| + |ΔE_potential| instead (never left at 0 when it is not).
    double energy_balance_error = 0.0;
    double max_sinkage_m = 0.0;
    int sunk_steps = 0;  ///< wheel-steps with θ_f clamped at 90°
    long steps = 0;
    /// The spin motors' work per metre of the centre of mass' path [J/m] (none before it moved).
    std::optional<double> energy_per_m_j;
    /// The wheels' tractive efficiency over the run, ∫ Σ F_x v_x dt / ∫ Σ M_y ω dt [-]
    /// (docs/traction.md §1 as an energy ratio).
    std::optional<double> mean_efficiency;
    /// RMS of s − s_set over the wheels at the control ticks after the first second [-]; only a
    /// slip controller has a set-point.
    std::optional<double> slip_tracking_rms;
    /// The traction-limited mode, when enabled (docs/traction.md §5): its engagements plus
    /// releases, and the time the set-points ran raised above the plans [s].
    std::optional<int> traction_limited_switches;
    std::optional<double> traction_limited_s;
    /// Simulated time over the wall-clock time of the stepping loop [-] (measured: it varies from
    /// run to run, unlike everything else here).
    std::optional<double> real_time_factor;
    /// A field run: the cells at least one wheel passed over (docs/field.md, F10).
    std::optional<long> cells_touched;
    /// A mission run: whether and when the path's end was reached, how closely it was followed.
    std::optional<MissionOutcome> mission;
};

/// The maps of a drive as they grew (docs/field.md, "The maps over time"): every passage written
/// to a cell inside the maps, in the order written, with the value each map took there after it.
/// mapAt (core/scenario/map_layers.h) draws a map as it was at a time t from it.
struct MapHistory {
    std::vector<double> time_s;      ///< when each passage was written [s], non-decreasing
    std::vector<std::int32_t> cell;  ///< its cell in the maps' rasters: row × cols + col
    /// A map's key (mapRasters) → its value at that cell after each passage. A map without an
    /// entry is drawn from its final value at the passages' times (mapAt).
    std::map<std::string, std::vector<double>> values;

    std::size_t size() const { return time_s.size(); }
};

/// The maps a field run leaves (docs/field.md, "Maps of a drive"), on the memory's cells over the
/// field's extent (ESRI ASCII grids in writeResults).
struct FieldMaps {
    field::Raster rut_depth_m;  ///< z_p [m]: the rut after the elastic rebound (R2); 0 untouched
    field::Raster passes;       ///< wheels that passed [-]
    /// The largest σ_z at `risk_depth_m` over σ_pc of the cell's soil there [-] (> 1.1: red,
    /// Terranimo's bands); NaN (no data) where the soil has no profile reaching that depth.
    field::Raster compaction_risk;
    double risk_depth_m = 0.0;
    /// The largest |s| of the wheels that passed (F11) [-]; NaN (no data) where none did.
    field::Raster slip;
    /// The energy the wheels lost into the soil there per metre their contact points travelled
    /// over it, E / d (F12) [J/m]; NaN (no data) where no wheel passed.
    field::Raster energy_per_m_j;
    MapHistory history;  ///< how the maps grew (the studio's time scrub)
};

struct RunResult {
    /// kDiverged: a NaN, or a state no robot on flat soil reaches (a speed beyond twice the
    /// fastest rim speed commanded plus 0.5 m/s, roll or pitch beyond 60°, the centre of mass
    /// 1 m up or a wheel radius down, the energy balance off by more than 50 %); `message` says
    /// when and why (docs/dynamics.md, "Step size and stability").
    enum class Status { kCompleted, kCancelled, kDiverged };
    Status status = Status::kCompleted;
    std::string message;
    Table series;  ///< one row per output interval (columns: docs/dynamics.md)
    Summary summary;
    Table streaming;                ///< streaming identification updates (empty without the hook)
    TractionMetrics traction;       ///< the drive's energy, efficiency, tracking and settling
    std::optional<FieldMaps> maps;  ///< a field run's maps
    bool usable() const { return series.rows.size() > 1; }
};

/// Runs the scenario. Throws std::invalid_argument when the robot cannot be set up (invalid
/// parameters, no static equilibrium on the starting soil).
RunResult runScenario(const Scenario& scenario, const RunOptions& options = {});

/// The summary as JSON: duration_s, x_m, y_m, yaw_rad, distance_m, mean_slip {FL, FR, RL, RR},
/// energy_J and the rest, with "status" and "scenario"; a field run's cells_touched, risk_depth_m,
/// max_rut_depth_m and max_compaction_risk (null without a profile).
nlohmann::json toJson(const RunResult& result, const Scenario& scenario);

/// The names of a field run's maps in the output directory.
inline constexpr std::array<const char*, 5> kMapFiles{
    "rut_depth_m.asc", "passes.asc", "compaction_risk.asc", "slip.asc", "energy_per_m_J.asc"};

/// The formats every map is written in, side by side as DIR/<key><extension>: ESRI ASCII grid,
/// GeoTIFF (Float64, core/io/geotiff.h) and a PNG picture with its legend
/// (core/scenario/map_image.h).
inline constexpr std::array<const char*, 3> kMapFormats{".asc", ".tif", ".png"};

/// The maps as one table of the cells a wheel passed, beside the rasters: DIR/maps.csv.
inline constexpr const char* kMapTableFile = "maps.csv";

/// Every file of a field run's maps, map by map in kMapFiles' order, each in kMapFormats' order
/// ("rut_depth_m.asc", "rut_depth_m.tif", "rut_depth_m.png", "passes.asc", …), then
/// kMapTableFile.
std::vector<std::string> mapFileNames();

/// The cells a wheel passed (passes > 0), one row each, north to south and west to east: x_m and
/// y_m of the cell's centre, then every map of mapRasters by its key ("rut_depth_m", "passes",
/// …). A field's maps cover all of it (50 m × 20 m on 2 cm cells: 2.5 million cells, most never
/// touched), so the table keeps only the cells with something to say; the rasters have the rest
/// (0 there). What writeResults writes as kMapTableFile.
Table touchedCells(const FieldMaps& maps);

/// A field run's maps by name, in kMapFiles' order: the key is the file's stem ("rut_depth_m").
/// What writeResults writes and the studio's layer chooser lists (core/scenario/map_layers.h): a
/// map added to FieldMaps is added here.
std::vector<std::pair<std::string, const field::Raster*>> mapRasters(const FieldMaps& maps);
std::vector<std::pair<std::string, field::Raster*>> mapRasters(FieldMaps& maps);

/// Writes timeseries.csv, summary.json (and streaming.csv; a field run's mapFileNames) into
/// `directory` (created), each atomically. An error message, or nothing.
std::optional<std::string> writeResults(const RunResult& result, const Scenario& scenario,
                                        const std::filesystem::path& directory);

}  // namespace terra::scenario
