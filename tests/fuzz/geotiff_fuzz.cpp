// Fuzz harness: a GeoTIFF raster (io::parseGeoTiff, the reader of every .tif/.tiff a field or a
// scenario names, through libtiff). A raster read must have a valid layout and must come back
// the same through the writer (Float64: every value bit for bit).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string_view>

#include "core/io/geotiff.h"
#include "tests/fuzz/fuzz_support.h"

TERRA_FUZZ_HARNESS(geotiff) {
    using namespace terra;
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    const Result<field::Raster> raster = io::parseGeoTiff(bytes, "fuzz.tif");
    fuzz::checkResult(raster);
    if (!raster) return 0;
    if (!field::validate(*raster, "fuzz.tif").empty())
        fuzz::fail("a raster read with a bad layout");
    const Result<std::string> written = io::toGeoTiff(*raster);
    if (!written) fuzz::fail("a raster read cannot be written: " + written.message());
    const Result<field::Raster> back = io::parseGeoTiff(*written, "back.tif");
    if (!back) fuzz::fail("the writer's file is refused: " + back.message());
    const auto& a = raster->values;
    const auto& b = back->values;
    if (a.size() != b.size() || back->x_min_m != raster->x_min_m ||
        back->y_min_m != raster->y_min_m || back->cell_m != raster->cell_m ||
        back->epsg != raster->epsg)
        fuzz::fail("the writer's file reads back another raster");
    for (std::size_t k = 0; k < a.size(); ++k) {
        if (std::isnan(a[k]) != std::isnan(b[k]) ||
            (!std::isnan(a[k]) && std::memcmp(&a[k], &b[k], sizeof(double)) != 0))
            fuzz::fail("cell " + std::to_string(k) + " changed through the writer");
    }
    return 0;
}
