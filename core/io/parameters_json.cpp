#include "core/io/parameters_json.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "core/common/build_info.h"
#include "core/io/atomic_file.h"

namespace terra::io {
namespace {

using nlohmann::json;

std::string typeName(const json& value) { return value.type_name(); }

// Reads one numeric field into `out`; reports a missing key, a wrong type or a non-finite value.
bool readNumber(const json& object, const std::string& key, const std::string& where,
                const Range& range, const std::string& unit, bool required, double& out,
                std::vector<Issue>& issues) {
    const auto it = object.find(key);
    if (it == object.end()) {
        if (required) {
            issues.push_back({where + key, "missing; expected a number in " + range.describe() +
                                               (unit.empty() || unit == "-" ? "" : " " + unit)});
        }
        return false;
    }
    if (!it->is_number()) {
        issues.push_back({where + key, "expected a number in " + range.describe() + ", got " +
                                           typeName(*it) + " " + it->dump()});
        return false;
    }
    out = it->get<double>();
    return checkRange(issues, where + key, out, range, unit == "-" ? "" : unit);
}

void readText(const json& object, const char* key, const std::string& where, std::string& out,
              std::vector<Issue>& issues) {
    const auto it = object.find(key);
    if (it == object.end()) return;
    if (!it->is_string()) {
        issues.push_back({where + key, std::string("expected a string, got ") + typeName(*it)});
        return;
    }
    out = it->get<std::string>();
}

void rejectUnknownKeys(const json& object, const std::string& where,
                       const std::vector<std::string>& known, std::vector<Issue>& issues) {
    for (const auto& [key, value] : object.items()) {
        if (std::find(known.begin(), known.end(), key) == known.end()) {
            std::string list;
            for (const std::string& k : known) list += (list.empty() ? "" : ", ") + k;
            issues.push_back({where + key, "unknown key; allowed keys: " + list});
        }
    }
}

template <typename T, typename Parse>
Result<T> loadJsonFile(const std::filesystem::path& path, Parse parse) {
    std::string text;
    if (const auto error = readFile(path, text)) return std::vector<Issue>{{path.string(), *error}};
    json document;
    try {
        document = json::parse(text);
    } catch (const json::parse_error& e) {
        return std::vector<Issue>{{path.string(), std::string("invalid JSON: ") + e.what()}};
    }
    return parse(document, path.string());
}

template <typename T, typename Load>
Result<T> resolve(const PresetLocations& locations, const std::string& kind,
                  const std::string& name_or_path, Load load) {
    namespace fs = std::filesystem;
    std::error_code ec;
    // A bare name ("A", "sandy-loam") is a preset even if a file of that name happens to be in
    // the working directory; anything with a '/' or a ".json" ending is a path.
    const bool looks_like_path = name_or_path.find('/') != std::string::npos ||
                                 fs::path(name_or_path).extension() == ".json";
    if (looks_like_path && fs::is_regular_file(name_or_path, ec)) return load(name_or_path);
    for (const fs::path& dir : locations.directories) {
        const fs::path candidate = dir / kind / (name_or_path + ".json");
        if (fs::is_regular_file(candidate, ec)) return load(candidate);
    }
    if (fs::is_regular_file(name_or_path, ec)) return load(name_or_path);
    const std::string field = kind == "soils" ? "soil" : "wheel";
    if (looks_like_path) {
        // A path is never a preset name: say what is wrong with the path.
        return std::vector<Issue>{{field, fs::exists(name_or_path, ec)
                                              ? "'" + name_or_path + "' is not a regular file"
                                              : "file '" + name_or_path + "' does not exist"}};
    }
    std::string names;
    for (const std::string& n : presetNames(locations, kind))
        names += (names.empty() ? "" : ", ") + n;
    return std::vector<Issue>{{field, "'" + name_or_path +
                                          "' is neither a file nor a preset; presets: " +
                                          (names.empty() ? "(none found)" : names)}};
}

}  // namespace

Result<soil::SoilParameters> soilFromJson(const json& object, const std::string& where) {
    const std::string at = where.empty() ? "" : where + ": ";
    if (!object.is_object()) return std::vector<Issue>{{where, "expected a JSON object"}};
    std::vector<Issue> issues;
    soil::SoilParameters soil;
    readText(object, "name", at, soil.name, issues);
    readText(object, "source", at, soil.source, issues);
    std::vector<std::string> known{"name", "source"};
    for (const soil::SoilField& field : soil::soilFields()) {
        known.emplace_back(field.key);
        double value = 0.0;
        if (readNumber(object, field.key, at, field.range, field.unit, field.required, value,
                       issues)) {
            soil::setUserValue(soil, field, value);
        }
    }
    rejectUnknownKeys(object, at, known, issues);
    if (issues.empty()) {
        for (Issue& issue : soil::validate(soil, at)) issues.push_back(std::move(issue));
    }
    if (!issues.empty()) return issues;
    return soil;
}

Result<wheel::WheelParameters> wheelFromJson(const json& object, const std::string& where) {
    const std::string at = where.empty() ? "" : where + ": ";
    if (!object.is_object()) return std::vector<Issue>{{where, "expected a JSON object"}};
    std::vector<Issue> issues;
    wheel::WheelParameters wheel;
    readText(object, "name", at, wheel.name, issues);
    readText(object, "source", at, wheel.source, issues);
    readNumber(object, "r_m", at, wheel::kRadiusRange, "m", true, wheel.radius_m, issues);
    readNumber(object, "b_m", at, wheel::kWidthRange, "m", true, wheel.width_m, issues);
    rejectUnknownKeys(object, at, {"name", "source", "r_m", "b_m"}, issues);
    if (!issues.empty()) return issues;
    return wheel;
}

json toJson(const soil::SoilParameters& soil) {
    json out{{"name", soil.name}};
    if (!soil.source.empty()) out["source"] = soil.source;
    for (const soil::SoilField& field : soil::soilFields()) {
        const double value = soil::userValue(soil, field);
        if (!field.required) {
            const bool unset =
                std::isinf(value) ||
                (field.member == &soil::SoilParameters::sinkage_exponent_slip && value == 0.0);
            if (unset) continue;
        }
        out[field.key] = value;
    }
    return out;
}

json toJson(const wheel::WheelParameters& wheel) {
    json out{{"name", wheel.name}, {"r_m", wheel.radius_m}, {"b_m", wheel.width_m}};
    if (!wheel.source.empty()) out["source"] = wheel.source;
    return out;
}

Result<soil::SoilParameters> loadSoil(const std::filesystem::path& path) {
    return loadJsonFile<soil::SoilParameters>(path, soilFromJson);
}

Result<wheel::WheelParameters> loadWheel(const std::filesystem::path& path) {
    return loadJsonFile<wheel::WheelParameters>(path, wheelFromJson);
}

PresetLocations PresetLocations::standard(const std::filesystem::path& executable_dir) {
    PresetLocations out;
    if (const char* env = std::getenv("TERRASTUDIO_RESOURCES"); env && *env) {
        out.directories.emplace_back(env);
    }
    if (!executable_dir.empty()) {
        out.directories.push_back(executable_dir / build_info::kDataDirFromExecutable);
        out.directories.push_back(executable_dir / "resources");
    }
    return out;
}

std::vector<std::string> presetNames(const PresetLocations& locations, const std::string& kind) {
    namespace fs = std::filesystem;
    std::vector<std::string> names;
    std::error_code ec;
    for (const fs::path& dir : locations.directories) {
        if (!fs::is_directory(dir / kind, ec)) continue;
        for (const auto& entry : fs::directory_iterator(dir / kind, ec)) {
            if (entry.path().extension() == ".json") names.push_back(entry.path().stem().string());
        }
    }
    std::sort(names.begin(), names.end());
    names.erase(std::unique(names.begin(), names.end()), names.end());
    return names;
}

Result<soil::SoilParameters> resolveSoil(const PresetLocations& locations,
                                         const std::string& name_or_path) {
    return resolve<soil::SoilParameters>(
        locations, "soils", name_or_path,
        [](const std::filesystem::path& p) { return loadSoil(p); });
}

Result<wheel::WheelParameters> resolveWheel(const PresetLocations& locations,
                                            const std::string& name_or_path) {
    return resolve<wheel::WheelParameters>(
        locations, "wheels", name_or_path,
        [](const std::filesystem::path& p) { return loadWheel(p); });
}

}  // namespace terra::io
