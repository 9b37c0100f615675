#include "core/project/project.h"

#include <algorithm>
#include <cctype>

#include "core/io/json.h"
#include "core/io/parameters_json.h"
#include "core/project/panels.h"

namespace terra::project {

using io::ObjectReader;
using io::Presence;

bool Project::operator==(const Project& other) const { return toJson(*this) == toJson(other); }

nlohmann::json toJson(const Project& project) {
    nlohmann::json out{{"format", kFormat},
                       {"version", kVersion},
                       {"soil_preset", project.soil_preset},
                       {"soil", io::toJson(project.soil)},
                       {"wheel_preset", project.wheel_preset},
                       {"wheel", io::toJson(project.wheel)},
                       {"conditions", analysis::toJson(project.conditions)},
                       {"data_sets", project.data_sets},
                       {"scenarios", project.scenarios},
                       {"panels", project.panels}};
    if (!project.experiment.empty()) out["experiment"] = project.experiment;
    return out;
}

Result<Project> projectFromJson(const nlohmann::json& json, const std::string& where,
                                const io::PresetLocations* locations,
                                const std::filesystem::path& project_dir) {
    std::vector<Issue> issues;
    ObjectReader r(json, issues, where);
    if (!r.isObject()) return issues;
    std::string format;
    if (!r.text("format", format) || format != kFormat) {
        return std::vector<Issue>{
            {where, "not a TerraStudio project (\"format\": \"terrastudio-project\")"}};
    }
    int version = kVersion;
    r.integer("version", version, kVersion, kVersion);
    Project project;
    r.text("soil_preset", project.soil_preset);
    r.text("wheel_preset", project.wheel_preset);
    if (r.has("soil")) {
        ObjectReader soil = r.object("soil");
        project.soil = io::readSoil(soil);
        soil.finish();
    }
    if (r.has("wheel")) {
        ObjectReader wheel = r.object("wheel");
        project.wheel = io::readWheel(wheel);
        wheel.finish();
    }
    ObjectReader conditions = r.object("conditions");
    analysis::readConditions(conditions, project.conditions);
    conditions.finish();
    r.texts("data_sets", project.data_sets);
    r.texts("scenarios", project.scenarios);
    // Only the reference ("" or absent: none): the test is read when the studio shows it (like
    // the data sets), so a moved test file does not keep the project from opening.
    r.text("experiment", project.experiment);
    ObjectReader panels = r.object("panels");
    readPanels(panels, locations, project_dir);
    panels.finish();
    if (panels.isObject() && r.has("panels")) project.panels = json["panels"];
    r.finish();
    if (!issues.empty()) return issues;
    return project;
}

Result<Project> loadProject(const std::filesystem::path& path,
                            const io::PresetLocations* locations) {
    return io::readJsonFileWith<Project>(
        path, [&](const nlohmann::json& document, const std::string& source) {
            return projectFromJson(document, source, locations, path.parent_path());
        });
}

namespace {

/// A file name in a panel's settings.
struct PanelFile {
    const char* panel;
    const char* key;
    bool json_only;  ///< a file only when it ends in ".json" (else a preset's name)
};

/// The panels' files: the identification panel's data, the rover panel's scenario when it is one
/// of the project's scenario files (a preset is chosen by its name, never a ".json").
constexpr PanelFile kPanelFiles[] = {{"identification", "csv", false},
                                     {"identification", "stream_csv", false},
                                     {"rover", "scenario", true}};

/// Applies `convert` to every file name of the project (empty names are left alone).
template <typename Convert>
Project convertPaths(Project project, Convert convert) {
    auto one = [&convert](std::string& path) {
        if (!path.empty()) path = convert(std::filesystem::path(path)).generic_string();
    };
    for (std::string& path : project.data_sets) one(path);
    for (std::string& path : project.scenarios) one(path);
    one(project.experiment);
    for (const PanelFile& file : kPanelFiles) {
        if (!project.panels.contains(file.panel) || !project.panels[file.panel].is_object())
            continue;
        nlohmann::json& panel = project.panels[file.panel];
        if (!panel.contains(file.key) || !panel[file.key].is_string()) continue;
        std::string path = panel[file.key].get<std::string>();
        if (file.json_only && !isScenarioFileName(path)) continue;
        one(path);
        panel[file.key] = path;
    }
    // The rover panel's edits are kept by scenario: a scenario file's edit by its path. An edit's
    // robot file (a robot dropped onto the window) is a file name too; a preset's name is not.
    if (project.panels.contains("rover") && project.panels["rover"].is_object() &&
        project.panels["rover"].contains("edited") &&
        project.panels["rover"]["edited"].is_object()) {
        nlohmann::json converted = nlohmann::json::object();
        for (const auto& [name, scenario] : project.panels["rover"]["edited"].items()) {
            std::string key = name;
            if (isScenarioFileName(key)) one(key);
            nlohmann::json edit = scenario;
            if (edit.is_object() && edit.contains("robot") && edit["robot"].is_string()) {
                std::string robot = edit["robot"].get<std::string>();
                if (isScenarioFileName(robot)) {
                    one(robot);
                    edit["robot"] = robot;
                }
            }
            converted[key] = std::move(edit);
        }
        project.panels["rover"]["edited"] = std::move(converted);
    }
    return project;
}

/// Whether `path` (absolute, normalised) lies inside `dir` (absolute, normalised).
bool isInside(const std::filesystem::path& path, const std::filesystem::path& dir) {
    const std::filesystem::path rel = path.lexically_relative(dir);
    return !rel.empty() && *rel.begin() != "..";
}

}  // namespace

bool isScenarioFileName(std::string_view name) {
    constexpr std::string_view kSuffix = ".json";
    if (name.size() < kSuffix.size()) return false;
    const std::string_view tail = name.substr(name.size() - kSuffix.size());
    return std::equal(tail.begin(), tail.end(), kSuffix.begin(), [](char a, char b) {
        return std::tolower(static_cast<unsigned char>(a)) == b;
    });
}

Project withRelativePaths(const Project& project, const std::filesystem::path& project_dir) {
    const std::filesystem::path dir = std::filesystem::absolute(project_dir).lexically_normal();
    return convertPaths(project, [&dir](const std::filesystem::path& path) {
        if (path.is_relative()) return path;  // already relative to the project
        const std::filesystem::path normal = path.lexically_normal();
        return isInside(normal, dir) ? normal.lexically_relative(dir) : path;
    });
}

Project withAbsolutePaths(const Project& project, const std::filesystem::path& project_dir) {
    const std::filesystem::path dir = std::filesystem::absolute(project_dir).lexically_normal();
    return convertPaths(project, [&dir](const std::filesystem::path& path) {
        return path.is_absolute() ? path : (dir / path).lexically_normal();
    });
}

analysis::Inputs inputsOf(const Project& project) {
    return {project.soil, project.wheel, project.conditions};
}

}  // namespace terra::project
