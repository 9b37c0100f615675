#include "core/scenario/scenario_json.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>

#include "core/common/quoted.h"
#include "core/common/range.h"
#include "core/common/units.h"
#include "core/io/atomic_file.h"
#include "core/io/csv.h"
#include "core/io/field_json.h"
#include "core/io/json.h"

namespace terra::scenario {
namespace {

using io::ObjectReader;
using io::Presence;
using nlohmann::json;
namespace fs = std::filesystem;

// A preset name or a path; relative paths also tried against base_dir.
std::string locate(const std::string& name_or_path, const fs::path& base_dir) {
    std::error_code ec;
    const bool looks_like_path = name_or_path.find('/') != std::string::npos ||
                                 fs::path(name_or_path).extension() == ".json";
    if (looks_like_path && !base_dir.empty() && fs::path(name_or_path).is_relative() &&
        fs::is_regular_file(base_dir / name_or_path, ec)) {
        return (base_dir / name_or_path).string();
    }
    return name_or_path;
}

// The issues of a resolved file or preset, reported at `key` of `r`.
void reportAt(ObjectReader& r, const std::string& key, const std::vector<Issue>& issues) {
    for (const Issue& issue : issues)
        r.report(key, (issue.where.empty() ? "" : issue.where + ": ") + issue.message);
}

// A signal at `key`: a number (constant) or {"type": ..., ...}; `scale` converts file units to SI.
std::optional<Signal> readSignal(ObjectReader& parent, const std::string& key, const Range& range,
                                 const std::string& unit, double scale) {
    const json* value = parent.value(key);
    if (value == nullptr) return std::nullopt;
    Signal signal;
    const std::size_t before = parent.issues().size();
    if (value->is_number()) {
        double v = 0.0;
        parent.number(key, v, range, unit);
        signal.value = v * scale;
        return signal;
    }
    if (!value->is_object()) {
        parent.report(key,
                      "expected a number or an object {\"type\": constant|step|pulse|ramp|"
                      "table, ...}, got " +
                          io::describeJson(*value));
        return std::nullopt;
    }
    ObjectReader r = parent.object(key);
    std::string type = "constant";
    if (!r.choiceName("type", type, {"constant", "step", "pulse", "ramp", "table"}) &&
        r.has("type")) {
        return std::nullopt;  // the other keys depend on the type: nothing more to say
    }
    const Range any{-1e9, 1e9};
    const Range time{0.0, 1e6};
    if (type == "constant") {
        r.number("value", signal.value, range, unit, Presence::kRequired);
    } else if (type == "step" || type == "pulse" || type == "ramp") {
        signal.kind = type == "step"    ? Signal::Kind::kStep
                      : type == "pulse" ? Signal::Kind::kPulse
                                        : Signal::Kind::kRamp;
        r.number("value", signal.value, range, unit);
        r.number("amplitude", signal.amplitude, any, unit, Presence::kRequired);
        r.number("start_s", signal.start_s, time, "s", Presence::kRequired);
        if (type != "step") {
            r.number("duration_s", signal.duration_s, time, "s", Presence::kRequired);
        }
        if (parent.issues().size() == before) {
            std::vector<Issue> sum;
            if (!checkRange(sum, "", signal.value + signal.amplitude, range, unit))
                r.report("", "(value + amplitude) " + sum.front().message);
        }
        signal.amplitude *= scale;
    } else if (type == "table") {
        signal.kind = Signal::Kind::kTable;
        const json* t = r.value("t_s");
        const json* v = r.value("values");
        if (t == nullptr || v == nullptr || !t->is_array() || !v->is_array() ||
            t->size() != v->size() || t->empty()) {
            r.report("", "a table needs arrays t_s and values of the same, non-zero length");
            r.finish();
            return std::nullopt;
        }
        for (std::size_t i = 0; i < t->size(); ++i) {
            const std::string at = "t_s[" + std::to_string(i) + "]";
            if (!(*t)[i].is_number() || !(*v)[i].is_number()) {
                r.report(at, "t_s and values must hold numbers");
                continue;
            }
            const double ti = (*t)[i].get<double>(), vi = (*v)[i].get<double>();
            std::vector<Issue> time_issues;
            if (!checkRange(time_issues, "", ti, time, "s")) {
                r.report(at, time_issues.front().message);
            } else if (!signal.times_s.empty() && !(ti > signal.times_s.back())) {
                r.report(at, "t_s = " + formatNumber(ti) +
                                 " must be greater than the previous time " +
                                 formatNumber(signal.times_s.back()));
            }
            std::vector<Issue> value_issues;
            if (!checkRange(value_issues, "", vi, range, unit))
                r.report("values[" + std::to_string(i) + "]", value_issues.front().message);
            signal.times_s.push_back(ti);
            signal.values.push_back(vi);
        }
    }
    r.finish();
    signal.value *= scale;
    for (double& v : signal.values) v *= scale;
    if (parent.issues().size() != before) return std::nullopt;
    return signal;
}

// A soil at `key`: a preset name, a file (relative to base_dir) or an inline soil object.
void readTerrainSoil(ObjectReader& r, const std::string& key, const io::PresetLocations& locations,
                     const fs::path& base_dir, soil::SoilParameters& out) {
    const json* v = r.value(key, Presence::kRequired, "a soil preset name, a file or an object");
    if (v == nullptr) return;
    if (v->is_string()) {
        Result<soil::SoilParameters> resolved =
            io::resolveSoil(locations, locate(v->get<std::string>(), base_dir));
        if (resolved) {
            out = resolved.value();
        } else {
            reportAt(r, key, resolved.issues());
        }
    } else if (v->is_object()) {
        ObjectReader soil = r.object(key);
        out = io::readSoil(soil);
        soil.finish();
    } else {
        r.report(key,
                 "expected a soil preset name, a file or an object, got " + io::describeJson(*v));
    }
}

// The keys of a field terrain (docs/field.md, "Field scenarios").
bool isFieldTerrain(const json& value) {
    return value.is_object() && (value.contains("height") || value.contains("soils") ||
                                 value.contains("legend") || value.contains("field"));
}

// A field terrain: {"height", "soils", "legend", "soil"} (rasters relative to the scenario) or
// {"field": FIELD.json}, with the memory's options. The maps are read by the field files' reader
// (io::fieldFromJson), with the scenario's key "soils" for its "soil_classes".
void readFieldTerrain(ObjectReader& r, const io::PresetLocations& locations,
                      const fs::path& base_dir, Scenario& s) {
    const json& value = *r.value("terrain");
    ObjectReader t = r.object("terrain");
    const std::string where = t.where("");
    Result<io::FieldFile> file = std::vector<Issue>{};
    if (value.contains("field")) {
        std::string path;
        t.text("field", path, Presence::kRequired);
        for (const char* key : {"height", "soils", "legend", "soil"}) {
            if (value.contains(key)) {
                t.allow(key);
                t.report(key, "give the maps either in the scenario or in \"field\", not both");
            }
        }
        const fs::path located =
            fs::path(path).is_relative() && !base_dir.empty() ? base_dir / path : fs::path(path);
        file = io::loadField(located, locations);
    } else {
        json field = json::object();
        for (const auto& [from, to] :
             std::initializer_list<std::pair<const char*, const char*>>{{"height", "height"},
                                                                        {"soils", "soil_classes"},
                                                                        {"legend", "legend"},
                                                                        {"soil", "soil"},
                                                                        {"name", "name"}}) {
            if (value.contains(from)) field[to] = value.at(from);
            t.allow(from);
        }
        // Without "soil", the soil outside the class map is the lowest class's.
        if (!field.contains("soil") && field.contains("legend") && field["legend"].is_object() &&
            !field["legend"].empty()) {
            const json* lowest = nullptr;
            double lowest_code = std::numeric_limits<double>::infinity();
            for (const auto& [code, entry] : field["legend"].items()) {
                double c = 0.0;
                if (io::parseNumber(code, c) && c < lowest_code) lowest_code = c, lowest = &entry;
            }
            if (lowest != nullptr)
                field["soil"] =
                    lowest->is_object() && lowest->contains("soil") ? lowest->at("soil") : *lowest;
        }
        if (!field.contains("soils") && !field.contains("soil_classes") &&
            !field.contains("soil")) {
            t.report("soils",
                     "missing: a field terrain needs \"soils\" and \"legend\" (or "
                     "\"soil\" for one soil everywhere)");
        }
        file = io::fieldFromJson(field, where.empty() ? "terrain" : where, base_dir, locations);
    }
    if (!file) {
        for (Issue issue : file.issues()) {
            // The scenario's names for the field file's keys.
            for (std::string* text : {&issue.where, &issue.message}) {
                for (std::size_t at = text->find("soil_classes"); at != std::string::npos;
                     at = text->find("soil_classes", at))
                    text->replace(at, 12, "soils");
            }
            t.issues().push_back(std::move(issue));
        }
    } else {
        io::FieldFile f = std::move(file).value();
        // The maps must cover the same ground (F1: a wheel reads both at one point).
        if (f.map.height && f.map.soil_class) {
            const field::Raster& h = *f.map.height;
            const field::Raster& c = *f.map.soil_class;
            auto box = [](const field::Raster& m) {
                return "[" + formatNumber(m.x_min_m) + ", " + formatNumber(m.y_min_m) + "] to [" +
                       formatNumber(m.xMax()) + ", " + formatNumber(m.yMax()) + "] m";
            };
            const double tolerance = 1e-6 * std::max(h.cell_m, c.cell_m);
            if (std::abs(h.x_min_m - c.x_min_m) > tolerance ||
                std::abs(h.y_min_m - c.y_min_m) > tolerance ||
                std::abs(h.xMax() - c.xMax()) > tolerance ||
                std::abs(h.yMax() - c.yMax()) > tolerance) {
                t.report("soils", "covers " + box(c) + ", the height map " + box(h) +
                                      ": the maps must cover the same ground");
            }
        }
        // ESRI ASCII grids carry their coordinate system in a .prj beside them: two that differ
        // put the maps in different places.
        if (!value.contains("field") && value.contains("height") && value.contains("soils") &&
            value["height"].is_string() && value["soils"].is_string()) {
            auto prj = [&](const std::string& path) {
                fs::path p = fs::path(path).is_relative() && !base_dir.empty() ? base_dir / path
                                                                               : fs::path(path);
                p.replace_extension(".prj");
                std::string text;
                std::error_code ec;
                if (fs::is_regular_file(p, ec)) io::readFile(p, text);
                while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back())))
                    text.pop_back();
                return text;
            };
            const std::string height_prj = prj(value["height"].get<std::string>());
            const std::string soils_prj = prj(value["soils"].get<std::string>());
            if (!height_prj.empty() && !soils_prj.empty() && height_prj != soils_prj) {
                t.report("soils", "its coordinate system (.prj) differs from the height map's");
            }
        }
        s.terrain.base = f.map.base;
        s.field_labels = f.labels;
        s.field = std::make_shared<const field::FieldMap>(std::move(f.map));
    }
    dynamics::FieldTerrainOptions& o = s.field_options;
    t.boolean("repeated_passes", o.repeated_passes);
    t.boolean("shear_memory", o.law.shear_memory);
    t.boolean("across_width", o.across_width);
    t.boolean("read_across_width", o.read_across_width);
    t.number("cell_m", o.cell_m, {0.001, 100.0}, "m");
    double risk_depth = o.stress_depths_m.front();
    if (t.number("risk_depth_m", risk_depth, {0.01, 10.0}, "m")) o.stress_depths_m = {risk_depth};
    t.number("concentration", o.concentration, {2.0, 12.0, true, false});
    t.finish();
}

dynamics::Terrain readTerrain(ObjectReader& r, const io::PresetLocations& locations,
                              const fs::path& base_dir, Scenario& s) {
    dynamics::Terrain terrain;
    const json* value =
        r.value("terrain", Presence::kRequired, "a soil name or {\"soil\", \"patches\"}");
    if (value != nullptr && isFieldTerrain(*value)) {
        readFieldTerrain(r, locations, base_dir, s);
        return s.terrain;
    }
    if (value == nullptr) return terrain;
    if (value->is_string()) {
        readTerrainSoil(r, "terrain", locations, base_dir, terrain.base);
        return terrain;
    }
    if (!value->is_object()) {
        r.report("terrain", "expected a soil name or {\"soil\": ..., \"patches\": [...]}, got " +
                                io::describeJson(*value));
        return terrain;
    }
    ObjectReader t = r.object("terrain");
    readTerrainSoil(t, "soil", locations, base_dir, terrain.base);
    if (const json* patches = t.array("patches")) {
        const double inf = std::numeric_limits<double>::infinity();
        const Range coordinate{-1e6, 1e6};
        for (std::size_t i = 0; i < patches->size(); ++i) {
            ObjectReader p = t.element("patches", *patches, i);
            if (!p.isObject()) continue;
            dynamics::SoilPatch patch;
            readTerrainSoil(p, "soil", locations, base_dir, patch.soil);
            patch.x_min_m = -inf, patch.x_max_m = inf, patch.y_min_m = -inf, patch.y_max_m = inf;
            p.number("x_min_m", patch.x_min_m, coordinate, "m");
            p.number("x_max_m", patch.x_max_m, coordinate, "m");
            p.number("y_min_m", patch.y_min_m, coordinate, "m");
            p.number("y_max_m", patch.y_max_m, coordinate, "m");
            p.finish();
            terrain.patches.push_back(std::move(patch));
        }
    }
    t.finish();
    return terrain;
}

dynamics::RobotParameters readRobot(ObjectReader& r, const io::PresetLocations& locations) {
    dynamics::RobotParameters robot;
    const std::size_t before = r.issues().size();
    r.text("name", robot.name);
    r.text("source", robot.source);
    const json* wheel = r.value("wheel", Presence::kRequired,
                                "a wheel preset (\"A\", \"B\"), a file or an object "
                                "{\"r_m\", \"b_m\"}");
    if (wheel != nullptr && wheel->is_string()) {
        Result<wheel::WheelParameters> w = io::resolveWheel(locations, wheel->get<std::string>());
        if (w) {
            robot.wheel = w.value();
        } else {
            reportAt(r, "wheel", w.issues());
        }
    } else if (wheel != nullptr) {
        ObjectReader w = r.object("wheel");
        robot.wheel = io::readWheel(w);
        w.finish();
    }
    for (const dynamics::RobotField& field : dynamics::robotFields()) {
        r.field(field, robot.*field.member,
                field.required ? Presence::kRequired : Presence::kOptional);
    }
    const FieldInfo& inertia = dynamics::chassisInertiaField();
    std::vector<double> moments;
    if (r.numbers(inertia.key, moments, inertia.range, inertia.displayUnit(), 3, 3,
                  Presence::kRequired)) {
        for (int i = 0; i < 3; ++i) robot.chassis_inertia_kg_m2[i] = moments[i];
    }
    if (r.issues().size() == before) {
        for (Issue& issue : dynamics::validate(robot)) r.report(issue.where, issue.message);
    }
    return robot;
}

const Range kDrawbarForceRange{0.0, 1e5};
const Range kDrawbarPerSpeedRange{0.0, 1e5};

// "controller": {"type": constant-speed|fixed-slip|optimal|oracle, "slip", "objective",
// "slip_min", "slip_max", "max_torque_Nm", "max_omega_rad_s", "min_omega_rad_s", "kp", "ki_per_s",
// "interval_s", "replan_samples", "replan_interval_s", "dither", "dither_period_s",
// "traction_limited", "limit_margin", "robust", "quantile", "posterior_samples",
// "posterior_method", "identifier", "sensors": {...}}
// (docs/traction.md §5, §8).
void readController(ObjectReader& r, ControllerSpec& out) {
    if (!r.has("controller")) {
        r.allow("controller");
        return;
    }
    ObjectReader c = r.object("controller");
    if (!c.isObject()) return;
    std::string type = controllerName(out.type);
    if (c.choiceName("type", type, controllerNames(), Presence::kRequired))
        out.type = *controllerFromName(type);
    const ControllerRanges& range = kControllerRanges;
    c.number("slip", out.slip, range.slip);
    c.choice<SlipObjective>(
        "objective", out.objective,
        {{"efficiency", SlipObjective::kEfficiency}, {"drawbar", SlipObjective::kDrawbar}});
    c.number("slip_min", out.slip_min, range.slip);
    c.number("slip_max", out.slip_max, range.slip);
    c.number("max_torque_Nm", out.max_torque_nm, range.torque, "N·m");
    c.number("max_omega_rad_s", out.max_spin_rate_rad_s, range.spin_rate, "rad/s");
    c.number("min_omega_rad_s", out.min_spin_rate_rad_s, range.min_spin_rate, "rad/s");
    c.number("kp", out.kp, range.gain);
    c.number("ki_per_s", out.ki_per_s, range.gain, "1/s");
    c.number("interval_s", out.interval_s, range.interval, "s");
    c.integer("replan_samples", out.replan_samples, 1, 10000);
    c.number("replan_interval_s", out.replan_interval_s, range.replan_interval, "s");
    c.number("dither", out.dither, {0.0, 0.3});
    c.number("dither_period_s", out.dither_period_s, {0.01, 1000.0}, "s");
    c.boolean("traction_limited", out.traction_limited);
    c.number("limit_margin", out.limit_margin, range.limit_margin);
    c.choice<RobustSlip>("robust", out.robust,
                         {{"none", RobustSlip::kNone},
                          {"expected", RobustSlip::kExpected},
                          {"quantile", RobustSlip::kQuantile}});
    c.field(robustQuantileField(), out.quantile);
    c.integer("posterior_samples", out.posterior_samples, kMinPosteriorSamples,
              kMaxPosteriorSamples);
    c.choice<PosteriorMethod>(
        "posterior_method", out.posterior_method,
        {{"sigma-points", PosteriorMethod::kSigmaPoints}, {"samples", PosteriorMethod::kSamples}});
    c.choice<SoilIdentifier>(
        "identifier", out.identifier,
        {{"decoupled", SoilIdentifier::kDecoupled}, {"full", SoilIdentifier::kFull}});
    if (c.has("sensors")) {
        ObjectReader n = c.object("sensors");
        if (n.isObject()) {
            SensorSpec& s = out.sensors;
            const Range noise{0.0, 100.0};
            n.number("encoder_noise_rad_s", s.encoder_noise_rad_s, noise, "rad/s");
            n.number("torque_noise_Nm", s.torque_noise_nm, noise, "N·m");
            n.number("accel_noise_m_s2", s.accel_noise_m_s2, noise, "m/s²");
            n.number("accel_bias_m_s2", s.accel_bias_m_s2, {-10.0, 10.0}, "m/s²");
            n.number("gyro_noise_rad_s", s.gyro_noise_rad_s, noise, "rad/s");
            n.number("gnss_rate_Hz", s.gnss_rate_hz, {0.0, 100.0}, "Hz");
            n.number("gnss_speed_noise_m_s", s.gnss_speed_noise_m_s, noise, "m/s");
            n.number("filter_time_constant_s", s.filter_time_constant_s, {0.01, 100.0}, "s");
            n.number("sinkage_noise_m", s.sinkage_noise_m, {0.0, 0.1}, "m");
            n.number("hub_force_noise_N", s.hub_force_noise_n, {0.0, 1e4}, "N");
            std::uint64_t seed = s.seed;
            if (n.integer("seed", seed, 0, 4294967295u)) s.seed = static_cast<unsigned>(seed);
        }
        n.finish();
    } else {
        c.allow("sensors");
    }
    c.finish();
}

// "mission": {"waypoints": [[x, y], ...] | "lanes": {"start", "heading_deg", "length_m",
// "spacing_m", "count", "turn_radius_m", "side"}, "speed_m_s", "lookahead_m", "max_steer_deg",
// "interval_s", "steer_by": "course" | "heading"} (docs/field.md, "Missions").
std::optional<MissionSpec> readMission(ObjectReader& r) {
    if (!r.has("mission")) {
        r.allow("mission");
        return std::nullopt;
    }
    ObjectReader m = r.object("mission");
    if (!m.isObject()) return std::nullopt;
    const std::size_t before = m.issues().size();
    MissionSpec mission;
    const MissionRanges& range = kMissionRanges;
    if (m.has("waypoints") == m.has("lanes")) {
        m.allow("waypoints");
        m.allow("lanes");
        m.report("", "give either \"waypoints\": [[x, y], ...] or \"lanes\": {...} (one of them)");
    } else if (const json* points = m.array("waypoints")) {
        if (points->size() < 2 || points->size() > range.max_waypoints) {
            m.report("waypoints", "holds " + std::to_string(points->size()) +
                                      " points; allowed [2, " +
                                      std::to_string(range.max_waypoints) + "] points [x, y]");
        }
        for (std::size_t i = 0; i < points->size(); ++i) {
            const std::string at = "waypoints[" + std::to_string(i) + "]";
            const json& p = (*points)[i];
            if (!p.is_array() || p.size() != 2 || !p[0].is_number() || !p[1].is_number()) {
                m.report(at, "expected a point [x_m, y_m], got " + io::describeJson(p));
                continue;
            }
            const Eigen::Vector2d xy(p[0].get<double>(), p[1].get<double>());
            std::vector<Issue> issues;
            for (int k = 0; k < 2; ++k) {
                if (!checkRange(issues, "", xy[k], range.coordinate, "m"))
                    m.report(at + "[" + std::to_string(k) + "]", issues.back().message);
            }
            mission.waypoints.push_back(xy);
        }
    } else if (m.has("lanes")) {
        ObjectReader l = m.object("lanes");
        if (l.isObject()) {
            LanesSpec lanes;
            std::vector<double> start;
            if (l.numbers("start", start, range.coordinate, "m", 2, 2, Presence::kRequired))
                lanes.start_m = {start[0], start[1]};
            double heading_deg = 0.0;
            if (l.number("heading_deg", heading_deg, {-360.0, 360.0}, "deg", Presence::kRequired))
                lanes.heading_rad = units::degToRad(heading_deg);
            l.number("length_m", lanes.length_m, range.length, "m", Presence::kRequired);
            l.number("spacing_m", lanes.spacing_m, range.spacing, "m", Presence::kRequired);
            l.integer("count", lanes.count, 1, range.max_count, Presence::kRequired);
            l.number("turn_radius_m", lanes.turn_radius_m, range.turn_radius, "m",
                     Presence::kRequired);
            std::string side = "left";
            if (l.choiceName("side", side, {"left", "right"})) lanes.to_left = side == "left";
            mission.lanes = lanes;
        }
        l.finish();
    }
    m.number("speed_m_s", mission.speed_m_s, range.speed, "m/s", Presence::kRequired);
    m.number("lookahead_m", mission.lookahead_m, range.lookahead, "m");
    double max_steer_deg = units::radToDeg(mission.max_steer_rad);
    if (m.number("max_steer_deg", max_steer_deg, range.max_steer_deg, "deg"))
        mission.max_steer_rad = units::degToRad(max_steer_deg);
    m.number("interval_s", mission.interval_s, range.interval, "s");
    std::string steer_by = mission.follow_course ? "course" : "heading";
    if (m.choiceName("steer_by", steer_by, {"course", "heading"}))
        mission.follow_course = steer_by == "course";
    m.finish();
    if (m.issues().size() != before) return std::nullopt;
    return mission;
}

}  // namespace

Result<dynamics::RobotParameters> robotFromJson(const json& object, const std::string& where,
                                                const io::PresetLocations& locations) {
    std::vector<Issue> issues;
    ObjectReader r(object, issues, where);
    dynamics::RobotParameters robot = readRobot(r, locations);
    r.finish();
    if (!issues.empty()) return issues;
    return robot;
}

Result<dynamics::RobotParameters> resolveRobot(const io::PresetLocations& locations,
                                               const std::string& name_or_path) {
    std::error_code ec;
    const bool looks_like_path = name_or_path.find('/') != std::string::npos ||
                                 fs::path(name_or_path).extension() == ".json";
    fs::path file;
    // A path to something that is not a regular file goes to the reader, which names its kind.
    if (looks_like_path && fs::exists(name_or_path, ec)) file = name_or_path;
    for (const fs::path& dir : locations.directories) {
        if (!file.empty()) break;
        if (fs::is_regular_file(dir / "robots" / (name_or_path + ".json"), ec)) {
            file = dir / "robots" / (name_or_path + ".json");
        }
    }
    if (file.empty()) {
        std::string names;
        for (const std::string& n : io::presetNames(locations, "robots"))
            names += (names.empty() ? "" : ", ") + n;
        return std::vector<Issue>{{"robot", quoteText(name_or_path) +
                                                " is neither a file nor a preset; presets: " +
                                                (names.empty() ? "(none found)" : names)}};
    }
    return io::readJsonFileWith<dynamics::RobotParameters>(
        file, [&](const json& document, const std::string& source) {
            return robotFromJson(document, source, locations);
        });
}

Scenario readScenario(ObjectReader& r, const io::PresetLocations& locations,
                      const fs::path& base_dir) {
    Scenario s;
    const std::size_t before = r.issues().size();
    r.text("name", s.name);
    r.text("description", s.description);

    // Robot: preset, file or inline object; default: the shipped robot.
    const json* robot_value = r.value("robot");
    if (robot_value == nullptr || robot_value->is_string()) {
        const std::string name = robot_value ? robot_value->get<std::string>() : "default";
        Result<dynamics::RobotParameters> robot = resolveRobot(locations, locate(name, base_dir));
        if (robot) {
            s.robot = robot.value();
        } else {
            reportAt(r, "robot", robot.issues());
        }
    } else if (robot_value->is_object()) {
        ObjectReader robot = r.object("robot");
        s.robot = readRobot(robot, locations);
        robot.finish();
    } else {
        r.report("robot", "expected a robot preset name, a file or an object, got " +
                              io::describeJson(*robot_value));
    }

    r.number("duration_s", s.duration_s, kDurationRange, "s", Presence::kRequired);
    r.number("time_step_s", s.time_step_s, kTimeStepRange, "s", Presence::kRequired);
    s.output_interval_s = std::max(s.output_interval_s, s.time_step_s);
    r.number("output_interval_s", s.output_interval_s, {s.time_step_s, 3600.0}, "s");

    r.choice<contact::ContactModel>(
        "model", s.options.contact.model,
        {{"full", contact::ContactModel::kFull}, {"quadratic", contact::ContactModel::kQuadratic}});
    r.choice<contact::BulldozingModel>("bulldozing", s.options.contact.bulldozing,
                                       {{"bekker", contact::BulldozingModel::kBekker},
                                        {"hegedus", contact::BulldozingModel::kHegedus}});
    r.choice<bool>("reload_contact", s.options.contact.closed_form_reload,
                   {{"integrated", false}, {"closed-form", true}});
    r.choice<dynamics::Integrator>("integrator", s.options.integrator,
                                   {{"explicit", dynamics::Integrator::kExplicit},
                                    {"implicit", dynamics::Integrator::kImplicit}});
    r.integer("jacobian_every", s.options.jacobian_every, 1, 10);
    const FieldInfo& exit = contact::exitAngleField();
    r.field(exit, s.options.contact.exit_angle_rad);

    if (r.has("initial")) {
        ObjectReader i = r.object("initial");
        i.number("x_m", s.initial.x_m, {-1e6, 1e6}, "m");
        i.number("y_m", s.initial.y_m, {-1e6, 1e6}, "m");
        double yaw_deg = 0.0;
        if (i.number("yaw_deg", yaw_deg, {-360.0, 360.0}, "deg"))
            s.initial.yaw_rad = units::degToRad(yaw_deg);
        i.number("speed_m_s", s.initial.speed_m_s, {0.0, 100.0}, "m/s");
        i.finish();
    } else {
        r.allow("initial");
    }

    s.terrain = readTerrain(r, locations, base_dir, s);

    // Wheels: "all" first, then per-wheel overrides of either input.
    const Range spin_range{0.0, 1000.0};
    const Range steer_range{-60.0, 60.0};
    const json* wheels = r.value("wheels");
    // A mission's path controller drives the wheels: signals beside it would be ignored.
    const bool mission = r.has("mission");
    if (mission) {
        if (wheels != nullptr) {
            r.report("wheels",
                     "not used with a \"mission\" (its path controller steers and drives every "
                     "wheel): remove it");
        }
    } else if (wheels == nullptr || !wheels->is_object()) {
        r.report("wheels",
                 "missing; expected {\"all\": {\"omega_rad_s\": ..., \"steer_deg\": ...}, "
                 "\"FL\": {...}, ...}");
    } else {
        ObjectReader w = r.object("wheels");
        std::array<bool, dynamics::kWheelCount> has_spin{};
        auto readWheel = [&](const std::string& key, int only) {
            if (!w.has(key)) {
                w.allow(key);
                return;
            }
            ObjectReader e = w.object(key);
            if (!e.isObject()) return;
            // Read once (one message per problem), then give to the wheel(s) it is for.
            const std::optional<Signal> spin =
                readSignal(e, "omega_rad_s", spin_range, "rad/s", 1.0);
            const std::optional<Signal> steer =
                readSignal(e, "steer_deg", steer_range, "deg", units::degToRad(1.0));
            const bool spin_given = e.has("omega_rad_s");
            e.finish();
            for (int i = 0; i < dynamics::kWheelCount; ++i) {
                if (only >= 0 && i != only) continue;
                if (spin) s.wheels[i].spin_rate_rad_s = *spin;
                if (spin_given) has_spin[i] = true;
                if (steer) s.wheels[i].steer_angle_rad = *steer;
            }
        };
        readWheel("all", -1);
        for (int i = 0; i < dynamics::kWheelCount; ++i) readWheel(dynamics::kCornerNames[i], i);
        for (int i = 0; i < dynamics::kWheelCount; ++i) {
            if (!has_spin[i]) {
                w.report(std::string(dynamics::kCornerNames[i]) + ".omega_rad_s",
                         "missing (give it under \"all\" or per wheel)");
            }
        }
        w.finish();
    }

    if (r.has("streaming")) {
        ObjectReader h = r.object("streaming");
        if (h.isObject()) {
            StreamingHook hook;
            std::string wheel_name = "FL";
            const std::vector<std::string> corners(dynamics::kCornerNames.begin(),
                                                   dynamics::kCornerNames.end());
            if (h.choiceName("wheel", wheel_name, corners)) {
                hook.wheel = static_cast<int>(
                    std::find(corners.begin(), corners.end(), wheel_name) - corners.begin());
            }
            h.number("interval_s", hook.interval_s, {1e-3, 10.0}, "s");
            h.number("slip_noise", hook.slip_noise, {0.0, 0.5});
            double theta_noise_deg = units::radToDeg(hook.entry_angle_noise_rad);
            if (h.number("entry_angle_noise_deg", theta_noise_deg, {0.0, 10.0}, "deg")) {
                hook.entry_angle_noise_rad = units::degToRad(theta_noise_deg);
            }
            h.number("force_noise_N", hook.force_noise_n, {0.0, 1e4}, "N");
            h.number("torque_noise_Nm", hook.torque_noise_nm, {0.0, 1e4}, "N·m");
            std::uint64_t seed = hook.seed;
            if (h.integer("seed", seed, 0, 4294967295u)) hook.seed = static_cast<unsigned>(seed);
            std::string samples = hook.from_observer ? "observer" : "truth";
            if (h.choiceName("samples", samples, {"truth", "observer"}))
                hook.from_observer = samples == "observer";
            s.streaming = hook;
        }
        h.finish();
    } else {
        r.allow("streaming");
    }

    readController(r, s.controller);
    s.mission = readMission(r);
    if (r.has("drawbar_load")) {
        ObjectReader d = r.object("drawbar_load");
        if (d.isObject()) {
            if (const std::optional<Signal> force =
                    readSignal(d, "force_N", kDrawbarForceRange, "N", 1.0)) {
                s.drawbar_load.force_n = *force;
            }
            d.number("per_speed_N_s_m", s.drawbar_load.per_speed_n_s_m, kDrawbarPerSpeedRange,
                     "N·s/m");
        }
        d.finish();
    } else {
        r.allow("drawbar_load");
    }

    if (r.issues().size() == before) {
        for (Issue& issue : validate(s)) r.report(issue.where, issue.message);
    }
    return s;
}

Result<Scenario> scenarioFromJson(const json& object, const std::string& where,
                                  const io::PresetLocations& locations, const fs::path& base_dir) {
    std::vector<Issue> issues;
    ObjectReader r(object, issues, where);
    if (!r.isObject()) return issues;
    Scenario s = readScenario(r, locations, base_dir);
    r.finish();
    if (!issues.empty()) return issues;
    return s;
}

Result<Scenario> loadScenario(const fs::path& path, const io::PresetLocations& locations) {
    Result<Scenario> s =
        io::readJsonFileWith<Scenario>(path, [&](const json& document, const std::string& source) {
            return scenarioFromJson(document, source, locations, path.parent_path());
        });
    if (!s) return s;
    Scenario out = s.value();
    if (out.name.empty()) out.name = path.stem().string();
    return out;
}

Result<Scenario> resolveScenario(const io::PresetLocations& locations,
                                 const std::string& name_or_path) {
    std::error_code ec;
    const bool looks_like_path = name_or_path.find('/') != std::string::npos ||
                                 fs::path(name_or_path).extension() == ".json";
    // A path to something that is not a regular file goes to the reader, which names its kind.
    if (looks_like_path && fs::exists(name_or_path, ec))
        return loadScenario(name_or_path, locations);
    for (const fs::path& dir : locations.directories) {
        const fs::path candidate = dir / "scenarios" / (name_or_path + ".json");
        if (fs::is_regular_file(candidate, ec)) return loadScenario(candidate, locations);
    }
    if (fs::is_regular_file(name_or_path, ec)) return loadScenario(name_or_path, locations);
    std::string names;
    for (const std::string& n : io::presetNames(locations, "scenarios"))
        names += (names.empty() ? "" : ", ") + n;
    return std::vector<Issue>{{"scenario", quoteText(name_or_path) +
                                               " is neither a file nor a scenario; scenarios: " +
                                               (names.empty() ? "(none found)" : names)}};
}

}  // namespace terra::scenario
