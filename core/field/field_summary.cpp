#include "core/field/field_summary.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace terra::field {

FieldSummary summarize(const FieldMap& field, const std::map<int, std::string>& labels) {
    FieldSummary s;
    s.name = field.name;
    bool any = false;
    const auto extend = [&](const Raster& r) {
        s.x_min_m = any ? std::min(s.x_min_m, r.x_min_m) : r.x_min_m;
        s.y_min_m = any ? std::min(s.y_min_m, r.y_min_m) : r.y_min_m;
        s.x_max_m = any ? std::max(s.x_max_m, r.xMax()) : r.xMax();
        s.y_max_m = any ? std::max(s.y_max_m, r.yMax()) : r.yMax();
        any = true;
    };
    if (field.height) {
        extend(*field.height);
        s.height_cell_m = field.height->cell_m;
        const auto [lo, hi] = field.height->valueRange();
        s.height_min_m = lo;
        s.height_max_m = hi;
        const std::optional<Raster> slope = slopeRaster(field);
        double sum = 0.0;
        for (double v : slope->values) {
            s.max_slope_rad = std::max(s.max_slope_rad, v * std::numbers::pi / 180.0);
            sum += v * std::numbers::pi / 180.0;
        }
        s.mean_slope_rad = sum / static_cast<double>(slope->values.size());
    }
    if (field.soil_class) {
        const Raster& c = *field.soil_class;
        extend(c);
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
    for (const ParameterRaster& p : field.parameters) {
        s.parameters.emplace_back(p.field->key);
        extend(p.raster);
    }
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
            r.value(col, row) = std::atan(std::hypot(gx, gy)) * 180.0 / std::numbers::pi;
        }
    }
    return r;
}

}  // namespace terra::field
