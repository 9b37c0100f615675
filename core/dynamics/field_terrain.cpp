#include "core/dynamics/field_terrain.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <utility>

#include "core/common/range.h"
#include "core/compaction/footprint.h"
#include "core/compaction/stress_at_depth.h"
#include "core/contact/stress_field.h"

namespace terra::dynamics {
namespace {

// The memory's cells: `cell_m`, or the finest raster cell, from the class (else height) raster's
// lower-left corner so that memory cells nest in the map's cells.
field::CellGrid makeGrid(const field::FieldMap& map, const FieldTerrainOptions& options) {
    double cell = options.cell_m;
    double x0 = 0.0, y0 = 0.0;
    const field::Raster* anchor = map.soil_class ? &*map.soil_class
                                  : map.height   ? &*map.height
                                                 : nullptr;
    if (anchor != nullptr) x0 = anchor->x_min_m, y0 = anchor->y_min_m;
    if (!(cell > 0.0)) {
        cell = 1.0;
        if (map.height) cell = map.height->cell_m;
        if (map.soil_class)
            cell = map.height ? std::min(cell, map.soil_class->cell_m) : map.soil_class->cell_m;
    }
    return field::CellGrid(cell, x0, y0, options.stress_depths_m);
}

}  // namespace

FieldTerrain::FieldTerrain(std::shared_ptr<const field::FieldMap> map, const RobotParameters& robot,
                           FieldTerrainOptions options)
    : map_(std::move(map)),
      options_(std::move(options)),
      wheel_(robot.wheel),
      cells_(makeGrid(*map_, options_)) {
    axle_.fill({0.0, 1.0});
    soils_.push_back(map_->base);
    for (const auto& [code, soil] : map_->legend) {
        codes_.push_back(code);
        soils_.push_back(soil);
    }
    class_soils_ = soils_.size();
    if (!map_->parameters.empty()) enumerateSoils();
}

std::vector<soil::SoilParameters> FieldTerrain::stepLimitSoils() const {
    if (soils_.size() <= kStepLimitSoils) return soils_;
    // The corners of the box of the rasters' values (a step bound for every soil inside when
    // the corner's stiffness grows or falls with each value alone: docs/field.md, F14).
    std::vector<std::pair<double, double>> box;
    for (const field::ParameterRaster& p : map_->parameters) {
        double lo = HUGE_VAL, hi = -HUGE_VAL;
        for (double v : p.raster.values) {
            if (std::isnan(v)) continue;
            lo = std::min(lo, v), hi = std::max(hi, v);
        }
        box.emplace_back(lo, hi);
    }
    const std::size_t corners = std::size_t{1} << std::min<std::size_t>(box.size(), 6);
    std::vector<soil::SoilParameters> out(soils_.begin(), soils_.begin() + class_soils_);
    for (std::size_t c = 0; c < class_soils_; ++c) {
        for (std::size_t corner = 0; corner < corners; ++corner) {
            soil::SoilParameters soil = soils_[c];
            for (std::size_t i = 0; i < box.size(); ++i) {
                if (box[i].first > box[i].second) continue;  // a raster without data
                const bool high = i < 6 && ((corner >> i) & 1U) != 0;
                soil::setUserValue(soil, *map_->parameters[i].field,
                                   high ? box[i].second : box[i].first);
            }
            out.push_back(std::move(soil));
        }
    }
    return out;
}

int FieldTerrain::classIndexOf(std::optional<int> code) const {
    if (!code) return 0;
    const auto it = std::lower_bound(codes_.begin(), codes_.end(), *code);
    return it != codes_.end() && *it == *code ? static_cast<int>(it - codes_.begin()) + 1 : 0;
}

int FieldTerrain::classIndexAt(double x_m, double y_m) const {
    return classIndexOf(map_->classAt(x_m, y_m));
}

void FieldTerrain::soilKey(double x_m, double y_m, std::vector<double>& key) const {
    key.clear();
    key.push_back(classIndexAt(x_m, y_m));
    for (const field::ParameterRaster& p : map_->parameters) {
        const double v = p.raster.nearest(x_m, y_m);
        key.push_back(std::isnan(v) ? std::numeric_limits<double>::infinity() : v);
    }
}

namespace {

// One axis of a raster as Raster::cellAt sees it: the column of x (or the row of y) where the
// point is inside the raster's extent along that axis, −1 before it and `cells` beyond it
// (monotone in x; in y the row falls as y rises, so the class is the row counted from the other
// end). Exactly cellAt's arithmetic, so that the classes change where cellAt's answer does.
struct AxisClass {
    const field::Raster* r;
    bool y_axis;
    int operator()(double v) const {
        if (!y_axis) {
            if (!(v >= r->x_min_m)) return -1;
            if (!(v < r->xMax())) return r->cols;
            return std::min(static_cast<int>(std::floor((v - r->x_min_m) / r->cell_m)),
                            r->cols - 1);
        }
        if (!(v >= r->y_min_m)) return -1;
        if (!(v < r->yMax())) return r->rows;
        const int row =
            std::min(static_cast<int>(std::floor((r->yMax() - v) / r->cell_m)), r->rows - 1);
        return r->rows - 1 - row;  // rising with y
    }
    int cells() const { return y_axis ? r->rows : r->cols; }
    double origin() const { return y_axis ? r->y_min_m : r->x_min_m; }
    // The raster's column (or row) from a class, or −1 outside.
    int index(int c) const {
        if (c < 0 || c >= cells()) return -1;
        return y_axis ? r->rows - 1 - c : c;
    }
};

// The exact doubles where any of `axes` changes its class (the smallest v with the class of the
// cell above each computed edge), sorted, with the midpoints between them and a point before
// the first: a sample of every distinct tuple of classes along the axis. Consecutive samples
// with the same tuple are one; returns each tuple of indices (column or row, −1 outside).
std::vector<std::vector<int>> axisTuples(const std::vector<AxisClass>& axes) {
    std::vector<double> changes;
    for (const AxisClass& a : axes) {
        const double h = a.r->cell_m;
        for (int k = 0; k <= a.cells(); ++k) {
            const double e = a.origin() + k * h;  // the edge as computed; cellAt may differ by ulps
            const int above = a(e + 0.5 * h);
            double v = e;
            if (a(v) == above) {
                for (int i = 0; i < 64 && a(std::nextafter(v, -HUGE_VAL)) == above; ++i)
                    v = std::nextafter(v, -HUGE_VAL);
            } else {
                for (int i = 0; i < 64 && a(v) != above; ++i) v = std::nextafter(v, HUGE_VAL);
            }
            changes.push_back(v);
        }
    }
    std::sort(changes.begin(), changes.end());
    changes.erase(std::unique(changes.begin(), changes.end()), changes.end());
    std::vector<double> samples{changes.front() - 1.0};
    for (std::size_t i = 0; i < changes.size(); ++i) {
        samples.push_back(changes[i]);
        if (i + 1 < changes.size()) samples.push_back(0.5 * (changes[i] + changes[i + 1]));
    }
    samples.push_back(changes.back() + 1.0);
    std::vector<std::vector<int>> tuples;
    std::vector<int> t(axes.size());
    for (double v : samples) {
        for (std::size_t j = 0; j < axes.size(); ++j) t[j] = axes[j].index(axes[j](v));
        if (tuples.empty() || tuples.back() != t) tuples.push_back(t);
    }
    return tuples;
}

}  // namespace

// F14: every soil the map holds. Each raster's cell (Raster::cellAt) depends on x through its
// column and on y through its row alone, so the distinct columns-of-every-raster along x (found
// at the exact doubles where a column changes and between them) times the distinct rows along y
// meet every combination the map has, edges included. Soils equal in class and values are one.
void FieldTerrain::enumerateSoils() {
    std::vector<const field::Raster*> rasters;
    if (map_->soil_class) rasters.push_back(&*map_->soil_class);
    for (const field::ParameterRaster& p : map_->parameters) rasters.push_back(&p.raster);
    std::vector<AxisClass> xs, ys;
    for (const field::Raster* r : rasters) {
        xs.push_back({r, false});
        ys.push_back({r, true});
    }
    const std::vector<std::vector<int>> cols = axisTuples(xs), rows = axisTuples(ys);
    // The product is walked key by key (≈ 10 ns each): rasters whose edges interleave over a
    // large field (a long strip crossing another) would take minutes, refused by name instead.
    const double keys = static_cast<double>(cols.size()) * static_cast<double>(rows.size());
    if (keys > kMaxSoilKeys) {
        throw std::invalid_argument(
            "the field's classes and parameter rasters cut it into " + formatNumber(keys) +
            " pieces of distinct cells, more than the " + formatNumber(kMaxSoilKeys) +
            " the rover enumerates; use parameter rasters on the class raster's grid or "
            "coarser ones");
    }
    const bool classes = map_->soil_class.has_value();
    std::vector<double> key(1 + map_->parameters.size()), last;
    for (const std::vector<int>& row : rows) {
        for (const std::vector<int>& col : cols) {
            // The key as soilKey computes it at a point of this column and row.
            std::size_t j = 0;
            int class_index = 0;
            if (classes) {
                if (col[0] >= 0 && row[0] >= 0)
                    class_index =
                        classIndexOf(field::classCode(map_->soil_class->value(col[0], row[0])));
                j = 1;
            }
            key[0] = class_index;
            for (std::size_t i = 0; i < map_->parameters.size(); ++i, ++j) {
                double v = std::numeric_limits<double>::quiet_NaN();
                if (col[j] >= 0 && row[j] >= 0)
                    v = map_->parameters[i].raster.value(col[j], row[j]);
                key[i + 1] = std::isnan(v) ? std::numeric_limits<double>::infinity() : v;
            }
            if (key == last || soil_of_key_.count(key) != 0) {
                last = key;
                continue;
            }
            last = key;
            const auto index = static_cast<std::size_t>(key.front());
            // The map's own soils keep their indices (0: base, then the legend): a class cell
            // without a parameter value is its class's soil.
            const bool plain =
                std::all_of(key.begin() + 1, key.end(), [](double v) { return std::isinf(v); });
            if (!plain && soils_.size() >= kMaxSoils) {
                throw std::invalid_argument(
                    "the field's classes and parameter rasters make more than " +
                    std::to_string(kMaxSoils) +
                    " distinct soils, the most the rover takes; use coarser parameter rasters "
                    "or fewer distinct values");
            }
            const int at = plain ? static_cast<int>(index) : static_cast<int>(soils_.size());
            if (!plain) {
                soil::SoilParameters soil = soils_[index];
                for (std::size_t i = 0; i < map_->parameters.size(); ++i) {
                    if (std::isfinite(key[i + 1]))
                        soil::setUserValue(soil, *map_->parameters[i].field, key[i + 1]);
                }
                soils_.push_back(std::move(soil));
            }
            soil_of_key_.emplace(key, at);
        }
    }
}

int FieldTerrain::soilIndexAt(double x_m, double y_m) const {
    if (soil_of_key_.empty()) return classIndexAt(x_m, y_m);
    std::vector<double> key;
    key.reserve(1 + map_->parameters.size());
    soilKey(x_m, y_m, key);
    const auto it = soil_of_key_.find(key);
    // Every key is enumerated (F14); a point on a shared edge whose rasters round to sides no
    // rectangle has would take its class's soil.
    return it != soil_of_key_.end() ? it->second : classIndexAt(x_m, y_m);
}

std::array<double, 2> FieldTerrain::gradientAt(double x_m, double y_m) const {
    const Eigen::Vector2d g = map_->gradientAt(x_m, y_m);
    return {g.x(), g.y()};
}

const compaction::TrackMemory* FieldTerrain::memoryUnder(int wheel, double x_m, double y_m) {
    Passage& p = passages_[static_cast<std::size_t>(wheel)];
    const field::CellKey key = cells_.keyAt(x_m, y_m);
    // F12: the step to this point belongs to the passage open before it (the one it may leave),
    // as the energy of the steps in the margin does.
    std::optional<std::array<double, 2>>& last = last_contact_[static_cast<std::size_t>(wheel)];
    if (p.open && last) p.travel_m += std::hypot(x_m - (*last)[0], y_m - (*last)[1]);
    last = std::array<double, 2>{x_m, y_m};
    if (p.open && (key.ix != p.key.ix || key.iy != p.key.iy)) {
        // F10: the wheel leaves its cell only once its contact point is a quarter cell beyond
        // the cell's edges, so a wheel that stands or turns on an edge is one passage, not many.
        const double h = cells_.cellSize(), margin = 0.25 * h;
        const double x0 = cells_.centreX(p.key.ix) - 0.5 * h;
        const double y0 = cells_.centreY(p.key.iy) - 0.5 * h;
        const bool inside = x_m >= x0 - margin && x_m < x0 + h + margin && y_m >= y0 - margin &&
                            y_m < y0 + h + margin;
        if (!inside) commit(p);
    }
    if (!p.open) {
        p = Passage{};
        p.open = true;
        p.key = key;
        p.entry = {x_m, y_m};
        p.entry_axle = axle_[static_cast<std::size_t>(wheel)];
        if (const field::CellState* s = cells_.find(key)) p.before = s->track;
        // A wheel leaving a cell sideways (through the quarter-cell margin at its side) can enter
        // one its last passage has just written (F13): it meets that cell as it was before its
        // own pass, not its own rut.
        ownBefore(static_cast<std::size_t>(wheel), key, p.before, options_.read_across_width);
        sampleBand(static_cast<std::size_t>(wheel), p);
    }
    return options_.repeated_passes && !p.before.untouched() ? &p.before : nullptr;
}

double FieldTerrain::bandSpan(const std::array<double, 2>& axle) const {
    // A written cell's centre lies within b/2 of its writer's centre line (F13), and a point lies
    // within h (|a_x| + |a_y|)/2 of its cell's centre along a (a square's half-extent along a unit
    // vector): the points within b/2 − h (|a_x| + |a_y|)/2 of a centre line fall in that line's
    // written cells, wherever the line lies on the grid.
    const double reach = cells_.cellSize() * (std::abs(axle[0]) + std::abs(axle[1]));
    return std::max(0.0, wheel_.width_m - reach);
}

int FieldTerrain::bandSamples(const std::array<double, 2>& axle) const {
    // Points h/4 apart at most over the span, the middle one on the contact point.
    const double span = bandSpan(axle);
    if (!(span > 0.0)) return 1;
    const double h = cells_.cellSize();
    const int gaps = static_cast<int>(std::min<double>(std::ceil(span / (0.25 * h)), 1e6));
    return std::min(gaps % 2 == 0 ? gaps + 1 : gaps + 2, kMaxBandSamples);
}

namespace {

// Two memories a wheel meets alike: onTrack reads neither the pass count nor anything but these.
bool sameGround(const compaction::TrackMemory& a, const compaction::TrackMemory& b) {
    return a.untouched() == b.untouched() && a.max_sinkage_m == b.max_sinkage_m &&
           a.max_pressure_pa == b.max_pressure_pa && a.rut_depth_m == b.rut_depth_m &&
           a.shear_m == b.shear_m;
}

}  // namespace

void FieldTerrain::sampleBand(std::size_t wheel, const Passage& p) {
    std::vector<compaction::TrackMemory>& memories = band_memory_[wheel];
    std::vector<BandShare>& band = band_[wheel];
    memories.clear();
    band.clear();
    const std::array<double, 2> axle = p.entry_axle;
    const int samples = bandSamples(axle);
    if (!options_.repeated_passes || !options_.across_width || !options_.read_across_width ||
        samples == 1)
        return;
    // F15: m points t_j = (j − (m − 1)/2) S/(m − 1) along the axle through the contact point, S =
    // bandSpan (b less a cell's extent along the axle: a wheel in the exact track of one before it
    // meets that wheel's written band at every point), the middle one the contact point (its
    // cell's memory is p.before). Point j stands for the width between its neighbours' midpoints,
    // the two outer ones out to the width's edges ±b/2. Each cell is met as it was before the
    // wheel's own recent passages (F13, ownBefore).
    memories.reserve(kMaxBandSamples);
    std::array<double, kMaxBandSamples> width{};
    bool differs = false;
    const double b = wheel_.width_m;
    const double step = bandSpan(axle) / (samples - 1);
    for (int j = 0; j < samples; ++j) {
        const double t = (j - 0.5 * (samples - 1)) * step;
        const double from = j == 0 ? -0.5 * b : t - 0.5 * step;
        const double to = j == samples - 1 ? 0.5 * b : t + 0.5 * step;
        const field::CellKey key = cells_.keyAt(p.entry[0] + t * axle[0], p.entry[1] + t * axle[1]);
        compaction::TrackMemory memory;
        if (const field::CellState* s = cells_.find(key)) memory = s->track;
        ownBefore(wheel, key, memory, true);
        differs = differs || !sameGround(memory, p.before);
        std::size_t g = 0;
        while (g < memories.size() && !sameGround(memories[g], memory)) ++g;
        if (g == memories.size()) memories.push_back(memory);
        width[g] += to - from;
    }
    if (!differs) {
        memories.clear();
        return;
    }
    for (std::size_t g = 0; g < memories.size(); ++g) {
        band.push_back({memories[g].untouched() ? nullptr : &memories[g], width[g] / b});
    }
}

void FieldTerrain::ownBefore(std::size_t wheel, field::CellKey key, compaction::TrackMemory& memory,
                             bool recent) const {
    auto find = [&](const std::vector<std::pair<field::CellKey, compaction::TrackMemory>>& list) {
        for (const auto& [written, before] : list) {
            if (written.ix == key.ix && written.iy == key.iy) {
                memory = before;
                return true;
            }
        }
        return false;
    };
    if (recent) {
        for (const auto& list : recent_written_[wheel]) {
            if (find(list)) return;
        }
    }
    find(last_written_[wheel]);
}

void FieldTerrain::archiveWritten(std::size_t wheel) {
    auto& last = last_written_[wheel];
    if (last.empty()) return;  // a passage that wrote nothing is not remembered
    auto& recent = recent_written_[wheel];
    recent.push_back(std::exchange(last, {}));
    if (recent.size() > kRecentPassages) recent.pop_front();
}

void FieldTerrain::imprint(int wheel, const WheelImprint& imprint) {
    Passage& p = passages_[static_cast<std::size_t>(wheel)];
    p.last_power_w = imprint.power_w;
    axle_[static_cast<std::size_t>(wheel)] = imprint.axle;
    // The first passage opened before the wheel's first imprint told its axle.
    if (!axle_known_[static_cast<std::size_t>(wheel)]) p.entry_axle = imprint.axle;
    axle_known_[static_cast<std::size_t>(wheel)] = true;
    if (!p.open || !imprint.in_contact) return;
    p.max_slip = std::max(p.max_slip, std::abs(imprint.op.slip));
    if (!p.contacted || imprint.depth_m > p.max_depth_m) {
        p.contacted = true;
        p.max_depth_m = imprint.depth_m;
        p.soil_index = imprint.soil_index;
        p.params = imprint.params;
        p.op = imprint.op;
        p.footprint_scale = imprint.footprint_scale;
    }
}

void FieldTerrain::advanced(double dt_s) {
    // Summed as the rover sums its own clock (state.time_s += dt), so that a passage's time is
    // bit for bit the time of the series' row it was written in.
    time_s_ += dt_s;
    for (Passage& p : passages_) {
        if (p.open) p.energy_j += p.last_power_w * dt_s;
    }
}

void FieldTerrain::finish() {
    for (Passage& p : passages_) {
        if (p.open) commit(p);
    }
    // A last short passage that wrote no cell: its energy and distance go to the cells the
    // wheel's last passage wrote, so that the field holds the whole run's.
    for (std::size_t wheel = 0; wheel < carry_.size(); ++wheel) {
        const auto& written = last_written_[wheel];
        if (written.empty()) continue;
        const double share = 1.0 / static_cast<double>(written.size());
        for (const auto& [key, before] : written) {
            field::CellState& cell = cells_.touch(key);
            cell.energy_j += static_cast<float>(carry_[wheel].energy_j * share);
            cell.travel_m += static_cast<float>(carry_[wheel].travel_m * share);
        }
        carry_[wheel] = {};
    }
}

double FieldTerrain::concentrationAt(const Passage& p, double depth_m) const {
    if (options_.concentration > 0.0) return options_.concentration;
    const soil::SoilParameters& soil = soils_[static_cast<std::size_t>(p.soil_index)];
    if (soil.profile) {
        const soil::SoilLayer* layer = soil.profile->layerAt(depth_m);
        if (layer && layer->concentration) return *layer->concentration;
    }
    return compaction::kDefaultConcentration;
}

namespace {

// Whether (x, y) lies inside the quadrilateral q (even–odd rule: a ray towards +x crosses its
// edges an odd number of times; a twisted quadrilateral, a wheel turning about a point inside its
// width, counts each of its two triangles).
bool insideQuad(const std::array<std::array<double, 2>, 4>& q, double x, double y) {
    bool inside = false;
    for (std::size_t i = 0, j = 3; i < 4; j = i++) {
        const double yi = q[i][1], yj = q[j][1];
        if ((yi > y) != (yj > y)) {
            const double x_cross = q[i][0] + (y - yi) / (yj - yi) * (q[j][0] - q[i][0]);
            if (x < x_cross) inside = !inside;
        }
    }
    return inside;
}

}  // namespace

std::vector<FieldTerrain::SweptCell> FieldTerrain::sweptCells(const Passage& p,
                                                              std::size_t wheel) const {
    if (!options_.across_width) return {{p.key, 0.0}};
    const double h = cells_.cellSize();
    const std::array<double, 2> exit = last_contact_[wheel].value_or(p.entry);
    const std::array<double, 2> a0 = p.entry_axle, a1 = axle_[wheel];
    // The centre line's lateral direction over the passage (the mean axle; a wheel that turned
    // half a revolution keeps its last one).
    std::array<double, 2> a{a0[0] + a1[0], a0[1] + a1[1]};
    const double a_norm = std::hypot(a[0], a[1]);
    a = a_norm > 1e-9 ? std::array<double, 2>{a[0] / a_norm, a[1] / a_norm} : a1;
    // The signed distance from the centre line (through the exit point, along the travel) to the
    // cell's nearest point: d − sign(d) h (|ā_x| + |ā_y|)/2, d the cell centre's offset along ā (a
    // square's half-extent along a unit vector), 0 for a cell the line crosses. Signed: σ_z is
    // not symmetric across the wheel under a side shear.
    auto offsetOf = [&](field::CellKey key) {
        const double d =
            (cells_.centreX(key.ix) - exit[0]) * a[0] + (cells_.centreY(key.iy) - exit[1]) * a[1];
        const double reach = 0.5 * h * (std::abs(a[0]) + std::abs(a[1]));
        return std::copysign(std::max(0.0, std::abs(d) - reach), d);
    };
    // F13: the quadrilateral the wheel's width swept from the passage's entry to its exit. A
    // contact point that moved more than a few cells and a wheel's width within one passage
    // jumped (a restart): the cell under it alone.
    const double w = 0.5 * wheel_.width_m;
    if (std::hypot(exit[0] - p.entry[0], exit[1] - p.entry[1]) > 4.0 * h + 2.0 * w)
        return {{p.key, 0.0}};
    const std::array<std::array<double, 2>, 4> q{{{p.entry[0] - w * a0[0], p.entry[1] - w * a0[1]},
                                                  {p.entry[0] + w * a0[0], p.entry[1] + w * a0[1]},
                                                  {exit[0] + w * a1[0], exit[1] + w * a1[1]},
                                                  {exit[0] - w * a1[0], exit[1] - w * a1[1]}}};
    double x_lo = q[0][0], x_hi = q[0][0], y_lo = q[0][1], y_hi = q[0][1];
    for (const auto& c : q) {
        x_lo = std::min(x_lo, c[0]), x_hi = std::max(x_hi, c[0]);
        y_lo = std::min(y_lo, c[1]), y_hi = std::max(y_hi, c[1]);
    }
    const field::CellKey lo = cells_.keyAt(x_lo, y_lo), hi = cells_.keyAt(x_hi, y_hi);
    std::vector<SweptCell> out;
    for (std::int64_t iy = lo.iy; iy <= hi.iy; ++iy) {
        for (std::int64_t ix = lo.ix; ix <= hi.ix; ++ix) {
            if (!insideQuad(q, cells_.centreX(ix), cells_.centreY(iy))) continue;
            out.push_back({field::CellKey{ix, iy}, offsetOf(field::CellKey{ix, iy})});
        }
    }
    // Membership is by the quadrilateral alone, so that consecutive passages tile the band. On
    // cells coarser than the wheel it may hold no centre: the cell under the contact point is
    // written (F10). On finer cells an empty one is a short passage (a corner cut through the
    // quarter-cell margin): nothing is written, its energy and distance go to the wheel's next
    // passage (commit).
    if (out.empty() && 2.0 * w < h) out.push_back({p.key, offsetOf(p.key)});
    return out;
}

void FieldTerrain::commit(Passage& p) {
    p.open = false;
    const auto wheel = static_cast<std::size_t>(&p - passages_.data());
    std::vector<std::pair<field::CellKey, compaction::TrackMemory>>& written = last_written_[wheel];
    if (!p.contacted) {
        archiveWritten(wheel);
        return;
    }
    // F11: the memory after one more wheel — it sank to its deepest point below the untouched
    // surface with N = n₀ + n₁ s, and left the shear |j(θ_r)| (Eq. 2.15, without the offset).
    // afterPass reads K_s, n and j_max, which the memory (onTrack) leaves as the soil's.
    const contact::ContactParameters<double>& untouched = p.params;
    double exit_shear = 0.0;
    contact::ContactParameters<double> plain = p.params;
    plain.shear_offset_m = 0.0;
    try {
        const contact::StressField<double> field(plain, p.op);
        exit_shear = field.locked() ? 0.0 : std::abs(field.at(field.exitAngle()).shear);
    } catch (const std::invalid_argument&) {
        exit_shear = 0.0;  // an operating point outside the model's domain leaves no shear
    }
    const double n = untouched.sinkage_exponent + untouched.sinkage_exponent_slip * p.op.slip;
    // The footprint of the deepest instant and its propagation at each depth's ν, built once
    // for the passage's cells; σ_z is then taken at each cell's distance from the centre line
    // (the cells on either side at one distance share it).
    const std::vector<double>& depths = cells_.stressDepths();
    std::vector<compaction::PointLoad> footprint;
    try {
        if (!depths.empty()) footprint = compaction::wheelFootprint(p.params, p.op);
        // F15: the most loaded part's footprint, scaled to carry the wheel's load.
        if (p.footprint_scale != 1.0) {
            for (compaction::PointLoad& load : footprint) load.force *= p.footprint_scale;
        }
    } catch (const std::invalid_argument&) {
        footprint.clear();  // outside the model's domain: no stress at depth from this passage
    }
    std::vector<std::optional<compaction::StressPropagation>> propagation(depths.size());
    for (std::size_t k = 0; k < depths.size() && !footprint.empty(); ++k) {
        try {
            propagation[k].emplace(footprint, concentrationAt(p, depths[k]));
        } catch (const std::invalid_argument&) {
            propagation[k].reset();
        }
    }
    // Per depth: the peak under the centre line — from the wheel's last passage's peak (F16),
    // else and every options_.full_scan_every passages by the full scan —, then each cell's
    // distance from the line by Brent's method near that peak (maxVerticalStressNear); cells at one
    // distance share it.
    std::vector<std::optional<compaction::VerticalStressPeak>> centre(depths.size());
    std::vector<std::optional<compaction::VerticalStressPeak>>& last_peak = last_peak_[wheel];
    last_peak.resize(depths.size());
    // Counted once a passage that searches a peak (not one that writes no cell or has no
    // footprint), so that every options_.full_scan_every-th such passage scans.
    std::optional<bool> full_scan;
    auto centrePeak = [&](std::size_t k, const compaction::StressPropagation& q) {
        if (!full_scan) {
            full_scan = ++since_full_scan_[wheel] >= options_.full_scan_every;
            if (*full_scan) since_full_scan_[wheel] = 0;
        }
        if (last_peak[k] && !*full_scan) {
            centre[k] = compaction::verticalStressPeakNear(q, *last_peak[k], 0.0, depths[k]);
        } else {
            centre[k] = compaction::verticalStressPeak(q, 0.0, depths[k]);
            ++full_scans_;
        }
        last_peak[k] = centre[k];
    };
    struct Known {
        std::size_t depth;
        double offset_m, sigma_pa;
    };
    std::vector<Known> known;
    auto sigmaAt = [&](std::size_t k, double offset_m) {
        for (const Known& e : known) {
            if (e.depth == k && e.offset_m == offset_m) return e.sigma_pa;
        }
        double sigma = 0.0;
        const std::optional<compaction::StressPropagation>& q = propagation[k];
        if (q && depths[k] > q->deepestLoad()) {
            try {
                if (!centre[k]) centrePeak(k, *q);
                sigma = offset_m == 0.0 ? centre[k]->sigma_z_pa
                                        : compaction::maxVerticalStressNear(*q, *centre[k],
                                                                            offset_m, depths[k]);
            } catch (const std::invalid_argument&) {
                sigma = 0.0;
            }
        }
        known.push_back({k, offset_m, sigma});
        return sigma;
    };
    // F13: every cell under the wheel's width takes the pass; the energy and the distance are
    // shared equally, so that their sums over the cells are the passage's and each cell's ratio
    // is the passage's energy per metre.
    const std::vector<SweptCell> swept = sweptCells(p, wheel);
    Carry& carry = carry_[wheel];
    if (swept.empty()) {  // a short passage whose band holds no cell centre
        carry.energy_j += p.energy_j, carry.travel_m += p.travel_m;
        return;
    }
    const double energy_j = p.energy_j + carry.energy_j, travel_m = p.travel_m + carry.travel_m;
    carry = {};
    archiveWritten(wheel);
    const double share = 1.0 / static_cast<double>(swept.size());
    for (const SweptCell& target : swept) {
        field::CellState& cell = cells_.touch(target.key);
        written.emplace_back(target.key, cell.track);
        if (cell.track.untouched()) ++cells_touched_;
        cell.track = compaction::afterPass(cell.track, options_.law, untouched,
                                           std::max(0.0, p.max_depth_m), n, exit_shear);
        cell.max_slip = std::max(cell.max_slip, static_cast<float>(p.max_slip));
        cell.energy_j += static_cast<float>(energy_j * share);
        cell.travel_m += static_cast<float>(travel_m * share);
        for (std::size_t k = 0; k < depths.size(); ++k) {
            const double sigma = sigmaAt(k, target.offset_m);
            cell.max_stress_pa[k] = std::max(cell.max_stress_pa[k], static_cast<float>(sigma));
        }
        if (options_.record_passages) {
            log_.push_back(CellPassage{time_s_, target.key, cell.track.rut_depth_m,
                                       cell.track.passes,
                                       depths.empty() ? 0.0f : cell.max_stress_pa[0], cell.max_slip,
                                       cell.energy_j, cell.travel_m});
        }
    }
}

}  // namespace terra::dynamics
