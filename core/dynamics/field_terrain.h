#pragma once
/// @file field_terrain.h
/// The rover's ground on a field (docs/field.md, "The rover on a field"): the field map's
/// surface (bilinear height and gradient, F1–F2) and soils (class 0 = the base soil, then the
/// legend's classes in ascending code; with parameter rasters, every distinct soil the map holds:
/// F14), and the cell grid's memory of every wheel that passed.
/// Each wheel reads the memory of the cell under its contact point as the cell was when the wheel
/// arrived there (across its width where the memories differ, F15), and writes its passage back
/// once, when it leaves the cell (F10–F11), to every cell under its width (F13): the track memory
/// after one more pass (compaction::afterPass), the largest slip, the energy it lost there and the
/// largest vertical stress at the grid's depths.

#include <array>
#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "core/compaction/stress_at_depth.h"
#include "core/compaction/track_memory.h"
#include "core/dynamics/robot.h"
#include "core/dynamics/terrain.h"
#include "core/field/cell_grid.h"
#include "core/field/field_map.h"

namespace terra::dynamics {

/// Wong's reload law with the rut and the reload branch, without the shear memory.
inline compaction::ReloadLaw noShearMemory() {
    compaction::ReloadLaw law;
    law.shear_memory = false;
    return law;
}

/// How a field remembers.
struct FieldTerrainOptions {
    /// The wheels meet the memory of earlier passes (Wong's reload law, the rut, the shear);
    /// false: every wheel meets untouched soil, as on the patch terrain (the memory is still
    /// written, so the maps are drawn either way).
    bool repeated_passes = true;
    /// k₀, A_u and whether shear is carried (docs/compaction.md R1). The shear memory is off by
    /// default here (docs/field.md, F11): its offset j₀ makes F_x jump at s = 0 (the shear's
    /// magnitude starts at τ(j₀) while its direction follows the slip), which the explicit step
    /// turns into chatter of the 4WD robot, whose wheels run near s = 0 once the rear ones push.
    compaction::ReloadLaw law = noShearMemory();
    /// Cell side of the memory [m]; 0: the finest cell of the field's rasters.
    double cell_m = 0.0;
    /// Depths [m] where each cell keeps its largest σ_z (at most field::kMaxStressDepths);
    /// empty: no stress at depth is computed.
    std::vector<double> stress_depths_m{0.3};
    /// ν for the stress at depth; 0: the layer's own ν at each depth, else 5 (Söhne's "normal").
    double concentration = 0.0;
    /// Keep every passage written (FieldTerrain::takePassages): when and where, and what the maps
    /// show of the cell after it, so that the maps can be drawn as they were at any time (the
    /// studio's time scrub). 56 bytes a passage.
    bool record_passages = false;
    /// Write each passage to every cell under the wheel's width (docs/field.md F13: the cells
    /// whose centres the wheel's width swept during the passage, and the cell under its contact
    /// point); false: the cell under the contact point only, a track one cell wide per wheel.
    bool across_width = true;
    /// A wheel meets the memories across its width where they differ (docs/field.md F15: a rut's
    /// edge); false: the memory of the cell under its contact point for the whole width (F10).
    /// Only with across_width (a one-cell-wide rut is met by the contact point alone).
    bool read_across_width = true;
    /// The peak of σ_z under a wheel's centre line is searched from the wheel's last passage's
    /// peak, with the full scan every this many passages of the wheel (docs/field.md F16); ≤ 1: the
    /// full scan every passage.
    int full_scan_every = 16;
};

/// One wheel's passage as it was written to one of its cells (F10, F13): what the maps show of
/// the cell once the passage was written (the cell's whole state is 72 bytes, this 56; a 1-hour
/// mission writes ~10⁶ of them).
struct CellPassage {
    /// The rover's time when the wheel left the cell (or the run ended with the wheel on it) [s]:
    /// the sum of the steps the terrain was told of, as the rover's own clock.
    double time_s = 0.0;
    field::CellKey key;
    double rut_depth_m = 0.0;    ///< z_p after it (CellState::track)
    int passes = 0;              ///< wheels that have passed, this one included
    float max_stress_pa = 0.0f;  ///< largest σ_z at the first stress depth (0: none)
    float max_slip = 0.0f;       ///< CellState::max_slip after it
    float energy_j = 0.0f;       ///< CellState::energy_j after it
    float travel_m = 0.0f;       ///< CellState::travel_m after it
};

class FieldTerrain final : public TerrainModel {
public:
    /// The most distinct soils a field's classes and parameter rasters may make (F14).
    static constexpr std::size_t kMaxSoils = 65536;
    /// The most pieces (distinct columns of all rasters × distinct rows) F14 enumerates: about
    /// 3 s at 10 ns a piece.
    static constexpr double kMaxSoilKeys = 3e8;

    /// Throws std::invalid_argument for a field the rover cannot drive on: parameter rasters
    /// that make more than kMaxSoils distinct soils, or a cell size out of CellGrid's range.
    FieldTerrain(std::shared_ptr<const field::FieldMap> map, const RobotParameters& robot,
                 FieldTerrainOptions options = {});
    // The bands (memoriesAcross) point into the terrain's own storage.
    FieldTerrain(const FieldTerrain&) = delete;
    FieldTerrain& operator=(const FieldTerrain&) = delete;

    int soilCount() const override { return static_cast<int>(soils_.size()); }
    const soil::SoilParameters& soil(int index) const override {
        return soils_[static_cast<std::size_t>(index)];
    }
    int soilIndexAt(double x_m, double y_m) const override;
    /// Every soil, or with more than kStepLimitSoils: each class's soil and it with every corner
    /// of the box of the parameter rasters' values (their least and greatest value each; F14).
    std::vector<soil::SoilParameters> stepLimitSoils() const override;
    static constexpr std::size_t kStepLimitSoils = 64;
    bool remembers() const override { return true; }
    double heightAt(double x_m, double y_m) const override { return map_->heightAt(x_m, y_m); }
    std::array<double, 2> gradientAt(double x_m, double y_m) const override;

    const compaction::TrackMemory* memoryUnder(int wheel, double x_m, double y_m) override;
    /// F15: the memories met across the wheel's width, sampled when its passage opened at
    /// bandSamples() points along its axle through the contact point (the middle one the contact
    /// point's cell); empty when they all equal memoryUnder's, when the passage writes one cell
    /// (`across_width` false), when `read_across_width` is false or when the wheels meet untouched
    /// soil (`repeated_passes` false).
    std::span<const BandShare> memoriesAcross(int wheel) const override {
        return band_[static_cast<std::size_t>(wheel)];
    }
    /// The width F15 samples for a wheel whose axle (on the map, normalised) is `axle`:
    /// b − h (|a_x| + |a_y|), never below 0 (b the wheel's width, h the cell side).
    double bandSpan(const std::array<double, 2>& axle) const;
    /// The points F15 samples across it: the least odd count at most h/4 apart, at most
    /// kMaxBandSamples; 1 (the contact point alone) when the span is 0.
    int bandSamples(const std::array<double, 2>& axle) const;
    static constexpr int kMaxBandSamples = 41;
    compaction::ReloadLaw reloadLaw() const override { return options_.law; }
    void imprint(int wheel, const WheelImprint& imprint) override;
    void advanced(double dt_s) override;

    /// Writes every wheel's open passage to its cell (the end of a run).
    void finish();

    const field::FieldMap& map() const { return *map_; }
    const field::CellGrid& cells() const { return cells_; }
    const FieldTerrainOptions& options() const { return options_; }
    /// Cells that at least one wheel passed over.
    long cellsTouched() const { return cells_touched_; }
    /// The σ_z peaks under a wheel's centre line found by the full scan, one a passage and depth
    /// (F16: the others start from the wheel's last passage's peak).
    long fullScans() const { return full_scans_; }
    /// Every passage written, in the order written (time non-decreasing), when
    /// options().record_passages (empty otherwise), handed over: the terrain's log is empty after
    /// it. The runner frees them once the maps' history is drawn from them, before the maps.
    std::deque<CellPassage> takePassages() { return std::exchange(log_, {}); }

private:
    // One wheel's passage over one cell (F10): opened when the wheel's contact point enters the
    // cell, written back when it leaves it by more than a quarter cell.
    struct Passage {
        bool open = false;
        field::CellKey key;
        // The contact point and the axle's direction when the passage opened (F13).
        std::array<double, 2> entry{};
        std::array<double, 2> entry_axle{0.0, 1.0};
        compaction::TrackMemory before;  // the cell's memory when the wheel arrived
        bool contacted = false;
        int soil_index = 0;
        double max_depth_m = 0.0;
        double max_slip = 0.0;
        double energy_j = 0.0;
        double travel_m = 0.0;  // the contact point's path while the passage is open
        double last_power_w = 0.0;
        contact::ContactParameters<double> params;  // at the deepest point
        contact::OperatingPoint<double> op{};       // at the deepest point
        double footprint_scale = 1.0;               // at the deepest point (F15)
    };
    // A cell a passage is written to, and the distance from the wheel's centre line to the
    // cell's nearest point (its σ_z at depth is taken there).
    struct SweptCell {
        field::CellKey key;
        double offset_m = 0.0;
    };
    void commit(Passage& passage);
    std::vector<SweptCell> sweptCells(const Passage& passage, std::size_t wheel) const;
    // ν at a depth: the scenario's, else the passage's soil layer's, else 5.
    double concentrationAt(const Passage& passage, double depth_m) const;

    std::shared_ptr<const field::FieldMap> map_;
    FieldTerrainOptions options_;
    wheel::WheelParameters wheel_;
    std::vector<soil::SoilParameters> soils_;  // 0: base, then the legend
    std::vector<int> codes_;                   // the legend's codes, ascending
    std::size_t class_soils_ = 0;              // soils_[0, class_soils_): base and legend
    // F14, with parameter rasters: (class soil index, each raster's value or +inf where it has
    // none) → the soil's index in soils_.
    std::map<std::vector<double>, int> soil_of_key_;
    void soilKey(double x_m, double y_m, std::vector<double>& key) const;
    int classIndexOf(std::optional<int> code) const;  // 0: no code or none in the legend
    int classIndexAt(double x_m, double y_m) const;
    void enumerateSoils();
    field::CellGrid cells_;
    std::array<Passage, kWheelCount> passages_{};
    // Each wheel's last contact point (the passage's travel; F12).
    std::array<std::optional<std::array<double, 2>>, kWheelCount> last_contact_{};
    // Each wheel's axle on the map at its last imprint (F13), and whether it has had one.
    std::array<std::array<double, 2>, kWheelCount> axle_{};
    std::array<bool, kWheelCount> axle_known_{};
    // The cells each wheel's last passage wrote, with their memory before it (F13: a wheel that
    // enters one of them next meets it as it was).
    std::array<std::vector<std::pair<field::CellKey, compaction::TrackMemory>>, kWheelCount>
        last_written_{};
    // The same of the kRecentPassages passages before the last that wrote cells, oldest first
    // (F15: a wheel's width reaches back over cells its own earlier passages wrote), and the rule
    // that reads them: `memory` becomes the cell's memory before the earliest of the wheel's own
    // last kRecentPassages + 1 passages over it (`recent`), or before its last one only (F13).
    static constexpr std::size_t kRecentPassages = 3;
    std::array<std::deque<std::vector<std::pair<field::CellKey, compaction::TrackMemory>>>,
               kWheelCount>
        recent_written_{};
    void ownBefore(std::size_t wheel, field::CellKey key, compaction::TrackMemory& memory,
                   bool recent) const;
    void archiveWritten(std::size_t wheel);
    // The energy and distance of a wheel's short passages that wrote no cell, added to its next.
    struct Carry {
        double energy_j = 0.0;
        double travel_m = 0.0;
    };
    std::array<Carry, kWheelCount> carry_{};
    // F16: each wheel's last peak of σ_z under its centre line at each risk depth (the next
    // passage's search starts there), and its passages since the last full scan.
    std::array<std::vector<std::optional<compaction::VerticalStressPeak>>, kWheelCount>
        last_peak_{};
    std::array<int, kWheelCount> since_full_scan_{};
    long full_scans_ = 0;
    // F15: each wheel's band when its memories differ across its width; the shares point into
    // band_memory_, whose capacity (kMaxBandSamples) is reserved so that they stay valid.
    void sampleBand(std::size_t wheel, const Passage& passage);
    std::array<std::vector<compaction::TrackMemory>, kWheelCount> band_memory_;
    std::array<std::vector<BandShare>, kWheelCount> band_;
    long cells_touched_ = 0;
    double time_s_ = 0.0;  // the sum of the steps advanced() was told of
    // A deque: a long run's log grows in blocks, never copied to a buffer twice its size.
    std::deque<CellPassage> log_;
};

}  // namespace terra::dynamics
