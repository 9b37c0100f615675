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
    const std::string field = kind == "soils" ? "soil" : kind == "profiles" ? "profile" : "wheel";
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
    if (r.has("profile")) {
        ObjectReader p = r.object("profile");
        soil.profile = readProfile(p);
        p.finish();
    }
    // The identification's posterior that `identify --save-soil` writes beside the soil: read
    // (and checked) by those that sample from it (traction, bands, gsa --posterior), not part of
    // the soil.
    r.allow("posterior");
    return soil;
}

soil::SoilProfile readProfile(ObjectReader& r) {
    soil::SoilProfile profile;
    const std::size_t before = r.issues().size();
    r.text("name", profile.name);
    r.text("source", profile.source);
    const json* layers = r.array("layers", Presence::kRequired);
    const Range depth{0.0, 10.0};
    for (std::size_t i = 0; layers && i < layers->size(); ++i) {
        ObjectReader l = r.element("layers", *layers, i);
        soil::SoilLayer layer;
        l.number("top_m", layer.top_m, depth, "m", Presence::kRequired);
        l.number("bottom_m", layer.bottom_m, depth, "m", Presence::kRequired);
        double value = 0.0;
        // Clay's range is checked by soil::validate, which knows a percentage when it sees one.
        if (l.number("clay_kg_kg", value, Range{-1e300, 1e300})) layer.clay_kg_kg = value;
        if (l.number("bulk_density_Mg_m3", value, Range{0.5, 2.2}, "Mg/m3"))
            layer.bulk_density_kg_m3 = value * 1e3;
        if (l.number("particle_density_Mg_m3", value, Range{2.0, 3.0}, "Mg/m3"))
            layer.particle_density_kg_m3 = value * 1e3;
        if (l.number("matric_suction_hPa", value, Range{-1e300, 1e300}))
            layer.matric_suction_pa = value * 100.0;
        if (l.number("sigma_pc_kPa", value, Range{1.0, 5000.0}, "kPa"))
            layer.precompression_pa = value * 1e3;
        if (l.number("nu", value, Range{2.5, 12.0})) layer.concentration = value;
        if (l.has("compression")) {
            ObjectReader c = l.object("compression");
            soil::CompressionLaw law;
            if (c.number("N", value, Range{1.0, 5.0})) law.virgin_n = value;
            c.number("lambda", law.lambda, Range{1e-4, 1.0}, {}, Presence::kRequired);
            c.number("kappa", law.kappa, Range{0.0, 1.0}, {}, Presence::kRequired);
            if (c.number("kappa2", value, Range{0.0, 1.0})) law.kappa_steep = value;
            c.number("m", law.yield_offset, Range{0.0, 10.0});
            c.finish();
            layer.compression = law;
        }
        l.finish();
        profile.layers.push_back(layer);
    }
    if (r.issues().size() == before) {
        std::vector<Issue> rules = soil::validate(profile, "");
        for (Issue& issue : rules) {
            // "" prefix gives ".layers[1].x": the reader's path names the profile.
            std::string where = issue.where;
            if (!where.empty() && where.front() == '.') where.erase(0, 1);
            r.report(where, std::move(issue.message));
        }
    }
    return profile;
}

json toJson(const soil::SoilProfile& profile) {
    json out{{"name", profile.name}};
    if (!profile.source.empty()) out["source"] = profile.source;
    json layers = json::array();
    for (const soil::SoilLayer& l : profile.layers) {
        json layer{{"top_m", l.top_m},
                   {"bottom_m", l.bottom_m},
                   {"bulk_density_Mg_m3", l.bulk_density_kg_m3 / 1e3}};
        if (l.clay_kg_kg) layer["clay_kg_kg"] = *l.clay_kg_kg;
        if (l.matric_suction_pa) layer["matric_suction_hPa"] = *l.matric_suction_pa / 100.0;
        if (l.precompression_pa) layer["sigma_pc_kPa"] = *l.precompression_pa / 1e3;
        if (l.concentration) layer["nu"] = *l.concentration;
        if (l.particle_density_kg_m3 != soil::SoilLayer{}.particle_density_kg_m3)
            layer["particle_density_Mg_m3"] = l.particle_density_kg_m3 / 1e3;
        if (l.compression) {
            const soil::CompressionLaw& c = *l.compression;
            json law{{"lambda", c.lambda}, {"kappa", c.kappa}};
            if (c.virgin_n) law["N"] = *c.virgin_n;
            if (c.kappa_steep) law["kappa2"] = *c.kappa_steep;
            if (c.yield_offset != 0.0) law["m"] = c.yield_offset;
            layer["compression"] = law;
        }
        layers.push_back(layer);
    }
    out["layers"] = layers;
    return out;
}

Result<soil::SoilProfile> profileFromJson(const json& object, const std::string& where) {
    std::vector<Issue> issues;
    ObjectReader r(object, issues, where);
    soil::SoilProfile profile = readProfile(r);
    r.finish();
    if (!issues.empty()) return issues;
    return profile;
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
    if (soil.profile) out["profile"] = toJson(*soil.profile);
    for (const soil::SoilField& field : soil::soilFields()) {
        const double value = soil::userValue(soil, field);
        if (!field.required) {
            const bool unset = std::isinf(value) ||
                               ((field.member == &soil::SoilParameters::sinkage_exponent_slip ||
                                 field.member == &soil::SoilParameters::slip_sinkage_coefficient) &&
                                value == 0.0);
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

Result<soil::SoilProfile> loadProfile(const std::filesystem::path& path) {
    return loadJsonFile<soil::SoilProfile>(path, profileFromJson);
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

Result<soil::SoilProfile> resolveProfile(const PresetLocations& locations,
                                         const std::string& name_or_path) {
    return resolve<soil::SoilProfile>(
        locations, "profiles", name_or_path,
        [](const std::filesystem::path& p) { return loadProfile(p); });
}

}  // namespace terra::io
