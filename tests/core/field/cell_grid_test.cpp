#include "core/field/cell_grid.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <stdexcept>
#include <utility>

namespace terra::field {
namespace {

TEST(CellGrid, FindsWhatWasTouchedOnEitherSideOfTheOrigin) {
    CellGrid grid(0.05, 1.0, -2.0);
    for (const auto& [x, y] :
         {std::pair{1.01, -1.99}, std::pair{-3.7, -9.2}, std::pair{0.99, 4.4}}) {
        EXPECT_EQ(grid.find(x, y), nullptr);
        grid.touch(x, y).track.passes = 3;
        ASSERT_NE(grid.find(x, y), nullptr);
        EXPECT_EQ(grid.find(x, y)->track.passes, 3);
    }
    // The cell (1.00–1.05, −2.00–−1.95) holds (1.01, −1.99) and its neighbour does not.
    EXPECT_EQ(grid.keyAt(1.01, -1.99).ix, 0);
    EXPECT_EQ(grid.keyAt(0.99, -2.01).ix, -1);
    EXPECT_EQ(grid.keyAt(0.99, -2.01).iy, -1);
    ASSERT_NE(grid.find(1.09, -1.96), nullptr);  // same tile: allocated, untouched
    EXPECT_EQ(grid.find(1.09, -1.96)->track.passes, 0);
}

// Memory follows the area driven on: a 0.4 m wide track 100 m long on 5 cm cells allocates the
// tiles it crosses, counted here independently of the grid's own bookkeeping.
TEST(CellGrid, TilesAreAllocatedOnlyWhereWheelsGo) {
    const double cell = 0.05;
    CellGrid grid(cell);
    std::set<std::pair<long, long>> tiles;
    for (double x = 0.0; x < 100.0; x += 0.01) {
        for (double y = 10.0; y < 10.4; y += 0.01) {
            grid.touch(x, y).track.passes += 1;
            const long ix = static_cast<long>(std::floor(x / cell));
            const long iy = static_cast<long>(std::floor(y / cell));
            constexpr long t = CellGrid::kTileCells;
            tiles.insert(
                {ix >= 0 ? ix / t : (ix - t + 1) / t, iy >= 0 ? iy / t : (iy - t + 1) / t});
        }
    }
    EXPECT_EQ(grid.tileCount(), tiles.size());
    // 100 m / (4 × 5 cm) = 500 tiles along; the 0.4 m strip (8 cells) covers two or three tile
    // rows.
    static_assert(CellGrid::kTileCells == 4);
    EXPECT_LE(grid.tileCount(), 3u * 500u);
    // A whole 100 m × 100 m field would be 500² tiles: the strip holds under 1 % of it.
    EXPECT_LT(grid.stateBytes(), 500u * 500u * 4u * 4u * sizeof(CellState) / 100u);
    const auto [lo, hi] = grid.touchedBounds();
    EXPECT_EQ(lo.ix, 0);
    EXPECT_GE(hi.ix, static_cast<std::int64_t>(100.0 / cell) - 1);
}

TEST(CellGrid, RasterOfAStateRunsFromTheNorth) {
    CellGrid grid(1.0);
    grid.touch(0.5, 0.5).track.rut_depth_m = 0.01;  // south-west cell
    grid.touch(2.5, 1.5).track.rut_depth_m = 0.03;  // north-east cell
    const Raster r =
        grid.toRaster(0.0, 0.0, 3.0, 2.0, [](const CellState& s) { return s.track.rut_depth_m; });
    ASSERT_EQ(r.cols, 3);
    ASSERT_EQ(r.rows, 2);
    EXPECT_EQ(r.x_min_m, 0.0);
    EXPECT_EQ(r.y_min_m, 0.0);
    EXPECT_DOUBLE_EQ(r.value(0, 1), 0.01);
    EXPECT_DOUBLE_EQ(r.value(2, 0), 0.03);
    EXPECT_DOUBLE_EQ(r.value(1, 0), 0.0);
    EXPECT_DOUBLE_EQ(r.nearest(2.5, 1.5), 0.03);  // the raster's own lookup agrees
}

TEST(CellGrid, RefusesBadArguments) {
    EXPECT_THROW(CellGrid(0.0), std::invalid_argument);
    EXPECT_THROW(CellGrid(0.05, std::nan(""), 0.0), std::invalid_argument);
    EXPECT_THROW(CellGrid(0.05, 0.0, 0.0, {0.1, 0.2, 0.3, 0.4, 0.5}), std::invalid_argument);
    EXPECT_THROW(CellGrid(0.05, 0.0, 0.0, {-0.1}), std::invalid_argument);
    EXPECT_NO_THROW(CellGrid(0.05, 0.0, 0.0, {0.1, 0.3}));
}

}  // namespace
}  // namespace terra::field
