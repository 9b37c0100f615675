#include "core/scenario/map_image.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <nlohmann/json.hpp>

namespace terra::scenario {

namespace {

// The built-in font: 5 × 7 dots a glyph, one row a byte (bit 4 the leftmost dot), drawn with
// one dot's spacing between glyphs. Enough for the maps' titles, units and tick values.
struct MapGlyph {
    char32_t code;
    std::array<std::uint8_t, 7> rows;
};

constexpr MapGlyph kMapFont[] = {
    {U'0', {0b01110, 0b10001, 0b10011, 0b10101, 0b11001, 0b10001, 0b01110}},
    {U'1', {0b00100, 0b01100, 0b00100, 0b00100, 0b00100, 0b00100, 0b01110}},
    {U'2', {0b01110, 0b10001, 0b00001, 0b00010, 0b00100, 0b01000, 0b11111}},
    {U'3', {0b11111, 0b00010, 0b00100, 0b00010, 0b00001, 0b10001, 0b01110}},
    {U'4', {0b00010, 0b00110, 0b01010, 0b10010, 0b11111, 0b00010, 0b00010}},
    {U'5', {0b11111, 0b10000, 0b11110, 0b00001, 0b00001, 0b10001, 0b01110}},
    {U'6', {0b00110, 0b01000, 0b10000, 0b11110, 0b10001, 0b10001, 0b01110}},
    {U'7', {0b11111, 0b00001, 0b00010, 0b00100, 0b01000, 0b01000, 0b01000}},
    {U'8', {0b01110, 0b10001, 0b10001, 0b01110, 0b10001, 0b10001, 0b01110}},
    {U'9', {0b01110, 0b10001, 0b10001, 0b01111, 0b00001, 0b00010, 0b01100}},
    {U'.', {0b00000, 0b00000, 0b00000, 0b00000, 0b00000, 0b01100, 0b01100}},
    {U'-', {0b00000, 0b00000, 0b00000, 0b01110, 0b00000, 0b00000, 0b00000}},
    {U'+', {0b00000, 0b00100, 0b00100, 0b11111, 0b00100, 0b00100, 0b00000}},
    {U'%', {0b11000, 0b11001, 0b00010, 0b00100, 0b01000, 0b10011, 0b00011}},
    {U'/', {0b00000, 0b00001, 0b00010, 0b00100, 0b01000, 0b10000, 0b00000}},
    {U'[', {0b01110, 0b01000, 0b01000, 0b01000, 0b01000, 0b01000, 0b01110}},
    {U']', {0b01110, 0b00010, 0b00010, 0b00010, 0b00010, 0b00010, 0b01110}},
    {U'(', {0b00010, 0b00100, 0b01000, 0b01000, 0b01000, 0b00100, 0b00010}},
    {U')', {0b01000, 0b00100, 0b00010, 0b00010, 0b00010, 0b00100, 0b01000}},
    {U'a', {0b00000, 0b00000, 0b01110, 0b00001, 0b01111, 0b10001, 0b01111}},
    {U'b', {0b10000, 0b10000, 0b10110, 0b11001, 0b10001, 0b10001, 0b11110}},
    {U'c', {0b00000, 0b00000, 0b01110, 0b10000, 0b10000, 0b10001, 0b01110}},
    {U'd', {0b00001, 0b00001, 0b01101, 0b10011, 0b10001, 0b10001, 0b01111}},
    {U'e', {0b00000, 0b00000, 0b01110, 0b10001, 0b11111, 0b10000, 0b01110}},
    {U'f', {0b00110, 0b01001, 0b01000, 0b11100, 0b01000, 0b01000, 0b01000}},
    {U'g', {0b00000, 0b01111, 0b10001, 0b10001, 0b01111, 0b00001, 0b01110}},
    {U'h', {0b10000, 0b10000, 0b10110, 0b11001, 0b10001, 0b10001, 0b10001}},
    {U'i', {0b00100, 0b00000, 0b01100, 0b00100, 0b00100, 0b00100, 0b01110}},
    {U'j', {0b00010, 0b00000, 0b00110, 0b00010, 0b00010, 0b10010, 0b01100}},
    {U'k', {0b10000, 0b10000, 0b10010, 0b10100, 0b11000, 0b10100, 0b10010}},
    {U'l', {0b01100, 0b00100, 0b00100, 0b00100, 0b00100, 0b00100, 0b01110}},
    {U'm', {0b00000, 0b00000, 0b11010, 0b10101, 0b10101, 0b10001, 0b10001}},
    {U'n', {0b00000, 0b00000, 0b10110, 0b11001, 0b10001, 0b10001, 0b10001}},
    {U'o', {0b00000, 0b00000, 0b01110, 0b10001, 0b10001, 0b10001, 0b01110}},
    {U'p', {0b00000, 0b00000, 0b11110, 0b10001, 0b11110, 0b10000, 0b10000}},
    {U'q', {0b00000, 0b00000, 0b01101, 0b10011, 0b01111, 0b00001, 0b00001}},
    {U'r', {0b00000, 0b00000, 0b10110, 0b11001, 0b10000, 0b10000, 0b10000}},
    {U's', {0b00000, 0b00000, 0b01110, 0b10000, 0b01110, 0b00001, 0b11110}},
    {U't', {0b01000, 0b01000, 0b11100, 0b01000, 0b01000, 0b01001, 0b00110}},
    {U'u', {0b00000, 0b00000, 0b10001, 0b10001, 0b10001, 0b10011, 0b01101}},
    {U'v', {0b00000, 0b00000, 0b10001, 0b10001, 0b10001, 0b01010, 0b00100}},
    {U'w', {0b00000, 0b00000, 0b10001, 0b10001, 0b10101, 0b10101, 0b01010}},
    {U'x', {0b00000, 0b00000, 0b10001, 0b01010, 0b00100, 0b01010, 0b10001}},
    {U'y', {0b00000, 0b00000, 0b10001, 0b10001, 0b01111, 0b00001, 0b01110}},
    {U'z', {0b00000, 0b00000, 0b11111, 0b00010, 0b00100, 0b01000, 0b11111}},
    {U'J', {0b00111, 0b00010, 0b00010, 0b00010, 0b00010, 0b10010, 0b01100}},
    {U'N', {0b10001, 0b10001, 0b11001, 0b10101, 0b10011, 0b10001, 0b10001}},
    {U'P', {0b11110, 0b10001, 0b10001, 0b11110, 0b10000, 0b10000, 0b10000}},
    {U'W', {0b10001, 0b10001, 0b10001, 0b10101, 0b10101, 0b10101, 0b01010}},
    {U'\u03c3', {0b00000, 0b00000, 0b01111, 0b10010, 0b10001, 0b10001, 0b01110}},
    {U'\u00b2', {0b01100, 0b00010, 0b00100, 0b01110, 0b00000, 0b00000, 0b00000}},
};

constexpr std::array<std::uint8_t, 7> kMissingGlyph{0b11111, 0b10001, 0b10001, 0b10001,
                                                    0b10001, 0b10001, 0b11111};
constexpr int kGlyphWidth = 5, kGlyphHeight = 7, kGlyphAdvance = 6;  // in dots

const std::array<std::uint8_t, 7>* glyphFor(char32_t c) {
    for (const MapGlyph& g : kMapFont) {
        if (g.code == c) return &g.rows;
    }
    return c == U' ' ? nullptr : &kMissingGlyph;
}

// The code points of UTF-8 text (one- and two-byte sequences; anything longer becomes U+FFFD).
std::u32string codePoints(const std::string& text) {
    std::u32string out;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const auto c = static_cast<unsigned char>(text[i]);
        if (c < 0x80) {
            out += static_cast<char32_t>(c);
        } else if ((c & 0xE0) == 0xC0 && i + 1 < text.size()) {
            out += static_cast<char32_t>(((c & 0x1F) << 6) |
                                         (static_cast<unsigned char>(text[i + 1]) & 0x3F));
            ++i;
        } else if ((c & 0xC0) != 0x80) {
            out += U'\uFFFD';
        }
    }
    return out;
}

constexpr std::uint8_t kInk[3] = {40, 40, 40};

int textWidth(const std::string& text, int px) {
    const std::size_t n = codePoints(text).size();
    return n == 0 ? 0 : static_cast<int>(n) * kGlyphAdvance * px - px;
}

void fillRect(io::RgbaImage& image, int x0, int y0, int x1, int y1, const std::uint8_t rgb[3]) {
    for (int y = std::max(y0, 0); y < std::min(y1, image.height); ++y) {
        for (int x = std::max(x0, 0); x < std::min(x1, image.width); ++x) {
            std::uint8_t* p = image.at(x, y);
            p[0] = rgb[0];
            p[1] = rgb[1];
            p[2] = rgb[2];
            p[3] = 255;
        }
    }
}

void drawText(io::RgbaImage& image, int x, int y, const std::string& text, int px) {
    for (char32_t c : codePoints(text)) {
        if (const auto* rows = glyphFor(c)) {
            for (int r = 0; r < kGlyphHeight; ++r) {
                for (int d = 0; d < kGlyphWidth; ++d) {
                    if (((*rows)[r] >> (kGlyphWidth - 1 - d)) & 1)
                        fillRect(image, x + d * px, y + r * px, x + (d + 1) * px, y + (r + 1) * px,
                                 kInk);
                }
            }
        }
        x += kGlyphAdvance * px;
    }
}

}  // namespace

MapImageLayout mapImageLayout(int cols, int rows) {
    MapImageLayout l;
    // Scaled up to the minimum width, but never past kMaxMapImageSide tall (a thin, long map).
    l.cell_px = cols >= kMinMapImageWidth ? 1 : (kMinMapImageWidth + cols - 1) / cols;
    l.cell_px = std::max(1, std::min(l.cell_px, kMaxMapImageSide / std::max(rows, 1)));
    l.map_width = cols * l.cell_px;
    l.map_height = rows * l.cell_px;
    l.width = std::max(l.map_width, kMinMapImageWidth);
    l.text_px = std::clamp(l.width / 300, 2, 6);
    const int px = l.text_px, margin = 4 * px, half_label = 9 * px;
    l.legend_top = l.map_height;
    l.title_top = l.legend_top + margin;
    l.bar_left = margin + half_label;
    l.bar_right = l.width - margin - half_label;
    l.bar_top = l.title_top + (kGlyphHeight + 3) * px;
    l.bar_bottom = l.bar_top + 6 * px;
    l.labels_top = l.bar_bottom + 3 * px;
    l.height = l.labels_top + kGlyphHeight * px + margin;
    return l;
}

std::vector<double> scaleTicks(const std::string& key, const LayerScale& scale) {
    const double span = scale.upper - scale.lower;
    if (!(span > 0.0) || !std::isfinite(span)) return {scale.lower};
    const double raw = span / 5.0;
    const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
    const double norm = raw / magnitude;
    const double step = (norm < 1.5 ? 1.0 : norm < 3.5 ? 2.0 : norm < 7.5 ? 5.0 : 10.0) * magnitude;
    std::vector<double> ticks;
    const double tolerance = 1e-9 * span;
    if (key == "compaction_risk") {
        for (double band : {0.5, 1.1}) {
            if (band >= scale.lower - tolerance && band <= scale.upper + tolerance)
                ticks.push_back(band);
        }
    }
    // Step ticks closer than a step to a band edge give way to it.
    const std::size_t bands = ticks.size();
    for (double k = std::ceil(scale.lower / step - 1e-9); k * step <= scale.upper + tolerance;
         k += 1.0) {
        const double v = std::abs(k * step) < tolerance ? 0.0 : k * step;
        const bool near_band = std::any_of(ticks.begin(), ticks.begin() + bands,
                                           [&](double b) { return std::abs(b - v) < step; });
        if (!near_band) ticks.push_back(v);
    }
    std::sort(ticks.begin(), ticks.end());
    return ticks;
}

std::string tickText(double value, double step) {
    char text[32];
    const int decimals =
        step > 0.0 ? std::max(0, static_cast<int>(-std::floor(std::log10(step) + 1e-9))) : 0;
    if (std::abs(value) >= 1e6 || (step > 0.0 && step < 1e-4)) {
        std::snprintf(text, sizeof text, "%.3g", value);
    } else {
        std::snprintf(text, sizeof text, "%.*f", decimals, value);
    }
    std::string s = text;
    if (s == "-0" || s.find_first_not_of("-0.") == std::string::npos) s = s.substr(s[0] == '-');
    return s;
}

io::RgbaImage renderMap(const MapLayer& layer, const LayerScale& scale, const field::Raster& map) {
    const field::Raster shown = map.cols > kMaxMapImageSide || map.rows > kMaxMapImageSide
                                    ? coarsen(map, kMaxMapImageSide, LayerKind::kContinuous)
                                    : map;
    const MapImageLayout l = mapImageLayout(shown.cols, shown.rows);
    io::RgbaImage image = io::RgbaImage::filled(l.width, l.height, 0, 0, 0, 0);
    const std::vector<ColorStop> stops = layerColors(layer, scale);
    const double span = scale.upper - scale.lower;
    const auto fraction = [&](double v) { return (v - scale.lower) / span; };
    // A map is mostly untouched soil (0) or no data: the colour of the last value is kept.
    double last = std::numeric_limits<double>::quiet_NaN();
    std::uint8_t rgb[3] = {0, 0, 0};
    for (int row = 0; row < shown.rows; ++row) {
        for (int col = 0; col < shown.cols; ++col) {
            const double v = shown.value(col, row);
            if (std::isnan(v)) continue;  // transparent
            if (v != last) {
                const Rgb c = colorAt(stops, fraction(v * scale.factor));
                rgb[0] = c.r;
                rgb[1] = c.g;
                rgb[2] = c.b;
                last = v;
            }
            if (l.cell_px == 1) {
                std::uint8_t* p = image.at(col, row);
                p[0] = rgb[0];
                p[1] = rgb[1];
                p[2] = rgb[2];
                p[3] = 255;
            } else {
                fillRect(image, col * l.cell_px, row * l.cell_px, (col + 1) * l.cell_px,
                         (row + 1) * l.cell_px, rgb);
            }
        }
    }
    // The legend: white band, title, colour bar with a frame, ticks and their values.
    const std::uint8_t white[3] = {255, 255, 255};
    fillRect(image, 0, l.legend_top, l.width, l.height, white);
    const int px = l.text_px;
    drawText(image, l.bar_left, l.title_top, scale.title, px);
    const int bar_width = l.bar_right - l.bar_left;
    for (int x = l.bar_left; x < l.bar_right; ++x) {
        const Rgb c = colorAt(stops, (x - l.bar_left + 0.5) / bar_width);
        const std::uint8_t rgb[3] = {c.r, c.g, c.b};
        fillRect(image, x, l.bar_top, x + 1, l.bar_bottom, rgb);
    }
    const std::vector<double> ticks = scaleTicks(layer.key, scale);
    double step = span;
    for (std::size_t i = 1; i < ticks.size(); ++i) step = std::min(step, ticks[i] - ticks[i - 1]);
    int last_right = -1;  // a label that would overlap the one before is left out
    for (double t : ticks) {
        const int x = l.bar_left + static_cast<int>(std::lround(fraction(t) * bar_width));
        const int tick_x = std::min(x, l.bar_right - std::max(1, px / 2));
        fillRect(image, tick_x, l.bar_bottom, tick_x + std::max(1, px / 2), l.labels_top - px,
                 kInk);
        const std::string text = tickText(t, step);
        const int w = textWidth(text, px);
        const int left = std::clamp(x - w / 2, 0, std::max(0, l.width - w));
        if (left <= last_right + 2 * px) continue;
        drawText(image, left, l.labels_top, text, px);
        last_right = left + w;
    }
    // The legend as text too (tEXt chunks), for a program that reads the picture: the scale,
    // its ticks and colours, and where the map's cells are on the ground and in the picture.
    nlohmann::json legend{{"layer", layer.key},   {"title", scale.title},
                          {"unit", scale.unit},   {"factor", scale.factor},
                          {"lower", scale.lower}, {"upper", scale.upper},
                          {"ticks", ticks},       {"clear_zero", scale.clear_zero}};
    nlohmann::json colours = nlohmann::json::array();
    for (const ColorStop& stop : stops) {
        char hex[8];
        std::snprintf(hex, sizeof hex, "#%02x%02x%02x", stop.color.r, stop.color.g, stop.color.b);
        colours.push_back({{"at", scale.lower + stop.at * span}, {"rgb", hex}});
    }
    legend["colours"] = std::move(colours);
    legend["cells"] = {{"x_min_m", shown.x_min_m}, {"y_min_m", shown.y_min_m},
                       {"cell_m", shown.cell_m},   {"cols", shown.cols},
                       {"rows", shown.rows},       {"cell_px", l.cell_px}};
    if (map.epsg) legend["epsg"] = *map.epsg;
    image.text = {
        {"Title", scale.title}, {"Software", "TerraStudio"}, {"terrastudio:legend", legend.dump()}};
    return image;
}

std::optional<std::string> writeMapPngs(const FieldMaps& maps,
                                        const std::filesystem::path& directory) {
    for (const auto& [key, raster] : mapRasters(maps)) {
        const MapLayer layer = runMapLayer(key, maps);
        const LayerScale scale = layerScale(layer, *raster);
        if (auto error = io::writePng(directory / (key + ".png"), renderMap(layer, scale, *raster)))
            return error;
    }
    return std::nullopt;
}

}  // namespace terra::scenario
