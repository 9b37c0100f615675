#include "core/io/field_json.h"

#include <cmath>

#include "core/common/units.h"
#include "core/io/csv.h"
#include "core/io/json.h"
#include "core/io/json_reader.h"
#include "core/io/raster_io.h"

namespace terra::io {

namespace {

using nlohmann::json;
namespace fs = std::filesystem;

fs::path beside(const std::string& path, const fs::path& base_dir) {
    const fs::path p(path);
    return p.is_relative() && !base_dir.empty() ? base_dir / p : p;
}

// A preset name, or a path relative to the field file when one exists there.
std::string locate(const std::string& name_or_path, const fs::path& base_dir) {
    std::error_code ec;
    const fs::path there = beside(name_or_path, base_dir);
    return fs::is_regular_file(there, ec) ? there.string() : name_or_path;
}

void reportAll(ObjectReader& r, const std::string& key, const std::vector<Issue>& issues) {
    for (const Issue& issue : issues)
        r.report(key, (issue.where.empty() ? "" : issue.where + ": ") + issue.message);
}

// A raster of the field that names its coordinate system (a GeoTIFF's EPSG code).
struct RasterCrs {
    std::string where;  // "field.json: height"
    std::string key;    // "height", "parameters.c_kPa"
    std::string file;
    int epsg = 0;
};

std::optional<field::Raster> readRasterAt(ObjectReader& r, const std::string& key,
                                          const fs::path& base_dir, Presence presence,
                                          std::vector<RasterCrs>& crs) {
    std::string path;
    if (!r.text(key, path, presence)) return std::nullopt;
    const fs::path file = beside(path, base_dir);
    Result<field::Raster> raster = readRaster(file);
    if (!raster) {
        reportAll(r, key, raster.issues());
        return std::nullopt;
    }
    if (raster->epsg) crs.push_back({r.where(key), r.pathOf(key), file.string(), *raster->epsg});
    return std::move(raster).value();
}

// The issue's "a coordinate system that differs from the other map": every raster naming a code
// other than the first one's, with both files and codes.
void checkOneCrs(const std::vector<RasterCrs>& crs, std::vector<Issue>& issues) {
    for (const RasterCrs& c : crs) {
        if (c.epsg == crs.front().epsg) continue;
        issues.push_back(
            {c.where, c.file + " is in EPSG:" + std::to_string(c.epsg) + ", but " +
                          crs.front().key + " (" + crs.front().file +
                          ") is in EPSG:" + std::to_string(crs.front().epsg) +
                          ": a field's rasters must share one coordinate system (reproject one "
                          "with gdalwarp -t_srs EPSG:" +
                          std::to_string(crs.front().epsg) + ")"});
    }
}

// A soil: a preset name or file, or an inline object; its "profile" likewise.
std::optional<soil::SoilParameters> readSoilAt(ObjectReader& r, const std::string& key,
                                               const fs::path& base_dir,
                                               const PresetLocations& locations,
                                               Presence presence) {
    const json* v = r.value(key, presence, "a soil preset name, a file or an object");
    if (v == nullptr) return std::nullopt;
    if (v->is_string()) {
        Result<soil::SoilParameters> soil =
            resolveSoil(locations, locate(v->get<std::string>(), base_dir));
        if (!soil) {
            reportAll(r, key, soil.issues());
            return std::nullopt;
        }
        return std::move(soil).value();
    }
    if (v->is_object()) {
        const std::size_t before = r.issues().size();
        ObjectReader s = r.object(key);
        soil::SoilParameters soil = readSoil(s);
        s.finish();
        if (r.issues().size() != before) return std::nullopt;
        return soil;
    }
    r.report(key, "expected a soil preset name, a file or an object, got " + describeJson(*v));
    return std::nullopt;
}

// A legend entry: a soil (name, file or object), or {"label", "soil", "profile"}.
std::optional<soil::SoilParameters> readLegendEntry(ObjectReader& legend, const std::string& code,
                                                    const fs::path& base_dir,
                                                    const PresetLocations& locations,
                                                    std::string& label) {
    const json* v = legend.value(code);
    if (v == nullptr) return std::nullopt;
    if (v->is_string()) return readSoilAt(legend, code, base_dir, locations, Presence::kRequired);
    if (!v->is_object() || !v->contains("soil")) {
        legend.report(code,
                      "expected a soil preset name or {\"label\", \"soil\", \"profile\"}, got " +
                          describeJson(*v));
        return std::nullopt;
    }
    ObjectReader entry = legend.object(code);
    entry.text("label", label);
    std::optional<soil::SoilParameters> soil =
        readSoilAt(entry, "soil", base_dir, locations, Presence::kRequired);
    std::string profile;
    if (entry.text("profile", profile)) {
        Result<soil::SoilProfile> p = resolveProfile(locations, locate(profile, base_dir));
        if (!p) {
            reportAll(entry, "profile", p.issues());
        } else if (soil) {
            soil->profile = std::move(p).value();
        }
    }
    entry.finish();
    return soil;
}

}  // namespace

Result<FieldFile> fieldFromJson(const json& json_value, const std::string& where,
                                const fs::path& base_dir, const PresetLocations& locations) {
    std::vector<Issue> issues;
    ObjectReader r(json_value, issues, where);
    FieldFile file;
    r.text("name", file.map.name);
    r.text("source", file.source);
    std::vector<RasterCrs> crs;
    file.map.height = readRasterAt(r, "height", base_dir, Presence::kOptional, crs);
    if (std::optional<soil::SoilParameters> base =
            readSoilAt(r, "soil", base_dir, locations, Presence::kRequired))
        file.map.base = *base;
    file.map.soil_class = readRasterAt(r, "soil_classes", base_dir, Presence::kOptional, crs);
    if (r.has("legend")) {
        const json* legend_value = r.value("legend");
        if (legend_value != nullptr && !legend_value->is_object()) {
            r.report("legend",
                     "expected an object of class code → soil, got " + describeJson(*legend_value));
        } else if (legend_value != nullptr) {
            ObjectReader legend = r.object("legend");
            for (const auto& [code_text, entry] : legend_value->items()) {
                double code = 0.0;
                const bool whole = parseNumber(code_text, code) && code == std::round(code) &&
                                   std::abs(code) <= 1e9;
                if (!whole) {
                    legend.allow(code_text);
                    legend.report(code_text, "a class code must be a whole number, like \"1\"");
                    continue;
                }
                std::string label;
                if (std::optional<soil::SoilParameters> soil =
                        readLegendEntry(legend, code_text, base_dir, locations, label)) {
                    const int c = static_cast<int>(code);
                    file.labels[c] = label.empty() ? soil->name : label;
                    file.map.legend[c] = std::move(*soil);
                }
            }
            legend.finish();
        }
    } else if (file.map.soil_class) {
        r.report("legend", "missing: soil_classes needs a legend of class code → soil");
    }
    ObjectReader params = r.object("parameters");
    if (const json* p = r.has("parameters") ? &json_value.at("parameters") : nullptr;
        p != nullptr && p->is_object()) {
        for (const auto& [key, value] : p->items()) {
            const soil::SoilField* f = soil::findSoilField(key);
            if (f == nullptr) {
                params.allow(key);
                std::vector<std::string> keys;
                for (const soil::SoilField& sf : soil::soilFields()) keys.emplace_back(sf.key);
                const std::string near = nearestName(key, keys);
                params.report(
                    key, "is not a soil parameter" +
                             (near.empty() ? std::string() : " (did you mean '" + near + "'?)"));
                continue;
            }
            if (std::optional<field::Raster> raster =
                    readRasterAt(params, key, base_dir, Presence::kRequired, crs))
                file.map.parameters.push_back({f, std::move(*raster)});
        }
    }
    params.finish();
    r.finish();
    checkOneCrs(crs, issues);
    if (issues.empty()) {
        for (Issue& issue : field::validate(file.map)) {
            issue.where = where + ": " + issue.where;
            issues.push_back(std::move(issue));
        }
    }
    if (!issues.empty()) return issues;
    return file;
}

nlohmann::json toJson(const field::FieldSummary& s) {
    json j = {{"name", s.name},
              {"extent_m", {s.x_min_m, s.y_min_m, s.x_max_m, s.y_max_m}},
              {"height_m", s.height_min_m ? json{*s.height_min_m, *s.height_max_m} : json(nullptr)},
              {"max_slope_deg", units::radToDeg(s.max_slope_rad)},
              {"mean_slope_deg", units::radToDeg(s.mean_slope_rad)},
              {"height_cell_m", s.height_cell_m},
              {"class_cell_m", s.class_cell_m},
              {"classes", json::array()},
              {"parameters", s.parameters}};
    for (const field::ClassArea& c : s.classes) {
        j["classes"].push_back({{"code", c.code},
                                {"label", c.label},
                                {"soil", c.soil},
                                {"profile", c.profile},
                                {"area_m2", c.area_m2},
                                {"share", c.share}});
    }
    return j;
}

Result<FieldFile> loadField(const fs::path& path, const PresetLocations& locations) {
    Result<json> parsed = readJsonFile(path);
    if (!parsed) return parsed.issues();
    return fieldFromJson(parsed.value(), path.string(), path.parent_path(), locations);
}

}  // namespace terra::io
