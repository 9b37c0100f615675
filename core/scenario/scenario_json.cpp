#include "core/scenario/scenario_json.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "core/common/range.h"
#include "core/common/units.h"
#include "core/io/atomic_file.h"

namespace terra::scenario {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

// A reader of one JSON object that collects issues under a field path ("file: wheels.FL.").
struct Reader {
    const json& object;
    std::string at;  // prefix of every issue location
    std::vector<Issue>& issues;

    bool has(const char* key) const { return object.contains(key); }

    bool number(const char* key, const Range& range, const std::string& unit, double& out,
                bool required = false) const {
        const auto it = object.find(key);
        const std::string u = unit.empty() ? "" : " " + unit;
        if (it == object.end()) {
            if (required)
                issues.push_back(
                    {at + key, "missing; expected a number in " + range.describe() + u});
            return false;
        }
        if (!it->is_number()) {
            issues.push_back({at + key, "expected a number in " + range.describe() + u + ", got " +
                                            std::string(it->type_name()) + " " + it->dump()});
            return false;
        }
        const double value = it->get<double>();
        if (!checkRange(issues, at + key, value, range, unit)) return false;
        out = value;
        return true;
    }

    bool text(const char* key, std::string& out) const {
        const auto it = object.find(key);
        if (it == object.end()) return false;
        if (!it->is_string()) {
            issues.push_back({at + key, std::string("expected a string, got ") + it->type_name()});
            return false;
        }
        out = it->get<std::string>();
        return true;
    }

    void rejectUnknown(const std::vector<std::string>& known) const {
        for (const auto& [key, value] : object.items()) {
            if (std::find(known.begin(), known.end(), key) != known.end()) continue;
            std::string list;
            for (const std::string& k : known) list += (list.empty() ? "" : ", ") + k;
            issues.push_back({at + key, "unknown key; allowed keys: " + list});
        }
    }
};

Result<json> readJson(const fs::path& path) {
    std::string content;
    if (const auto error = io::readFile(path, content))
        return std::vector<Issue>{{path.string(), *error}};
    try {
        return json::parse(content);
    } catch (const json::parse_error& e) {
        return std::vector<Issue>{{path.string(), std::string("invalid JSON: ") + e.what()}};
    }
}

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

void append(std::vector<Issue>& issues, const std::vector<Issue>& more, const std::string& at) {
    for (const Issue& issue : more) issues.push_back({at + issue.where, issue.message});
}

// A signal: a number (constant) or {"type": ..., ...}; `scale` converts file units to SI.
Signal readSignal(const json& value, const std::string& at, const Range& range,
                  const std::string& unit, double scale, std::vector<Issue>& issues) {
    Signal signal;
    if (value.is_number()) {
        const double v = value.get<double>();
        checkRange(issues, at, v, range, unit);
        signal.value = v * scale;
        return signal;
    }
    if (!value.is_object()) {
        issues.push_back({at,
                          "expected a number or an object {\"type\": constant|step|pulse|ramp|"
                          "table, ...}, got " +
                              std::string(value.type_name())});
        return signal;
    }
    const std::size_t before = issues.size();
    Reader r{value, at + ".", issues};
    std::string type = "constant";
    r.text("type", type);
    const Range any{-1e9, 1e9};
    const Range time{0.0, 1e6};
    if (type == "constant") {
        r.rejectUnknown({"type", "value"});
        r.number("value", range, unit, signal.value, true);
    } else if (type == "step" || type == "pulse" || type == "ramp") {
        signal.kind = type == "step"    ? Signal::Kind::kStep
                      : type == "pulse" ? Signal::Kind::kPulse
                                        : Signal::Kind::kRamp;
        std::vector<std::string> known{"type", "value", "amplitude", "start_s"};
        if (type != "step") known.push_back("duration_s");
        r.rejectUnknown(known);
        r.number("value", range, unit, signal.value);
        r.number("amplitude", any, unit, signal.amplitude, true);
        r.number("start_s", time, "s", signal.start_s, true);
        if (type != "step") r.number("duration_s", time, "s", signal.duration_s, true);
        if (issues.size() == before)
            checkRange(issues, at + " (value + amplitude)", signal.value + signal.amplitude, range,
                       unit);
        signal.amplitude *= scale;
    } else if (type == "table") {
        signal.kind = Signal::Kind::kTable;
        r.rejectUnknown({"type", "t_s", "values"});
        const auto t = value.find("t_s");
        const auto v = value.find("values");
        if (t == value.end() || v == value.end() || !t->is_array() || !v->is_array() ||
            t->size() != v->size() || t->empty()) {
            issues.push_back(
                {at, "a table needs arrays t_s and values of the same, non-zero length"});
            return signal;
        }
        for (std::size_t i = 0; i < t->size(); ++i) {
            const std::string where = at + ".t_s[" + std::to_string(i) + "]";
            if (!(*t)[i].is_number() || !(*v)[i].is_number()) {
                issues.push_back({where, "t_s and values must hold numbers"});
                continue;
            }
            const double ti = (*t)[i].get<double>(), vi = (*v)[i].get<double>();
            if (!signal.times_s.empty() && !(ti > signal.times_s.back())) {
                issues.push_back({where, "t_s = " + formatNumber(ti) +
                                             " must be greater than the previous time " +
                                             formatNumber(signal.times_s.back())});
            }
            checkRange(issues, at + ".values[" + std::to_string(i) + "]", vi, range, unit);
            signal.times_s.push_back(ti);
            signal.values.push_back(vi);
        }
    } else {
        issues.push_back({at + ".type", "'" + type +
                                            "' is not a signal type; allowed: constant, "
                                            "step, pulse, ramp, table"});
    }
    signal.value *= scale;
    for (double& v : signal.values) v *= scale;
    return signal;
}

dynamics::Terrain readTerrain(const json& value, const std::string& at,
                              const io::PresetLocations& locations, const fs::path& base_dir,
                              std::vector<Issue>& issues) {
    dynamics::Terrain terrain;
    auto soil = [&](const json& v, const std::string& where, soil::SoilParameters& out) {
        Result<soil::SoilParameters> resolved =
            v.is_string()   ? io::resolveSoil(locations, locate(v.get<std::string>(), base_dir))
            : v.is_object() ? io::soilFromJson(v, where)
                            : Result<soil::SoilParameters>(std::vector<Issue>{
                                  {where, "expected a soil preset name, a file or an object"}});
        if (resolved) {
            out = resolved.value();
        } else {
            append(issues, resolved.issues(), v.is_string() ? where + ": " : "");
        }
    };
    if (value.is_string()) {
        soil(value, at, terrain.base);
        return terrain;
    }
    if (!value.is_object()) {
        issues.push_back({at, "expected a soil name or {\"soil\": ..., \"patches\": [...]}"});
        return terrain;
    }
    Reader r{value, at + ".", issues};
    r.rejectUnknown({"soil", "patches"});
    if (!value.contains("soil")) {
        issues.push_back({at + ".soil", "missing; expected a soil preset name or file"});
    } else {
        soil(value["soil"], at + ".soil", terrain.base);
    }
    if (value.contains("patches")) {
        const json& patches = value["patches"];
        if (!patches.is_array()) {
            issues.push_back({at + ".patches", "expected an array of patches"});
            return terrain;
        }
        const double inf = std::numeric_limits<double>::infinity();
        const Range coordinate{-1e6, 1e6};
        for (std::size_t i = 0; i < patches.size(); ++i) {
            const std::string where = at + ".patches[" + std::to_string(i) + "]";
            if (!patches[i].is_object()) {
                issues.push_back({where, "expected an object {\"soil\", \"x_min_m\", ...}"});
                continue;
            }
            Reader p{patches[i], where + ".", issues};
            p.rejectUnknown({"soil", "x_min_m", "x_max_m", "y_min_m", "y_max_m"});
            dynamics::SoilPatch patch;
            if (!patches[i].contains("soil")) {
                issues.push_back({where + ".soil", "missing; expected a soil preset name or file"});
            } else {
                soil(patches[i]["soil"], where + ".soil", patch.soil);
            }
            patch.x_min_m = -inf, patch.x_max_m = inf, patch.y_min_m = -inf, patch.y_max_m = inf;
            p.number("x_min_m", coordinate, "m", patch.x_min_m);
            p.number("x_max_m", coordinate, "m", patch.x_max_m);
            p.number("y_min_m", coordinate, "m", patch.y_min_m);
            p.number("y_max_m", coordinate, "m", patch.y_max_m);
            terrain.patches.push_back(std::move(patch));
        }
    }
    return terrain;
}

}  // namespace

Result<dynamics::RobotParameters> robotFromJson(const json& object, const std::string& where,
                                                const io::PresetLocations& locations) {
    const std::string at = where.empty() ? "" : where + ": ";
    if (!object.is_object()) return std::vector<Issue>{{where, "expected a JSON object"}};
    std::vector<Issue> issues;
    Reader r{object, at, issues};
    r.rejectUnknown({"name", "source", "wheel", "chassis_mass_kg", "chassis_inertia_kg_m2",
                     "wheel_mass_kg", "wheel_spin_inertia_kg_m2", "wheelbase_m", "track_m",
                     "com_height_m", "com_forward_m", "vertical_damping_ratio"});
    dynamics::RobotParameters robot;
    r.text("name", robot.name);
    r.text("source", robot.source);
    const auto wheel = object.find("wheel");
    if (wheel == object.end()) {
        issues.push_back({at + "wheel",
                          "missing; expected a wheel preset (\"A\", \"B\"), a file or "
                          "an object {\"r_m\", \"b_m\"}"});
    } else {
        Result<wheel::WheelParameters> w =
            wheel->is_string() ? io::resolveWheel(locations, wheel->get<std::string>())
                               : io::wheelFromJson(*wheel, at + "wheel");
        if (w) {
            robot.wheel = w.value();
        } else {
            append(issues, w.issues(), wheel->is_string() ? at + "wheel: " : "");
        }
    }
    const Range positive{0.0, 1e6, true, false};
    r.number("chassis_mass_kg", positive, "kg", robot.chassis_mass_kg, true);
    if (const auto it = object.find("chassis_inertia_kg_m2"); it != object.end()) {
        if (!it->is_array() || it->size() != 3) {
            issues.push_back({at + "chassis_inertia_kg_m2", "expected [Ixx, Iyy, Izz] in kg·m²"});
        } else {
            for (int i = 0; i < 3; ++i) {
                const std::string key = at + "chassis_inertia_kg_m2[" + std::to_string(i) + "]";
                if (!(*it)[i].is_number()) {
                    issues.push_back({key, "expected a number"});
                } else if (checkRange(issues, key, (*it)[i].get<double>(), positive, "kg·m²")) {
                    robot.chassis_inertia_kg_m2[i] = (*it)[i].get<double>();
                }
            }
        }
    } else {
        issues.push_back(
            {at + "chassis_inertia_kg_m2", "missing; expected [Ixx, Iyy, Izz] in kg·m²"});
    }
    r.number("wheel_mass_kg", {0.0, 1e6}, "kg", robot.wheel_mass_kg, true);
    r.number("wheel_spin_inertia_kg_m2", {0.0, 1e6}, "kg·m²", robot.wheel_spin_inertia_kg_m2);
    r.number("wheelbase_m", {0.0, 100.0, true, false}, "m", robot.wheelbase_m, true);
    r.number("track_m", {0.0, 100.0, true, false}, "m", robot.track_m, true);
    r.number("com_height_m", {-10.0, 10.0}, "m", robot.com_height_m);
    r.number("com_forward_m", {-50.0, 50.0}, "m", robot.com_forward_m);
    r.number("vertical_damping_ratio", {0.0, 10.0}, "", robot.vertical_damping_ratio);
    if (issues.empty()) {
        for (Issue& issue : dynamics::validate(robot))
            issues.push_back({at + issue.where, issue.message});
    }
    if (!issues.empty()) return issues;
    return robot;
}

Result<dynamics::RobotParameters> resolveRobot(const io::PresetLocations& locations,
                                               const std::string& name_or_path) {
    std::error_code ec;
    const bool looks_like_path = name_or_path.find('/') != std::string::npos ||
                                 fs::path(name_or_path).extension() == ".json";
    fs::path file;
    if (looks_like_path && fs::is_regular_file(name_or_path, ec)) file = name_or_path;
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
        return std::vector<Issue>{{"robot", "'" + name_or_path +
                                                "' is neither a file nor a preset; presets: " +
                                                (names.empty() ? "(none found)" : names)}};
    }
    Result<json> document = readJson(file);
    if (!document) return document.issues();
    return robotFromJson(document.value(), file.string(), locations);
}

Result<Scenario> scenarioFromJson(const json& object, const std::string& where,
                                  const io::PresetLocations& locations, const fs::path& base_dir) {
    const std::string at = where.empty() ? "" : where + ": ";
    if (!object.is_object()) return std::vector<Issue>{{where, "expected a JSON object"}};
    std::vector<Issue> issues;
    Reader r{object, at, issues};
    r.rejectUnknown({"name", "description", "robot", "duration_s", "time_step_s",
                     "output_interval_s", "model", "bulldozing", "exit_angle_deg", "initial",
                     "terrain", "wheels", "streaming"});
    Scenario s;
    r.text("name", s.name);
    r.text("description", s.description);

    // Robot: preset, file or inline object; default: the shipped robot.
    const json robot_value = object.contains("robot") ? object["robot"] : json("default");
    Result<dynamics::RobotParameters> robot =
        robot_value.is_string()
            ? resolveRobot(locations, locate(robot_value.get<std::string>(), base_dir))
        : robot_value.is_object()
            ? robotFromJson(robot_value, "", locations)
            : Result<dynamics::RobotParameters>(std::vector<Issue>{
                  {at + "robot", "expected a robot preset name, a file or an object"}});
    if (robot) {
        s.robot = robot.value();
    } else {
        append(issues, robot.issues(), robot_value.is_string() ? at + "robot: " : at + "robot.");
    }

    r.number("duration_s", {0.0, 86400.0, true, false}, "s", s.duration_s, true);
    r.number("time_step_s", {1e-6, 0.05}, "s", s.time_step_s, true);
    s.output_interval_s = std::max(s.output_interval_s, s.time_step_s);
    r.number("output_interval_s", {s.time_step_s, 3600.0}, "s", s.output_interval_s);

    std::string model = "full";
    if (r.text("model", model) && model != "full" && model != "quadratic") {
        issues.push_back(
            {at + "model", "'" + model + "' is not a contact model; allowed: full, quadratic"});
    }
    s.options.contact.model =
        model == "quadratic" ? contact::ContactModel::kQuadratic : contact::ContactModel::kFull;
    std::string bulldozing = "bekker";
    if (r.text("bulldozing", bulldozing) && bulldozing != "bekker" && bulldozing != "hegedus") {
        issues.push_back(
            {at + "bulldozing", "'" + bulldozing + "' is not allowed; allowed: bekker, hegedus"});
    }
    s.options.contact.bulldozing = bulldozing == "hegedus" ? contact::BulldozingModel::kHegedus
                                                           : contact::BulldozingModel::kBekker;
    double exit_deg = 0.0;
    if (r.number("exit_angle_deg", {-90.0, 0.0}, "deg", exit_deg)) {
        s.options.contact.exit_angle_rad = units::degToRad(exit_deg);
    }

    if (const auto it = object.find("initial"); it != object.end()) {
        if (!it->is_object()) {
            issues.push_back({at + "initial", "expected an object {x_m, y_m, yaw_deg, speed_m_s}"});
        } else {
            Reader i{*it, at + "initial.", issues};
            i.rejectUnknown({"x_m", "y_m", "yaw_deg", "speed_m_s"});
            i.number("x_m", {-1e6, 1e6}, "m", s.initial.x_m);
            i.number("y_m", {-1e6, 1e6}, "m", s.initial.y_m);
            double yaw_deg = 0.0;
            if (i.number("yaw_deg", {-360.0, 360.0}, "deg", yaw_deg))
                s.initial.yaw_rad = units::degToRad(yaw_deg);
            i.number("speed_m_s", {0.0, 100.0}, "m/s", s.initial.speed_m_s);
        }
    }

    if (!object.contains("terrain")) {
        issues.push_back(
            {at + "terrain", "missing; expected a soil name or {\"soil\", \"patches\"}"});
    } else {
        s.terrain = readTerrain(object["terrain"], at + "terrain", locations, base_dir, issues);
    }

    // Wheels: "all" first, then per-wheel overrides of either input.
    const Range spin_range{0.0, 1000.0};
    const Range steer_range{-60.0, 60.0};
    if (const auto it = object.find("wheels"); it == object.end() || !it->is_object()) {
        issues.push_back({at + "wheels",
                          "missing; expected {\"all\": {\"omega_rad_s\": ..., "
                          "\"steer_deg\": ...}, \"FL\": {...}, ...}"});
    } else {
        Reader w{*it, at + "wheels.", issues};
        w.rejectUnknown({"all", "FL", "FR", "RL", "RR"});
        std::array<bool, dynamics::kWheelCount> has_spin{};
        auto readWheel = [&](const std::string& key, int only) {
            const auto entry = it->find(key);
            if (entry == it->end()) return;
            const std::string where = at + "wheels." + key;
            if (!entry->is_object()) {
                issues.push_back({where, "expected an object {\"omega_rad_s\", \"steer_deg\"}"});
                return;
            }
            Reader e{*entry, where + ".", issues};
            e.rejectUnknown({"omega_rad_s", "steer_deg"});
            // Read once (one message per problem), then give to the wheel(s) it is for.
            std::optional<Signal> spin, steer;
            if (entry->contains("omega_rad_s")) {
                spin = readSignal((*entry)["omega_rad_s"], where + ".omega_rad_s", spin_range,
                                  "rad/s", 1.0, issues);
            }
            if (entry->contains("steer_deg")) {
                steer = readSignal((*entry)["steer_deg"], where + ".steer_deg", steer_range, "deg",
                                   units::degToRad(1.0), issues);
            }
            for (int i = 0; i < dynamics::kWheelCount; ++i) {
                if (only >= 0 && i != only) continue;
                if (spin) {
                    s.wheels[i].spin_rate_rad_s = *spin;
                    has_spin[i] = true;
                }
                if (steer) s.wheels[i].steer_angle_rad = *steer;
            }
        };
        readWheel("all", -1);
        for (int i = 0; i < dynamics::kWheelCount; ++i) readWheel(dynamics::kCornerNames[i], i);
        for (int i = 0; i < dynamics::kWheelCount; ++i) {
            if (!has_spin[i]) {
                issues.push_back({at + "wheels." + dynamics::kCornerNames[i] + ".omega_rad_s",
                                  "missing (give it under \"all\" or per wheel)"});
            }
        }
    }

    if (const auto it = object.find("streaming"); it != object.end()) {
        if (!it->is_object()) {
            issues.push_back(
                {at + "streaming", "expected an object {\"wheel\", \"interval_s\", ...}"});
        } else {
            Reader h{*it, at + "streaming.", issues};
            h.rejectUnknown({"wheel", "interval_s", "slip_noise", "entry_angle_noise_deg",
                             "force_noise_N", "torque_noise_Nm", "seed"});
            StreamingHook hook;
            std::string wheel_name = "FL";
            h.text("wheel", wheel_name);
            const auto found =
                std::find(dynamics::kCornerNames.begin(), dynamics::kCornerNames.end(), wheel_name);
            if (found == dynamics::kCornerNames.end()) {
                issues.push_back({at + "streaming.wheel",
                                  "'" + wheel_name + "' is not a wheel; allowed: FL, FR, RL, RR"});
            } else {
                hook.wheel = static_cast<int>(found - dynamics::kCornerNames.begin());
            }
            h.number("interval_s", {1e-3, 10.0}, "s", hook.interval_s);
            h.number("slip_noise", {0.0, 0.5}, "", hook.slip_noise);
            double theta_noise_deg = units::radToDeg(hook.entry_angle_noise_rad);
            if (h.number("entry_angle_noise_deg", {0.0, 10.0}, "deg", theta_noise_deg)) {
                hook.entry_angle_noise_rad = units::degToRad(theta_noise_deg);
            }
            h.number("force_noise_N", {0.0, 1e4}, "N", hook.force_noise_n);
            h.number("torque_noise_Nm", {0.0, 1e4}, "N·m", hook.torque_noise_nm);
            double seed = hook.seed;
            if (h.number("seed", {0.0, 4294967295.0}, "", seed))
                hook.seed = static_cast<unsigned>(seed);
            s.streaming = hook;
        }
    }

    if (issues.empty()) {
        for (Issue& issue : validate(s)) issues.push_back({at + issue.where, issue.message});
    }
    if (!issues.empty()) return issues;
    return s;
}

Result<Scenario> loadScenario(const fs::path& path, const io::PresetLocations& locations) {
    Result<json> document = readJson(path);
    if (!document) return document.issues();
    Result<Scenario> s =
        scenarioFromJson(document.value(), path.string(), locations, path.parent_path());
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
    if (looks_like_path && fs::is_regular_file(name_or_path, ec))
        return loadScenario(name_or_path, locations);
    for (const fs::path& dir : locations.directories) {
        const fs::path candidate = dir / "scenarios" / (name_or_path + ".json");
        if (fs::is_regular_file(candidate, ec)) return loadScenario(candidate, locations);
    }
    if (fs::is_regular_file(name_or_path, ec)) return loadScenario(name_or_path, locations);
    std::string names;
    for (const std::string& n : io::presetNames(locations, "scenarios"))
        names += (names.empty() ? "" : ", ") + n;
    return std::vector<Issue>{{"scenario", "'" + name_or_path +
                                               "' is neither a file nor a scenario; scenarios: " +
                                               (names.empty() ? "(none found)" : names)}};
}

}  // namespace terra::scenario
