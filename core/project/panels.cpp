#include "core/project/panels.h"

#include <algorithm>
#include <limits>
#include <type_traits>

#include "core/contact/operating_fields.h"
#include "core/gsa/wheel_target.h"
#include "core/io/declared_json.h"
#include "core/scenario/scenario_json.h"

namespace terra::project {

using io::ObjectReader;

void readPanelSettings(ObjectReader& r, ForcesPanelSettings& out) { io::readFields(r, out); }

void readPanelSettings(ObjectReader& r, StressPanelSettings& out) { io::readFields(r, out); }

void readPanelSettings(ObjectReader& r, CompactionPanelSettings& out,
                       const io::PresetLocations* locations) {
    analysis::readCompactionSettings(r, out.analysis, locations);
}

void readPanelSettings(ObjectReader& r, SensitivityPanelSettings& out) {
    io::readFields(r, out);
    analysis::reportSensitivityRules(r, out.analysis);
}

std::vector<std::string> splitPriorItems(const std::string& text) {
    std::vector<std::string> out;
    std::size_t begin = 0;
    while (begin <= text.size()) {
        const std::size_t comma = std::min(text.find(',', begin), text.size());
        const std::string item = text.substr(begin, comma - begin);
        const std::size_t first = item.find_first_not_of(" \t");
        if (first != std::string::npos)
            out.push_back(item.substr(first, item.find_last_not_of(" \t") - first + 1));
        begin = comma + 1;
    }
    return out;
}

void readOldPriorItems(ObjectReader& r, const char* key, analysis::IdentificationSettings& fit) {
    std::string text;
    if (r.text(key, text)) fit.prior_items = splitPriorItems(text);
}

void readOldValidation(ObjectReader& r, const char* key, analysis::IdentificationSettings& fit) {
    std::string validation;
    if (!r.choiceName(key, validation, {"none", "holdout", "folds"})) return;
    fit.holdout_fraction = validation == "holdout" ? kPanelHoldoutFraction : 0.0;
    fit.folds = validation == "folds" ? kPanelFolds : 0;
}

void readPanelSettings(ObjectReader& r, IdentificationPanelSettings& out) {
    io::readFields(r, out);
    // An old parameter key in the priors (either form) or "fix" ("Ks", issue 26): read as its
    // new one, with the note the command line gives (the panel shows it).
    analysis::noteDeprecatedParameterKeys(
        r, out.fit, r.has("prior_items") && !r.has("priors") ? "prior_items" : "priors");
}

void readEditedScenarios(ObjectReader& r, const char* key, nlohmann::json& out) {
    if (!r.has(key)) {
        r.allow(key);
        return;
    }
    ObjectReader edited = r.object(key);
    if (!edited.isObject()) return;
    const nlohmann::json& all = *r.value(key);
    for (const auto& [name, scenario] : all.items()) {
        edited.allow(name);
        if (!scenario.is_object())
            edited.report(name, "expected a scenario object, got " + io::describeJson(scenario));
    }
    out = all;
}

void readPanelSettings(ObjectReader& r, RoverPanelSettings& out,
                       const io::PresetLocations* locations,
                       const std::filesystem::path& base_dir) {
    io::readFields(r, out);
    // Each edited scenario checked as a scenario (the presets it may name are needed; its relative
    // file names, a dropped robot's, against the project's folder).
    if (locations == nullptr || !r.has("edited") || !r.value("edited")->is_object()) return;
    for (const auto& [name, scenario] : r.value("edited")->items()) {
        if (!scenario.is_object()) continue;  // reported by readEditedScenarios
        const Result<scenario::Scenario> parsed =
            scenario::scenarioFromJson(scenario, "", *locations, base_dir);
        for (const Issue& issue : parsed.issues())
            r.report("edited." + name,
                     (issue.where.empty() ? "" : issue.where + ": ") + issue.message);
    }
}

const std::vector<fields::Name<std::string>>& globalSensitivityOutputNames() {
    static const std::vector<std::string> names = gsa::outputNames();
    static const std::vector<fields::Name<std::string>> choices = [] {
        std::vector<fields::Name<std::string>> out;
        for (const std::string& name : names) out.push_back({name.c_str(), name});
        return out;
    }();
    return choices;
}

void readPanelSettings(ObjectReader& r, GlobalSensitivityPanelSettings& out) {
    io::readFields(r, out);
}

nlohmann::json toJson(const GlobalSensitivityPanelSettings& s) { return io::fieldsToJson(s); }

nlohmann::json toJson(const ForcesPanelSettings& s) { return io::fieldsToJson(s); }

nlohmann::json toJson(const StressPanelSettings& s) { return io::fieldsToJson(s); }

nlohmann::json toJson(const CompactionPanelSettings& s) { return analysis::toJson(s.analysis); }

nlohmann::json toJson(const SensitivityPanelSettings& s) { return io::fieldsToJson(s); }

nlohmann::json toJson(const IdentificationPanelSettings& s) { return io::fieldsToJson(s); }

nlohmann::json toJson(const RoverPanelSettings& s) { return io::fieldsToJson(s); }

void readPanels(ObjectReader& panels, const io::PresetLocations* locations,
                const std::filesystem::path& base_dir) {
    // Each panel's settings are read into a default-constructed value (by reference: GCC 12
    // warns of a maybe-uninitialized vector when a temporary is copied into the lambda).
    auto check = [&](const char* name, auto& settings) {
        if (!panels.has(name)) {
            panels.allow(name);
            return;
        }
        ObjectReader r = panels.object(name);
        using Settings = std::remove_cvref_t<decltype(settings)>;
        if constexpr (std::is_same_v<Settings, RoverPanelSettings>) {
            readPanelSettings(r, settings, locations, base_dir);
        } else if constexpr (std::is_same_v<Settings, CompactionPanelSettings>) {
            readPanelSettings(r, settings, locations);
        } else {
            readPanelSettings(r, settings);
        }
        r.finish();
    };
    ForcesPanelSettings forces;
    StressPanelSettings stresses;
    CompactionPanelSettings compaction;
    SensitivityPanelSettings sensitivity;
    IdentificationPanelSettings identification;
    RoverPanelSettings rover;
    GlobalSensitivityPanelSettings global_sensitivity;
    check("forces", forces);
    check("stresses", stresses);
    check("compaction", compaction);
    check("sensitivity", sensitivity);
    check("identification", identification);
    check("rover", rover);
    check("global-sensitivity", global_sensitivity);
}

}  // namespace terra::project
