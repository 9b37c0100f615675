// The compaction's settings on their declared field list (CompactionSettings::visitFields): the
// keys scripts and projects hold are read as before, toJson writes what the reader reads back, a
// struct built in code is checked in the reader's words.
#include <gtest/gtest.h>

#include <string>

#include "core/analysis/compaction.h"
#include "tests/core/test_support.h"

namespace terra::analysis {
namespace compaction_settings_test {

using terra::testing::contains;
using terra::testing::kLocations;
using terra::testing::messageOf;
using terra::testing::sandyLoamOnA;

// The settings of `json` (a script's analysis object, profiles found among the presets) and the
// issues of reading them.
std::pair<CompactionSettings, std::vector<Issue>> readCompactionOf(const nlohmann::json& json) {
    std::vector<Issue> issues;
    io::ObjectReader r(json, issues, "script.json", "analyses[0]");
    CompactionSettings s;
    readCompactionSettings(r, s, &kLocations);
    r.finish();
    return {s, issues};
}

// The message of the issue at `key`, or "(none)".
std::string compactionIssueAt(const std::vector<Issue>& issues, const std::string& key) {
    for (const Issue& issue : issues) {
        if (issue.where == "script.json: analyses[0]." + key) return issue.message;
    }
    return "(none)";
}

TEST(CompactionSettingsKeys, EveryKeyIsReadIntoItsMemberAndWrittenBack) {
    const auto [s, issues] = readCompactionOf({{"slip", 0.2},
                                               {"slip_angle_deg", 5.0},
                                               {"concentration", 4.0},
                                               {"depths_m", {0.2, 0.4, 0.6}},
                                               {"passes", 3},
                                               {"width", "parabolic"},
                                               {"risk_stress", "sigma_1"},
                                               {"reload_k0_kPa_m", 40000.0},
                                               {"reload_Au_kPa_m2", 250.0},
                                               {"shear_memory", false},
                                               {"profile", "loam-moist"},
                                               {"map_points", {12, 8}},
                                               {"map_pass", 2},
                                               {"bulldozing", "hegedus"}});
    ASSERT_TRUE(issues.empty()) << formatIssues(issues);
    EXPECT_EQ(s.slip, 0.2);
    EXPECT_EQ(s.slip_angle_deg, 5.0);
    EXPECT_EQ(s.concentration.value_or(0.0), 4.0);
    EXPECT_EQ(s.depths_m, (std::vector<double>{0.2, 0.4, 0.6}));
    EXPECT_EQ(s.passes, 3);
    EXPECT_EQ(s.width, compaction::WidthProfile::kParabolic);
    EXPECT_EQ(s.risk_stress, RiskStress::kMajor);
    EXPECT_EQ(s.reload.k0_pa_m, 40000.0 * 1e3);  // kPa/m in the file, Pa/m in the member
    EXPECT_EQ(s.reload.au_pa_m2, 250.0 * 1e3);
    EXPECT_FALSE(s.reload.shear_memory);
    ASSERT_TRUE(s.profile.has_value());  // the preset, found by name
    EXPECT_EQ(s.profile->name, io::resolveProfile(kLocations, "loam-moist").value().name);
    EXPECT_EQ(s.map_x_points, 12);
    EXPECT_EQ(s.map_z_points, 8);
    EXPECT_EQ(s.map_pass, 2);
    EXPECT_EQ(s.model.bulldozing, contact::BulldozingModel::kHegedus);

    // toJson writes every key the reader read (the profile as its object), and reads back to
    // the same settings.
    const nlohmann::json j = toJson(s);
    EXPECT_EQ(j, (nlohmann::json{{"slip", 0.2},
                                 {"slip_angle_deg", 5.0},
                                 {"concentration", 4.0},
                                 {"depths_m", {0.2, 0.4, 0.6}},
                                 {"passes", 3},
                                 {"width", "parabolic"},
                                 {"risk_stress", "sigma_1"},
                                 {"reload_k0_kPa_m", 40000.0},
                                 {"reload_Au_kPa_m2", 250.0},
                                 {"shear_memory", false},
                                 {"profile", io::toJson(*s.profile)},
                                 {"map_points", {12, 8}},
                                 {"map_pass", 2},
                                 {"bulldozing", "hegedus"}}));
    const auto [back, back_issues] = readCompactionOf(j);
    ASSERT_TRUE(back_issues.empty()) << formatIssues(back_issues);
    EXPECT_EQ(toJson(back), j);
}

TEST(CompactionSettingsKeys, AbsentKeysKeepTheDefaultsAndNoMapWritesNoMapKeys) {
    const auto [s, issues] = readCompactionOf(nlohmann::json::object());
    ASSERT_TRUE(issues.empty()) << formatIssues(issues);
    EXPECT_EQ(toJson(s), toJson(CompactionSettings{}));
    const nlohmann::json j = toJson(s);
    EXPECT_EQ(j["reload_k0_kPa_m"], 50000.0);  // Chrono SCM's K_e
    EXPECT_EQ(j["depths_m"].size(), 19u);
    for (const char* key : {"concentration", "profile", "map_points", "map_pass", "bulldozing"})
        EXPECT_FALSE(j.contains(key)) << key;
}

TEST(CompactionSettingsKeys, BadValuesAreNamedWithTheirRanges) {
    const auto [s, issues] = readCompactionOf({{"slip", 1.5},
                                               {"passes", 0},
                                               {"depths_m", {0.3, 0.2}},
                                               {"concentration", 1.0},
                                               {"reload_k0_kPa_m", -1.0},
                                               {"width", "parabola"},
                                               {"map_points", {12, 8}},
                                               {"map_pass", 3},
                                               {"pases", 2}});
    EXPECT_EQ(issues.size(), 7u) << formatIssues(issues);
    EXPECT_EQ(compactionIssueAt(issues, "slip"), "1.5 is outside the allowed range [-1, 1]");
    EXPECT_EQ(compactionIssueAt(issues, "passes"), "0 is outside the allowed range [1, 1000]");
    EXPECT_EQ(compactionIssueAt(issues, "depths_m"), "depths must increase (0.2 after 0.3)");
    EXPECT_EQ(compactionIssueAt(issues, "concentration"),
              "1 is outside the allowed range [2.5, 12]");
    EXPECT_EQ(compactionIssueAt(issues, "reload_k0_kPa_m"),
              "-1 is outside the allowed range [0, 1e+09] kPa/m");
    EXPECT_TRUE(contains(compactionIssueAt(issues, "width"), "did you mean \"parabolic\""))
        << formatIssues(issues);
    // A map pass beyond the passes is compute's to refuse (a panel merges partial objects).
    EXPECT_EQ(compactionIssueAt(issues, "map_pass"), "(none)");
    EXPECT_TRUE(contains(compactionIssueAt(issues, "pases"), "did you mean \"passes\""))
        << formatIssues(issues);
}

// A struct built in code (a panel's, Python's) is checked in the reader's words when computed.
TEST(CompactionSettingsKeys, ComputeChecksASettingsStructBuiltInCode) {
    CompactionSettings s;
    s.slip = 1.5;
    s.passes = 0;
    s.concentration = 1.0;
    const std::string message = messageOf([&] { computeCompaction(sandyLoamOnA(), s); });
    EXPECT_TRUE(contains(message, "slip: 1.5 is outside the allowed range [-1, 1]")) << message;
    EXPECT_TRUE(contains(message, "passes: 0 is outside the allowed range [1, 1000]")) << message;
    EXPECT_TRUE(contains(message, "concentration: 1 is outside the allowed range [2.5, 12]"))
        << message;
    s = {};
    s.depths_m = {0.3, 0.2};
    s.reload.k0_pa_m = 0.0;
    EXPECT_EQ(messageOf([&] { computeCompaction(sandyLoamOnA(), s); }),
              "depths_m: depths must increase (0.2 after 0.3)\n"
              "reload_k0_kPa_m: the reload stiffness k0 + Au z must be > 0: give k0 > 0 or Au > 0");
    s = {};
    s.map_x_points = 12;
    s.map_z_points = 8;
    s.map_pass = 3;
    EXPECT_EQ(messageOf([&] { computeCompaction(sandyLoamOnA(), s); }),
              "map_pass: 3 is outside [1, passes = 1]");
    s = {};
    s.depths_m.clear();
    EXPECT_EQ(messageOf([&] { computeCompaction(sandyLoamOnA(), s); }),
              "depths_m: give at least one depth");
    EXPECT_TRUE(computeCompaction(sandyLoamOnA(), CompactionSettings{}).ok());
}

}  // namespace compaction_settings_test
}  // namespace terra::analysis
