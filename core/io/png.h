#pragma once
/// @file png.h
/// Pictures as PNG files through libpng (docs/field.md, "Maps as files"): 8-bit RGBA, written
/// into memory and then to disk atomically.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/common/issue.h"

namespace terra::io {

/// An 8-bit RGBA picture, rows from the top, 4 bytes a pixel (alpha 0: transparent).
struct RgbaImage {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> pixels;  ///< height × width × 4
    /// Text chunks: keyword (1–79 printable Latin-1 characters, no leading, trailing or double
    /// space) and UTF-8 text without NUL, written as tEXt when ASCII, else iTXt; e.g. {"Title",
    /// "rut depth [mm]"}.
    std::vector<std::pair<std::string, std::string>> text;

    /// A picture of `width` × `height` pixels, every one (r, g, b, a).
    static RgbaImage filled(int width, int height, std::uint8_t r, std::uint8_t g, std::uint8_t b,
                            std::uint8_t a);
    std::uint8_t* at(int x, int y) {
        return &pixels[(static_cast<std::size_t>(y) * width + x) * 4];
    }
    const std::uint8_t* at(int x, int y) const {
        return &pixels[(static_cast<std::size_t>(y) * width + x) * 4];
    }
};

/// The picture as PNG bytes (8-bit RGBA, libpng's fast compression; its text as tEXt/iTXt
/// chunks before IEND), or the error (a keyword or text PNG does not allow, named).
Result<std::string> toPng(const RgbaImage& image);

/// Writes the picture as a PNG file atomically; the error message, or nothing on success.
std::optional<std::string> writePng(const std::filesystem::path& path, const RgbaImage& image);

}  // namespace terra::io
