#include "core/io/geotiff.h"

#include <tiffio.h>

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <vector>

#include "core/common/range.h"
#include "core/io/atomic_file.h"

namespace terra::io {

namespace {

// The GeoTIFF tags (GeoTIFF 1.1, OGC 19-008r4, section 7) and GDAL's no-data tag: libtiff 4.5
// names them (tiff.h) but defines none, so without these definitions it reads them as anonymous
// tags and refuses to write them.
constexpr ttag_t kPixelScaleTag = 33550;
constexpr ttag_t kTiepointTag = 33922;
constexpr ttag_t kTransformationTag = 34264;
constexpr ttag_t kGeoKeyDirectoryTag = 34735;
constexpr ttag_t kGeoDoubleParamsTag = 34736;
constexpr ttag_t kGeoAsciiParamsTag = 34737;

// GeoKeys (GeoTIFF 1.1, section 7.5) and their values read here.
constexpr int kModelTypeKey = 1024;   // 1 projected, 2 geographic, 3 geocentric
constexpr int kRasterTypeKey = 1025;  // 1 PixelIsArea, 2 PixelIsPoint
constexpr int kGeographicTypeKey = 2048;
constexpr int kProjectedTypeKey = 3072;
constexpr int kLinearUnitsKey = 3076;
constexpr int kUserDefined = 32767;
constexpr int kMetre = 9001;  // EPSG's unit code

// Count −1 (TIFF_VARIABLE) with passcount: TIFFGetField hands a uint16_t count and a pointer.
char kPixelScaleName[] = "ModelPixelScaleTag";
char kTiepointName[] = "ModelTiepointTag";
char kTransformationName[] = "ModelTransformationTag";
char kGeoKeyDirectoryName[] = "GeoKeyDirectoryTag";
char kGeoDoubleParamsName[] = "GeoDoubleParamsTag";
char kGeoAsciiParamsName[] = "GeoAsciiParamsTag";
char kGdalNoDataName[] = "GDALNoDataValue";
const TIFFFieldInfo kGeoFields[] = {
    {kPixelScaleTag, -1, -1, TIFF_DOUBLE, FIELD_CUSTOM, 1, 1, kPixelScaleName},
    {kTiepointTag, -1, -1, TIFF_DOUBLE, FIELD_CUSTOM, 1, 1, kTiepointName},
    {kTransformationTag, -1, -1, TIFF_DOUBLE, FIELD_CUSTOM, 1, 1, kTransformationName},
    {kGeoKeyDirectoryTag, -1, -1, TIFF_SHORT, FIELD_CUSTOM, 1, 1, kGeoKeyDirectoryName},
    {kGeoDoubleParamsTag, -1, -1, TIFF_DOUBLE, FIELD_CUSTOM, 1, 1, kGeoDoubleParamsName},
    {kGeoAsciiParamsTag, -1, -1, TIFF_ASCII, FIELD_CUSTOM, 1, 0, kGeoAsciiParamsName},
    {TIFFTAG_GDAL_NODATA, -1, -1, TIFF_ASCII, FIELD_CUSTOM, 1, 0, kGdalNoDataName},
};

TIFFExtendProc parent_extender = nullptr;

// libtiff's tag extender: runs whenever a directory is set up, before its tags are read, so the
// GeoTIFF tags are known with their types (not read as anonymous tags).
void extendWithGeoTags(TIFF* tif) {
    TIFFMergeFieldInfo(tif, kGeoFields, sizeof(kGeoFields) / sizeof(kGeoFields[0]));
    if (parent_extender != nullptr) parent_extender(tif);
}

void registerGeoTags() {
    static std::once_flag once;
    std::call_once(once, [] { parent_extender = TIFFSetTagExtender(extendWithGeoTags); });
}

// A TIFF in memory: libtiff reads and writes through these procedures, so that the file is read
// whole with readFile's bound and written with writeFileAtomically.
struct TiffMemoryFile {
    std::string_view in;  // reading
    std::string out;      // writing
    bool writing = false;
    toff_t pos = 0;
    std::string errors;  // libtiff's error messages

    toff_t size() const { return writing ? out.size() : in.size(); }
};

TiffMemoryFile& fileOf(thandle_t handle) { return *static_cast<TiffMemoryFile*>(handle); }

tmsize_t readProc(thandle_t handle, void* buffer, tmsize_t n) {
    TiffMemoryFile& f = fileOf(handle);
    const std::string_view data = f.writing ? std::string_view(f.out) : f.in;
    if (n < 0 || f.pos >= data.size()) return 0;
    const std::size_t count =
        std::min<std::size_t>(static_cast<std::size_t>(n), data.size() - f.pos);
    std::memcpy(buffer, data.data() + f.pos, count);
    f.pos += count;
    return static_cast<tmsize_t>(count);
}

tmsize_t writeProc(thandle_t handle, void* buffer, tmsize_t n) {
    TiffMemoryFile& f = fileOf(handle);
    if (!f.writing || n < 0) return -1;
    const std::size_t count = static_cast<std::size_t>(n);
    if (f.pos + count > f.out.size()) f.out.resize(f.pos + count);
    std::memcpy(f.out.data() + f.pos, buffer, count);
    f.pos += count;
    return n;
}

toff_t seekProc(thandle_t handle, toff_t offset, int whence) {
    TiffMemoryFile& f = fileOf(handle);
    // offset is unsigned; SEEK_CUR and SEEK_END with a negative offset wrap modulo 2^64 as
    // intended.
    if (whence == SEEK_SET) {
        f.pos = offset;
    } else if (whence == SEEK_CUR) {
        f.pos += offset;
    } else if (whence == SEEK_END) {
        f.pos = f.size() + offset;
    }
    return f.pos;
}

int closeProc(thandle_t) { return 0; }
toff_t sizeProc(thandle_t handle) { return fileOf(handle).size(); }
int mapProc(thandle_t, void**, toff_t*) { return 0; }  // no mapping: reads go through readProc
void unmapProc(thandle_t, void*, toff_t) {}

int collectError(TIFF*, void* user_data, const char* module, const char* format, va_list args) {
    char text[512];
    std::vsnprintf(text, sizeof text, format, args);
    std::string& errors = static_cast<TiffMemoryFile*>(user_data)->errors;
    if (errors.size() > 300) return 1;  // a broken file's first complaints say enough
    if (!errors.empty()) errors += "; ";
    errors += (module != nullptr && *module != '\0') ? std::string(module) + ": " + text : text;
    return 1;  // handled: nothing printed to stderr
}

int ignoreWarning(TIFF*, void*, const char*, const char*, va_list) { return 1; }

struct TiffCloser {
    void operator()(TIFF* tif) const { TIFFClose(tif); }
};
using TiffHandle = std::unique_ptr<TIFF, TiffCloser>;

TiffHandle openMemory(TiffMemoryFile& file, const char* mode) {
    registerGeoTags();
    TIFFOpenOptions* options = TIFFOpenOptionsAlloc();
    TIFFOpenOptionsSetErrorHandlerExtR(options, collectError, &file);
    TIFFOpenOptionsSetWarningHandlerExtR(options, ignoreWarning, nullptr);
    TIFF* tif = TIFFClientOpenExt("libtiff", mode, &file, readProc, writeProc, seekProc, closeProc,
                                  sizeProc, mapProc, unmapProc, options);
    TIFFOpenOptionsFree(options);
    return TiffHandle(tif);
}

// A tag's values with their count, whichever way libtiff passes them: the count's type follows
// the field's read count (TIFF_VARIABLE2: uint32_t, else uint16_t), and a field without
// passcount hands the pointer alone (a tag defined elsewhere first, by another tag extender or a
// later libtiff, may differ from kGeoFields). Nothing when the file lacks the tag.
template <typename T>
std::optional<std::vector<T>> tagValues(TIFF* tif, ttag_t tag) {
    const TIFFField* field = TIFFFindField(tif, tag, TIFF_ANY);
    if (field == nullptr) return std::nullopt;
    T* data = nullptr;
    std::uint32_t count = 0;
    int found = 0;
    if (!TIFFFieldPassCount(field)) {
        found = TIFFGetField(tif, tag, &data);
        count = 1;
    } else if (TIFFFieldReadCount(field) == TIFF_VARIABLE2) {
        found = TIFFGetField(tif, tag, &count, &data);
    } else {
        std::uint16_t count16 = 0;
        found = TIFFGetField(tif, tag, &count16, &data);
        count = count16;
    }
    if (found != 1 || data == nullptr) return std::nullopt;
    return std::vector<T>(data, data + count);
}

// A tag of `count` values, or an empty vector when the file lacks it.
template <typename T>
std::vector<T> arrayTag(TIFF* tif, ttag_t tag) {
    return tagValues<T>(tif, tag).value_or(std::vector<T>{});
}

// An ASCII tag's text, or nothing.
std::optional<std::string> asciiTag(TIFF* tif, ttag_t tag) {
    const TIFFField* field = TIFFFindField(tif, tag, TIFF_ANY);
    if (field == nullptr) return std::nullopt;
    if (!TIFFFieldPassCount(field)) {
        char* text = nullptr;
        if (TIFFGetField(tif, tag, &text) != 1 || text == nullptr) return std::nullopt;
        return std::string(text);
    }
    const std::optional<std::vector<char>> chars = tagValues<char>(tif, tag);
    if (!chars) return std::nullopt;
    return std::string(chars->data(), strnlen(chars->data(), chars->size()));
}

// Sets an ASCII tag, with its count (the terminating NUL included) when libtiff asks for one.
void setAsciiTag(TIFF* tif, ttag_t tag, const char* text) {
    const TIFFField* field = TIFFFindField(tif, tag, TIFF_ANY);
    if (field != nullptr && TIFFFieldPassCount(field)) {
        TIFFSetField(tif, tag, static_cast<std::uint32_t>(std::strlen(text) + 1), text);
    } else {
        TIFFSetField(tif, tag, text);
    }
}

// The sample formats read, as (SampleFormat, bits).
struct TiffSampleType {
    int format = SAMPLEFORMAT_UINT;
    int bits = 8;
};

bool isReadSampleType(TiffSampleType t) {
    if (t.format == SAMPLEFORMAT_IEEEFP) return t.bits == 32 || t.bits == 64;
    if (t.format == SAMPLEFORMAT_UINT || t.format == SAMPLEFORMAT_INT)
        return t.bits == 8 || t.bits == 16 || t.bits == 32;
    return false;
}

std::string sampleTypeName(TiffSampleType t) {
    const char* kind = t.format == SAMPLEFORMAT_UINT     ? "UInt"
                       : t.format == SAMPLEFORMAT_INT    ? "Int"
                       : t.format == SAMPLEFORMAT_IEEEFP ? "Float"
                                                         : nullptr;
    if (kind == nullptr)
        return "sample format " + std::to_string(t.format) + " with " + std::to_string(t.bits) +
               " bits";
    return kind + std::to_string(t.bits);
}

// One sample at `p` as a double.
double sampleAt(const unsigned char* p, TiffSampleType t) {
    const auto load = [p](auto v) {
        std::memcpy(&v, p, sizeof v);
        return static_cast<double>(v);
    };
    if (t.format == SAMPLEFORMAT_IEEEFP) return t.bits == 32 ? load(float{}) : load(double{});
    if (t.format == SAMPLEFORMAT_INT) {
        if (t.bits == 8) return load(std::int8_t{});
        return t.bits == 16 ? load(std::int16_t{}) : load(std::int32_t{});
    }
    if (t.bits == 8) return load(std::uint8_t{});
    return t.bits == 16 ? load(std::uint16_t{}) : load(std::uint32_t{});
}

// The GeoKeys with their value in the directory itself (location 0), by key id.
struct TiffGeoKeys {
    std::optional<int> model_type, raster_type, geographic, projected, linear_units;
};

std::optional<std::string> readGeoKeys(const std::vector<std::uint16_t>& dir, TiffGeoKeys& keys) {
    if (dir.empty()) return std::nullopt;
    if (dir.size() < 4 || dir.size() < 4 + 4 * static_cast<std::size_t>(dir[3]))
        return "the GeoKeyDirectoryTag holds " + std::to_string(dir.size()) +
               " values, fewer than its header's key count says";
    for (std::size_t k = 0; k < dir[3]; ++k) {
        const std::uint16_t* e = &dir[4 + 4 * k];
        if (e[1] != 0) continue;  // a value in GeoDoubleParams or GeoAsciiParams: none read here
        const int value = e[3];
        switch (e[0]) {
            case kModelTypeKey:
                keys.model_type = value;
                break;
            case kRasterTypeKey:
                keys.raster_type = value;
                break;
            case kGeographicTypeKey:
                keys.geographic = value;
                break;
            case kProjectedTypeKey:
                keys.projected = value;
                break;
            case kLinearUnitsKey:
                keys.linear_units = value;
                break;
            default:
                break;
        }
    }
    return std::nullopt;
}

// The coordinate system's problem for a field laid out in metres, or nothing; `epsg` set.
std::optional<std::string> checkCrs(const TiffGeoKeys& keys, std::optional<int>& epsg) {
    const auto code = [](int c) { return "EPSG:" + std::to_string(c); };
    const bool geographic =
        keys.model_type ? *keys.model_type == 2 : keys.geographic.has_value() && !keys.projected;
    if (geographic) {
        const std::string which = keys.geographic && *keys.geographic != kUserDefined
                                      ? " (" + code(*keys.geographic) + ")"
                                      : "";
        return "its coordinates are geographic (degrees of latitude and longitude" + which +
               "); a field needs metres: reproject it to a projected system, e.g. its UTM zone "
               "(gdalwarp -t_srs EPSG:326NN)";
    }
    if (keys.model_type && *keys.model_type == 3)
        return "its coordinates are geocentric (GTModelTypeGeoKey 3); a field needs a projected "
               "system in metres";
    if (keys.linear_units && *keys.linear_units != kMetre)
        return "its linear unit is EPSG unit " + std::to_string(*keys.linear_units) +
               ", not the metre (9001); a field is laid out in metres";
    if (keys.projected && *keys.projected > 0 && *keys.projected != kUserDefined)
        epsg = *keys.projected;
    return std::nullopt;
}

struct TiffGeoreference {
    double x_min = 0.0, y_min = 0.0, cell = 1.0;
};

std::optional<std::string> readGeoreference(TIFF* tif, int rows, bool pixel_is_point,
                                            TiffGeoreference& g) {
    const std::vector<double> scale = arrayTag<double>(tif, kPixelScaleTag);
    const std::vector<double> tie = arrayTag<double>(tif, kTiepointTag);
    const std::vector<double> matrix = arrayTag<double>(tif, kTransformationTag);
    double sx = 0.0, sy = 0.0, x0 = 0.0, y0 = 0.0;  // (x0, y0): raster (0, rows) → south-west
    if (matrix.size() == 16) {
        if (matrix[1] != 0.0 || matrix[4] != 0.0)
            return "its ModelTransformationTag rotates or shears the grid (terms " +
                   formatNumber(matrix[1]) + ", " + formatNumber(matrix[4]) +
                   "); only north-up rasters are read (gdalwarp resamples one)";
        sx = matrix[0];
        sy = -matrix[5];
        x0 = matrix[3];
        y0 = matrix[7] - rows * sy;
    } else if (!matrix.empty()) {
        return "its ModelTransformationTag holds " + std::to_string(matrix.size()) +
               " values, not 16";
    } else if (scale.size() >= 2 && tie.size() == 6) {
        sx = scale[0];
        sy = scale[1];
        // x = X + (i − I) sx, y = Y − (j − J) sy: the south-west corner is raster (0, rows).
        x0 = tie[3] - tie[0] * sx;
        y0 = tie[4] - (rows - tie[1]) * sy;
    } else if (tie.size() > 6 && tie.size() % 6 == 0) {
        return "it has " + std::to_string(tie.size() / 6) +
               " tie points: a raster warped through tie points is not read (one tie point with a "
               "pixel scale is)";
    } else {
        return "it has no georeferencing (ModelPixelScaleTag with one ModelTiepointTag, or a "
               "ModelTransformationTag)";
    }
    if (!(std::isfinite(sx) && std::isfinite(sy) && std::isfinite(x0) && std::isfinite(y0)))
        return "its georeferencing is not finite";
    if (!(sx > 0.0) || !(sy > 0.0))
        return "its pixel scale (" + formatNumber(sx) + ", " + formatNumber(sy) +
               ") is not positive: a flipped grid is not read (north up, east right)";
    if (std::abs(sx - sy) > 1e-9 * std::max(sx, sy))
        return "its cells are not square (" + formatNumber(sx) + " × " + formatNumber(sy) +
               " m); a field's rasters have square cells (gdalwarp -tr H H resamples one)";
    g.cell = sx;
    g.x_min = x0;
    g.y_min = y0;
    if (pixel_is_point) {  // the tie point is a cell's centre: its corner is west and north
        g.x_min -= 0.5 * sx;
        g.y_min += 0.5 * sy;
    }
    return std::nullopt;
}

// The pixels as doubles, row-major from the top (north) row.
std::optional<std::string> readPixels(TIFF* tif, int cols, int rows, TiffSampleType type,
                                      std::vector<double>& out) {
    const std::size_t bytes = static_cast<std::size_t>(type.bits / 8);
    out.assign(static_cast<std::size_t>(cols) * rows, 0.0);
    if (TIFFIsTiled(tif)) {
        std::uint32_t tw = 0, th = 0;
        TIFFGetField(tif, TIFFTAG_TILEWIDTH, &tw);
        TIFFGetField(tif, TIFFTAG_TILELENGTH, &th);
        if (tw == 0 || th == 0) return std::string("its tiles have no size");
        std::vector<unsigned char> tile(static_cast<std::size_t>(TIFFTileSize(tif)));
        if (tile.size() < static_cast<std::size_t>(tw) * th * bytes)
            return std::string("its tiles are smaller than their width × length");
        for (std::uint32_t y = 0; y < static_cast<std::uint32_t>(rows); y += th) {
            for (std::uint32_t x = 0; x < static_cast<std::uint32_t>(cols); x += tw) {
                if (TIFFReadTile(tif, tile.data(), x, y, 0, 0) < 0)
                    return "cannot read the tile at column " + std::to_string(x) + ", row " +
                           std::to_string(y);
                const std::uint32_t h = std::min<std::uint32_t>(th, rows - y);
                const std::uint32_t w = std::min<std::uint32_t>(tw, cols - x);
                for (std::uint32_t r = 0; r < h; ++r) {
                    for (std::uint32_t c = 0; c < w; ++c)
                        out[static_cast<std::size_t>(y + r) * cols + x + c] =
                            sampleAt(&tile[(static_cast<std::size_t>(r) * tw + c) * bytes], type);
                }
            }
        }
        return std::nullopt;
    }
    std::vector<unsigned char> line(static_cast<std::size_t>(TIFFScanlineSize(tif)));
    if (line.size() < static_cast<std::size_t>(cols) * bytes)
        return std::string("its rows are shorter than its width");
    for (int row = 0; row < rows; ++row) {
        if (TIFFReadScanline(tif, line.data(), static_cast<std::uint32_t>(row), 0) < 0)
            return "cannot read row " + std::to_string(row);
        for (int col = 0; col < cols; ++col)
            out[static_cast<std::size_t>(row) * cols + col] =
                sampleAt(&line[static_cast<std::size_t>(col) * bytes], type);
    }
    return std::nullopt;
}

}  // namespace

Result<field::Raster> parseGeoTiff(std::string_view bytes, const std::string& where) {
    const auto fail = [&where](const std::string& message) {
        return std::vector<Issue>{{where, message}};
    };
    TiffMemoryFile file;
    file.in = bytes;
    TiffHandle tif = openMemory(file, "rm");
    if (!tif) return fail("is not a TIFF file libtiff reads (" + file.errors + ")");
    std::uint32_t width = 0, height = 0;
    std::uint16_t spp = 1, bits = 1, format = SAMPLEFORMAT_UINT, orientation = ORIENTATION_TOPLEFT;
    TIFFGetField(tif.get(), TIFFTAG_IMAGEWIDTH, &width);
    TIFFGetField(tif.get(), TIFFTAG_IMAGELENGTH, &height);
    TIFFGetFieldDefaulted(tif.get(), TIFFTAG_SAMPLESPERPIXEL, &spp);
    TIFFGetFieldDefaulted(tif.get(), TIFFTAG_BITSPERSAMPLE, &bits);
    TIFFGetFieldDefaulted(tif.get(), TIFFTAG_SAMPLEFORMAT, &format);
    TIFFGetFieldDefaulted(tif.get(), TIFFTAG_ORIENTATION, &orientation);
    if (spp != 1)
        return fail("has " + std::to_string(spp) +
                    " bands (samples per pixel); a raster file holds one (gdal_translate -b N "
                    "extracts band N)");
    const TiffSampleType type{format, bits};
    if (!isReadSampleType(type))
        return fail("holds " + sampleTypeName(type) +
                    " samples; read are UInt8, Int8, UInt16, Int16, UInt32, Int32, Float32 and "
                    "Float64");
    if (orientation != ORIENTATION_TOPLEFT)
        return fail("has orientation " + std::to_string(orientation) +
                    "; only the first row at the top (orientation 1) is read");
    if (width < 1 || height < 1 || width > 100000 || height > 100000)
        return fail("is " + std::to_string(width) + " × " + std::to_string(height) +
                    " pixels; each side must be in [1, 100000]");
    std::uint64_t max_cells = 0;
    if (auto error = maxInputBytes(max_cells)) return fail(*error);
    // A compressed file can claim far more cells than its bytes: bounded as an uncompressed
    // one-byte raster within the input limit would be.
    if (static_cast<std::uint64_t>(width) * height > max_cells)
        return fail("has " + std::to_string(static_cast<std::uint64_t>(width) * height) +
                    " cells, more than the input limit of " + std::to_string(max_cells) +
                    " (docs/cli.md, \"Input files\")");
    TiffGeoKeys keys;
    if (auto error = readGeoKeys(arrayTag<std::uint16_t>(tif.get(), kGeoKeyDirectoryTag), keys))
        return fail(*error);
    field::Raster r;
    if (auto error = checkCrs(keys, r.epsg)) return fail(*error);
    r.cols = static_cast<int>(width);
    r.rows = static_cast<int>(height);
    TiffGeoreference g;
    const bool pixel_is_point = keys.raster_type && *keys.raster_type == 2;
    if (auto error = readGeoreference(tif.get(), r.rows, pixel_is_point, g)) return fail(*error);
    r.x_min_m = g.x_min;
    r.y_min_m = g.y_min;
    r.cell_m = g.cell;
    std::vector<Issue> layout =
        field::validate(field::makeRaster(r.cols, r.rows, r.x_min_m, r.y_min_m, r.cell_m), where);
    if (!layout.empty()) return layout;
    if (auto error = readPixels(tif.get(), r.cols, r.rows, type, r.values))
        return fail(*error + (file.errors.empty() ? "" : " (" + file.errors + ")"));

    std::optional<double> nodata;
    if (const std::optional<std::string> text = asciiTag(tif.get(), TIFFTAG_GDAL_NODATA)) {
        char* end = nullptr;
        const double v = std::strtod(text->c_str(), &end);
        if (end == text->c_str()) return fail("its GDAL_NODATA \"" + *text + "\" is not a number");
        nodata = v;
    }
    std::vector<Issue> issues;
    constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
    // A Float32 file's no-data value is written in decimal: compared in single precision.
    const bool single = type.format == SAMPLEFORMAT_IEEEFP && type.bits == 32;
    for (std::size_t k = 0; k < r.values.size(); ++k) {
        double& v = r.values[k];
        if (nodata &&
            (single ? static_cast<float>(v) == static_cast<float>(*nodata) : v == *nodata)) {
            v = kNaN;
        } else if (std::isinf(v) && issues.size() < kMaxIssuesShown) {
            issues.push_back({where, "cell (col " + std::to_string(k % r.cols) + ", row " +
                                         std::to_string(k / r.cols) + ") is " + formatNumber(v) +
                                         ", not a finite number"});
        }
    }
    if (!issues.empty()) return issues;
    return r;
}

Result<std::string> toGeoTiff(const field::Raster& raster) {
    const auto fail = [](const std::string& message) {
        return std::vector<Issue>{{"GeoTIFF", message}};
    };
    std::vector<Issue> layout = field::validate(raster, "GeoTIFF");
    if (!layout.empty()) return layout;
    TiffMemoryFile file;
    file.writing = true;
    TiffHandle tif = openMemory(file, "w");
    if (!tif) return fail("libtiff cannot open a file for writing (" + file.errors + ")");
    TIFF* t = tif.get();
    TIFFSetField(t, TIFFTAG_IMAGEWIDTH, static_cast<std::uint32_t>(raster.cols));
    TIFFSetField(t, TIFFTAG_IMAGELENGTH, static_cast<std::uint32_t>(raster.rows));
    TIFFSetField(t, TIFFTAG_SAMPLESPERPIXEL, 1);
    TIFFSetField(t, TIFFTAG_BITSPERSAMPLE, 64);
    TIFFSetField(t, TIFFTAG_SAMPLEFORMAT, SAMPLEFORMAT_IEEEFP);
    TIFFSetField(t, TIFFTAG_PHOTOMETRIC, PHOTOMETRIC_MINISBLACK);
    TIFFSetField(t, TIFFTAG_PLANARCONFIG, PLANARCONFIG_CONTIG);
    if (TIFFIsCODECConfigured(COMPRESSION_ADOBE_DEFLATE)) {
        TIFFSetField(t, TIFFTAG_COMPRESSION, COMPRESSION_ADOBE_DEFLATE);
        TIFFSetField(t, TIFFTAG_PREDICTOR, PREDICTOR_FLOATINGPOINT);
    }
    TIFFSetField(t, TIFFTAG_ROWSPERSTRIP, TIFFDefaultStripSize(t, 0));
    TIFFSetField(t, TIFFTAG_SOFTWARE, "TerraStudio");
    const double scale[3] = {raster.cell_m, raster.cell_m, 0.0};
    const double tie[6] = {
        0.0, static_cast<double>(raster.rows), 0.0, raster.x_min_m, raster.y_min_m, 0.0};
    TIFFSetField(t, kPixelScaleTag, 3, scale);
    TIFFSetField(t, kTiepointTag, 6, tie);
    const std::uint16_t projected =
        static_cast<std::uint16_t>(raster.epsg ? *raster.epsg : kUserDefined);
    const std::uint16_t keys[] = {1,
                                  1,
                                  0,
                                  4,  // header, 4 keys
                                  kModelTypeKey,
                                  0,
                                  1,
                                  1,  // projected
                                  kRasterTypeKey,
                                  0,
                                  1,
                                  1,  // PixelIsArea
                                  kProjectedTypeKey,
                                  0,
                                  1,
                                  projected,  // EPSG or user
                                  kLinearUnitsKey,
                                  0,
                                  1,
                                  kMetre};  // metre
    TIFFSetField(t, kGeoKeyDirectoryTag, static_cast<int>(std::size(keys)), keys);
    setAsciiTag(t, TIFFTAG_GDAL_NODATA, "nan");
    std::vector<double> row(static_cast<std::size_t>(raster.cols));
    for (int r = 0; r < raster.rows; ++r) {
        std::copy_n(raster.values.begin() + static_cast<std::ptrdiff_t>(r) * raster.cols,
                    raster.cols, row.begin());
        if (TIFFWriteScanline(t, row.data(), static_cast<std::uint32_t>(r), 0) != 1)
            return fail("libtiff cannot write row " + std::to_string(r) + " (" + file.errors + ")");
    }
    if (TIFFWriteDirectory(t) != 1) return fail("libtiff cannot write the directory");
    tif.reset();
    if (!file.errors.empty()) return fail(file.errors);
    return std::move(file.out);
}

}  // namespace terra::io
