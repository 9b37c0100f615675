#include "core/project/saved_rover.h"

#include <stdexcept>

#include "core/project/result_json.h"

namespace terra::project::saved {

template <>
struct Fields<scenario::MissionOutcome> {
    template <typename V>
    static void visit(V& v, scenario::MissionOutcome& m) {
        v("completed", m.completed);
        v("path_length_m", m.path_length_m);
        v("progress_m", m.progress_m);
        v("error_rms_m", m.error_rms_m);
        v("error_max_m", m.error_max_m);
        v("time_s", m.time_s);
    }
};

template <>
struct Fields<scenario::Summary> {
    template <typename V>
    static void visit(V& v, scenario::Summary& s) {
        v("duration_s", s.duration_s);
        v("x_m", s.x_m);
        v("y_m", s.y_m);
        v("yaw_rad", s.yaw_rad);
        v("distance_m", s.distance_m);
        v("mean_slip", s.mean_slip);
        v("energy_j", s.energy_j);
        v("dissipated_j", s.dissipated_j);
        v("kinetic_change_j", s.kinetic_change_j);
        v("potential_change_j", s.potential_change_j);
        v("energy_balance_error", s.energy_balance_error);
        v("max_sinkage_m", s.max_sinkage_m);
        v("sunk_steps", s.sunk_steps);
        v("steps", s.steps);
        // Optional keys the old reader also took absent (kSince): the first three have always
        // been written; the rest came with the traction-limited mode and the field rover.
        v("energy_per_m_j", s.energy_per_m_j, kSince);
        v("mean_efficiency", s.mean_efficiency, kSince);
        v("slip_tracking_rms", s.slip_tracking_rms, kSince);
        v("traction_limited_switches", s.traction_limited_switches, kSince);
        v("traction_limited_s", s.traction_limited_s, kSince);
        v("real_time_factor", s.real_time_factor, kSince);
        v("cells_touched", s.cells_touched, kSince);
        v("mission", s.mission, kSince);  // null: a run without a mission
    }
};

template <>
struct Fields<scenario::TractionMetrics> {
    template <typename V>
    static void visit(V& v, scenario::TractionMetrics& t) {
        v("drive_energy_j", t.drive_energy_j);
        v("wheel_output_j", t.wheel_output_j);
        v("wheel_input_j", t.wheel_input_j);
        v("drawbar_work_j", t.drawbar_work_j);
        v("slip_error_sq_sum", t.slip_error_sq_sum);
        v("slip_error_count", t.slip_error_count);
        v("rear_sinkage_sum_m", t.rear_sinkage_sum_m);
        v("rear_sinkage_count", t.rear_sinkage_count);
        v("border_time_s", t.border_time_s, kSince);
        v("settling_time_s", t.settling_time_s, kSince);
        v("settling_band_time_s", t.settling_band_time_s, kSince);
        v("settle_band", t.settle_band, kSince);
        v("limit_switches", t.limit_switches, kSince);
        v("limited_time_s", t.limited_time_s, kSince);
        // Not saved: `plans` (each with its request's soil and posterior); the set-points they
        // gave are the series' <wheel>_slip_plan columns.
    }
};

/// A map of a field run (its coordinate system is the scenario's, not saved).
template <>
struct Fields<field::Raster> {
    template <typename V>
    static void visit(V& v, field::Raster& r) {
        v("cols", r.cols);
        v("rows", r.rows);
        v("x_min_m", r.x_min_m);
        v("y_min_m", r.y_min_m);
        v("cell_m", r.cell_m);
        v("values", r.values);
    }
};

}  // namespace terra::project::saved

namespace terra::project {
namespace {

using nlohmann::json;
using saved::fieldsFrom;
using saved::fieldsJson;
using saved::number;
using saved::numberAt;
using saved::readKey;

using Numbers = saved::Value<std::vector<double>>;

constexpr const char* kStatus[] = {"completed", "cancelled", "diverged"};

std::vector<double> numbersFrom(const json& j) {
    std::vector<double> out;
    Numbers::read(j, out);
    return out;
}

field::Raster rasterFrom(const json& j) {
    field::Raster r = fieldsFrom<field::Raster>(j);
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
    for (const auto& [key, raster] : scenario::mapRasters(m)) rasters[key] = fieldsJson(*raster);
    json values = json::object();
    for (const auto& [key, v] : m.history.values) values[key] = Numbers::write(v);
    return {{"risk_depth_m", number(m.risk_depth_m)},
            {"rasters", std::move(rasters)},
            {"history",
             {{"time_s", Numbers::write(m.history.time_s)},
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
            {"summary", fieldsJson(r.run.summary)},
            {"streaming", saved::tableJson(r.run.streaming)},
            {"traction", fieldsJson(r.run.traction)},
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
        r.run.summary = readKey(j, "summary", fieldsFrom<scenario::Summary>);
        r.run.streaming = readKey(j, "streaming", saved::tableFrom);
        r.run.traction = readKey(j, "traction", fieldsFrom<scenario::TractionMetrics>);
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
