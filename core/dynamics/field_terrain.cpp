#include "core/dynamics/field_terrain.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

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
    if (!map_->parameters.empty()) {
        throw std::invalid_argument("field: parameter rasters (" +
                                    std::string(map_->parameters.front().field->key) +
                                    ") are not read by the rover yet; give the soil by class");
    }
    soils_.push_back(map_->base);
    for (const auto& [code, soil] : map_->legend) {
        codes_.push_back(code);
        soils_.push_back(soil);
    }
}

int FieldTerrain::soilIndexAt(double x_m, double y_m) const {
    const std::optional<int> code = map_->classAt(x_m, y_m);
    if (!code) return 0;
    const auto it = std::lower_bound(codes_.begin(), codes_.end(), *code);
    return it != codes_.end() && *it == *code ? static_cast<int>(it - codes_.begin()) + 1 : 0;
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
        if (const field::CellState* s = cells_.find(key)) p.before = s->track;
    }
    return options_.repeated_passes && !p.before.untouched() ? &p.before : nullptr;
}

void FieldTerrain::imprint(int wheel, const WheelImprint& imprint) {
    Passage& p = passages_[static_cast<std::size_t>(wheel)];
    p.last_power_w = imprint.power_w;
    if (!p.open || !imprint.in_contact) return;
    p.max_slip = std::max(p.max_slip, std::abs(imprint.op.slip));
    if (!p.contacted || imprint.depth_m > p.max_depth_m) {
        p.contacted = true;
        p.max_depth_m = imprint.depth_m;
        p.soil_index = imprint.soil_index;
        p.params = imprint.params;
        p.op = imprint.op;
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
}

double FieldTerrain::stressAt(const Passage& p, double depth_m) const {
    double nu = options_.concentration;
    if (!(nu > 0.0)) {
        nu = compaction::kDefaultConcentration;
        const soil::SoilParameters& soil = soils_[static_cast<std::size_t>(p.soil_index)];
        if (soil.profile) {
            const soil::SoilLayer* layer = soil.profile->layerAt(depth_m);
            if (layer && layer->concentration) nu = *layer->concentration;
        }
    }
    const compaction::StressPropagation propagation(compaction::wheelFootprint(p.params, p.op), nu);
    if (!(depth_m > propagation.deepestLoad())) return 0.0;
    return compaction::maxVerticalStress(propagation, 0.0, depth_m);
}

void FieldTerrain::commit(Passage& p) {
    p.open = false;
    if (!p.contacted) return;
    field::CellState& cell = cells_.touch(p.key);
    if (cell.track.untouched()) ++cells_touched_;
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
    cell.track = compaction::afterPass(cell.track, options_.law, untouched,
                                       std::max(0.0, p.max_depth_m), n, exit_shear);
    cell.max_slip = std::max(cell.max_slip, static_cast<float>(p.max_slip));
    cell.energy_j += static_cast<float>(p.energy_j);
    cell.travel_m += static_cast<float>(p.travel_m);
    const std::vector<double>& depths = cells_.stressDepths();
    for (std::size_t k = 0; k < depths.size(); ++k) {
        double sigma = 0.0;
        try {
            sigma = stressAt(p, depths[k]);
        } catch (const std::invalid_argument&) {
            sigma = 0.0;
        }
        cell.max_stress_pa[k] = std::max(cell.max_stress_pa[k], static_cast<float>(sigma));
    }
    if (options_.record_passages) {
        const auto wheel = static_cast<int>(&p - passages_.data());
        log_.push_back(CellPassage{time_s_, p.key, wheel, cell});
    }
}

}  // namespace terra::dynamics
