#include "core/io/parameters_json.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "core/common/build_info.h"
#include "core/common/quoted.h"
#include "core/io/atomic_file.h"
#include "core/io/json.h"

namespace terra::io {
namespace {

using nlohmann::json;

template <typename T, typename Parse>
Result<T> loadJsonFile(const std::filesystem::path& path, Parse parse) {
    return readJsonFileWith<T>(path, parse);
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
    // A path to something that is not a regular file (a folder, /dev/zero, a FIFO) goes to the
    // reader too, which refuses it naming its kind.
    if (looks_like_path && fs::exists(name_or_path, ec)) return load(name_or_path);
    for (const fs::path& dir : locations.directories) {
        const fs::path candidate = dir / kind / (name_or_path + ".json");
        if (fs::is_regular_file(candidate, ec)) return load(candidate);
    }
    if (fs::is_regular_file(name_or_path, ec)) return load(name_or_path);
    const std::string field = kind == "soils" ? "soil" : "wheel";
    if (looks_like_path) {
        // A path is never a preset name: say what is wrong with the path.
        return std::vector<Issue>{{field, "file " + quoteText(name_or_path) + " does not exist"}};
    }
    std::string names;
    for (const std::string& n : presetNames(locations, kind))
        names += (names.empty() ? "" : ", ") + n;
    return std::vector<Issue>{{field, quoteText(name_or_path) +
                                          " is neither a file nor a preset; presets: " +
                                          (names.empty() ? "(none found)" : names)}};
}

}  // namespace

soil::SoilParameters readSoil(ObjectReader& r) {
    soil::SoilParameters soil;
    const std::size_t before = r.issues().size();
    r.text("name", soil.name);
    r.text("source", soil.source);
    for (const soil::SoilField& field : soil::soilFields()) {
        r.field(field, soil.*field.member,
                field.required ? Presence::kRequired : Presence::kOptional);
    }
    // The rules across fields (N = n + n1 s in range) once every field is valid on its own.
    if (r.isObject() && r.issues().size() == before) {
        for (Issue& issue : soil::validate(soil)) r.report(issue.where, std::move(issue.message));
    }
    return soil;
}

wheel::WheelParameters readWheel(ObjectReader& r) {
    wheel::WheelParameters wheel;
    r.text("name", wheel.name);
    r.text("source", wheel.source);
    const std::size_t before = r.issues().size();
    for (const wheel::WheelField& field : wheel::wheelFields()) {
        r.field(field, wheel.*field.member,
                field.required ? Presence::kRequired : Presence::kOptional);
    }
    // The rules across fields (a whole grouser count, grousers below the radius).
    if (r.isObject() && r.issues().size() == before) {
        for (Issue& issue : wheel::validate(wheel)) r.report(issue.where, std::move(issue.message));
    }
    return wheel;
}

Result<soil::SoilParameters> soilFromJson(const json& object, const std::string& where) {
    std::vector<Issue> issues;
    ObjectReader r(object, issues, where);
    soil::SoilParameters soil = readSoil(r);
    r.finish();
    if (!issues.empty()) return issues;
    return soil;
}

Result<wheel::WheelParameters> wheelFromJson(const json& object, const std::string& where) {
    std::vector<Issue> issues;
    ObjectReader r(object, issues, where);
    wheel::WheelParameters wheel = readWheel(r);
    r.finish();
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
    for (const wheel::WheelField& field : wheel::wheelFields()) {
        if (!field.required && wheel.*field.member != 0.0) out[field.key] = field.userValue(wheel);
    }
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
