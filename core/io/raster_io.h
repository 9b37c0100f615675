#pragma once
/// @file raster_io.h
/// Rasters in files (docs/field.md, "Raster files"): ESRI ASCII grid (.asc, the plain-text
/// format every GIS reads and writes), CSV (cell centres as x_m, y_m, value rows on a regular
/// grid, any missing cell without data) and single-band GeoTIFF (.tif, .tiff: core/io/geotiff.h).
/// Problems come back with file:line; nothing throws. Writing is atomic.

#include <filesystem>
#include <optional>
#include <string>

#include "core/common/issue.h"
#include "core/field/raster.h"

namespace terra::io {

/// ESRI ASCII grid text: the header (ncols, nrows, xllcorner or xllcenter, yllcorner or
/// yllcenter, cellsize, optional NODATA_value; keys in any case) then nrows × ncols numbers from
/// the north-west corner, row by row. `where` names the source in messages.
Result<field::Raster> parseAsciiGrid(const std::string& text, const std::string& where);
/// The raster as ESRI ASCII grid text (NODATA_value -9999, numbers in shortest round-trip form).
std::string toAsciiGrid(const field::Raster& raster);

/// CSV text with columns x_m, y_m and one value column (`value_column`, or the only other
/// column when empty): one row per cell centre on a square grid. The cell side is the smallest
/// spacing between distinct x (and y) values; every centre must lie on that grid (within 10⁻⁶
/// of a cell), no cell twice; cells without a row have no data.
Result<field::Raster> parseRasterCsv(const std::string& text, const std::string& where,
                                     const std::string& value_column = {});
/// The raster as CSV: x_m, y_m, `value_column` for every cell with data, west to east, north to
/// south.
std::string toRasterCsv(const field::Raster& raster, const std::string& value_column = "value");

/// A raster file by its extension: .asc (ESRI ASCII grid), .csv or .tif/.tiff (GeoTIFF). Any
/// other extension is an error naming the ones read.
Result<field::Raster> readRaster(const std::filesystem::path& path,
                                 const std::string& value_column = {});
/// Writes .asc, .csv or .tif/.tiff (Float64 GeoTIFF) atomically; the error message, or nothing
/// on success.
std::optional<std::string> writeRaster(const std::filesystem::path& path,
                                       const field::Raster& raster,
                                       const std::string& value_column = "value");

}  // namespace terra::io
