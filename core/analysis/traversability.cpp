#include "core/analysis/traversability.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <stdexcept>

#include "core/analysis/traction.h"
#include "core/common/range.h"
#include "core/common/units.h"
#include "core/contact/contact_parameters.h"
#include "core/field/field_summary.h"
#include "core/io/declared_json.h"
#include "core/io/json_reader.h"
#include "core/scenario/map_image.h"
#include "core/scenario/map_layers.h"

namespace terra::analysis {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// Loads are binned to this fraction of the level-ground load (T3): 0.25 %.
constexpr double kLoadBin = 0.0025;

// The F_x(s) curve of one soil at one load (T2), on evenly spaced slips.
struct Curve {
    std::vector<double> slip, fx;  // only points with an equilibrium
};

// The slip needed for the pull `pull_n` on a curve: the first crossing, interpolated (T2).
std::pair<TraverseStatus, double> slipFor(const Curve& c, double pull_n, double slip_min) {
    if (c.slip.empty()) return {TraverseStatus::kStall, kNaN};
    if (pull_n <= c.fx.front()) {
        if (pull_n < 0.0) return {TraverseStatus::kBraking, kNaN};
        return {TraverseStatus::kOk, slip_min};  // at most s_min (a bound)
    }
    for (std::size_t i = 1; i < c.fx.size(); ++i) {
        if (c.fx[i] >= pull_n) {
            const double t = (pull_n - c.fx[i - 1]) / (c.fx[i] - c.fx[i - 1]);
            return {TraverseStatus::kOk, c.slip[i - 1] + t * (c.slip[i] - c.slip[i - 1])};
        }
    }
    return {TraverseStatus::kStall, kNaN};
}

}  // namespace

const char* statusName(TraverseStatus status) {
    switch (status) {
        case TraverseStatus::kOk:
            return "ok";
        case TraverseStatus::kStall:
            return "stall";
        case TraverseStatus::kBraking:
            return "braking";
    }
    return "?";
}

std::vector<Issue> traversabilityRuleIssues(const TraversabilitySettings& s) {
    std::vector<Issue> issues;
    if (kTraversabilitySlipRange.contains(s.slip_min) &&
        kTraversabilitySlipRange.contains(s.slip_max) && !(s.slip_min < s.slip_max)) {
        issues.push_back({"slip_max", formatNumber(s.slip_max) +
                                          " must be above slip_min = " + formatNumber(s.slip_min)});
    }
    return issues;
}

void readTraversabilitySettings(io::ObjectReader& r, TraversabilitySettings& out) {
    io::readFields(r, out);
    for (Issue& issue : traversabilityRuleIssues(out))
        r.report(issue.where, std::move(issue.message));
}

nlohmann::json toJson(const TraversabilitySettings& s) { return io::fieldsToJson(s); }

TraversabilityResult computeTraversability(const field::FieldMap& field,
                                           const dynamics::RobotParameters& robot,
                                           const TraversabilitySettings& s,
                                           const Control& control) {
    // The reader's checks, in its words, for settings built in code (Python's, a test's).
    std::vector<Issue> settings_issues = io::fieldIssues(s);
    for (Issue& issue : traversabilityRuleIssues(s)) settings_issues.push_back(std::move(issue));
    if (!settings_issues.empty()) throw std::invalid_argument(formatIssues(settings_issues));
    if (std::vector<Issue> issues = wheel::validate(robot.wheel); !issues.empty())
        throw std::invalid_argument(formatIssues(issues));
    const std::optional<std::array<double, 4>> box = field::extent(field);
    if (!box)
        throw std::invalid_argument(
            "the field has no map (height, classes or parameters) to cover");
    // Plain names, not a structured binding: clang 14 (the CI's check) cannot capture a binding.
    const double x_min = (*box)[0];
    const double y_min = (*box)[1];
    const double x_max = (*box)[2];
    const double y_max = (*box)[3];
    TraversabilityResult out;
    out.robot_mass_kg = robot.totalMass();
    const double cell = s.cell_m           ? *s.cell_m
                        : field.height     ? field.height->cell_m
                        : field.soil_class ? field.soil_class->cell_m
                                           : 1.0;
    const int cols = std::max(1, static_cast<int>(std::ceil((x_max - x_min) / cell - 1e-9)));
    const int rows = std::max(1, static_cast<int>(std::ceil((y_max - y_min) / cell - 1e-9)));
    // Every map of the result on the same cells.
    const auto blank = [&](double fill) {
        return field::makeRaster(cols, rows, x_min, y_min, cell, fill);
    };
    out.grid = blank(0.0);
    out.worst_slip = blank(kNaN);
    out.stall_share = blank(0.0);
    for (int h = 0; h < s.headings; ++h) {
        HeadingMap m;
        m.heading_rad = 2.0 * std::numbers::pi * h / s.headings;
        m.slip = blank(kNaN);
        m.status = blank(0.0);
        out.headings.push_back(std::move(m));
    }

    // T1: one wheel's share of the weight; T3: curves per soil and load bin.
    const double level_load = out.robot_mass_kg * units::kGravity / dynamics::kWheelCount;
    const double bin = kLoadBin * level_load;
    TractionSettings ts;
    ts.slip_min = s.slip_min;
    ts.slip_max = s.slip_max;
    ts.model = s.model;
    const contact::ContactModel model =
        s.quadratic ? contact::ContactModel::kQuadratic : contact::ContactModel::kFull;
    std::map<std::vector<double>, int> soil_ids;
    std::vector<contact::ContactParameters<double>> soil_params;
    std::map<std::pair<int, long>, Curve> curves;
    const auto curveFor = [&](int soil_id, long load_bin) -> const Curve& {
        auto [it, added] = curves.try_emplace({soil_id, load_bin});
        if (added) {
            for (int i = 0; i < s.curve_points; ++i) {
                const double slip =
                    s.slip_min + (s.slip_max - s.slip_min) * i / (s.curve_points - 1);
                const TractionPoint p =
                    tractionPoint(soil_params[soil_id], load_bin * bin, slip, ts, model);
                if (!p.ok) continue;
                it->second.slip.push_back(slip);
                it->second.fx.push_back(p.fx_n);
            }
        }
        return it->second;
    };

    for (int row = 0; row < rows; ++row) {
        if (control.cancelled()) {
            out.cancelled = true;
            break;
        }
        for (int col = 0; col < cols; ++col) {
            const double x = out.grid.centreX(col), y = out.grid.centreY(row);
            out.grid.value(col, row) = units::radToDeg(field.slopeAt(x, y));
            const soil::SoilParameters soil = field.soilAt(x, y);
            std::vector<double> key;
            for (const soil::SoilField& f : soil::soilFields()) key.push_back(soil.*f.member);
            auto [id, added] = soil_ids.try_emplace(key, static_cast<int>(soil_params.size()));
            if (added) soil_params.push_back(contact::makeContactParameters(soil, robot.wheel));
            int stalls = 0;
            double worst = kNaN;
            for (HeadingMap& m : out.headings) {
                const field::LocalSlope slope = field.slopeUnder(x, y, m.heading_rad);
                const double load =
                    level_load * std::cos(slope.grade_rad) * std::cos(slope.cross_rad);
                const double pull = level_load * std::sin(slope.grade_rad);
                const long load_bin = std::max(1L, std::lround(load / bin));
                // The pull scaled to the bin's load (F_x ∝ W to first order; T3).
                const auto [status, slip] = slipFor(curveFor(id->second, load_bin),
                                                    pull * (load_bin * bin) / load, s.slip_min);
                m.status.value(col, row) = static_cast<double>(status);
                m.slip.value(col, row) = slip;
                if (status == TraverseStatus::kStall) {
                    ++m.stalled;
                    ++stalls;
                } else if (status == TraverseStatus::kBraking) {
                    ++m.braking;
                } else if (std::isnan(worst) || slip > worst) {
                    worst = slip;
                }
            }
            out.worst_slip.value(col, row) = worst;
            out.stall_share.value(col, row) = static_cast<double>(stalls) / s.headings;
        }
        control.report(static_cast<double>(row + 1) / rows);
    }
    out.curves = static_cast<int>(curves.size());
    return out;
}

nlohmann::json toJson(const TraversabilityResult& r) {
    nlohmann::json headings = nlohmann::json::array();
    double max_slip = kNaN;
    for (const HeadingMap& m : r.headings) {
        const auto [lo, hi] = m.slip.valueRange();
        (void)lo;
        headings.push_back(
            {{"heading_deg", units::radToDeg(m.heading_rad)},
             {"stalled", m.stalled},
             {"braking", m.braking},
             {"max_slip", std::isnan(hi) ? nlohmann::json(nullptr) : nlohmann::json(hi)}});
        if (!std::isnan(hi) && (std::isnan(max_slip) || hi > max_slip)) max_slip = hi;
    }
    std::size_t stall_cells = 0;
    for (double v : r.stall_share.values) stall_cells += v > 0.0 ? 1 : 0;
    return {{"cells", r.grid.values.size()},
            {"cell_m", r.grid.cell_m},
            {"headings", headings},
            {"stall_cells", stall_cells},
            {"max_slip", std::isnan(max_slip) ? nlohmann::json(nullptr) : nlohmann::json(max_slip)},
            {"robot_mass_kg", r.robot_mass_kg},
            {"curves", r.curves},
            {"cancelled", r.cancelled}};
}

Summary traversabilitySummary(const TraversabilityResult& r) {
    using Emphasis = SummaryRow::Emphasis;
    const nlohmann::json j = toJson(r);
    Summary out;
    out.push_back({"traversability", formatNumber(r.robot_mass_kg) + " kg robot", "",
                   std::to_string(r.grid.cols) + " x " + std::to_string(r.grid.rows) +
                       " cells of " + formatNumber(r.grid.cell_m) + " m, " +
                       std::to_string(r.curves) + " slip curves",
                   Emphasis::kHeading, ""});
    if (r.cancelled) out.push_back({"status", "cancelled", "", "", Emphasis::kWarning, ""});
    const auto count = [&](std::string label, const std::string& pointer) {
        const double n = j.at(nlohmann::json::json_pointer(pointer)).get<double>();
        out.push_back({std::move(label), std::to_string(static_cast<long long>(n)), "", "",
                       Emphasis::kNormal, pointer, n});
    };
    count("cells", "/cells");
    count("cells where a heading stalls", "/stall_cells");
    // The largest slip needed: none where every cell and heading stalls or brakes.
    auto slip = [&](std::string label, const std::string& pointer, std::string detail) {
        const nlohmann::json& v = j.at(nlohmann::json::json_pointer(pointer));
        if (v.is_null()) {
            out.push_back({std::move(label), "none", "", std::move(detail), Emphasis::kNormal, ""});
        } else {
            out.push_back({std::move(label), formatFixed(v.get<double>(), 3), "", std::move(detail),
                           Emphasis::kNormal, pointer, v.get<double>()});
        }
    };
    slip("largest slip", "/max_slip", "");
    for (std::size_t k = 0; k < r.headings.size(); ++k) {
        const std::string at = "/headings/" + std::to_string(k);
        const HeadingMap& m = r.headings[k];
        const std::string heading =
            "heading " +
            formatFixed(j.at(nlohmann::json::json_pointer(at + "/heading_deg")).get<double>(), 1) +
            " deg";
        count(heading + ", stalled cells", at + "/stalled");
        out.back().detail = std::to_string(m.braking) + " braking";
        slip(heading + ", largest slip", at + "/max_slip", "");
    }
    return out;
}

Table traversabilityTable(const TraversabilityResult& r, const field::FieldMap& field) {
    Table t;
    t.columns = {"x_m", "y_m", "heading_deg", "grade_deg", "slip", "status"};
    for (int row = 0; row < r.grid.rows; ++row) {
        for (int col = 0; col < r.grid.cols; ++col) {
            const double x = r.grid.centreX(col), y = r.grid.centreY(row);
            for (const HeadingMap& m : r.headings) {
                t.rows.push_back({x, y, units::radToDeg(m.heading_rad),
                                  units::radToDeg(field.slopeUnder(x, y, m.heading_rad).grade_rad),
                                  m.slip.value(col, row), m.status.value(col, row)});
            }
        }
    }
    return t;
}

io::RgbaImage traversabilityImage(const TraversabilityResult& result) {
    field::Raster slip = result.worst_slip;
    for (std::size_t i = 0; i < slip.values.size(); ++i) {
        // No slip holds the speed on any heading: the worst there is.
        if (std::isnan(slip.values[i]) && !std::isnan(result.grid.values[i])) slip.values[i] = 1.0;
    }
    scenario::MapLayer layer;
    layer.key = "slip";
    layer.label = "largest slip needed (1 is a stall)";  // the PNG font has no "," or "="
    layer.unit = "-";
    scenario::LayerScale scale = scenario::layerScale(layer, slip);
    scale.lower = 0.0;
    scale.upper = 1.0;
    return scenario::renderMap(layer, scale, slip);
}

}  // namespace terra::analysis
