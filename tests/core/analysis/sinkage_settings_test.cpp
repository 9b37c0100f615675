// The sinkage study's settings on their declared field list (SinkageSettings::visitFields): every
// key of a script into its member and back, bad values named with their ranges, an unknown key
// with the nearest, and a struct built in code refused by computeSinkage in the reader's words.
#include <gtest/gtest.h>

#include "core/analysis/sinkage_study.h"
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

std::pair<SinkageSettings, std::vector<Issue>> readSinkageOf(const nlohmann::json& json) {
    return readSettingsOf<SinkageSettings>(json, readSinkageSettings);
}

TEST(SinkageSettingsKeys, EveryKeyOfAScriptIsReadIntoItsMemberAndBack) {
    const nlohmann::json j{{"loads_N", {40.0, 80.0}},
                           {"slip", 0.3},
                           {"slip_angle_deg", 5.0},
                           {"exit_angle_deg", -4.0},
                           {"bulldozing", "hegedus"}};
    const auto [s, issues] = readSinkageOf(j);
    ASSERT_TRUE(issues.empty()) << formatIssues(issues);
    EXPECT_EQ(s.loads_n, (std::vector<double>{40.0, 80.0}));
    EXPECT_EQ(s.slip, 0.3);
    EXPECT_EQ(s.slip_angle_deg, 5.0);
    EXPECT_EQ(s.model.exit.value, units::degToRad(-4.0));
    EXPECT_EQ(s.model.bulldozing, contact::BulldozingModel::kHegedus);
    EXPECT_EQ(toJson(s), j);
    const auto [back, back_issues] = readSinkageOf(toJson(s));
    ASSERT_TRUE(back_issues.empty()) << formatIssues(back_issues);
    EXPECT_EQ(toJson(back), j);
    EXPECT_EQ(toJson(SinkageSettings{}), (nlohmann::json{{"slip", 0.0}, {"slip_angle_deg", 0.0}}));
}

TEST(SinkageSettingsKeys, BadValuesAndUnknownKeysAreNamed) {
    const auto [s, issues] = readSinkageOf(
        {{"loads_N", {40.0, 0.0}}, {"slip", -2.0}, {"rut_ratio", 2.0}, {"load_N", 50.0}});
    EXPECT_EQ(issues.size(), 4u) << formatIssues(issues);
    EXPECT_EQ(settingsIssueAt(issues, "loads_N[1]"),
              "0 is outside the allowed range [0.01, 1e+05] N");
    EXPECT_EQ(settingsIssueAt(issues, "slip"), "-2 is outside the allowed range [-1, 1]");
    EXPECT_EQ(settingsIssueAt(issues, "rut_ratio"), "2 is outside the allowed range [0, 1]");
    EXPECT_TRUE(contains(settingsIssueAt(issues, "load_N"), "did you mean \"loads_N\""))
        << formatIssues(issues);
}

TEST(SinkageSettingsKeys, ComputeChecksASettingsStructBuiltInCode) {
    SinkageSettings s;
    s.loads_n = {40.0, 0.0};
    s.slip_angle_deg = 100.0;
    const std::string message = messageOf([&] { computeSinkage(sandyLoamOnA(), s); });
    EXPECT_TRUE(contains(message, "loads_N[1]: 0 is outside the allowed range [0.01, 1e+05] N"))
        << message;
    EXPECT_TRUE(contains(message, "slip_angle_deg: 100 is outside the allowed range (-90, 90) deg"))
        << message;
    SinkageSettings fine;
    fine.loads_n = {40.0, 60.0};
    EXPECT_EQ(computeSinkage(sandyLoamOnA(), fine).table.rows.size(), 2u);
}

}  // namespace
}  // namespace terra::analysis
