#include "widgets/document/project.h"

#include "core/io/parameters_json.h"

namespace terra::ui {

bool Project::operator==(const Project& other) const { return toJson(*this) == toJson(other); }

nlohmann::json toJson(const Project& project) {
    const OperatingConditions& c = project.conditions;
    return {{"format", "terrastudio-project"},
            {"version", 1},
            {"soil_preset", project.soil_preset},
            {"soil", io::toJson(project.soil)},
            {"wheel_preset", project.wheel_preset},
            {"wheel", io::toJson(project.wheel)},
            {"conditions",
             {{"load_N", c.load_n},
              {"slip_angles_deg", c.slip_angles_deg},
              {"slip_count", c.slip_count},
              {"slip_max", c.slip_max},
              {"model", c.quadratic ? "quadratic" : "full"}}},
            {"data_sets", project.data_sets},
            {"scenarios", project.scenarios},
            {"panels", project.panels}};
}

namespace {

template <typename T>
bool read(const nlohmann::json& object, const char* key, T& value, std::vector<Issue>& issues,
          const std::string& where) {
    if (!object.contains(key)) return false;
    try {
        value = object.at(key).get<T>();
        return true;
    } catch (const nlohmann::json::exception&) {
        issues.push_back({where + key, "has the wrong type (" + object.at(key).dump() + ")"});
        return false;
    }
}

}  // namespace

Result<Project> projectFromJson(const nlohmann::json& json, const std::string& where) {
    std::vector<Issue> issues;
    if (!json.is_object() || json.value("format", "") != "terrastudio-project") {
        return std::vector<Issue>{
            {where, "not a TerraStudio project (\"format\": \"terrastudio-project\")"}};
    }
    Project project;
    const std::string at = where + ": ";
    read(json, "soil_preset", project.soil_preset, issues, at);
    read(json, "wheel_preset", project.wheel_preset, issues, at);
    if (json.contains("soil")) {
        auto soil = io::soilFromJson(json["soil"], where + ": soil");
        if (soil)
            project.soil = *soil;
        else
            issues.insert(issues.end(), soil.issues().begin(), soil.issues().end());
    }
    if (json.contains("wheel")) {
        auto wheel = io::wheelFromJson(json["wheel"], where + ": wheel");
        if (wheel)
            project.wheel = *wheel;
        else
            issues.insert(issues.end(), wheel.issues().begin(), wheel.issues().end());
    }
    if (json.contains("conditions")) {
        const auto& c = json["conditions"];
        OperatingConditions& out = project.conditions;
        const std::string cw = at + "conditions.";
        read(c, "load_N", out.load_n, issues, cw);
        checkRange(issues, cw + "load_N", out.load_n, kLoadRange, "N");
        read(c, "slip_angles_deg", out.slip_angles_deg, issues, cw);
        for (double beta : out.slip_angles_deg) {
            checkRange(issues, cw + "slip_angles_deg", beta, Range{-89.0, 89.0}, "deg");
        }
        read(c, "slip_count", out.slip_count, issues, cw);
        if (out.slip_count < 2 || out.slip_count > 10000) {
            issues.push_back({cw + "slip_count",
                              "= " + std::to_string(out.slip_count) + " is outside [2, 10000]"});
        }
        read(c, "slip_max", out.slip_max, issues, cw);
        checkRange(issues, cw + "slip_max", out.slip_max, Range{0.0, 1.0, true, false});
        std::string model = "full";
        read(c, "model", model, issues, cw);
        if (model != "full" && model != "quadratic") {
            issues.push_back({cw + "model", "= \"" + model + "\" is not one of full, quadratic"});
        }
        out.quadratic = model == "quadratic";
    }
    read(json, "data_sets", project.data_sets, issues, at);
    read(json, "scenarios", project.scenarios, issues, at);
    if (json.contains("panels") && json["panels"].is_object()) project.panels = json["panels"];
    if (!issues.empty()) return issues;
    return project;
}

}  // namespace terra::ui
