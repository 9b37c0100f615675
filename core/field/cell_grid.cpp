#include "core/field/cell_grid.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "core/common/range.h"

namespace terra::field {

namespace {

// Tile indices are kept within ±2³¹ tiles (±2.1 × 10⁹ × 32 cells): far beyond any field.
constexpr std::int64_t kTileOffset = std::int64_t{1} << 31;

std::int64_t floorDiv(std::int64_t a, std::int64_t b) {
    std::int64_t q = a / b;
    if ((a % b != 0) && ((a < 0) != (b < 0))) --q;
    return q;
}

}  // namespace

CellGrid::CellGrid(double cell_m, double x_origin_m, double y_origin_m,
                   std::vector<double> stress_depths_m)
    : cell_m_(cell_m),
      x_origin_m_(x_origin_m),
      y_origin_m_(y_origin_m),
      stress_depths_m_(std::move(stress_depths_m)) {
    if (!(cell_m > 0.0 && cell_m <= 100.0))
        throw std::invalid_argument("CellGrid: cell_m = " + formatNumber(cell_m) +
                                    " must be in (0, 100] m");
    if (!std::isfinite(x_origin_m) || !std::isfinite(y_origin_m))
        throw std::invalid_argument("CellGrid: the origin must be finite");
    if (stress_depths_m_.size() > static_cast<std::size_t>(kMaxStressDepths))
        throw std::invalid_argument("CellGrid: " + std::to_string(stress_depths_m_.size()) +
                                    " stress depths, at most " + std::to_string(kMaxStressDepths));
    for (double d : stress_depths_m_) {
        if (!(d > 0.0 && d <= 10.0))
            throw std::invalid_argument("CellGrid: stress depth " + formatNumber(d) +
                                        " m must be in (0, 10] m");
    }
}

CellKey CellGrid::keyAt(double x_m, double y_m) const {
    return {static_cast<std::int64_t>(std::floor((x_m - x_origin_m_) / cell_m_)),
            static_cast<std::int64_t>(std::floor((y_m - y_origin_m_) / cell_m_))};
}

std::uint64_t CellGrid::pack(std::int64_t tx, std::int64_t ty) {
    return (static_cast<std::uint64_t>(tx + kTileOffset) << 32) |
           static_cast<std::uint64_t>(static_cast<std::uint32_t>(ty + kTileOffset));
}

CellKey CellGrid::tileOrigin(std::uint64_t packed) {
    const auto tx = static_cast<std::int64_t>(packed >> 32) - kTileOffset;
    const auto ty = static_cast<std::int64_t>(packed & 0xffffffffu) - kTileOffset;
    return {tx * kTileCells, ty * kTileCells};
}

CellState& CellGrid::touch(CellKey key) {
    const std::int64_t tx = floorDiv(key.ix, kTileCells), ty = floorDiv(key.iy, kTileCells);
    const std::uint64_t packed = pack(tx, ty);
    if (packed != last_key_) {
        std::unique_ptr<Tile>& tile = tiles_[packed];
        if (!tile) tile = std::make_unique<Tile>();
        last_key_ = packed;
        last_tile_ = tile.get();
    }
    const auto i = static_cast<int>(key.ix - tx * kTileCells);
    const auto j = static_cast<int>(key.iy - ty * kTileCells);
    return last_tile_->cells[j * kTileCells + i];
}

const CellState* CellGrid::find(CellKey key) const {
    const std::int64_t tx = floorDiv(key.ix, kTileCells), ty = floorDiv(key.iy, kTileCells);
    const auto it = tiles_.find(pack(tx, ty));
    if (it == tiles_.end()) return nullptr;
    const auto i = static_cast<int>(key.ix - tx * kTileCells);
    const auto j = static_cast<int>(key.iy - ty * kTileCells);
    return &it->second->cells[j * kTileCells + i];
}

std::pair<CellKey, CellKey> CellGrid::touchedBounds() const {
    if (tiles_.empty()) return {CellKey{0, 0}, CellKey{-1, -1}};
    CellKey lo{INT64_MAX, INT64_MAX}, hi{INT64_MIN, INT64_MIN};
    for (const auto& [packed, tile] : tiles_) {
        const CellKey o = tileOrigin(packed);
        lo.ix = std::min(lo.ix, o.ix);
        lo.iy = std::min(lo.iy, o.iy);
        hi.ix = std::max(hi.ix, o.ix + kTileCells - 1);
        hi.iy = std::max(hi.iy, o.iy + kTileCells - 1);
    }
    return {lo, hi};
}

}  // namespace terra::field
