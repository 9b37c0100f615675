// The sensitivity's settings on their declared field list (SensitivitySettings::visitFields):
// every key of a script into its member and back, bad values named with their ranges, an unknown
// key with the nearest, the values against the parameter's field, and a struct built in code
// refused by computeSensitivity in the reader's words.
#include <gtest/gtest.h>

#include "core/analysis/sensitivity.h"
#include "core/common/units.h"
#include "tests/core/analysis/settings_test_support.h"
#include "tests/core/test_support.h"

namespace terra::analysis {
namespace {

using terra::testing::contains;
using terra::testing::messageOf;
using terra::testing::readSettingsOf;
using terra::testing::sandyLoamOnA;
using terra::testing::settingsIssueAt;

std::pair<SensitivitySettings, std::vector<Issue>> readSensitivityOf(const nlohmann::json& json) {
    return readSettingsOf<SensitivitySettings>(json, readSensitivitySettings);
}

TEST(SensitivitySettingsKeys, EveryKeyOfAScriptIsReadIntoItsMemberAndBack) {
    const nlohmann::json j{{"parameter", "c_kPa"},          {"values", {0.5, 1.5}},
                           {"slip_angle_deg", {0.0, 10.0}}, {"slip_count", 20},
                           {"tornado_slip", 0.4},           {"entry_angle_deg", 20.0},
                           {"slips", {0.1, 0.2}},           {"max_stress_angle_deg", 10.0}};
    const auto [s, issues] = readSensitivityOf(j);
    ASSERT_TRUE(issues.empty()) << formatIssues(issues);
    EXPECT_EQ(s.parameter, "c_kPa");
    EXPECT_EQ(s.values, (std::vector<double>{0.5, 1.5}));
    EXPECT_EQ(s.slip_angles_deg, (std::vector<double>{0.0, 10.0}));
    EXPECT_EQ(s.slip_count, 20);
    EXPECT_EQ(s.tornado_slip, 0.4);
    EXPECT_EQ(*s.sweep.entry_angle_deg, 20.0);
    EXPECT_EQ(s.sweep.slips, (std::vector<double>{0.1, 0.2}));
    EXPECT_EQ(*s.sweep.model.max_stress_angle_rad, units::degToRad(10.0));
    EXPECT_EQ(toJson(s), j);
    const auto [back, back_issues] = readSensitivityOf(toJson(s));
    ASSERT_TRUE(back_issues.empty()) << formatIssues(back_issues);
    EXPECT_EQ(toJson(back), j);
    // One slip angle is a number (the form scripts and projects hold), as before.
    EXPECT_EQ(toJson(SensitivitySettings{}), (nlohmann::json{{"parameter", "phi_deg"},
                                                             {"slip_angle_deg", 10.0},
                                                             {"slip_count", 50},
                                                             {"tornado_slip", 0.3}}));
    const auto [one, one_issues] = readSensitivityOf({{"slip_angle_deg", 5.0}});
    ASSERT_TRUE(one_issues.empty()) << formatIssues(one_issues);
    EXPECT_EQ(one.slip_angles_deg, (std::vector<double>{5.0}));
}

TEST(SensitivitySettingsKeys, BadValuesAndUnknownKeysAreNamed) {
    {
        const auto [s, issues] = readSensitivityOf({{"parameter", "phi"},
                                                    {"slip_angle_deg", {0.0, 95.0}},
                                                    {"tornado_slip", 2.0},
                                                    {"slip_cont", 10}});
        EXPECT_EQ(issues.size(), 4u) << formatIssues(issues);
        EXPECT_TRUE(contains(settingsIssueAt(issues, "parameter"), "did you mean \"phi_deg\""))
            << formatIssues(issues);
        EXPECT_EQ(settingsIssueAt(issues, "slip_angle_deg[1]"),
                  "95 is outside the allowed range (-90, 90) deg");
        EXPECT_EQ(settingsIssueAt(issues, "tornado_slip"),
                  "2 is outside the allowed range [-1, 1]");
        EXPECT_TRUE(contains(settingsIssueAt(issues, "slip_cont"), "did you mean \"slip_count\""))
            << formatIssues(issues);
    }
    {
        // The values against the parameter's field (a rule the list cannot say).
        const auto [s, issues] =
            readSensitivityOf({{"parameter", "phi_deg"}, {"values", {20, 70}}});
        ASSERT_EQ(issues.size(), 1u) << formatIssues(issues);
        EXPECT_TRUE(contains(settingsIssueAt(issues, "values[1]"), "phi_deg = 70 is outside"))
            << formatIssues(issues);
        const auto [a, all] = readSensitivityOf({{"parameter", "all"}, {"values", {1.0}}});
        EXPECT_EQ(settingsIssueAt(all, "values"), "values need a single parameter");
    }
}

TEST(SensitivitySettingsKeys, ComputeChecksASettingsStructBuiltInCode) {
    SensitivitySettings s;
    s.parameter = "phi";
    s.tornado_slip = 2.0;
    std::string message = messageOf([&] { computeSensitivity(sandyLoamOnA(), s); });
    EXPECT_TRUE(contains(message, "parameter: \"phi\" is not one of")) << message;
    EXPECT_TRUE(contains(message, "did you mean \"phi_deg\"")) << message;
    EXPECT_TRUE(contains(message, "tornado_slip: 2 is outside the allowed range [-1, 1]"))
        << message;
    s = {};
    s.values = {20.0, 70.0};
    message = messageOf([&] { computeSensitivity(sandyLoamOnA(), s); });
    EXPECT_TRUE(contains(message, "values[1]: phi_deg = 70 is outside")) << message;
    s = {};
    s.sweep.slips = {0.1, 1.5};
    message = messageOf([&] { computeSensitivity(sandyLoamOnA(), s); });
    EXPECT_TRUE(contains(message, "slips[1]: 1.5 is outside the allowed range [-1, 1]")) << message;
}

}  // namespace
}  // namespace terra::analysis
