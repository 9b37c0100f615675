// Issue 26 item 3 for the rover: roverSummary, what `terrastudio simulate` prints, shows every
// number of the run's summary JSON (scenario::toJson) at the pointer its row names, in the
// row's unit (the yaw in degrees of yaw_rad, the rut in mm, the path error in cm); a field run
// adds its cells, rut and risk, a mission its progress and path error, a cancelled run its status.
#include <gtest/gtest.h>

#include <atomic>
#include <string>
#include <vector>

#include "core/analysis/rover.h"
#include "core/io/json_reader.h"
#include "core/scenario/runner.h"
#include "tests/core/test_support.h"

namespace terra::analysis {
namespace {

using terra::testing::kLocations;

RoverResult runFor(const std::string& scenario, double duration_s, const Control& control = {}) {
    std::vector<Issue> issues;
    RoverSettings settings;
    const nlohmann::json object{{"scenario", scenario}, {"duration_s", duration_s}};
    io::ObjectReader r(object, issues);  // it reads `object` in place
    readRoverSettings(r, ReadContext{&kLocations, {}}, settings);
    r.finish();
    EXPECT_TRUE(issues.empty()) << scenario;
    return runRover(settings, control);
}

bool hasRow(const Summary& summary, const std::string& label) {
    for (const SummaryRow& row : summary)
        if (row.label == label) return true;
    return false;
}

TEST(RoverSummary, EveryNumberIsTheSummaryJsonsInItsUnit) {
    const RoverResult r = runFor("straight", 1.0);
    const Summary summary = roverSummary(r.run, r.scenario);
    terra::testing::expectSummaryIsTheJson(summary, scenario::toJson(r.run, r.scenario));
    ASSERT_FALSE(summary.empty());
    EXPECT_EQ(summary.front().label, "straight");
    EXPECT_EQ(summary.front().value, "1.000 s simulated");
    for (const char* label : {"final x", "final y", "final yaw", "distance", "mean slip FL",
                              "mean slip RR", "motor energy"})
        EXPECT_TRUE(hasRow(summary, label)) << label;
    EXPECT_FALSE(hasRow(summary, "status"));         // completed
    EXPECT_FALSE(hasRow(summary, "cells touched"));  // no field
}

TEST(RoverSummary, AFieldRunShowsItsCellsRutAndRisk) {
    const RoverResult r = runFor("field-slope-wet", 1.0);
    const Summary summary = roverSummary(r.run, r.scenario);
    const nlohmann::json j = scenario::toJson(r.run, r.scenario);
    terra::testing::expectSummaryIsTheJson(summary, j);
    for (const char* label : {"cells touched", "deepest rut", "largest compaction risk"})
        EXPECT_TRUE(hasRow(summary, label)) << label;
    ASSERT_TRUE(j.contains("max_compaction_risk"));
    EXPECT_TRUE(j["max_compaction_risk"].is_number());  // the field's soils have profiles
    EXPECT_GT(j["max_rut_depth_m"].get<double>(), 0.0);
}

TEST(RoverSummary, AMissionShowsItsProgressAndPathError) {
    // The cross slope's lanes: the robot crabs off its path by centimetres within 20 s (on the
    // controlled-traffic field it stays exactly on it, and a missing cm scale would pass).
    const RoverResult r = runFor("mission-slope-lanes", 20.0);
    const Summary summary = roverSummary(r.run, r.scenario);
    terra::testing::expectSummaryIsTheJson(summary, scenario::toJson(r.run, r.scenario));
    EXPECT_TRUE(hasRow(summary, "mission"));  // not completed in 1 s
    EXPECT_TRUE(hasRow(summary, "path progress"));
    EXPECT_TRUE(hasRow(summary, "path error RMS"));
    EXPECT_GT(scenario::toJson(r.run, r.scenario)["path_error_rms_m"].get<double>(), 0.01);
}

TEST(RoverSummary, ACancelledRunSaysSo) {
    const std::atomic<bool> cancel{true};
    const RoverResult r = runFor("straight", 5.0, Control(&cancel));
    ASSERT_EQ(r.run.status, scenario::RunResult::Status::kCancelled);
    const Summary summary = roverSummary(r.run, r.scenario);
    terra::testing::expectSummaryIsTheJson(summary, scenario::toJson(r.run, r.scenario));
    ASSERT_GE(summary.size(), 2u);
    EXPECT_EQ(summary[1].label, "status");
    EXPECT_EQ(summary[1].value, "cancelled");
    EXPECT_EQ(summary[1].emphasis, SummaryRow::Emphasis::kWarning);
}

}  // namespace
}  // namespace terra::analysis
