#include "core/field/field_summary.h"

#include <algorithm>
#include <cmath>

#include "core/common/units.h"

namespace terra::field {

std::optional<std::array<double, 4>> extent(const FieldMap& field) {
    std::optional<std::array<double, 4>> box;
    const auto extend = [&](const Raster& r) {
        if (!box) {
            box = {r.x_min_m, r.y_min_m, r.xMax(), r.yMax()};
            return;
        }
        auto& b = *box;
        b = {std::min(b[0], r.x_min_m), std::min(b[1], r.y_min_m), std::max(b[2], r.xMax()),
             std::max(b[3], r.yMax())};
    };
    if (field.height) extend(*field.height);
    if (field.soil_class) extend(*field.soil_class);
    for (const ParameterRaster& p : field.parameters) extend(p.raster);
    return box;
}

FieldSummary summarize(const FieldMap& field, const std::map<int, std::string>& labels) {
    FieldSummary s;
    s.name = field.name;
    if (const std::optional<std::array<double, 4>> box = extent(field)) {
        s.x_min_m = (*box)[0];
        s.y_min_m = (*box)[1];
        s.x_max_m = (*box)[2];
        s.y_max_m = (*box)[3];
    }
    if (field.height) {
        s.height_cell_m = field.height->cell_m;
        const auto [lo, hi] = field.height->valueRange();
        s.height_min_m = lo;
        s.height_max_m = hi;
        const std::optional<Raster> slope = slopeRaster(field);
        double sum = 0.0;
        for (double v : slope->values) {
            s.max_slope_rad = std::max(s.max_slope_rad, units::degToRad(v));
            sum += units::degToRad(v);
        }
        s.mean_slope_rad = sum / static_cast<double>(slope->values.size());
    }
    if (field.soil_class) {
        const Raster& c = *field.soil_class;
        s.class_cell_m = c.cell_m;
        std::map<int, std::size_t> counts;
        std::size_t total = 0;
        for (double v : c.values) {
            if (std::isnan(v)) continue;
            ++counts[static_cast<int>(std::lround(v))];
            ++total;
        }
        for (const auto& [code, soil] : field.legend) {
            ClassArea a;
            a.code = code;
            const auto label = labels.find(code);
            a.label = label != labels.end() ? label->second : soil.name;
            a.soil = soil.name;
            a.profile = soil.profile ? soil.profile->name : std::string();
            const std::size_t n = counts.count(code) != 0 ? counts[code] : 0;
            a.area_m2 = static_cast<double>(n) * c.cell_m * c.cell_m;
            a.share = total > 0 ? static_cast<double>(n) / static_cast<double>(total) : 0.0;
            s.classes.push_back(a);
        }
    }
    for (const ParameterRaster& p : field.parameters) s.parameters.emplace_back(p.field->key);
    return s;
}

std::optional<Raster> slopeRaster(const FieldMap& field) {
    if (!field.height) return std::nullopt;
    const Raster& h = *field.height;
    Raster r = makeRaster(h.cols, h.rows, h.x_min_m, h.y_min_m, h.cell_m);
    for (int row = 0; row < h.rows; ++row) {
        for (int col = 0; col < h.cols; ++col) {
            // At a centre the bilinear gradient's x part is the eastern cell's difference; the
            // centred difference of the neighbours is the symmetric (second-order) slope.
            const int w = std::max(col - 1, 0), e = std::min(col + 1, h.cols - 1);
            const int n = std::max(row - 1, 0), so = std::min(row + 1, h.rows - 1);
            const double gx =
                e > w ? (h.value(e, row) - h.value(w, row)) / ((e - w) * h.cell_m) : 0.0;
            const double gy =
                so > n ? (h.value(col, n) - h.value(col, so)) / ((so - n) * h.cell_m) : 0.0;
            r.value(col, row) = units::radToDeg(std::atan(std::hypot(gx, gy)));
        }
    }
    return r;
}

}  // namespace terra::field
