#pragma once
/// @file map_image.h
/// A run's map as a picture (docs/field.md, "Maps as files"): north up, one pixel per cell (a
/// block of k × k pixels when the map has fewer than kMinMapImageWidth columns), cells without
/// data transparent, the colours of the studio's layers (layerColors on layerScale), and below
/// the map a legend: the title with its unit, a colour bar over the scale and tick values under
/// it, drawn in a small built-in bitmap font (5 × 7 dots: digits, '.', '-', '+', 'e', '%', '/',
/// brackets, the lower-case letters, J, N, P, W, σ and ²; any other character is drawn as a box).

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/field/raster.h"
#include "core/io/png.h"
#include "core/scenario/map_layers.h"
#include "core/scenario/runner.h"

namespace terra::scenario {

/// A map narrower than this many cells is scaled up by whole pixels to at least this width.
inline constexpr int kMinMapImageWidth = 400;
/// A map with more cells on a side is first merged into blocks (coarsen: the largest value of
/// each) to this many; a picture of 16384² pixels is 1 GiB of RGBA already.
inline constexpr int kMaxMapImageSide = 16384;

/// Where the parts of a map's picture lie, in pixels from its top-left corner.
struct MapImageLayout {
    int cell_px = 1;                  ///< pixels per cell side (the map's cells after coarsening)
    int map_width = 0;                ///< the map's pixels: [0, map_width) × [0, map_height)
    int map_height = 0;               ///<
    int width = 0;                    ///< the whole picture (at least kMinMapImageWidth wide)
    int height = 0;                   ///<
    int legend_top = 0;               ///< the legend's first row: an opaque white band to `height`
    int text_px = 2;                  ///< pixels per dot of the font (a glyph is 5 × 7 dots)
    int title_top = 0;                ///< the title's first row, from x = bar_left
    int bar_left = 0, bar_right = 0;  ///< the colour bar's columns [bar_left, bar_right)
    int bar_top = 0, bar_bottom = 0;  ///< and rows [bar_top, bar_bottom)
    int labels_top = 0;               ///< the tick values' first row
};

/// The layout of the picture of a map of `cols` × `rows` cells (after coarsening).
MapImageLayout mapImageLayout(int cols, int rows);

/// The tick values along `scale` (in its unit): steps of 1, 2 or 5 × 10ⁿ, about five, plus the
/// compaction risk's band edges 0.5 and 1.1 for "compaction_risk" (a step's tick less than a
/// step from one of them gives way to it).
std::vector<double> scaleTicks(const std::string& key, const LayerScale& scale);

/// A tick's text: fixed with as many decimals as `step` needs, or the shortest %g form with an
/// exponent for values from 10⁶ or steps below 10⁻⁴.
std::string tickText(double value, double step);

/// The picture of `map` (see the file's comment) as `layer` on `scale`.
io::RgbaImage renderMap(const MapLayer& layer, const LayerScale& scale, const field::Raster& map);

/// Writes every map of `maps` as DIR/<key>.png (key: mapRasters), each on its layerScale. The
/// error message, or nothing.
std::optional<std::string> writeMapPngs(const FieldMaps& maps,
                                        const std::filesystem::path& directory);

}  // namespace terra::scenario
