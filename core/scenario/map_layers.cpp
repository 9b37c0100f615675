#include "core/scenario/map_layers.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "core/common/range.h"

namespace terra::scenario {
namespace {

constexpr double kNoData = std::numeric_limits<double>::quiet_NaN();

// Label and unit of a run's map from its key (runMapLayer).
void describeRunMap(const std::string& key, const FieldMaps& maps, MapLayer& layer) {
    if (key == "rut_depth_m") {
        layer.label = "rut depth";
        layer.unit = "m";
        return;
    }
    if (key == "passes") {
        layer.label = "wheel passes";
        layer.unit = "-";
        return;
    }
    if (key == "compaction_risk") {
        layer.label = std::isfinite(maps.risk_depth_m)
                          ? "compaction risk σz/σpc at " + formatNumber(maps.risk_depth_m) + " m"
                          : "compaction risk σz/σpc";
        layer.unit = "-";
        return;
    }
    if (key == "energy_per_m_J") {  // J per metre travelled (F12), not J
        layer.label = "energy per metre";
        layer.unit = "J/m";
        return;
    }
    // Longest first: "_J_m" before "_m".
    static const std::array<std::pair<const char*, const char*>, 9> kSuffixes{{{"_J_m2", "J/m²"},
                                                                               {"_J_m", "J/m"},
                                                                               {"_W_m2", "W/m²"},
                                                                               {"_Pa", "Pa"},
                                                                               {"_J", "J"},
                                                                               {"_W", "W"},
                                                                               {"_m", "m"},
                                                                               {"_s", "s"},
                                                                               {"_N", "N"}}};
    std::string words = key;
    layer.unit = "-";
    for (const auto& [suffix, unit] : kSuffixes) {
        const std::string s = suffix;
        if (words.size() > s.size() && words.compare(words.size() - s.size(), s.size(), s) == 0) {
            words.erase(words.size() - s.size());
            layer.unit = unit;
            break;
        }
    }
    std::replace(words.begin(), words.end(), '_', ' ');
    layer.label = words;
}

}  // namespace

MapLayer runMapLayer(const std::string& key, const FieldMaps& maps) {
    MapLayer layer;
    layer.key = key;
    layer.timed = true;
    describeRunMap(key, maps, layer);
    return layer;
}

LayerScale layerScale(const MapLayer& layer, const field::Raster& final_view) {
    LayerScale d;
    d.clear_zero = layer.timed;
    const auto [lo, hi] = final_view.valueRange();
    const bool any = std::isfinite(lo) && std::isfinite(hi);
    d.unit = layer.unit;
    if (layer.unit == "m" && layer.timed && (!any || std::max(std::abs(lo), std::abs(hi)) < 0.1)) {
        d.factor = 1e3;
        d.unit = "mm";
    }
    d.lower = any ? lo * d.factor : 0.0;
    d.upper = any ? hi * d.factor : 1.0;
    if (layer.timed) d.lower = std::min(d.lower, 0.0);  // untouched soil is the scale's start
    if (layer.key == "compaction_risk") d.upper = std::max(d.upper, 1.5);
    if (!(d.upper > d.lower)) d.upper = d.lower + 1.0;
    d.title = layer.label;
    if (layer.kind == LayerKind::kContinuous && !d.unit.empty()) d.title += " [" + d.unit + "]";
    return d;
}

std::vector<ColorStop> layerColors(const MapLayer& layer, const LayerScale& scale) {
    if (layer.key == "height")
        return {{0.0, {70, 120, 70}}, {0.5, {215, 205, 140}}, {1.0, {140, 95, 60}}};
    if (layer.key == "rut_depth_m") return {{0.0, {225, 160, 75}}, {1.0, {60, 30, 10}}};
    if (layer.key == "passes") return {{0.0, {190, 215, 240}}, {1.0, {20, 60, 140}}};
    if (layer.key == "compaction_risk") {
        const double span = std::max(scale.upper - scale.lower, 1e-9);
        const double green = (0.5 - scale.lower) / span, yellow = (1.1 - scale.lower) / span;
        constexpr double kEdge = 1e-4;  // a step between bands, not a blend
        return {{0.0, {215, 240, 205}},  {green - kEdge, {60, 160, 60}},
                {green, {245, 215, 60}}, {yellow - kEdge, {235, 175, 30}},
                {yellow, {220, 60, 45}}, {1.0, {130, 20, 20}}};
    }
    return {{0.0, {250, 240, 200}}, {1.0, {80, 30, 110}}};
}

Rgb colorAt(const std::vector<ColorStop>& stops, double fraction) {
    if (stops.empty()) throw std::invalid_argument("colorAt: no colour stops");
    const double f = std::clamp(std::isnan(fraction) ? 0.0 : fraction, 0.0, 1.0);
    if (f <= stops.front().at) return stops.front().color;
    for (std::size_t i = 1; i < stops.size(); ++i) {
        const ColorStop& a = stops[i - 1];
        const ColorStop& b = stops[i];
        if (f > b.at) continue;
        const double u = b.at > a.at ? (f - a.at) / (b.at - a.at) : 1.0;
        const auto mix = [u](std::uint8_t p, std::uint8_t q) {
            return static_cast<std::uint8_t>(std::lround(p + u * (q - p)));
        };
        return {mix(a.color.r, b.color.r), mix(a.color.g, b.color.g), mix(a.color.b, b.color.b)};
    }
    return stops.back().color;
}

std::vector<MapLayer> mapLayers(const Scenario& scenario, const FieldMaps* maps) {
    std::vector<MapLayer> out;
    if (scenario.field && scenario.field->height) {
        MapLayer height;
        height.key = "height";
        height.label = "height";
        height.unit = "m";
        out.push_back(std::move(height));
    }
    if (scenario.field && scenario.field->soil_class) {
        MapLayer classes;
        classes.key = "soil_classes";
        classes.label = "soil classes";
        classes.kind = LayerKind::kClasses;
        for (const auto& [code, soil] : scenario.field->legend) {
            const auto label = scenario.field_labels.find(code);
            classes.classes.emplace_back(
                code, label != scenario.field_labels.end() && !label->second.empty() ? label->second
                                                                                     : soil.name);
        }
        out.push_back(std::move(classes));
    }
    if (maps != nullptr) {
        for (const auto& [key, raster] : mapRasters(*maps)) {
            out.push_back(runMapLayer(key, *maps));
        }
    }
    return out;
}

const field::Raster* layerRaster(const Scenario& scenario, const FieldMaps* maps,
                                 const std::string& key) {
    if (key == "height" && scenario.field && scenario.field->height)
        return &*scenario.field->height;
    if (key == "soil_classes" && scenario.field && scenario.field->soil_class)
        return &*scenario.field->soil_class;
    if (maps != nullptr) {
        for (const auto& [k, raster] : mapRasters(*maps)) {
            if (k == key) return raster;
        }
    }
    return nullptr;
}

CellWindow windowOver(const field::Raster& r, double x_min_m, double y_min_m, double x_max_m,
                      double y_max_m) {
    if (!(std::isfinite(x_min_m) && std::isfinite(y_min_m) && std::isfinite(x_max_m) &&
          std::isfinite(y_max_m)) ||
        r.cols <= 0 || r.rows <= 0) {
        return {};
    }
    const auto clampTo = [](double v, int hi) {
        return static_cast<int>(std::clamp(v, 0.0, static_cast<double>(hi)));
    };
    const double h = r.cell_m;
    const int c0 = clampTo(std::floor((x_min_m - r.x_min_m) / h), r.cols);
    const int c1 = clampTo(std::ceil((x_max_m - r.x_min_m) / h), r.cols);
    const int r0 = clampTo(std::floor((r.yMax() - y_max_m) / h), r.rows);
    const int r1 = clampTo(std::ceil((r.yMax() - y_min_m) / h), r.rows);
    if (c1 <= c0 || r1 <= r0) return {};
    return {c0, r0, c1 - c0, r1 - r0};
}

field::Raster crop(const field::Raster& r, const CellWindow& w) {
    if (w.empty()) return field::Raster{0, 0, r.x_min_m, r.y_min_m, r.cell_m, {}, r.epsg};
    if (w.col < 0 || w.row < 0 || w.col + w.cols > r.cols || w.row + w.rows > r.rows)
        throw std::invalid_argument("crop: the window is not inside the raster");
    field::Raster out;
    out.cols = w.cols;
    out.rows = w.rows;
    out.cell_m = r.cell_m;
    out.epsg = r.epsg;
    out.x_min_m = r.x_min_m + w.col * r.cell_m;
    out.y_min_m = r.yMax() - (w.row + w.rows) * r.cell_m;
    out.values.resize(static_cast<std::size_t>(w.cols) * static_cast<std::size_t>(w.rows));
    for (int row = 0; row < w.rows; ++row) {
        const auto from =
            r.values.begin() + static_cast<std::ptrdiff_t>(static_cast<std::size_t>(w.row + row) *
                                                               static_cast<std::size_t>(r.cols) +
                                                           static_cast<std::size_t>(w.col));
        std::copy(from, from + w.cols,
                  out.values.begin() + static_cast<std::ptrdiff_t>(row) * w.cols);
    }
    return out;
}

std::array<double, 4> drivenArea(const Scenario& scenario, const Table& series) {
    double x0 = scenario.initial.x_m, x1 = x0, y0 = scenario.initial.y_m, y1 = y0;
    if (!series.rows.empty()) {
        const std::size_t xc = series.column("x_m"), yc = series.column("y_m");
        for (const std::vector<double>& row : series.rows) {
            if (!std::isfinite(row[xc]) || !std::isfinite(row[yc])) continue;  // a diverged end
            x0 = std::min(x0, row[xc]), x1 = std::max(x1, row[xc]);
            y0 = std::min(y0, row[yc]), y1 = std::max(y1, row[yc]);
        }
    }
    const dynamics::RobotParameters& robot = scenario.robot;
    const double reach = 0.6 * (robot.wheelbase_m + robot.track_m) + 2.0 * robot.wheel.radius_m;
    return {x0 - reach, y0 - reach, x1 + reach, y1 + reach};
}

FieldMaps cropMaps(const FieldMaps& maps, const CellWindow& window) {
    FieldMaps out;
    out.risk_depth_m = maps.risk_depth_m;
    const std::vector<std::pair<std::string, const field::Raster*>> from = mapRasters(maps);
    const std::vector<std::pair<std::string, field::Raster*>> to = mapRasters(out);
    for (std::size_t i = 0; i < from.size(); ++i) *to[i].second = crop(*from[i].second, window);
    const auto cols = static_cast<std::int64_t>(maps.rut_depth_m.cols);
    const MapHistory& h = maps.history;
    for (std::size_t i = 0; i < h.size(); ++i) {
        const std::int64_t row = h.cell[i] / cols - window.row, col = h.cell[i] % cols - window.col;
        if (row < 0 || col < 0 || row >= window.rows || col >= window.cols) continue;
        out.history.time_s.push_back(h.time_s[i]);
        out.history.cell.push_back(static_cast<std::int32_t>(row * window.cols + col));
        for (const auto& [key, values] : h.values) out.history.values[key].push_back(values[i]);
    }
    return out;
}

field::Raster mapAt(const FieldMaps& maps, const std::string& key, double t_s,
                    const CellWindow& window) {
    const field::Raster* final_map = nullptr;
    for (const auto& [k, raster] : mapRasters(maps)) {
        if (k == key) final_map = raster;
    }
    if (final_map == nullptr) throw std::invalid_argument("mapAt: no map \"" + key + "\"");
    field::Raster out = crop(*final_map, window);
    if (window.empty()) return out;
    const MapHistory& h = maps.history;
    const auto found = h.values.find(key);
    const std::vector<double>* after =
        found != h.values.end() && found->second.size() == h.size() ? &found->second : nullptr;
    // The cell's index in the window, or −1 outside it.
    const auto cols = static_cast<std::int64_t>(final_map->cols);
    auto local = [&](std::int32_t cell) -> std::int64_t {
        const std::int64_t row = cell / cols - window.row, col = cell % cols - window.col;
        if (row < 0 || col < 0 || row >= window.rows || col >= window.cols) return -1;
        return row * window.cols + col;
    };
    // Untouched first (every cell some passage wrote), then the passages up to t in the order
    // written: the last one at or before t wins.
    for (std::size_t i = 0; i < h.size(); ++i) {
        const std::int64_t at = local(h.cell[i]);
        if (at < 0) continue;
        const double final_value = final_map->values[static_cast<std::size_t>(h.cell[i])];
        out.values[static_cast<std::size_t>(at)] = std::isnan(final_value) ? kNoData : 0.0;
    }
    for (std::size_t i = 0; i < h.size() && h.time_s[i] <= t_s; ++i) {
        const std::int64_t at = local(h.cell[i]);
        if (at < 0) continue;
        out.values[static_cast<std::size_t>(at)] =
            after ? (*after)[i] : final_map->values[static_cast<std::size_t>(h.cell[i])];
    }
    return out;
}

field::Raster coarsen(const field::Raster& r, int max_side, LayerKind kind) {
    if (max_side < 1)
        throw std::invalid_argument("coarsen: max_side = " + std::to_string(max_side) +
                                    " is not at least 1");
    const int k =
        std::max({1, (r.cols + max_side - 1) / max_side, (r.rows + max_side - 1) / max_side});
    if (k == 1) return r;
    field::Raster out;
    out.cols = (r.cols + k - 1) / k;
    out.rows = (r.rows + k - 1) / k;
    out.cell_m = r.cell_m * k;
    out.x_min_m = r.x_min_m;
    out.y_min_m = r.yMax() - out.rows * out.cell_m;  // north edges stay aligned
    out.values.assign(static_cast<std::size_t>(out.cols) * static_cast<std::size_t>(out.rows),
                      kNoData);
    for (int orow = 0; orow < out.rows; ++orow) {
        const int r0 = orow * k, r1 = std::min(r.rows, r0 + k);
        for (int ocol = 0; ocol < out.cols; ++ocol) {
            const int c0 = ocol * k, c1 = std::min(r.cols, c0 + k);
            double& v = out.value(ocol, orow);
            if (kind == LayerKind::kClasses) {
                v = r.value(std::min(c0 + k / 2, c1 - 1), std::min(r0 + k / 2, r1 - 1));
                continue;
            }
            for (int row = r0; row < r1; ++row) {
                for (int col = c0; col < c1; ++col) {
                    const double x = r.value(col, row);
                    if (!std::isnan(x) && !(x <= v)) v = x;  // NaN v: the first with data
                }
            }
        }
    }
    return out;
}

field::Raster layerView(const Scenario& scenario, const FieldMaps* maps, const MapLayer& layer,
                        const std::array<double, 4>& box_m, double t_s, int max_side) {
    const field::Raster* raster = layerRaster(scenario, maps, layer.key);
    if (raster == nullptr) return field::Raster{0, 0, 0.0, 0.0, 1.0, {}, std::nullopt};
    const CellWindow window = windowOver(*raster, box_m[0], box_m[1], box_m[2], box_m[3]);
    if (window.empty())
        return field::Raster{0,  0,           raster->x_min_m, raster->y_min_m, raster->cell_m,
                             {}, raster->epsg};
    field::Raster view = layer.timed && maps != nullptr ? mapAt(*maps, layer.key, t_s, window)
                                                        : crop(*raster, window);
    return coarsen(view, max_side, layer.kind);
}

}  // namespace terra::scenario
