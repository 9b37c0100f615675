// The forces' settings on their declared field list (ForcesSettings::visitFields): every key of a
// script into its member and back, bad values named with their ranges, an unknown key with the
// nearest, and a struct built in code refused by computeForceSweep in the reader's words.
#include <gtest/gtest.h>

#include "core/analysis/forces.h"
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

std::pair<ForcesSettings, std::vector<Issue>> readForcesOf(const nlohmann::json& json) {
    return readSettingsOf<ForcesSettings>(json, readForcesSettings);
}

TEST(ForcesSettingsKeys, EveryKeyOfAScriptIsReadIntoItsMemberAndBack) {
    const nlohmann::json j{{"entry_angle_deg", 25.0},
                           {"slips", {0.1, 0.5}},
                           {"rut_ratio", 0.25},
                           {"max_stress_angle_deg", 12.0},
                           {"bulldozing", "hegedus"}};
    const auto [s, issues] = readForcesOf(j);
    ASSERT_TRUE(issues.empty()) << formatIssues(issues);
    ASSERT_TRUE(s.entry_angle_deg.has_value());
    EXPECT_EQ(*s.entry_angle_deg, 25.0);
    EXPECT_EQ(s.slips, (std::vector<double>{0.1, 0.5}));
    EXPECT_EQ(s.model.exit.kind, contact::ExitCondition::Kind::kRutRatio);
    EXPECT_EQ(s.model.exit.value, 0.25);
    EXPECT_EQ(*s.model.max_stress_angle_rad, units::degToRad(12.0));
    EXPECT_EQ(s.model.bulldozing, contact::BulldozingModel::kHegedus);
    EXPECT_EQ(toJson(s), j);
    const auto [back, back_issues] = readForcesOf(toJson(s));
    ASSERT_TRUE(back_issues.empty()) << formatIssues(back_issues);
    EXPECT_EQ(toJson(back), j);
    // The defaults: nothing to write (threads is code only).
    EXPECT_EQ(toJson(ForcesSettings{}), nlohmann::json::object());
}

TEST(ForcesSettingsKeys, BadValuesAndUnknownKeysAreNamed) {
    const auto [s, issues] = readForcesOf(
        {{"entry_angle_deg", 95.0}, {"slips", {0.1, 1.5}}, {"exit_angle_deg", 3.0}, {"slip", 0.2}});
    EXPECT_EQ(issues.size(), 4u) << formatIssues(issues);
    EXPECT_EQ(settingsIssueAt(issues, "entry_angle_deg"),
              "95 is outside the allowed range (0, 90] deg");
    EXPECT_EQ(settingsIssueAt(issues, "slips[1]"), "1.5 is outside the allowed range [-1, 1]");
    EXPECT_EQ(settingsIssueAt(issues, "exit_angle_deg"),
              "3 is outside the allowed range [-90, 0] deg");
    EXPECT_TRUE(contains(settingsIssueAt(issues, "slip"), "did you mean \"slips\""))
        << formatIssues(issues);
}

TEST(ForcesSettingsKeys, ComputeChecksASettingsStructBuiltInCode) {
    ForcesSettings s;
    s.entry_angle_deg = 95.0;
    s.slips = {0.1, 1.5};
    const std::string message = messageOf([&] { computeForceSweep(sandyLoamOnA(), s); });
    EXPECT_TRUE(contains(message, "entry_angle_deg: 95 is outside the allowed range (0, 90] deg"))
        << message;
    EXPECT_TRUE(contains(message, "slips[1]: 1.5 is outside the allowed range [-1, 1]")) << message;
    ForcesSettings fine;
    fine.slips = {0.1, 0.2};
    EXPECT_EQ(computeForceSweep(sandyLoamOnA(), fine).table.rows.size(),
              2u * OperatingConditions{}.slip_angles_deg.size());
}

}  // namespace
}  // namespace terra::analysis
