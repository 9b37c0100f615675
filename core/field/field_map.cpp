#include "core/field/field_map.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/common/range.h"

namespace terra::field {

namespace {

// (x, y) moved onto the raster (a hair inside its east and north edges).
Eigen::Vector2d clampTo(const Raster& r, double x_m, double y_m) {
    return {std::clamp(x_m, r.x_min_m, r.xMax()), std::clamp(y_m, r.y_min_m, r.yMax())};
}

bool inside(const Raster& r, double x_m, double y_m) {
    return x_m >= r.x_min_m && x_m <= r.xMax() && y_m >= r.y_min_m && y_m <= r.yMax();
}

std::string cellName(int col, int row) {
    return "cell (col " + std::to_string(col) + ", row " + std::to_string(row) + ")";
}

}  // namespace

double FieldMap::heightAt(double x_m, double y_m) const {
    if (!height) return 0.0;
    const Eigen::Vector2d p = clampTo(*height, x_m, y_m);
    return height->bilinear(p.x(), p.y());
}

Eigen::Vector2d FieldMap::gradientAt(double x_m, double y_m) const {
    if (!height || !inside(*height, x_m, y_m)) return Eigen::Vector2d::Zero();
    return height->gradient(x_m, y_m);
}

Eigen::Vector3d FieldMap::normalAt(double x_m, double y_m) const {
    const Eigen::Vector2d g = gradientAt(x_m, y_m);
    return Eigen::Vector3d(-g.x(), -g.y(), 1.0).normalized();
}

double FieldMap::slopeAt(double x_m, double y_m) const {
    return std::atan(gradientAt(x_m, y_m).norm());
}

LocalSlope FieldMap::slopeUnder(double x_m, double y_m, double heading_rad) const {
    const Eigen::Vector2d g = gradientAt(x_m, y_m);
    const Eigen::Vector2d d(std::cos(heading_rad), std::sin(heading_rad));
    const Eigen::Vector2d left(-d.y(), d.x());
    return {std::atan(g.dot(d)), std::atan(g.dot(left))};
}

std::optional<int> classCode(double value) {
    if (std::isnan(value)) return std::nullopt;
    return static_cast<int>(std::lround(value));
}

std::optional<int> FieldMap::classAt(double x_m, double y_m) const {
    if (!soil_class) return std::nullopt;
    return classCode(soil_class->nearest(x_m, y_m));
}

soil::SoilParameters FieldMap::soilAt(double x_m, double y_m) const {
    soil::SoilParameters soil = base;
    if (const std::optional<int> code = classAt(x_m, y_m)) {
        const auto it = legend.find(*code);
        if (it != legend.end()) soil = it->second;
    }
    for (const ParameterRaster& p : parameters) {
        const double v = p.raster.nearest(x_m, y_m);
        if (!std::isnan(v)) soil::setUserValue(soil, *p.field, v);
    }
    return soil;
}

std::vector<Issue> validate(const FieldMap& field) {
    std::vector<Issue> issues;
    constexpr double kMaxSlopeRad = 60.0 * std::numbers::pi / 180.0;
    if (field.height) {
        std::vector<Issue> layout = validate(*field.height, "height");
        if (!layout.empty()) {
            issues.insert(issues.end(), layout.begin(), layout.end());
        } else {
            const Raster& h = *field.height;
            std::size_t missing = 0;
            std::optional<Issue> first_missing, steep;
            const double max_step = std::tan(kMaxSlopeRad) * h.cell_m;
            for (int row = 0; row < h.rows; ++row) {
                for (int col = 0; col < h.cols; ++col) {
                    const double z = h.value(col, row);
                    if (!std::isfinite(z)) {
                        if (missing++ == 0)
                            first_missing = Issue{"height", cellName(col, row) + " has no height"};
                        continue;
                    }
                    const double east = col + 1 < h.cols ? h.value(col + 1, row) : z;
                    const double south = row + 1 < h.rows ? h.value(col, row + 1) : z;
                    const double step = std::max(std::abs(east - z), std::abs(south - z));
                    if (!steep && std::isfinite(step) && step > max_step)
                        steep =
                            Issue{"height", cellName(col, row) + ": a step of " +
                                                formatNumber(step) + " m over " +
                                                formatNumber(h.cell_m) + " m is steeper than 60°"};
                }
            }
            if (first_missing) {
                first_missing->message += missing > 1 ? " (and " + std::to_string(missing - 1) +
                                                            " other cells): every cell needs one"
                                                      : ": every cell needs one";
                issues.push_back(*first_missing);
            }
            if (steep) issues.push_back(*steep);
        }
    }
    if (field.soil_class) {
        std::vector<Issue> layout = validate(*field.soil_class, "soil_classes");
        if (!layout.empty()) {
            issues.insert(issues.end(), layout.begin(), layout.end());
        } else {
            const Raster& c = *field.soil_class;
            std::map<int, std::size_t> unknown;
            std::optional<Issue> fractional;
            for (int row = 0; row < c.rows; ++row) {
                for (int col = 0; col < c.cols; ++col) {
                    const double v = c.value(col, row);
                    if (std::isnan(v)) continue;
                    if (v != std::round(v) || std::abs(v) > 1e9) {
                        if (!fractional)
                            fractional = Issue{"soil_classes", cellName(col, row) + ": class " +
                                                                   formatNumber(v) +
                                                                   " is not a whole number"};
                        continue;
                    }
                    if (field.legend.count(static_cast<int>(v)) == 0)
                        ++unknown[static_cast<int>(v)];
                }
            }
            if (fractional) issues.push_back(*fractional);
            for (const auto& [code, count] : unknown)
                issues.push_back({"soil_classes", "class " + std::to_string(code) + " (" +
                                                      std::to_string(count) +
                                                      (count == 1 ? " cell" : " cells") +
                                                      ") has no entry in the legend"});
        }
    }
    for (const ParameterRaster& p : field.parameters) {
        const std::string where = std::string("parameters.") + p.field->key;
        std::vector<Issue> layout = validate(p.raster, where);
        if (!layout.empty()) {
            issues.insert(issues.end(), layout.begin(), layout.end());
            continue;
        }
        std::size_t bad = 0;
        std::optional<Issue> first;
        for (int row = 0; row < p.raster.rows; ++row) {
            for (int col = 0; col < p.raster.cols; ++col) {
                const double v = p.raster.value(col, row);
                if (std::isnan(v) || p.field->range.contains(v)) continue;
                if (bad++ == 0)
                    first = Issue{where, cellName(col, row) + ": " + formatNumber(v) + " " +
                                             p.field->displayUnit() + " is outside " +
                                             p.field->range.describe()};
            }
        }
        if (first) {
            if (bad > 1) first->message += " (and " + std::to_string(bad - 1) + " other cells)";
            issues.push_back(*first);
        }
    }
    return issues;
}

std::optional<int> epsgCode(const FieldMap& field) {
    if (field.height && field.height->epsg) return field.height->epsg;
    if (field.soil_class && field.soil_class->epsg) return field.soil_class->epsg;
    for (const ParameterRaster& p : field.parameters) {
        if (p.raster.epsg) return p.raster.epsg;
    }
    return std::nullopt;
}

}  // namespace terra::field
