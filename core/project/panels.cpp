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

void readPanelSettings(ObjectReader& r, ForcesPanelSettings& out) { r.text("plot", out.plot); }

void readPanelSettings(ObjectReader& r, StressPanelSettings& out) {
    analysis::readStressSettings(r, out.analysis);
}

void readPanelSettings(ObjectReader& r, CompactionPanelSettings& out,
                       const io::PresetLocations* locations) {
    analysis::readCompactionSettings(r, out.analysis, locations);
}

void readPanelSettings(ObjectReader& r, SensitivityPanelSettings& out) {
    analysis::readSensitivitySettings(r, out.analysis);
    r.choiceName("plot", out.plot, {"Fx", "Fs", "tornado"});
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

void readPanelSettings(ObjectReader& r, RoverPanelSettings& out,
                       const io::PresetLocations* locations) {
    r.text("scenario", out.scenario);
    if (!r.has("edited")) {
        r.allow("edited");
        return;
    }
    ObjectReader edited = r.object("edited");
    if (!edited.isObject()) return;
    const nlohmann::json& all = *r.value("edited");
    for (const auto& [name, scenario] : all.items()) {
        edited.allow(name);
        if (locations != nullptr) {
            const Result<scenario::Scenario> parsed =
                scenario::scenarioFromJson(scenario, "", *locations);
            for (const Issue& issue : parsed.issues())
                edited.report(name,
                              (issue.where.empty() ? "" : issue.where + ": ") + issue.message);
        } else if (!scenario.is_object()) {
            edited.report(name, "expected a scenario object, got " + io::describeJson(scenario));
        }
    }
    out.edited = all;
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

nlohmann::json toJson(const ForcesPanelSettings& s) { return {{"plot", s.plot}}; }

nlohmann::json toJson(const StressPanelSettings& s) { return analysis::toJson(s.analysis); }

nlohmann::json toJson(const CompactionPanelSettings& s) { return analysis::toJson(s.analysis); }

nlohmann::json toJson(const SensitivityPanelSettings& s) {
    nlohmann::json out = analysis::toJson(s.analysis);
    out["plot"] = s.plot;
    return out;
}

nlohmann::json toJson(const IdentificationPanelSettings& s) { return io::fieldsToJson(s); }

nlohmann::json toJson(const RoverPanelSettings& s) {
    return {{"scenario", s.scenario}, {"edited", s.edited}};
}

void readPanels(ObjectReader& panels, const io::PresetLocations* locations) {
    // Each panel's settings are read into a default-constructed value (by reference: GCC 12
    // warns of a maybe-uninitialized vector when a temporary is copied into the lambda).
    auto check = [&](const char* name, auto& settings) {
        if (!panels.has(name)) {
            panels.allow(name);
            return;
        }
        ObjectReader r = panels.object(name);
        using Settings = std::remove_cvref_t<decltype(settings)>;
        if constexpr (std::is_same_v<Settings, RoverPanelSettings> ||
                      std::is_same_v<Settings, CompactionPanelSettings>) {
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
