#pragma once
/// @file geotiff.h
/// Single-band GeoTIFF rasters through libtiff (docs/field.md, "Raster files"), without GDAL or
/// libgeotiff: the GeoTIFF tags are registered with libtiff's field-info API and read here.
///
/// Read: one sample per pixel of UInt8, Int8, UInt16, Int16, UInt32, Int32, Float32 or Float64,
/// in strips or tiles, any compression libtiff decodes; the georeferencing from
/// ModelPixelScaleTag (33550) with one ModelTiepointTag (33922), or a ModelTransformationTag
/// (34264) without rotation; from the GeoKeyDirectoryTag (34735) the raster type (PixelIsArea or
/// PixelIsPoint, key 1025) and the EPSG code (ProjectedCSTypeGeoKey 3072); GDAL_NODATA (42113,
/// ASCII) as the value of cells without data. Refused, each with the file and the reason: a
/// rotated or sheared transform, several tie points, cells that are not square, a flipped axis,
/// several bands, a sample format not listed, a geographic (degrees) or geocentric coordinate
/// system or linear units other than the metre (a field is laid out in metres), no
/// georeferencing at all.
///
/// Written: Float64, deflate-compressed strips (floating-point predictor), PixelIsArea, the tie
/// point at the lower-left corner (raster (0, rows) ↔ (x_min, y_min), so that both corners come
/// back bit for bit), GDAL_NODATA "nan" (no-data cells are NaN), the raster's EPSG code or
/// "user-defined" (32767) when it has none, linear units metre.

#include <string>
#include <string_view>

#include "core/common/issue.h"
#include "core/field/raster.h"

namespace terra::io {

/// The GeoTIFF file's bytes as a raster; `where` names the source in messages.
Result<field::Raster> parseGeoTiff(std::string_view bytes, const std::string& where);

/// The raster as GeoTIFF bytes (see the file's comment), or the error message.
Result<std::string> toGeoTiff(const field::Raster& raster);

}  // namespace terra::io
