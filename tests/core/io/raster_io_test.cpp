#include "core/io/raster_io.h"

#include <gtest/gtest.h>

#include <cmath>

#include "tests/core/test_temp_dir.h"

namespace terra::io {
namespace {

const char* kGrid =
    "ncols 3\n"
    "NROWS 2\n"
    "xllcorner 100\n"
    "yllcorner 200.5\n"
    "cellsize 0.5\n"
    "NODATA_value -9999\n"
    "1 2 3\n"
    "4 -9999 6.25\n";

TEST(RasterIo, ReadsAnEsriAsciiGrid) {
    Result<field::Raster> r = parseAsciiGrid(kGrid, "g.asc");
    ASSERT_TRUE(r) << r.message();
    EXPECT_EQ(r->cols, 3);
    EXPECT_EQ(r->rows, 2);
    EXPECT_EQ(r->x_min_m, 100.0);
    EXPECT_EQ(r->y_min_m, 200.5);
    EXPECT_EQ(r->cell_m, 0.5);
    EXPECT_EQ(r->value(0, 0), 1.0);  // the first value is the north-west cell
    EXPECT_EQ(r->nearest(100.1, 201.4), 1.0);
    EXPECT_EQ(r->nearest(101.4, 200.6), 6.25);
    EXPECT_TRUE(std::isnan(r->value(1, 1)));
}

TEST(RasterIo, CentreHeadersPlaceTheCornerHalfACellAway) {
    Result<field::Raster> r =
        parseAsciiGrid("ncols 1\nnrows 1\nxllcenter 10\nyllcenter 20\ncellsize 2\n5\n", "c.asc");
    ASSERT_TRUE(r) << r.message();
    EXPECT_EQ(r->x_min_m, 9.0);
    EXPECT_EQ(r->y_min_m, 19.0);
}

TEST(RasterIo, AsciiGridAndCsvRoundTrip) {
    Result<field::Raster> r = parseAsciiGrid(kGrid, "g.asc");
    ASSERT_TRUE(r);
    Result<field::Raster> again = parseAsciiGrid(toAsciiGrid(*r), "again.asc");
    ASSERT_TRUE(again) << again.message();
    Result<field::Raster> csv = parseRasterCsv(toRasterCsv(*r, "z_m"), "r.csv");
    ASSERT_TRUE(csv) << csv.message();
    for (const field::Raster* other : {&again.value(), &csv.value()}) {
        EXPECT_EQ(other->cols, r->cols);
        EXPECT_EQ(other->rows, r->rows);
        EXPECT_DOUBLE_EQ(other->x_min_m, r->x_min_m);
        EXPECT_DOUBLE_EQ(other->y_min_m, r->y_min_m);
        for (std::size_t k = 0; k < r->values.size(); ++k) {
            if (std::isnan(r->values[k])) {
                EXPECT_TRUE(std::isnan(other->values[k]));
            } else {
                EXPECT_EQ(other->values[k], r->values[k]);
            }
        }
    }
}

TEST(RasterIo, AsciiGridProblemsAreNamed) {
    Result<field::Raster> short_grid =
        parseAsciiGrid("ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2 3\n", "s.asc");
    ASSERT_FALSE(short_grid);
    EXPECT_NE(short_grid.message().find("holds 3 values for ncols × nrows = 2 × 2 = 4"),
              std::string::npos)
        << short_grid.message();
    Result<field::Raster> key =
        parseAsciiGrid("ncols 1\nnrows 1\nxllcorner 0\nyllcorner 0\ncelsize 1\n1\n", "k.asc");
    ASSERT_FALSE(key);
    EXPECT_NE(key.message().find("k.asc:5: unknown header key 'celsize'"), std::string::npos)
        << key.message();
    Result<field::Raster> value =
        parseAsciiGrid("ncols 2\nnrows 1\nxllcorner 0\nyllcorner 0\ncellsize 1\n1\nnan\n", "v.asc");
    ASSERT_FALSE(value);
    EXPECT_NE(value.message().find("v.asc:7: value 2 'nan' is not a finite number"),
              std::string::npos)
        << value.message();
}

TEST(RasterIo, CsvCentresMustLieOnOneGrid) {
    Result<field::Raster> r =
        parseRasterCsv("x_m,y_m,k\n0.5,0.5,1\n1.5,0.5,2\n0.5,2.5,3\n", "r.csv");
    ASSERT_TRUE(r) << r.message();
    EXPECT_EQ(r->cols, 2);
    EXPECT_EQ(r->rows, 3);
    EXPECT_EQ(r->nearest(0.5, 2.5), 3.0);
    EXPECT_TRUE(std::isnan(r->nearest(0.5, 1.5)));  // no row: no data
    Result<field::Raster> off = parseRasterCsv("x_m,y_m,k\n0,0,1\n1,0,2\n2.3,0,3\n", "o.csv");
    ASSERT_FALSE(off);
    EXPECT_NE(off.message().find("o.csv:4: (2.3, 0) is not on the grid of 1 m"), std::string::npos)
        << off.message();
    // A row without a value (no data) before a bad one: the bad one's own line is named.
    Result<field::Raster> after_empty =
        parseRasterCsv("x_m,y_m,k\n0,0,\n0,1,1\n5.5,0,2\n", "e.csv");
    ASSERT_FALSE(after_empty);
    EXPECT_NE(after_empty.message().find("e.csv:4: (5.5, 0) is not on the grid"), std::string::npos)
        << after_empty.message();
    Result<field::Raster> twice = parseRasterCsv("x_m,y_m,k\n0,0,1\n0,0,2\n", "t.csv");
    ASSERT_FALSE(twice);
    EXPECT_NE(twice.message().find("given twice"), std::string::npos) << twice.message();
}

TEST(RasterIo, FilesByExtensionAndNoOtherFormat) {
    testing::TempDir temp;
    Result<field::Raster> r = parseAsciiGrid(kGrid, "g.asc");
    ASSERT_TRUE(r);
    ASSERT_FALSE(writeRaster(temp.path() / "out.asc", *r));
    ASSERT_FALSE(writeRaster(temp.path() / "out.csv", *r));
    EXPECT_TRUE(readRaster(temp.path() / "out.asc"));
    EXPECT_TRUE(readRaster(temp.path() / "out.csv"));
    Result<field::Raster> img = readRaster(temp.path() / "dem.img");
    ASSERT_FALSE(img);
    EXPECT_NE(img.message().find("GeoTIFF (.tif, .tiff); '.img' is none of them"),
              std::string::npos)
        << img.message();
}

}  // namespace
}  // namespace terra::io
