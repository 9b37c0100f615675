// A run's maps as PNG pictures (core/scenario/map_image.h), decoded here with libpng: the
// picture's size, a cell's colour against the studio's palette at its value (the stops'
// numbers written out here, the blend computed by hand), a cell without data transparent, the
// legend below the map; the scale's ticks and their texts.
#include "core/scenario/map_image.h"

#include <gtest/gtest.h>
#include <png.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>

#include "tests/core/test_temp_dir.h"

namespace terra::scenario {
namespace {

constexpr double kNoData = std::numeric_limits<double>::quiet_NaN();

struct Decoded {
    int width = 0, height = 0;
    std::vector<std::uint8_t> rgba;
    const std::uint8_t* at(int x, int y) const {
        return &rgba[(static_cast<std::size_t>(y) * width + x) * 4];
    }
};

Decoded decodePng(const std::filesystem::path& path) {
    png_image image;
    std::memset(&image, 0, sizeof image);
    image.version = PNG_IMAGE_VERSION;
    Decoded d;
    if (!png_image_begin_read_from_file(&image, path.c_str())) {
        ADD_FAILURE() << path << ": " << image.message;
        return d;
    }
    image.format = PNG_FORMAT_RGBA;
    d.width = static_cast<int>(image.width);
    d.height = static_cast<int>(image.height);
    d.rgba.resize(PNG_IMAGE_SIZE(image));
    if (!png_image_finish_read(&image, nullptr, d.rgba.data(), 0, nullptr))
        ADD_FAILURE() << path << ": " << image.message;
    return d;
}

// The colour expected at a fraction u between two stops (the studio's numbers), ±1 for rounding.
void expectBlend(const std::uint8_t* p, std::array<double, 3> a, std::array<double, 3> b, double u,
                 const std::string& what) {
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(p[c], a[c] + u * (b[c] - a[c]), 1.0) << what << " channel " << c;
    EXPECT_EQ(p[3], 255) << what;
}

// Five maps of 10 × 4 cells of 0.5 m; the rut from 0 to 9 mm along the first row, a cell
// without data, the risk with a cell in the yellow and one in the red band.
FieldMaps smallMaps() {
    FieldMaps maps;
    maps.risk_depth_m = 0.3;
    for (const auto& entry : mapRasters(maps))
        *entry.second = field::makeRaster(10, 4, 2.0, 3.0, 0.5);
    for (int col = 0; col < 10; ++col) maps.rut_depth_m.value(col, 0) = 1e-3 * col;
    maps.rut_depth_m.value(3, 2) = kNoData;
    maps.compaction_risk.value(1, 1) = 0.8;
    maps.compaction_risk.value(2, 1) = 1.2;
    maps.compaction_risk.value(3, 1) = kNoData;
    return maps;
}

TEST(MapImage, EachMapIsAPngWithThePalettesColoursAndALegend) {
    testing::TempDir temp;
    const FieldMaps maps = smallMaps();
    ASSERT_FALSE(writeMapPngs(maps, temp.path()));
    for (const auto& entry : mapRasters(maps))
        EXPECT_TRUE(std::filesystem::exists(temp.path() / (entry.first + ".png"))) << entry.first;

    const Decoded rut = decodePng(temp.path() / "rut_depth_m.png");
    // 10 columns scaled up by whole pixels to at least 400: 40 pixels a cell.
    constexpr int kCell = 40;
    EXPECT_EQ(rut.width, 10 * kCell);
    ASSERT_GT(rut.height, 4 * kCell);  // the legend lies below the map
    const auto centre = [&](const Decoded& d, int col, int row) {
        return d.at(col * kCell + kCell / 2, row * kCell + kCell / 2);
    };
    // The scale is [0, 9] mm: ochre (225, 160, 75) at 0 to dark brown (60, 30, 10) at 9 mm.
    expectBlend(centre(rut, 0, 0), {225, 160, 75}, {60, 30, 10}, 0.0, "0 mm");
    expectBlend(centre(rut, 9, 0), {225, 160, 75}, {60, 30, 10}, 1.0, "9 mm");
    expectBlend(centre(rut, 4, 0), {225, 160, 75}, {60, 30, 10}, 4.0 / 9.0, "4 mm");
    expectBlend(rut.at(6 * kCell, 0), {225, 160, 75}, {60, 30, 10}, 6.0 / 9.0, "a block's corner");
    EXPECT_EQ(centre(rut, 3, 2)[3], 0);  // no data: transparent
    EXPECT_EQ(centre(rut, 3, 1)[3], 255);
    // The legend: opaque; the colour bar runs from the scale's start to its end colour; the title
    // and tick values in dark ink.
    int ink = 0, bar_row = -1;
    for (int y = 4 * kCell; y < rut.height; ++y) {
        for (int x = 0; x < rut.width; ++x) {
            const std::uint8_t* p = rut.at(x, y);
            EXPECT_EQ(p[3], 255) << x << ", " << y;
            if (p[0] == 40 && p[1] == 40 && p[2] == 40) ++ink;
        }
        const std::uint8_t* mid = rut.at(rut.width / 2, y);
        if (bar_row < 0 && !(mid[0] == 255 && mid[1] == 255 && mid[2] == 255) && mid[0] != 40)
            bar_row = y;
    }
    EXPECT_GT(ink, 200);  // "rut depth [mm]" and "0 2 4 6 8": hundreds of dots
    ASSERT_GE(bar_row, 0);
    int left = 0, right = rut.width - 1;
    while (rut.at(left, bar_row)[0] == 255) ++left;
    while (rut.at(right, bar_row)[0] == 255) --right;
    expectBlend(rut.at(left, bar_row), {225, 160, 75}, {60, 30, 10}, 0.0, "bar start");
    expectBlend(rut.at(right, bar_row), {225, 160, 75}, {60, 30, 10}, 1.0, "bar end");

    // The compaction risk on [0, 1.5] in Terranimo's bands: 0.8 between yellow (245, 215, 60)
    // at 0.5 and orange (235, 175, 30) at 1.1; 1.2 between red (220, 60, 45) at 1.1 and dark red
    // (130, 20, 20) at 1.5.
    const Decoded risk = decodePng(temp.path() / "compaction_risk.png");
    expectBlend(centre(risk, 1, 1), {245, 215, 60}, {235, 175, 30}, 0.3 / 0.6, "risk 0.8");
    expectBlend(centre(risk, 2, 1), {220, 60, 45}, {130, 20, 20}, 0.1 / 0.4, "risk 1.2");
    expectBlend(centre(risk, 0, 0), {215, 240, 205}, {60, 160, 60}, 0.0, "risk 0");
    EXPECT_EQ(centre(risk, 3, 1)[3], 0);
}

// A PNG's tEXt chunks read by libpng's own reader (which drops a chunk whose CRC is wrong).
std::map<std::string, std::string> pngText(const std::filesystem::path& path) {
    std::map<std::string, std::string> out;
    FILE* file = std::fopen(path.c_str(), "rb");
    if (file == nullptr) return out;
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
    png_infop info = png_create_info_struct(png);
    if (setjmp(png_jmpbuf(png)) == 0) {
        png_init_io(png, file);
        png_read_png(png, info, PNG_TRANSFORM_IDENTITY, nullptr);  // to IEND: every chunk
        {
            png_textp text = nullptr;
            const int n = png_get_text(png, info, &text, nullptr);
            for (int i = 0; i < n; ++i)
                out[text[i].key] =
                    text[i].text;  // NUL-ended (iTXt has itxt_length, not text_length)
        }
    }
    png_destroy_read_struct(&png, &info, nullptr);
    std::fclose(file);
    return out;
}

// The legend travels as text too: a program that reads only the picture and its tEXt chunks
// finds each cell's value from its colour on the legend's stops (the inverse of the blend, with
// the picture's cells placed by the legend's geometry), within a colour step.
TEST(MapImage, ThePicturesTextGivesTheLegendAProgramCanReadValuesWith) {
    testing::TempDir temp;
    const FieldMaps maps = smallMaps();
    ASSERT_FALSE(writeMapPngs(maps, temp.path()));
    const std::map<std::string, std::string> text = pngText(temp.path() / "rut_depth_m.png");
    ASSERT_TRUE(text.count("terrastudio:legend")) << text.size();
    EXPECT_EQ(text.at("Title"), "rut depth [mm]");
    EXPECT_EQ(text.at("Software"), "TerraStudio");
    const nlohmann::json legend = nlohmann::json::parse(text.at("terrastudio:legend"));
    EXPECT_EQ(legend["layer"], "rut_depth_m");
    EXPECT_EQ(legend["unit"], "mm");
    EXPECT_EQ(legend["factor"], 1000.0);
    EXPECT_EQ(legend["cells"]["x_min_m"], 2.0);
    EXPECT_EQ(legend["cells"]["cols"], 10);
    const int px = legend["cells"]["cell_px"];
    const nlohmann::json& colours = legend["colours"];
    ASSERT_EQ(colours.size(), 2u);  // the rut's two stops
    auto rgb = [](const std::string& hex, int c) {
        return std::stoi(hex.substr(1 + 2 * c, 2), nullptr, 16);
    };
    const double v0 = colours[0]["at"], v1 = colours[1]["at"];
    const Decoded rut = decodePng(temp.path() / "rut_depth_m.png");
    for (int col = 0; col < 10; ++col) {
        const std::uint8_t* p = rut.at(col * px + px / 2, px / 2);  // row 0, the top
        // The red channel falls from the first stop to the second: its fraction gives the value.
        const double r0 = rgb(colours[0]["rgb"], 0), r1 = rgb(colours[1]["rgb"], 0);
        const double value = v0 + (p[0] - r0) / (r1 - r0) * (v1 - v0);
        EXPECT_NEAR(value, 1e3 * maps.rut_depth_m.value(col, 0), (v1 - v0) / std::abs(r1 - r0))
            << "col " << col;
    }
    for (double tick : legend["ticks"]) EXPECT_TRUE(tick >= v0 && tick <= v1) << tick;
    // A title beyond ASCII travels as UTF-8 (iTXt), not as Latin-1 mojibake.
    const auto risk = pngText(temp.path() / "compaction_risk.png");
    ASSERT_TRUE(risk.count("Title"));
    EXPECT_NE(risk.at("Title").find("σz/σpc"), std::string::npos) << risk.at("Title");
    // Every map carries its own legend.
    for (const auto& entry : mapRasters(maps)) {
        const auto t = pngText(temp.path() / (entry.first + ".png"));
        ASSERT_TRUE(t.count("terrastudio:legend")) << entry.first;
        EXPECT_EQ(nlohmann::json::parse(t.at("terrastudio:legend"))["layer"], entry.first);
    }
    // Text PNG does not allow is refused by name, not written.
    io::RgbaImage bad = io::RgbaImage::filled(2, 2, 0, 0, 0, 255);
    bad.text = {{" Title", "x"}};
    const Result<std::string> refused = io::toPng(bad);
    ASSERT_FALSE(refused.ok());
    EXPECT_NE(refused.message().find("' Title'"), std::string::npos) << refused.message();
}

// The maps of a drive other than the risk darken along their scale: the relative luminance
// (sRGB decoded to linear light, ITU-R BT.709 weights) falls at every step.
TEST(MapImage, TheSequentialPalettesDarkenAlongTheScale) {
    const auto linear = [](double c) {
        c /= 255.0;
        return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
    };
    for (const char* key : {"rut_depth_m", "passes", "slip", "energy_per_m_J"}) {
        MapLayer layer;
        layer.key = key;
        const std::vector<ColorStop> stops = layerColors(layer, LayerScale{});
        double previous = 2.0;
        for (int i = 0; i <= 100; ++i) {
            const Rgb c = colorAt(stops, i / 100.0);
            const double y = 0.2126 * linear(c.r) + 0.7152 * linear(c.g) + 0.0722 * linear(c.b);
            EXPECT_LE(y, previous) << key << " at " << i << " %";
            previous = y;
        }
        EXPECT_LT(previous, 0.1) << key;  // dark at the end
    }
}

TEST(MapImage, AWideMapIsOnePixelPerCellAndALongOneStaysBounded) {
    const MapImageLayout wide = mapImageLayout(2500, 1000);
    EXPECT_EQ(wide.cell_px, 1);
    EXPECT_EQ(wide.map_width, 2500);
    EXPECT_EQ(wide.map_height, 1000);
    EXPECT_EQ(wide.legend_top, 1000);
    EXPECT_GT(wide.height, 1000);
    const MapImageLayout narrow = mapImageLayout(3, 10);
    EXPECT_EQ(narrow.cell_px, 134);  // ⌈400 / 3⌉
    EXPECT_EQ(narrow.width, 402);
    const MapImageLayout thin = mapImageLayout(1, 100000);
    EXPECT_EQ(thin.cell_px, 1);  // 400 pixels a cell would be 40 million rows
    EXPECT_EQ(thin.width, kMinMapImageWidth);
}

TEST(MapImage, TicksAreRoundStepsAndTheRiskBandEdges) {
    LayerScale rut;
    rut.lower = 0.0;
    rut.upper = 9.0;
    EXPECT_EQ(scaleTicks("rut_depth_m", rut), (std::vector<double>{0, 2, 4, 6, 8}));
    LayerScale risk;
    risk.lower = 0.0;
    risk.upper = 1.5;
    const std::vector<double> ticks = scaleTicks("compaction_risk", risk);
    const std::vector<double> expected{0.0, 0.2, 0.5, 0.8, 1.1, 1.4};
    ASSERT_EQ(ticks.size(), expected.size());
    for (std::size_t i = 0; i < ticks.size(); ++i) EXPECT_NEAR(ticks[i], expected[i], 1e-12);
    EXPECT_EQ(tickText(0.5, 0.3), "0.5");
    EXPECT_EQ(tickText(1.4000000000000001, 0.2), "1.4");
    EXPECT_EQ(tickText(-1e-17, 0.2), "0.0");
    EXPECT_EQ(tickText(250, 50), "250");
    EXPECT_EQ(tickText(2e6, 1e6), "2e+06");
    EXPECT_EQ(tickText(3e-5, 1e-5), "3e-05");
}

}  // namespace
}  // namespace terra::scenario
