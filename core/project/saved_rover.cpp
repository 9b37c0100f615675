#include "core/project/saved_rover.h"

#include <stdexcept>

#include "core/project/result_json.h"

namespace terra::project {
namespace {

using nlohmann::json;
using saved::number;
using saved::numberAt;
using saved::optionalAt;
using saved::optionalJson;
using saved::readKey;

constexpr const char* kStatus[] = {"completed", "cancelled", "diverged"};

json missionJson(const std::optional<scenario::MissionOutcome>& m) {
    if (!m) return nullptr;
    return {{"completed", m->completed},
            {"path_length_m", number(m->path_length_m)},
            {"progress_m", number(m->progress_m)},
            {"error_rms_m", number(m->error_rms_m)},
            {"error_max_m", number(m->error_max_m)},
            {"time_s", optionalJson(m->time_s)}};
}

std::optional<scenario::MissionOutcome> missionFrom(const json& j) {
    // A file written before missions has no key; a run without a mission null.
    if (!j.contains("mission") || j.at("mission").is_null()) return std::nullopt;
    const json& m = j.at("mission");
    scenario::MissionOutcome o;
    o.completed = m.at("completed").get<bool>();
    o.path_length_m = numberAt(m, "path_length_m");
    o.progress_m = numberAt(m, "progress_m");
    o.error_rms_m = numberAt(m, "error_rms_m");
    o.error_max_m = numberAt(m, "error_max_m");
    o.time_s = optionalAt(m, "time_s");
    return o;
}

json summaryJson(const scenario::Summary& s) {
    return {{"duration_s", number(s.duration_s)},
            {"x_m", number(s.x_m)},
            {"y_m", number(s.y_m)},
            {"yaw_rad", number(s.yaw_rad)},
            {"distance_m", number(s.distance_m)},
            {"mean_slip", saved::arrayJson(s.mean_slip)},
            {"energy_j", number(s.energy_j)},
            {"dissipated_j", number(s.dissipated_j)},
            {"kinetic_change_j", number(s.kinetic_change_j)},
            {"potential_change_j", number(s.potential_change_j)},
            {"energy_balance_error", number(s.energy_balance_error)},
            {"max_sinkage_m", number(s.max_sinkage_m)},
            {"sunk_steps", s.sunk_steps},
            {"steps", s.steps},
            {"energy_per_m_j", optionalJson(s.energy_per_m_j)},
            {"mean_efficiency", optionalJson(s.mean_efficiency)},
            {"slip_tracking_rms", optionalJson(s.slip_tracking_rms)},
            {"real_time_factor", optionalJson(s.real_time_factor)},
            {"cells_touched", s.cells_touched ? json(*s.cells_touched) : json(nullptr)},
            {"mission", missionJson(s.mission)}};
}

scenario::Summary summaryFrom(const json& j) {
    scenario::Summary s;
    s.duration_s = numberAt(j, "duration_s");
    s.x_m = numberAt(j, "x_m");
    s.y_m = numberAt(j, "y_m");
    s.yaw_rad = numberAt(j, "yaw_rad");
    s.distance_m = numberAt(j, "distance_m");
    s.mean_slip = saved::arrayFrom<dynamics::kWheelCount>(j.at("mean_slip"));
    s.energy_j = numberAt(j, "energy_j");
    s.dissipated_j = numberAt(j, "dissipated_j");
    s.kinetic_change_j = numberAt(j, "kinetic_change_j");
    s.potential_change_j = numberAt(j, "potential_change_j");
    s.energy_balance_error = numberAt(j, "energy_balance_error");
    s.max_sinkage_m = numberAt(j, "max_sinkage_m");
    s.sunk_steps = j.at("sunk_steps").get<int>();
    s.steps = j.at("steps").get<long>();
    s.energy_per_m_j = optionalAt(j, "energy_per_m_j");
    s.mean_efficiency = optionalAt(j, "mean_efficiency");
    s.slip_tracking_rms = optionalAt(j, "slip_tracking_rms");
    // Both keys came with the field rover: a file written before them has neither.
    s.real_time_factor = optionalAt(j, "real_time_factor");
    if (const std::optional<double> cells = optionalAt(j, "cells_touched"))
        s.cells_touched = static_cast<long>(*cells);
    s.mission = missionFrom(j);
    return s;
}

json tractionJson(const scenario::TractionMetrics& t) {
    return {{"drive_energy_j", number(t.drive_energy_j)},
            {"wheel_output_j", number(t.wheel_output_j)},
            {"wheel_input_j", number(t.wheel_input_j)},
            {"drawbar_work_j", number(t.drawbar_work_j)},
            {"slip_error_sq_sum", number(t.slip_error_sq_sum)},
            {"slip_error_count", t.slip_error_count},
            {"rear_sinkage_sum_m", number(t.rear_sinkage_sum_m)},
            {"rear_sinkage_count", t.rear_sinkage_count},
            {"border_time_s", optionalJson(t.border_time_s)},
            {"settling_time_s", optionalJson(t.settling_time_s)}};
}

scenario::TractionMetrics tractionFrom(const json& j) {
    scenario::TractionMetrics t;
    t.drive_energy_j = numberAt(j, "drive_energy_j");
    t.wheel_output_j = numberAt(j, "wheel_output_j");
    t.wheel_input_j = numberAt(j, "wheel_input_j");
    t.drawbar_work_j = numberAt(j, "drawbar_work_j");
    t.slip_error_sq_sum = numberAt(j, "slip_error_sq_sum");
    t.slip_error_count = j.at("slip_error_count").get<long>();
    t.rear_sinkage_sum_m = numberAt(j, "rear_sinkage_sum_m");
    t.rear_sinkage_count = j.at("rear_sinkage_count").get<long>();
    t.border_time_s = optionalAt(j, "border_time_s");
    t.settling_time_s = optionalAt(j, "settling_time_s");
    return t;
}

std::vector<double> numbersFrom(const json& j) {
    if (!j.is_array()) throw std::invalid_argument("expected an array of numbers");
    std::vector<double> out;
    out.reserve(j.size());
    for (const json& v : j) out.push_back(saved::numberOf(v));
    return out;
}

json numbersJson(const std::vector<double>& values) {
    json out = json::array();
    for (double v : values) out.push_back(number(v));
    return out;
}

json rasterJson(const field::Raster& r) {
    return {{"cols", r.cols},
            {"rows", r.rows},
            {"x_min_m", number(r.x_min_m)},
            {"y_min_m", number(r.y_min_m)},
            {"cell_m", number(r.cell_m)},
            {"values", numbersJson(r.values)}};
}

field::Raster rasterFrom(const json& j) {
    field::Raster r;
    r.cols = j.at("cols").get<int>();
    r.rows = j.at("rows").get<int>();
    r.x_min_m = numberAt(j, "x_min_m");
    r.y_min_m = numberAt(j, "y_min_m");
    r.cell_m = numberAt(j, "cell_m");
    r.values = readKey(j, "values", numbersFrom);
    if (r.cols < 0 || r.rows < 0 ||
        r.values.size() != static_cast<std::size_t>(r.cols) * static_cast<std::size_t>(r.rows))
        throw std::invalid_argument(std::to_string(r.values.size()) + " values for " +
                                    std::to_string(r.cols) + " × " + std::to_string(r.rows) +
                                    " cells");
    return r;
}

// A field run's maps: the rasters by key (mapRasters) and the history.
json mapsJson(const scenario::FieldMaps& m) {
    json rasters = json::object();
    for (const auto& [key, raster] : scenario::mapRasters(m)) rasters[key] = rasterJson(*raster);
    json values = json::object();
    for (const auto& [key, v] : m.history.values) values[key] = numbersJson(v);
    return {{"risk_depth_m", number(m.risk_depth_m)},
            {"rasters", std::move(rasters)},
            {"history",
             {{"time_s", numbersJson(m.history.time_s)},
              {"cell", m.history.cell},
              {"values", std::move(values)}}}};
}

scenario::FieldMaps mapsFrom(const json& j) {
    scenario::FieldMaps m;
    m.risk_depth_m = numberAt(j, "risk_depth_m");
    const json& rasters = j.at("rasters");
    std::size_t cells = 0;
    bool first = true;
    // A map this version draws but the file does not hold (saved before it existed) stays empty:
    // the studio lists no layer without cells.
    for (const auto& [key, raster] : scenario::mapRasters(m)) {
        if (!rasters.contains(key)) continue;
        *raster = readKey(rasters, key.c_str(), rasterFrom);
        const std::size_t n = raster->values.size();
        if (!first && n != cells)
            throw std::invalid_argument("rasters: " + key + " holds " + std::to_string(n) +
                                        " cells, the others " + std::to_string(cells));
        cells = n, first = false;
    }
    const json& h = j.at("history");
    scenario::MapHistory& out = m.history;
    out.time_s = readKey(h, "time_s", numbersFrom);
    out.cell = h.at("cell").get<std::vector<std::int32_t>>();
    if (out.cell.size() != out.time_s.size())
        throw std::invalid_argument("history: " + std::to_string(out.cell.size()) + " cells for " +
                                    std::to_string(out.time_s.size()) + " times");
    for (std::size_t i = 0; i < out.size(); ++i) {
        if (out.cell[i] < 0 || static_cast<std::size_t>(out.cell[i]) >= cells)
            throw std::invalid_argument("history: cell " + std::to_string(out.cell[i]) +
                                        " is outside the maps' " + std::to_string(cells) +
                                        " cells");
        if (i > 0 && !(out.time_s[i] >= out.time_s[i - 1]))
            throw std::invalid_argument("history: the times are not in order at passage " +
                                        std::to_string(i));
    }
    for (const auto& [key, values] : h.at("values").items()) {
        out.values[key] = numbersFrom(values);
        if (out.values[key].size() != out.size())
            throw std::invalid_argument("history: " + key + " holds " +
                                        std::to_string(out.values[key].size()) + " values for " +
                                        std::to_string(out.size()) + " passages");
    }
    return m;
}

}  // namespace

json savedJson(const SavedRoverRun& r) {
    return {{"status", kStatus[static_cast<int>(r.run.status)]},
            {"message", r.run.message},
            {"series", saved::tableJson(r.run.series)},
            {"summary", summaryJson(r.run.summary)},
            {"streaming", saved::tableJson(r.run.streaming)},
            {"traction", tractionJson(r.run.traction)},
            {"scenario_name", r.scenario_name},
            {"scenario", r.scenario},
            {"maps", r.run.maps ? mapsJson(*r.run.maps) : json(nullptr)}};
}

Result<SavedRoverRun> savedRoverRunFromJson(const json& j, const std::string& where) {
    try {
        SavedRoverRun r;
        const std::string status = j.at("status").get<std::string>();
        bool known = false;
        for (int i = 0; i < 3; ++i) {
            if (status != kStatus[i]) continue;
            r.run.status = static_cast<scenario::RunResult::Status>(i);
            known = true;
        }
        if (!known)
            return std::vector<Issue>{{where + ".status", "\"" + status +
                                                              "\" is not completed, cancelled "
                                                              "or diverged"}};
        r.run.message = j.at("message").get<std::string>();
        r.run.series = readKey(j, "series", saved::tableFrom);
        r.run.summary = readKey(j, "summary", summaryFrom);
        r.run.streaming = readKey(j, "streaming", saved::tableFrom);
        r.run.traction = readKey(j, "traction", tractionFrom);
        // A patch run, or a file written before field runs kept their maps: none.
        if (j.contains("maps") && !j["maps"].is_null()) r.run.maps = readKey(j, "maps", mapsFrom);
        r.scenario_name = j.at("scenario_name").get<std::string>();
        r.scenario = j.at("scenario");
        if (!r.scenario.is_object())
            return std::vector<Issue>{{where + ".scenario", "not a scenario object"}};
        return r;
    } catch (const std::exception& e) {
        return std::vector<Issue>{{where, e.what()}};
    }
}

}  // namespace terra::project
