// GeoTIFF rasters (core/io/geotiff.h): files built byte by byte here, by an encoder of their own
// (little-endian TIFF 6.0 with the GeoTIFF tags, no libtiff), read with their origin, cell size,
// values, no-data cells and EPSG code; the writer's files read back bit for bit; the refusals;
// and a field whose height map is a GeoTIFF driving exactly as with the ESRI ASCII grid.
#include "core/io/geotiff.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>

#include "core/io/atomic_file.h"
#include "core/io/field_json.h"
#include "core/io/raster_io.h"
#include "core/scenario/runner.h"
#include "core/scenario/scenario_json.h"
#include "tests/core/test_support.h"
#include "tests/core/test_temp_dir.h"

namespace terra::io {
namespace {

using terra::testing::contains;
using terra::testing::kLocations;

// TIFF 6.0 field types.
enum : std::uint16_t { kByte = 1, kAscii = 2, kShort = 3, kLong = 4, kDouble = 12 };

// A little-endian baseline TIFF, one image, written by hand: the pixel data first (at offset 8),
// then the directory, then the values too long for an entry. Entries are sorted by tag, as
// TIFF 6.0 requires.
class HandTiff {
public:
    void shorts(std::uint16_t tag, std::vector<std::uint16_t> v) {
        std::string b;
        for (std::uint16_t x : v) append(b, x);
        entries_[tag] = {kShort, static_cast<std::uint32_t>(v.size()), b};
    }
    void longs(std::uint16_t tag, std::vector<std::uint32_t> v) {
        std::string b;
        for (std::uint32_t x : v) append(b, x);
        entries_[tag] = {kLong, static_cast<std::uint32_t>(v.size()), b};
    }
    void doubles(std::uint16_t tag, std::vector<double> v) {
        std::string b;
        for (double x : v) append(b, x);
        entries_[tag] = {kDouble, static_cast<std::uint32_t>(v.size()), b};
    }
    void ascii(std::uint16_t tag, const std::string& text) {
        entries_[tag] = {kAscii, static_cast<std::uint32_t>(text.size() + 1),
                         text + std::string(1, '\0')};
    }
    // Pixel data in blocks (strips or tiles), each block's offset and size put in the tags
    // `offsets_tag` and `counts_tag`.
    void blocks(std::uint16_t offsets_tag, std::uint16_t counts_tag,
                const std::vector<std::string>& data) {
        std::vector<std::uint32_t> offsets, counts;
        for (const std::string& d : data) {
            offsets.push_back(8 + static_cast<std::uint32_t>(pixels_.size()));
            counts.push_back(static_cast<std::uint32_t>(d.size()));
            pixels_ += d;
        }
        longs(offsets_tag, offsets);
        longs(counts_tag, counts);
    }
    std::string bytes() const {
        std::string out = "II";
        append(out, std::uint16_t{42});
        std::string pixels = pixels_;
        if (pixels.size() % 2) pixels += '\0';
        const std::uint32_t ifd = 8 + static_cast<std::uint32_t>(pixels.size());
        append(out, ifd);
        out += pixels;
        std::uint32_t extra = ifd + 2 + 12 * static_cast<std::uint32_t>(entries_.size()) + 4;
        std::string directory, tail;
        append(directory, static_cast<std::uint16_t>(entries_.size()));
        for (const auto& [tag, e] : entries_) {
            append(directory, tag);
            append(directory, e.type);
            append(directory, e.count);
            if (e.data.size() <= 4) {
                directory += e.data + std::string(4 - e.data.size(), '\0');
            } else {
                append(directory, extra + static_cast<std::uint32_t>(tail.size()));
                tail += e.data;
                if (tail.size() % 2) tail += '\0';
            }
        }
        append(directory, std::uint32_t{0});  // no next image
        return out + directory + tail;
    }
    template <typename T>
    static void append(std::string& out, T v) {  // little-endian, as the machine's
        char b[sizeof v];
        std::memcpy(b, &v, sizeof v);
        out.append(b, sizeof v);
    }

private:
    struct Entry {
        std::uint16_t type;
        std::uint32_t count;
        std::string data;
    };
    std::map<std::uint16_t, Entry> entries_;
    std::string pixels_;
};

// A single-strip, one-band image of `bits` per sample in `format` (1 uint, 2 int, 3 float).
HandTiff strippedImage(int cols, int rows, int bits, int format, const std::string& pixels) {
    HandTiff t;
    t.longs(256, {static_cast<std::uint32_t>(cols)});
    t.longs(257, {static_cast<std::uint32_t>(rows)});
    t.shorts(258, {static_cast<std::uint16_t>(bits)});
    t.shorts(259, {1});  // no compression
    t.shorts(262, {1});  // black is zero
    t.shorts(277, {1});
    t.longs(278, {static_cast<std::uint32_t>(rows)});
    t.shorts(284, {1});
    t.shorts(339, {static_cast<std::uint16_t>(format)});
    t.blocks(273, 279, {pixels});
    return t;
}

template <typename T>
std::string samples(const std::vector<T>& v) {
    std::string out;
    for (T x : v) HandTiff::append(out, x);
    return out;
}

// GeoKeys: version 1.1.0, then (key, 0, 1, value) for each.
std::vector<std::uint16_t> geoKeys(const std::vector<std::pair<int, int>>& keys) {
    std::vector<std::uint16_t> d{1, 1, 0, static_cast<std::uint16_t>(keys.size())};
    for (const auto& [key, value] : keys) {
        d.insert(d.end(),
                 {static_cast<std::uint16_t>(key), 0, 1, static_cast<std::uint16_t>(value)});
    }
    return d;
}

// A 3 × 2 Float32 raster of 0.5 m cells in UTM 33N (EPSG:32633), top-left corner (500000,
// 4000000), one cell without data (-9999).
HandTiff utmFloat32() {
    HandTiff t =
        strippedImage(3, 2, 32, 3, samples<float>({1.5f, 2.0f, -3.25f, 4.0f, -9999.0f, 6.0f}));
    t.doubles(33550, {0.5, 0.5, 0.0});
    t.doubles(33922, {0, 0, 0, 500000.0, 4000000.0, 0});
    t.shorts(34735, geoKeys({{1024, 1}, {1025, 1}, {3072, 32633}}));
    t.ascii(42113, "-9999");
    return t;
}

TEST(GeoTiff, ReadsAHandWrittenFileWithItsPlaceCellsNoDataAndCrs) {
    Result<field::Raster> r = parseGeoTiff(utmFloat32().bytes(), "utm.tif");
    ASSERT_TRUE(r) << r.message();
    EXPECT_EQ(r->cols, 3);
    EXPECT_EQ(r->rows, 2);
    EXPECT_EQ(r->cell_m, 0.5);
    EXPECT_EQ(r->x_min_m, 500000.0);
    EXPECT_EQ(r->y_min_m, 4000000.0 - 2 * 0.5);  // the tie point is the top-left corner
    EXPECT_EQ(r->value(0, 0), 1.5);              // the first pixel is the north-west cell
    EXPECT_EQ(r->value(2, 0), -3.25);
    EXPECT_EQ(r->value(2, 1), 6.0);
    EXPECT_TRUE(std::isnan(r->value(1, 1)));
    EXPECT_EQ(r->cellsWithData(), 5u);
    EXPECT_EQ(r->epsg, 32633);
    // The top-left cell's centre (500000.25, 3999999.75) holds its value.
    EXPECT_EQ(r->nearest(500000.25, 3999999.75), 1.5);
}

TEST(GeoTiff, APixelIsPointTiePointIsTheCentreOfItsCell) {
    HandTiff t = strippedImage(2, 2, 64, 3, samples<double>({1, 2, 3, 4}));
    t.doubles(33550, {2.0, 2.0, 0.0});
    t.doubles(33922, {0, 0, 0, 10.0, 20.0, 0});
    t.shorts(34735, geoKeys({{1024, 1}, {1025, 2}, {3072, 25832}}));
    Result<field::Raster> r = parseGeoTiff(t.bytes(), "point.tif");
    ASSERT_TRUE(r) << r.message();
    EXPECT_EQ(r->x_min_m, 9.0);             // 10 − h/2
    EXPECT_EQ(r->y_min_m, 21.0 - 2 * 2.0);  // top edge 20 + h/2, two rows of 2 m below
    EXPECT_EQ(r->epsg, 25832);
    EXPECT_EQ(r->value(1, 1), 4.0);
}

// A soil-class map in 16 × 16 tiles (2 × 2 of them over 20 × 18 cells, the edge tiles padded),
// UInt8 with 0 as no data, and a ModelTransformationTag instead of scale and tie point.
TEST(GeoTiff, ReadsTiledIntegerClassMaps) {
    constexpr int kCols = 20, kRows = 18, kTile = 16;
    const auto code = [](int col, int row) {
        return static_cast<std::uint8_t>((col + 3 * row) % 5);
    };
    HandTiff t;
    t.longs(256, {kCols});
    t.longs(257, {kRows});
    t.shorts(258, {8});
    t.shorts(259, {1});
    t.shorts(262, {1});
    t.shorts(277, {1});
    t.shorts(284, {1});
    t.shorts(322, {kTile});
    t.shorts(323, {kTile});
    t.shorts(339, {1});
    std::vector<std::string> tiles;
    for (int ty = 0; ty < kRows; ty += kTile) {
        for (int tx = 0; tx < kCols; tx += kTile) {
            std::string tile;
            for (int r = 0; r < kTile; ++r) {
                for (int c = 0; c < kTile; ++c) {
                    const bool inside = tx + c < kCols && ty + r < kRows;
                    tile += static_cast<char>(inside ? code(tx + c, ty + r) : 99);
                }
            }
            tiles.push_back(tile);
        }
    }
    t.blocks(324, 325, tiles);
    t.doubles(34264, {1.0, 0, 0, 100.0, 0, -1.0, 0, 50.0, 0, 0, 0, 0, 0, 0, 0, 1});
    t.ascii(42113, "0");
    Result<field::Raster> r = parseGeoTiff(t.bytes(), "classes.tif");
    ASSERT_TRUE(r) << r.message();
    EXPECT_EQ(r->cols, kCols);
    EXPECT_EQ(r->rows, kRows);
    EXPECT_EQ(r->x_min_m, 100.0);
    EXPECT_EQ(r->y_min_m, 50.0 - kRows);
    EXPECT_FALSE(r->epsg);  // no GeoKeys: no code
    int no_data = 0;
    for (int row = 0; row < kRows; ++row) {
        for (int col = 0; col < kCols; ++col) {
            const double v = r->value(col, row);
            if (code(col, row) == 0) {
                ++no_data;
                EXPECT_TRUE(std::isnan(v)) << col << ", " << row;
            } else {
                EXPECT_EQ(v, code(col, row)) << col << ", " << row;
            }
        }
    }
    EXPECT_EQ(no_data, 72);  // (col + 3 row) % 5 == 0: one cell in five of 360
}

TEST(GeoTiff, SignedSixteenAndThirtyTwoBitIntegersKeepTheirSign) {
    for (const auto& [bits, pixels] :
         {std::pair{16, samples<std::int16_t>({-32768, 7})},
          std::pair{32, samples<std::int32_t>({-2147483647 - 1, 2147483647})}}) {
        HandTiff t = strippedImage(2, 1, bits, 2, pixels);
        t.doubles(33550, {1.0, 1.0, 0.0});
        t.doubles(33922, {0, 0, 0, 0.0, 1.0, 0});
        Result<field::Raster> r = parseGeoTiff(t.bytes(), "int.tif");
        ASSERT_TRUE(r) << r.message();
        EXPECT_EQ(r->value(0, 0), bits == 16 ? -32768.0 : -2147483648.0);
        EXPECT_EQ(r->value(1, 0), bits == 16 ? 7.0 : 2147483647.0);
    }
}

TEST(GeoTiff, TheWritersFileReadsBackBitForBit) {
    field::Raster r = field::makeRaster(7, 5, 0.1, 0.7, 0.1);
    for (std::size_t k = 0; k < r.values.size(); ++k)
        r.values[k] = std::sin(1.0 + k) * std::pow(10.0, static_cast<double>(k % 9) - 4.0);
    r.values[3] = std::numeric_limits<double>::quiet_NaN();
    r.values[4] = -9999.0;  // an ordinary value here: no data is NaN in the file
    r.values[5] = std::numeric_limits<double>::denorm_min();
    r.epsg = 25832;
    testing::TempDir temp;
    const auto path = temp.path() / "map.tif";
    ASSERT_EQ(writeRaster(path, r), std::nullopt);
    EXPECT_FALSE(std::filesystem::exists(temporaryPathFor(path)));
    Result<field::Raster> back = readRaster(path);
    ASSERT_TRUE(back) << back.message();
    EXPECT_EQ(back->cols, 7);
    EXPECT_EQ(back->rows, 5);
    EXPECT_EQ(back->x_min_m, 0.1);
    EXPECT_EQ(back->y_min_m, 0.7);
    EXPECT_EQ(back->cell_m, 0.1);
    EXPECT_EQ(back->epsg, 25832);
    ASSERT_EQ(back->values.size(), r.values.size());
    for (std::size_t k = 0; k < r.values.size(); ++k) {
        if (std::isnan(r.values[k])) {
            EXPECT_TRUE(std::isnan(back->values[k])) << k;
        } else {
            EXPECT_EQ(std::memcmp(&back->values[k], &r.values[k], sizeof(double)), 0) << k;
        }
    }
    // A raster without a code is written "user-defined" and read without one.
    r.epsg.reset();
    ASSERT_EQ(writeRaster(temp.path() / "local.tiff", r), std::nullopt);
    Result<field::Raster> local = readRaster(temp.path() / "local.tiff");
    ASSERT_TRUE(local) << local.message();
    EXPECT_FALSE(local->epsg);
}

// Each refusal names the file and the reason.
TEST(GeoTiff, RefusesWhatAFieldCannotUse) {
    const auto refusal = [](const HandTiff& t) {
        Result<field::Raster> r = parseGeoTiff(t.bytes(), "bad.tif");
        EXPECT_FALSE(r);
        return r.message();
    };
    const std::string float32 = samples<float>({1, 2, 3, 4});
    const auto georeferenced = [&](int bits = 32, int format = 3, std::string pixels = {}) {
        HandTiff t = strippedImage(2, 2, bits, format, pixels.empty() ? float32 : pixels);
        t.doubles(33550, {1.0, 1.0, 0.0});
        t.doubles(33922, {0, 0, 0, 0.0, 2.0, 0});
        return t;
    };
    {
        HandTiff t = georeferenced();
        t.doubles(34264, {0.8, 0.6, 0, 0, -0.6, 0.8, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1});
        const std::string m = refusal(t);
        EXPECT_TRUE(contains(m, "bad.tif: its ModelTransformationTag rotates or shears")) << m;
    }
    {
        HandTiff t = georeferenced();
        t.doubles(33550, {0.5, 0.25, 0.0});
        const std::string m = refusal(t);
        EXPECT_TRUE(contains(m, "bad.tif: its cells are not square (0.5 × 0.25 m)")) << m;
    }
    {
        HandTiff t = georeferenced();
        t.doubles(33922, {0, 0, 0, 0.0, 2.0, 0, 1, 1, 0, 1.0, 1.0, 0});
        const std::string m = refusal(t);
        EXPECT_TRUE(contains(m, "bad.tif: it has 2 tie points")) << m;
    }
    {
        HandTiff t = georeferenced(32, 3, samples<float>({1, 2, 3, 4, 5, 6, 7, 8}));
        t.shorts(258, {32, 32});
        t.shorts(277, {2});
        t.shorts(339, {3, 3});
        const std::string m = refusal(t);
        EXPECT_TRUE(contains(m, "bad.tif: has 2 bands")) << m;
    }
    {
        const std::string m = refusal(georeferenced(16, 3, samples<std::uint16_t>({1, 2, 3, 4})));
        EXPECT_TRUE(contains(m, "bad.tif: holds Float16 samples; read are UInt8")) << m;
    }
    {
        HandTiff t = georeferenced();
        t.shorts(34735, geoKeys({{1024, 2}, {1025, 1}, {2048, 4326}}));
        const std::string m = refusal(t);
        EXPECT_TRUE(contains(m,
                             "bad.tif: its coordinates are geographic (degrees of latitude "
                             "and longitude (EPSG:4326)); a field needs metres"))
            << m;
    }
    {
        HandTiff t = georeferenced();
        t.shorts(34735, geoKeys({{1024, 1}, {3072, 2227}, {3076, 9003}}));
        const std::string m = refusal(t);
        EXPECT_TRUE(contains(m, "bad.tif: its linear unit is EPSG unit 9003, not the metre")) << m;
    }
    {
        const std::string m = refusal(strippedImage(2, 2, 32, 3, float32));
        EXPECT_TRUE(contains(m, "bad.tif: it has no georeferencing")) << m;
    }
    {
        Result<field::Raster> r = parseGeoTiff("II*\0garbage", "junk.tif");
        ASSERT_FALSE(r);
        EXPECT_TRUE(contains(r.message(), "junk.tif: is not a TIFF file libtiff reads"))
            << r.message();
    }
}

// A file cut short anywhere (a copy interrupted, a download broken) is an error naming it, or —
// when only what follows the pixels and the georeferencing is lost (the software's name, the
// no-data text) — the same raster; never a crash or garbage.
TEST(GeoTiff, AFileCutShortIsRefusedOrComplete) {
    field::Raster r = field::makeRaster(40, 30, 0.0, 0.0, 1.0);
    for (std::size_t k = 0; k < r.values.size(); ++k) r.values[k] = std::cos(0.1 * k);
    const std::string whole = toGeoTiff(r).value();
    int refused = 0;
    for (std::size_t n = 0; n < whole.size(); n += 13) {
        Result<field::Raster> cut = parseGeoTiff(std::string_view(whole).substr(0, n), "cut.tif");
        if (!cut) {
            ++refused;
            EXPECT_TRUE(contains(cut.message(), "cut.tif: ")) << cut.message();
        } else {
            EXPECT_EQ(cut->values, r.values) << "cut at " << n << " of " << whole.size();
            EXPECT_EQ(cut->x_min_m, 0.0);
            EXPECT_EQ(cut->y_min_m, 0.0);
            EXPECT_EQ(cut->cell_m, 1.0);
        }
    }
    EXPECT_GT(refused, static_cast<int>(whole.size() / 13) - 5);  // all but the last few bytes
    EXPECT_TRUE(parseGeoTiff(whole, "whole.tif"));
}

// The "a coordinate system that differs from the other map": named with both files and
// codes.
TEST(GeoTiff, AFieldRefusesRastersInTwoCoordinateSystems) {
    testing::TempDir temp;
    field::Raster height = field::makeRaster(4, 4, 0.0, 0.0, 1.0, 100.0);
    height.epsg = 32633;
    field::Raster classes = field::makeRaster(4, 4, 0.0, 0.0, 1.0, 1.0);
    classes.epsg = 25833;
    ASSERT_EQ(writeRaster(temp.path() / "height.tif", height), std::nullopt);
    ASSERT_EQ(writeRaster(temp.path() / "classes.tif", classes), std::nullopt);
    const auto fieldWith = [&](const std::string& classes_file) {
        const nlohmann::json j = {{"height", "height.tif"},
                                  {"soil", "sandy-loam"},
                                  {"soil_classes", classes_file},
                                  {"legend", {{"1", "sandy-loam"}}}};
        return fieldFromJson(j, "field.json", temp.path(), kLocations);
    };
    Result<FieldFile> mixed = fieldWith("classes.tif");
    ASSERT_FALSE(mixed);
    const std::string m = mixed.message();
    EXPECT_TRUE(contains(m, "field.json: soil_classes: " + (temp.path() / "classes.tif").string() +
                                " is in EPSG:25833, but height (" +
                                (temp.path() / "height.tif").string() + ") is in EPSG:32633"))
        << m;
    classes.epsg = 32633;
    ASSERT_EQ(writeRaster(temp.path() / "classes.tif", classes), std::nullopt);
    Result<FieldFile> same = fieldWith("classes.tif");
    ASSERT_TRUE(same) << same.message();
    EXPECT_EQ(field::epsgCode(same->map), 32633);
}

// The shipped sloped field with its height map converted to GeoTIFF drives exactly as with the
// ESRI ASCII grid: the same time series and maps, bit for bit.
TEST(GeoTiff, AFieldWhoseHeightIsAGeoTiffRunsAsWithTheAsciiGrid) {
    testing::TempDir temp;
    const std::filesystem::path fields = std::filesystem::path(TERRA_RESOURCE_DIR) / "fields";
    Result<field::Raster> height = readRaster(fields / "sloped-wet" / "height.asc");
    ASSERT_TRUE(height) << height.message();
    ASSERT_EQ(writeRaster(temp.path() / "height.tif", *height), std::nullopt);
    Result<scenario::Scenario> shipped = scenario::resolveScenario(kLocations, "field-slope-wet");
    ASSERT_TRUE(shipped) << shipped.message();
    nlohmann::json j;
    {
        std::string text;
        ASSERT_FALSE(readFile(
            std::filesystem::path(TERRA_RESOURCE_DIR) / "scenarios" / "field-slope-wet.json",
            text));
        j = nlohmann::json::parse(text);
    }
    j["terrain"]["height"] = (temp.path() / "height.tif").string();
    j["terrain"]["soils"] = (fields / "sloped-wet" / "soil-classes.asc").string();
    j["duration_s"] = 3.0;
    Result<scenario::Scenario> tif =
        scenario::scenarioFromJson(j, "tif.json", kLocations, temp.path());
    ASSERT_TRUE(tif) << tif.message();
    scenario::Scenario asc = shipped.value();
    asc.duration_s = 3.0;
    const scenario::RunResult a = scenario::runScenario(asc);
    const scenario::RunResult b = scenario::runScenario(tif.value());
    ASSERT_TRUE(a.maps && b.maps);
    ASSERT_EQ(a.series.rows.size(), b.series.rows.size());
    for (std::size_t i = 0; i < a.series.rows.size(); ++i) {
        for (std::size_t c = 0; c < a.series.rows[i].size(); ++c) {
            const double x = a.series.rows[i][c], y = b.series.rows[i][c];
            ASSERT_TRUE(x == y || (std::isnan(x) && std::isnan(y))) << "row " << i << " col " << c;
        }
    }
    EXPECT_EQ(a.maps->rut_depth_m.values, b.maps->rut_depth_m.values);
    EXPECT_GT(a.maps->rut_depth_m.valueRange().second, 0.0);  // the run left a rut
}

}  // namespace
}  // namespace terra::io
