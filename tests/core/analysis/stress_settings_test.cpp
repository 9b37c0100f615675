// The stresses' settings on their declared field list (StressSettings::visitFields): every key of
// a script into its member and back, bad values named with their ranges, an unknown key with the
// nearest, and a struct built in code refused by computeStresses in the reader's words.
#include <gtest/gtest.h>

#include "core/analysis/stresses.h"
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

std::pair<StressSettings, std::vector<Issue>> readStressOf(const nlohmann::json& json) {
    return readSettingsOf<StressSettings>(json, readStressSettings);
}

TEST(StressSettingsKeys, EveryKeyOfAScriptIsReadIntoItsMemberAndBack) {
    const nlohmann::json j{{"slip", 0.2},
                           {"slip_angle_deg", -5.0},
                           {"entry_angle_deg", 30.0},
                           {"step_deg", 0.5},
                           {"stress", "tau_t"},
                           {"exit_angle_deg", -10.0},
                           {"max_stress_angle_deg", 15.0}};
    const auto [s, issues] = readStressOf(j);
    ASSERT_TRUE(issues.empty()) << formatIssues(issues);
    EXPECT_EQ(s.slip, 0.2);
    EXPECT_EQ(s.slip_angle_deg, -5.0);
    EXPECT_EQ(*s.entry_angle_deg, 30.0);
    EXPECT_EQ(s.step_deg, 0.5);
    EXPECT_EQ(s.stress, "tau_t");
    EXPECT_EQ(s.model.exit.value, units::degToRad(-10.0));
    EXPECT_EQ(*s.model.max_stress_angle_rad, units::degToRad(15.0));
    EXPECT_EQ(toJson(s), j);
    const auto [back, back_issues] = readStressOf(toJson(s));
    ASSERT_TRUE(back_issues.empty()) << formatIssues(back_issues);
    EXPECT_EQ(toJson(back), j);
    // The defaults are written (the grid step too: a default value is a value), the entry angle
    // left out when it is solved.
    EXPECT_EQ(toJson(StressSettings{}),
              (nlohmann::json{
                  {"slip", 0.3}, {"slip_angle_deg", 12.0}, {"step_deg", 0.01}, {"stress", "all"}}));
}

TEST(StressSettingsKeys, BadValuesAndUnknownKeysAreNamed) {
    const auto [s, issues] = readStressOf({{"slip", 1.5},
                                           {"slip_angle_deg", 90.0},
                                           {"step_deg", 0.0},
                                           {"stress", "sigm"},
                                           {"step", 0.1}});
    EXPECT_EQ(issues.size(), 5u) << formatIssues(issues);
    EXPECT_EQ(settingsIssueAt(issues, "slip"), "1.5 is outside the allowed range [-1, 1]");
    EXPECT_EQ(settingsIssueAt(issues, "slip_angle_deg"),
              "90 is outside the allowed range (-90, 90) deg");
    EXPECT_EQ(settingsIssueAt(issues, "step_deg"),
              "0 is outside the allowed range [1e-04, 10] deg");
    EXPECT_TRUE(contains(settingsIssueAt(issues, "stress"), "did you mean \"sigma\""))
        << formatIssues(issues);
    EXPECT_TRUE(contains(settingsIssueAt(issues, "step"), "did you mean \"step_deg\""))
        << formatIssues(issues);
}

TEST(StressSettingsKeys, ComputeChecksASettingsStructBuiltInCode) {
    StressSettings s;
    s.step_deg = 20.0;
    s.slip = -1.5;
    const std::string message = messageOf([&] { computeStresses(sandyLoamOnA(), s); });
    EXPECT_TRUE(contains(message, "step_deg: 20 is outside the allowed range [1e-04, 10] deg"))
        << message;
    EXPECT_TRUE(contains(message, "slip: -1.5 is outside the allowed range [-1, 1]")) << message;
    StressSettings fine;
    fine.step_deg = 1.0;
    EXPECT_TRUE(computeStresses(sandyLoamOnA(), fine).message.empty());
}

}  // namespace
}  // namespace terra::analysis
