// The soil curves' settings on their declared field list (SoilCurvesSettings::visitFields): every
// key of a script into its member and back, bad values named with their ranges, an unknown key
// with the nearest, and a struct built in code refused by computeSoilCurves in the reader's words.
#include <gtest/gtest.h>

#include "core/analysis/soil_curves.h"
#include "tests/core/analysis/settings_test_support.h"
#include "tests/core/test_support.h"

namespace terra::analysis {
namespace {

using terra::testing::contains;
using terra::testing::messageOf;
using terra::testing::readSettingsOf;
using terra::testing::sandyLoamOnA;
using terra::testing::settingsIssueAt;

std::pair<SoilCurvesSettings, std::vector<Issue>> readSoilCurvesOf(const nlohmann::json& json) {
    return readSettingsOf<SoilCurvesSettings>(json, readSoilCurvesSettings);
}

TEST(SoilCurvesSettingsKeys, EveryKeyOfAScriptIsReadIntoItsMemberAndBack) {
    const nlohmann::json j{
        {"points", 11}, {"max_sinkage_fraction_of_radius", 0.25}, {"max_load_factor", 3.0}};
    const auto [s, issues] = readSoilCurvesOf(j);
    ASSERT_TRUE(issues.empty()) << formatIssues(issues);
    EXPECT_EQ(s.points, 11);
    EXPECT_EQ(s.max_sinkage_fraction_of_radius, 0.25);
    EXPECT_EQ(s.max_load_factor, 3.0);
    EXPECT_EQ(toJson(s), j);
    const auto [back, back_issues] = readSoilCurvesOf(toJson(s));
    ASSERT_TRUE(back_issues.empty()) << formatIssues(back_issues);
    EXPECT_EQ(toJson(back), j);
}

TEST(SoilCurvesSettingsKeys, BadValuesAndUnknownKeysAreNamed) {
    const auto [s, issues] = readSoilCurvesOf({{"points", 1},
                                               {"max_sinkage_fraction_of_radius", 0.0},
                                               {"max_load_factor", 101.0},
                                               {"point", 5}});
    EXPECT_EQ(issues.size(), 4u) << formatIssues(issues);
    EXPECT_TRUE(contains(settingsIssueAt(issues, "points"), "[2, 10000]")) << formatIssues(issues);
    EXPECT_EQ(settingsIssueAt(issues, "max_sinkage_fraction_of_radius"),
              "0 is outside the allowed range (0, 1]");
    EXPECT_EQ(settingsIssueAt(issues, "max_load_factor"),
              "101 is outside the allowed range (0, 100]");
    EXPECT_TRUE(contains(settingsIssueAt(issues, "point"), "did you mean \"points\""))
        << formatIssues(issues);
}

TEST(SoilCurvesSettingsKeys, ComputeChecksASettingsStructBuiltInCode) {
    SoilCurvesSettings s;
    s.points = 1;
    s.max_load_factor = 0.0;
    const std::string message = messageOf([&] { computeSoilCurves(sandyLoamOnA(), s); });
    EXPECT_TRUE(contains(message, "points: ")) << message;
    EXPECT_TRUE(contains(message, "[2, 10000]")) << message;
    EXPECT_TRUE(contains(message, "max_load_factor: 0 is outside the allowed range (0, 100]"))
        << message;
    SoilCurvesSettings fine;
    fine.points = 5;
    EXPECT_EQ(computeSoilCurves(sandyLoamOnA(), fine).bulldozing.rows.size(), 5u);
}

}  // namespace
}  // namespace terra::analysis
