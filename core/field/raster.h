#pragma once
/// @file raster.h
/// A north-up regular grid of numbers: a height map, a soil-class map or a map of one soil
/// parameter (docs/field.md, "Rasters"). The layout is ESRI ASCII grid's and GeoTIFF's: row 0 is
/// the northern (top) row, (x_min, y_min) the lower-left corner of the lower-left cell. Cells
/// without data hold NaN.

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "core/common/issue.h"

namespace terra::field {

/// A column and row of a raster.
struct CellIndex {
    int col = 0;
    int row = 0;
};

struct Raster {
    int cols = 0;
    int rows = 0;
    double x_min_m = 0.0;        ///< [m] west edge
    double y_min_m = 0.0;        ///< [m] south edge
    double cell_m = 1.0;         ///< [m] square cell side
    std::vector<double> values;  ///< rows × cols, row-major from the north; NaN: no data
    /// The EPSG code of the coordinate system the file names (a GeoTIFF's ProjectedCSTypeGeoKey);
    /// none for ESRI ASCII grids, CSV and a GeoTIFF without one (docs/field.md, "Raster files").
    std::optional<int> epsg;

    double xMax() const { return x_min_m + cols * cell_m; }
    double yMax() const { return y_min_m + rows * cell_m; }
    double value(int col, int row) const {
        return values[static_cast<std::size_t>(row) * cols + col];
    }
    double& value(int col, int row) { return values[static_cast<std::size_t>(row) * cols + col]; }
    /// Centre of a cell [m].
    double centreX(int col) const { return x_min_m + (col + 0.5) * cell_m; }
    double centreY(int row) const { return y_min_m + (rows - row - 0.5) * cell_m; }

    /// The cell holding (x, y) (west and south edges inside, east and north outside), or none.
    std::optional<CellIndex> cellAt(double x_m, double y_m) const;
    /// The value of the cell holding (x, y); NaN outside the raster or on a cell without data.
    double nearest(double x_m, double y_m) const;
    /// The bilinear surface through the cell centres at (x, y) (docs/field.md, F1): between the
    /// outermost centres and the raster's edge the edge cells' values are extended. NaN outside
    /// the raster or when one of the four cells around (x, y) has no data.
    double bilinear(double x_m, double y_m) const;
    /// The gradient (∂v/∂x, ∂v/∂y) of that surface at (x, y) [value unit / m] (F2); NaN where
    /// bilinear is NaN. On a line between cells the side towards +x (+y) is taken.
    Eigen::Vector2d gradient(double x_m, double y_m) const;

    /// The smallest and largest value with data; {NaN, NaN} when no cell has data.
    std::pair<double, double> valueRange() const;
    /// The number of cells with data.
    std::size_t cellsWithData() const;
};

/// Every problem of a raster's layout, at `where`: sizes < 1 or above 100,000 per side, more
/// than 10⁹ cells, a cell side not in (0, 10⁴] m, a corner not finite, values not rows × cols.
std::vector<Issue> validate(const Raster& raster, const std::string& where);

/// A raster of `cols` × `rows` cells of side `cell_m` from (x_min, y_min), every value `fill`.
Raster makeRaster(int cols, int rows, double x_min_m, double y_min_m, double cell_m,
                  double fill = 0.0);

}  // namespace terra::field
