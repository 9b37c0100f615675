#include "core/project/panels.h"

#include <limits>
#include <type_traits>

#include "core/contact/operating_fields.h"
#include "core/gsa/wheel_target.h"
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

void readPanelSettings(ObjectReader& r, IdentificationPanelSettings& out) {
    const Range percent{0.0, 100.0};
    r.text("csv", out.csv);
    r.number("noise_percent", out.noise_percent, percent, "%");
    r.boolean("refine", out.refine);
    r.boolean("three_loads", out.three_loads);
    r.choiceName("page", out.page, {"fit", "streaming"});
    r.text("stream_csv", out.stream_csv);
    r.text("stream_second_soil", out.stream_second_soil);
    r.number("stream_noise_percent", out.stream_noise_percent, percent, "%");
    r.number("stream_speed", out.stream_speed, {0.0, 1000.0});
    r.boolean("stream_skip_bad_rows", out.stream_skip_bad_rows);
    r.text("prior_soil", out.prior_soil);
    r.text("prior_items", out.prior_items);
    r.choiceName("validation", out.validation, {"none", "holdout", "folds"});
    r.choiceName("loss", out.loss, {"l2", "huber", "cauchy"});
    r.text("wheel", out.wheel);
    r.choiceName("jmax", out.jmax, {"auto", "none", "fixed", "fit"});
    r.number("jmax_mm", out.jmax_mm, {0.1, 1000.0}, "mm");
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

void readPanelSettings(ObjectReader& r, GlobalSensitivityPanelSettings& out) {
    r.choiceName("page", out.page, {"indices", "bands"});
    r.choiceName("method", out.method, {"sobol", "morris"});
    r.choiceName("output", out.output, gsa::outputNames());
    r.numbers("slips", out.slips, contact::slipField().range, {}, 1, 1000);
    const FieldInfo& beta = contact::slipAngleField();
    r.number(beta.key, out.slip_angle_deg, beta.range, beta.displayUnit());
    r.integer("samples", out.samples, 2, 1 << 20);
    r.integer("band_samples", out.band_samples, 2, 1 << 20);
    r.integer("seed", out.seed, 0, std::numeric_limits<std::uint64_t>::max());
}

nlohmann::json toJson(const GlobalSensitivityPanelSettings& s) {
    return {{"page", s.page},
            {"method", s.method},
            {"output", s.output},
            {"slips", s.slips},
            {"slip_angle_deg", s.slip_angle_deg},
            {"samples", s.samples},
            {"band_samples", s.band_samples},
            {"seed", s.seed}};
}

nlohmann::json toJson(const ForcesPanelSettings& s) { return {{"plot", s.plot}}; }

nlohmann::json toJson(const StressPanelSettings& s) { return analysis::toJson(s.analysis); }

nlohmann::json toJson(const CompactionPanelSettings& s) { return analysis::toJson(s.analysis); }

nlohmann::json toJson(const SensitivityPanelSettings& s) {
    nlohmann::json out = analysis::toJson(s.analysis);
    out["plot"] = s.plot;
    return out;
}

nlohmann::json toJson(const IdentificationPanelSettings& s) {
    return {{"csv", s.csv},
            {"noise_percent", s.noise_percent},
            {"refine", s.refine},
            {"three_loads", s.three_loads},
            {"page", s.page},
            {"stream_csv", s.stream_csv},
            {"stream_second_soil", s.stream_second_soil},
            {"stream_noise_percent", s.stream_noise_percent},
            {"stream_speed", s.stream_speed},
            {"stream_skip_bad_rows", s.stream_skip_bad_rows},
            {"prior_soil", s.prior_soil},
            {"prior_items", s.prior_items},
            {"validation", s.validation},
            {"loss", s.loss},
            {"wheel", s.wheel},
            {"jmax", s.jmax},
            {"jmax_mm", s.jmax_mm}};
}

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
