// The traversability map's settings on their declared field list
// (TraversabilitySettings::visitFields): the keys scripts hold are read as before, toJson writes
// what the reader reads back, a struct built in code is checked in the reader's words.
#include <gtest/gtest.h>

#include <string>

#include "core/analysis/traversability.h"
#include "tests/core/test_support.h"

namespace terra::analysis {
namespace traversability_settings_test {

using terra::testing::contains;
using terra::testing::kLocations;
using terra::testing::messageOf;

std::pair<TraversabilitySettings, std::vector<Issue>> readTraversabilityOf(
    const nlohmann::json& json) {
    std::vector<Issue> issues;
    io::ObjectReader r(json, issues, "script.json", "analyses[0]");
    TraversabilitySettings s;
    readTraversabilitySettings(r, s);
    r.finish();
    return {s, issues};
}

std::string traversabilityIssueAt(const std::vector<Issue>& issues, const std::string& key) {
    for (const Issue& issue : issues) {
        if (issue.where == "script.json: analyses[0]." + key) return issue.message;
    }
    return "(none)";
}

// A level field of sandy loam, 4 × 3 cells of 1 m.
field::FieldMap levelField() {
    field::FieldMap f;
    f.base = io::resolveSoil(kLocations, "sandy-loam").value();
    f.height = field::makeRaster(4, 3, 0.0, 0.0, 1.0);
    return f;
}

TEST(TraversabilitySettingsKeys, EveryKeyIsReadIntoItsMemberAndWrittenBack) {
    const nlohmann::json given{{"headings", 4},    {"cell_m", 2.5},          {"slip_min", 0.02},
                               {"slip_max", 0.8},  {"curve_points", 100},    {"quadratic", false},
                               {"rut_ratio", 0.5}, {"bulldozing", "hegedus"}};
    const auto [s, issues] = readTraversabilityOf(given);
    ASSERT_TRUE(issues.empty()) << formatIssues(issues);
    EXPECT_EQ(s.headings, 4);
    EXPECT_EQ(s.cell_m.value_or(0.0), 2.5);
    EXPECT_EQ(s.slip_min, 0.02);
    EXPECT_EQ(s.slip_max, 0.8);
    EXPECT_EQ(s.curve_points, 100);
    EXPECT_FALSE(s.quadratic);
    EXPECT_EQ(s.model.exit.kind, contact::ExitCondition::Kind::kRutRatio);
    EXPECT_EQ(s.model.exit.value, 0.5);
    EXPECT_EQ(s.model.bulldozing, contact::BulldozingModel::kHegedus);
    const nlohmann::json j = toJson(s);
    EXPECT_EQ(j, given);
    const auto [back, back_issues] = readTraversabilityOf(j);
    ASSERT_TRUE(back_issues.empty()) << formatIssues(back_issues);
    EXPECT_EQ(toJson(back), j);
}

TEST(TraversabilitySettingsKeys, AbsentKeysKeepTheDefaults) {
    const auto [s, issues] = readTraversabilityOf(nlohmann::json::object());
    ASSERT_TRUE(issues.empty()) << formatIssues(issues);
    EXPECT_EQ(toJson(s), (nlohmann::json{{"headings", 8},
                                         {"slip_min", 0.01},
                                         {"slip_max", 0.9},
                                         {"curve_points", 200},
                                         {"quadratic", true}}));
}

TEST(TraversabilitySettingsKeys, BadValuesAreNamedWithTheirRanges) {
    {
        const auto [s, issues] = readTraversabilityOf({{"headings", 0},
                                                       {"cell_m", 0.0},
                                                       {"slip_max", 1.5},
                                                       {"curve_points", 5},
                                                       {"heading", 4}});
        EXPECT_EQ(issues.size(), 5u) << formatIssues(issues);
        EXPECT_EQ(traversabilityIssueAt(issues, "headings"),
                  "0 is outside the allowed range [1, 360]");
        EXPECT_EQ(traversabilityIssueAt(issues, "cell_m"),
                  "0 is outside the allowed range (0, 100] m");
        EXPECT_EQ(traversabilityIssueAt(issues, "slip_max"),
                  "1.5 is outside the allowed range [0, 0.99]");
        EXPECT_EQ(traversabilityIssueAt(issues, "curve_points"),
                  "5 is outside the allowed range [10, 5000]");
        EXPECT_TRUE(contains(traversabilityIssueAt(issues, "heading"), "did you mean \"headings\""))
            << formatIssues(issues);
    }
    {
        // The rule between two keys.
        const auto [s, issues] = readTraversabilityOf({{"slip_min", 0.5}, {"slip_max", 0.3}});
        ASSERT_EQ(issues.size(), 1u) << formatIssues(issues);
        EXPECT_EQ(traversabilityIssueAt(issues, "slip_max"), "0.3 must be above slip_min = 0.5");
    }
}

// A struct built in code (Python's, a test's) is checked in the reader's words when computed.
TEST(TraversabilitySettingsKeys, ComputeChecksASettingsStructBuiltInCode) {
    dynamics::RobotParameters robot;
    robot.wheel = io::resolveWheel(kLocations, "B").value();
    TraversabilitySettings s;
    s.headings = 0;
    s.curve_points = 5;
    EXPECT_EQ(messageOf([&] { computeTraversability(levelField(), robot, s); }),
              "headings: 0 is outside the allowed range [1, 360]\n"
              "curve_points: 5 is outside the allowed range [10, 5000]");
    s = {};
    s.slip_min = 0.5;
    s.slip_max = 0.3;
    EXPECT_EQ(messageOf([&] { computeTraversability(levelField(), robot, s); }),
              "slip_max: 0.3 must be above slip_min = 0.5");
    s = {};
    s.headings = 2;
    EXPECT_EQ(computeTraversability(levelField(), robot, s).headings.size(), 2u);
}

}  // namespace traversability_settings_test
}  // namespace terra::analysis
