#pragma once
/// @file terrain.h
/// What the rover drives on. `TerrainModel` is what a wheel asks of the ground at every step
/// (docs/field.md, "The rover on a field"): the untouched surface's height and gradient, the soil,
/// and the memory of earlier passes under the wheel; it is told what the wheel did there. Two
/// kinds: `PatchTerrain`, the flat plane z = 0 of soil patches (a base soil everywhere, overridden
/// by axis-aligned rectangles, the last listed patch that contains a point winning) that
/// remembers nothing, and `FieldTerrain` (field_terrain.h), a field map with its cell memory.

#include <array>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "core/compaction/track_memory.h"
#include "core/contact/contact_parameters.h"
#include "core/contact/wheel_forces.h"
#include "core/soil/soil_parameters.h"

namespace terra::dynamics {

/// A rectangle of one soil, x_min ≤ x < x_max and y_min ≤ y < y_max [m] (open sides: ±inf).
struct SoilPatch {
    soil::SoilParameters soil;
    double x_min_m = -std::numeric_limits<double>::infinity();
    double x_max_m = std::numeric_limits<double>::infinity();
    double y_min_m = -std::numeric_limits<double>::infinity();
    double y_max_m = std::numeric_limits<double>::infinity();

    bool contains(double x_m, double y_m) const {
        return x_m >= x_min_m && x_m < x_max_m && y_m >= y_min_m && y_m < y_max_m;
    }
};

/// The soil map.
struct Terrain {
    soil::SoilParameters base;       ///< soil outside every patch
    std::vector<SoilPatch> patches;  ///< later patches cover earlier ones

    /// Index of the soil at (x, y): 0 for the base, i + 1 for patches[i].
    int soilIndexAt(double x_m, double y_m) const {
        for (int i = static_cast<int>(patches.size()) - 1; i >= 0; --i) {
            if (patches[i].contains(x_m, y_m)) return i + 1;
        }
        return 0;
    }
    /// The soil of index `index` (see soilIndexAt).
    const soil::SoilParameters& soil(int index) const {
        return index == 0 ? base : patches[index - 1].soil;
    }
    int soilCount() const { return static_cast<int>(patches.size()) + 1; }
};

/// What one wheel did to the ground in one evaluation (Rover::evaluate), for a terrain that
/// remembers: the contact as it was solved there.
struct WheelImprint {
    bool in_contact = false;
    int soil_index = 0;
    double depth_m = 0.0;  ///< the rim's lowest point below the untouched surface [m] (F6)
    double load_n = 0.0;   ///< W along the surface normal [N]
    double power_w = 0.0;  ///< power into the soil [W]
    contact::ContactParameters<double> params;  ///< the soil's, with the memory used (if any)
    contact::OperatingPoint<double> op{};       ///< s, β, θ_f, θ_r of the contact
    /// The wheel's axle y_w (docs/field.md F7) projected on the map and normalised: the direction
    /// of its width on the ground (F13).
    std::array<double, 2> axle{0.0, 1.0};
    /// F15: where the width met different memories (memoriesAcross), `params` and `op` are the
    /// part's that carries the most load, and this the wheel's F_z over that part's F_z for its
    /// whole width: the footprint of the stress at depth is that part's, scaled to carry the
    /// wheel's load. 1 otherwise.
    double footprint_scale = 1.0;
};

/// A part of a wheel's width and the memory of the soil under it (docs/field.md, F15).
struct BandShare {
    const compaction::TrackMemory* memory = nullptr;  ///< nullptr: untouched soil
    double share = 1.0;                               ///< of the wheel's width, (0, 1]
};

/// The ground as a wheel meets it. Coordinates are the world's: x, y on the map, z up.
class TerrainModel {
public:
    virtual ~TerrainModel() = default;

    virtual int soilCount() const = 0;
    /// The soil of index `index` (0 ≤ index < soilCount()).
    virtual const soil::SoilParameters& soil(int index) const = 0;
    /// Index of the soil at (x, y).
    virtual int soilIndexAt(double x_m, double y_m) const = 0;
    /// The soils the largest stable step is taken over (dynamics::largestStableStep): every
    /// soil; a terrain of very many soils may give fewer that bound them (FieldTerrain, F14).
    virtual std::vector<soil::SoilParameters> stepLimitSoils() const {
        std::vector<soil::SoilParameters> out;
        for (int i = 0; i < soilCount(); ++i) out.push_back(soil(i));
        return out;
    }
    /// z [m] of the untouched surface at (x, y).
    virtual double heightAt(double x_m, double y_m) const = 0;
    /// ∇z = (∂z/∂x, ∂z/∂y) [-] of the untouched surface at (x, y).
    virtual std::array<double, 2> gradientAt(double x_m, double y_m) const = 0;

    /// Whether the terrain keeps what the wheels did (imprint() is then called for every wheel at
    /// every evaluation; a terrain that remembers nothing is spared building the imprints).
    virtual bool remembers() const { return false; }
    /// The memory of the soil that wheel `wheel` (0…3) stands on, its contact point at (x, y), as
    /// the soil was when the wheel arrived there; nullptr when the wheel meets untouched soil (and
    /// always on a terrain that remembers nothing). Called once per wheel per evaluation, before
    /// imprint().
    virtual const compaction::TrackMemory* memoryUnder(int wheel, double x_m, double y_m) {
        (void)wheel, (void)x_m, (void)y_m;
        return nullptr;
    }
    /// The memories under the width of wheel `wheel` where memoryUnder last placed it, when they
    /// differ across it (F15: a wheel on a rut's edge), each with its share of the width (the
    /// shares sum to 1); empty when the whole width meets memoryUnder's memory. Called right after
    /// memoryUnder; valid until its next call.
    virtual std::span<const BandShare> memoriesAcross(int wheel) const {
        (void)wheel;
        return {};
    }
    /// The reload law that memoryUnder's memories are met with.
    virtual compaction::ReloadLaw reloadLaw() const { return {}; }
    /// What wheel `wheel` did at the contact memoryUnder was last asked about.
    virtual void imprint(int wheel, const WheelImprint& imprint) { (void)wheel, (void)imprint; }
    /// dt [s] passed with the forces of the last imprints (Rover::advance).
    virtual void advanced(double dt_s) { (void)dt_s; }
};

/// The flat patch terrain of a Terrain: the plane z = 0, nothing remembered (today's rover).
class PatchTerrain final : public TerrainModel {
public:
    explicit PatchTerrain(Terrain terrain) : terrain_(std::move(terrain)) {}
    int soilCount() const override { return terrain_.soilCount(); }
    const soil::SoilParameters& soil(int index) const override { return terrain_.soil(index); }
    int soilIndexAt(double x_m, double y_m) const override {
        return terrain_.soilIndexAt(x_m, y_m);
    }
    double heightAt(double, double) const override { return 0.0; }
    std::array<double, 2> gradientAt(double, double) const override { return {0.0, 0.0}; }
    const Terrain& terrain() const { return terrain_; }

private:
    Terrain terrain_;
};

}  // namespace terra::dynamics
