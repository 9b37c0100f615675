#pragma once
/// @file cell_grid.h
/// The memory of a field's soil, cell by cell (docs/field.md, "Cell state"): what every wheel
/// left in each cell it touched — the track memory of the repeated-pass law (passes, deepest
/// sinkage and its pressure, rut, shear; core/compaction/track_memory.h), the largest vertical
/// stress at chosen depths, the largest slip and the energy lost there. Cells live in square
/// tiles allocated when a wheel first touches them, so memory grows with the area driven on,
/// not with the field.

#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <unordered_map>
#include <vector>

#include "core/compaction/track_memory.h"
#include "core/field/raster.h"

namespace terra::field {

/// Depths at which a cell keeps its largest vertical stress, at most this many.
inline constexpr int kMaxStressDepths = 4;

/// What a cell remembers.
struct CellState {
    compaction::TrackMemory track;  ///< passes, z_u, p_u, rut z_p and shear j₀ (R1–R4)
    /// Largest σ_z [Pa] at the grid's depths (CellGrid::stressDepths), 0 until loaded.
    std::array<float, kMaxStressDepths> max_stress_pa{};
    float max_slip = 0.0f;  ///< largest |s| of a wheel over the cell [-]
    float energy_j = 0.0f;  ///< energy the wheels lost in the soil of the cell [J]
    /// The distance the wheels' contact points travelled while their passages were open [m]
    /// (docs/field.md F12: energy_j / travel_m is the energy lost per metre there).
    float travel_m = 0.0f;
};

/// A cell's integer position: column ix and row iy counted east and north from the origin.
struct CellKey {
    std::int64_t ix = 0;
    std::int64_t iy = 0;
};

/// Cells of side `cell_m` from the origin (x₀, y₀), unbounded in every direction.
class CellGrid {
public:
    /// Cells per tile side: 8 × 8 cells (4.5 KiB of state) per tile. A wheel's band is a few
    /// cells wide: small tiles hold little beside it (docs/performance.md, "Memory").
    static constexpr int kTileCells = 4;

    /// Throws std::invalid_argument when cell_m is not in (0, 100] m, the origin is not finite,
    /// there are more than kMaxStressDepths depths or a depth is not in (0, 10] m.
    CellGrid(double cell_m, double x_origin_m = 0.0, double y_origin_m = 0.0,
             std::vector<double> stress_depths_m = {});

    double cellSize() const { return cell_m_; }
    double xOrigin() const { return x_origin_m_; }
    double yOrigin() const { return y_origin_m_; }
    const std::vector<double>& stressDepths() const { return stress_depths_m_; }

    /// The cell holding (x, y) (west and south edges inside).
    CellKey keyAt(double x_m, double y_m) const;
    /// Centre of a cell [m].
    double centreX(std::int64_t ix) const { return x_origin_m_ + (ix + 0.5) * cell_m_; }
    double centreY(std::int64_t iy) const { return y_origin_m_ + (iy + 0.5) * cell_m_; }

    /// The cell's state, allocating its tile on first touch.
    CellState& touch(CellKey key);
    CellState& touch(double x_m, double y_m) { return touch(keyAt(x_m, y_m)); }
    /// The cell's state, or nullptr when its tile was never allocated (a virgin cell). Safe to
    /// call from several threads while nobody touches the grid.
    const CellState* find(CellKey key) const;
    const CellState* find(double x_m, double y_m) const { return find(keyAt(x_m, y_m)); }

    std::size_t tileCount() const { return tiles_.size(); }
    /// Bytes held by the tiles' cell states.
    std::size_t stateBytes() const { return tiles_.size() * sizeof(Tile); }

    /// Calls f(key, state) for every cell of every allocated tile, touched or not.
    template <typename F>
    void forEachCell(F&& f) const {
        for (const auto& [packed, tile] : tiles_) {
            const CellKey origin = tileOrigin(packed);
            for (int j = 0; j < kTileCells; ++j) {
                for (int i = 0; i < kTileCells; ++i) {
                    f(CellKey{origin.ix + i, origin.iy + j}, tile->cells[j * kTileCells + i]);
                }
            }
        }
    }

    /// The bounding box of the allocated tiles as cell keys [min, max] (inclusive); {0,0},{−1,−1}
    /// when nothing was touched.
    std::pair<CellKey, CellKey> touchedBounds() const;

    /// A raster of `value(state)` over [x_min, x_max] × [y_min, y_max] on this grid's cells (the
    /// box widened to whole cells); cells never touched take `value` of a default state.
    template <typename F>
    Raster toRaster(double x_min_m, double y_min_m, double x_max_m, double y_max_m,
                    F&& value) const {
        const CellKey lo = keyAt(x_min_m, y_min_m);
        const CellKey hi =
            keyAt(std::nextafter(x_max_m, x_min_m), std::nextafter(y_max_m, y_min_m));
        // Every cell takes the virgin value, then the allocated tiles' cells inside the box are
        // written: the cost grows with the area driven on, not with the box.
        const CellState virgin;
        Raster r = makeRaster(static_cast<int>(hi.ix - lo.ix + 1),
                              static_cast<int>(hi.iy - lo.iy + 1), x_origin_m_ + lo.ix * cell_m_,
                              y_origin_m_ + lo.iy * cell_m_, cell_m_, value(virgin));
        forEachCell([&](CellKey key, const CellState& state) {
            if (key.ix < lo.ix || key.ix > hi.ix || key.iy < lo.iy || key.iy > hi.iy) return;
            r.value(static_cast<int>(key.ix - lo.ix), static_cast<int>(hi.iy - key.iy)) =
                value(state);
        });
        return r;
    }

private:
    struct Tile {
        std::array<CellState, kTileCells * kTileCells> cells{};
    };
    static std::uint64_t pack(std::int64_t tx, std::int64_t ty);
    static CellKey tileOrigin(std::uint64_t packed);

    double cell_m_;
    double x_origin_m_;
    double y_origin_m_;
    std::vector<double> stress_depths_m_;
    std::unordered_map<std::uint64_t, std::unique_ptr<Tile>> tiles_;
    // The last tile touched: a wheel stays on one tile for many steps.
    std::uint64_t last_key_ = ~std::uint64_t{0};
    Tile* last_tile_ = nullptr;
};

}  // namespace terra::field
