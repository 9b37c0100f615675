// Issue 27: a rover run saved with a project (core/project/saved_rover.h) reads back to the same
// time series, summary and status; a damaged one is refused by name.
#include "core/project/saved_rover.h"

#include <gtest/gtest.h>

#include <cmath>
#include <tuple>

#include "core/analysis/rover.h"
#include "core/io/json.h"
#include "core/scenario/map_layers.h"
#include "core/scenario/scenario_json.h"
#include "tests/core/test_support.h"

namespace terra::project {
namespace {

using nlohmann::json;

using terra::testing::kLocations;

/// A shipped scenario run for `duration_s`.
analysis::RoverResult runShipped(const std::string& name, double duration_s) {
    analysis::RoverSettings s;
    s.scenario = name;
    s.loaded = scenario::resolveScenario(kLocations, s.scenario).value();
    s.duration_s = duration_s;
    return analysis::runRover(s);
}

TEST(SavedRover, ARunReadsBackToTheSameSeriesAndSummary) {
    const analysis::RoverResult computed = runShipped("straight", 1.0);
    ASSERT_GT(computed.run.series.rows.size(), 5u);
    const json scenario_json =
        io::readJsonFile(std::filesystem::path(TERRA_RESOURCE_DIR) / "scenarios/straight.json")
            .value();
    const SavedRoverRun run{computed.run, "straight", scenario_json};
    const json saved = savedJson(run);
    const Result<SavedRoverRun> read = savedRoverRunFromJson(json::parse(saved.dump()), "rover");
    ASSERT_TRUE(read.ok()) << read.message();
    const Table& a = read->run.series;
    const Table& b = computed.run.series;
    ASSERT_EQ(a.columns, b.columns);
    ASSERT_EQ(a.rows.size(), b.rows.size());
    for (std::size_t r = 0; r < a.rows.size(); ++r) {
        for (std::size_t c = 0; c < a.columns.size(); ++c) {
            EXPECT_EQ(std::isnan(a.rows[r][c]), std::isnan(b.rows[r][c])) << a.columns[c];
            if (!std::isnan(b.rows[r][c])) {
                EXPECT_EQ(a.rows[r][c], b.rows[r][c]) << a.columns[c];
            }
        }
    }
    // The summary as `terrastudio run` writes it (another writer): every number the same.
    const scenario::Scenario& ran = computed.scenario;
    EXPECT_EQ(scenario::toJson(read->run, ran), scenario::toJson(computed.run, ran));
    EXPECT_EQ(read->run.status, computed.run.status);
    EXPECT_EQ(read->scenario_name, "straight");
    EXPECT_EQ(read->scenario, scenario_json);
    EXPECT_EQ(read->run.summary.mean_efficiency, computed.run.summary.mean_efficiency);
    EXPECT_EQ(savedJson(*read), saved);
}

// A mission run's outcome (docs/field.md, "Missions") reads back with the rest of the summary.
TEST(SavedRover, AMissionRunKeepsItsOutcome) {
    analysis::RoverSettings s;
    s.scenario = "mission-controlled-traffic";
    s.loaded = scenario::resolveScenario(kLocations, s.scenario).value();
    s.duration_s = 1.0;
    const analysis::RoverResult computed = analysis::runRover(s);
    ASSERT_TRUE(computed.run.summary.mission);
    const SavedRoverRun run{computed.run, s.scenario, json::object()};
    const Result<SavedRoverRun> read =
        savedRoverRunFromJson(json::parse(savedJson(run).dump()), "rover");
    ASSERT_TRUE(read.ok()) << read.message();
    ASSERT_TRUE(read->run.summary.mission);
    EXPECT_EQ(read->run.summary.mission->progress_m, computed.run.summary.mission->progress_m);
    EXPECT_FALSE(read->run.summary.mission->time_s);
    // The summary's mission keys as `terrastudio simulate` writes them (the maps are not saved).
    const json a = scenario::toJson(read->run, computed.scenario);
    const json b = scenario::toJson(computed.run, computed.scenario);
    for (const char* key : {"mission_completed", "mission_time_s", "path_length_m",
                            "path_progress_m", "path_error_rms_m", "path_error_max_m"}) {
        ASSERT_TRUE(b.contains(key)) << key;
        EXPECT_EQ(a.at(key), b.at(key)) << key;
    }
}

TEST(SavedRover, ACancelledRunStaysCancelledAndDamageIsNamed) {
    SavedRoverRun run;
    run.run.status = scenario::RunResult::Status::kCancelled;
    run.run.message = "cancelled at t = 0.8 s";
    run.run.series.columns = {"t_s", "x_m"};
    run.run.series.rows = {{0.0, 0.0}, {0.1, std::nan("")}};
    run.run.summary.energy_per_m_j = std::nullopt;
    run.run.summary.mean_efficiency = 0.42;
    run.scenario_name = "straight (edited)";
    run.scenario = json{{"duration_s", 2.0}};
    const json saved = savedJson(run);
    const Result<SavedRoverRun> read = savedRoverRunFromJson(json::parse(saved.dump()), "rover");
    ASSERT_TRUE(read.ok()) << read.message();
    EXPECT_EQ(read->run.status, scenario::RunResult::Status::kCancelled);
    EXPECT_EQ(read->run.message, run.run.message);
    EXPECT_TRUE(std::isnan(read->run.series.rows[1][1]));
    EXPECT_EQ(read->run.series.rows[1][0], 0.1);
    EXPECT_FALSE(read->run.summary.energy_per_m_j.has_value());
    EXPECT_EQ(read->run.summary.mean_efficiency, 0.42);

    json bad = saved;
    bad["status"] = "exploded";
    Result<SavedRoverRun> refused = savedRoverRunFromJson(bad, "rover");
    ASSERT_FALSE(refused.ok());
    EXPECT_NE(refused.message().find("exploded"), std::string::npos) << refused.message();
    bad = saved;
    bad["series"]["rows"][1] = {0.2};
    refused = savedRoverRunFromJson(bad, "rover");
    ASSERT_FALSE(refused.ok());
    EXPECT_NE(refused.message().find("series"), std::string::npos) << refused.message();
    EXPECT_NE(refused.message().find("1 values for 2 columns"), std::string::npos)
        << refused.message();
    bad = saved;
    bad["summary"]["x_m"] = "far";
    refused = savedRoverRunFromJson(bad, "rover");
    ASSERT_FALSE(refused.ok());
    EXPECT_NE(refused.message().find("summary: x_m"), std::string::npos) << refused.message();
}

// The figures a slip controller's run adds (docs/traction.md): the settling within the
// posterior's band and the traction-limited mode's switches and raised time read back (they were
// dropped before the saved summary was a declared field list); a file written before any of the
// keys that came later reads, with them empty.
TEST(SavedRover, AControlledRunKeepsItsSettlingAndTractionLimitedFigures) {
    SavedRoverRun run;
    run.run.series.columns = {"t_s"};
    run.run.series.rows = {{0.0}};
    scenario::Summary& m = run.run.summary;
    m.traction_limited_switches = 3;
    m.traction_limited_s = 11.5;
    m.real_time_factor = 812.0;
    m.cells_touched = 4321;
    scenario::TractionMetrics& t = run.run.traction;
    t.drive_energy_j = 812.5;
    t.border_time_s = 5.4;
    t.settling_time_s = 8.1;
    t.settling_band_time_s = 6.25;
    t.settle_band = 0.041;
    t.limit_switches = 3;
    t.limited_time_s = 11.5;
    run.scenario = json::object();
    const json saved = json::parse(savedJson(run).dump());
    const Result<SavedRoverRun> read = savedRoverRunFromJson(saved, "rover");
    ASSERT_TRUE(read.ok()) << read.message();
    EXPECT_EQ(read->run.summary.traction_limited_switches, 3);
    EXPECT_EQ(read->run.summary.traction_limited_s, 11.5);
    EXPECT_EQ(read->run.summary.cells_touched, 4321);
    EXPECT_EQ(read->run.traction.settling_band_time_s, 6.25);
    EXPECT_EQ(read->run.traction.settle_band, 0.041);
    EXPECT_EQ(read->run.traction.limit_switches, 3);
    EXPECT_EQ(read->run.traction.limited_time_s, 11.5);
    EXPECT_EQ(read->run.traction.border_time_s, 5.4);
    EXPECT_EQ(read->run.traction.settling_time_s, 8.1);
    EXPECT_EQ(read->run.summary.real_time_factor, 812.0);
    EXPECT_EQ(read->run.traction.drive_energy_j, 812.5);

    json old = saved;
    for (const char* key :
         {"energy_per_m_j", "mean_efficiency", "slip_tracking_rms", "traction_limited_switches",
          "traction_limited_s", "real_time_factor", "cells_touched", "mission"})
        ASSERT_EQ(old["summary"].erase(key), 1u) << key;
    for (const char* key : {"border_time_s", "settling_time_s", "settling_band_time_s",
                            "settle_band", "limit_switches", "limited_time_s"})
        ASSERT_EQ(old["traction"].erase(key), 1u) << key;
    const Result<SavedRoverRun> before = savedRoverRunFromJson(old, "rover");
    ASSERT_TRUE(before.ok()) << before.message();
    EXPECT_FALSE(before->run.summary.traction_limited_s);
    EXPECT_FALSE(before->run.summary.cells_touched);
    EXPECT_FALSE(before->run.traction.settling_band_time_s);
    EXPECT_EQ(before->run.traction.drive_energy_j, run.run.traction.drive_energy_j);
    // A key every file has stays required.
    old["summary"].erase("x_m");
    const Result<SavedRoverRun> damaged = savedRoverRunFromJson(old, "rover");
    ASSERT_FALSE(damaged.ok());
    EXPECT_NE(damaged.message().find("summary: x_m"), std::string::npos) << damaged.message();
}

// A field run keeps its maps and their history (cropped to the driven area, as the rover panel
// saves them): read back, every raster and every passage is the same, so the studio draws the
// layers and scrubs them without running again. A file from before (no "maps") reads without.
TEST(SavedRover, AFieldRunKeepsItsMapsAndTheirHistory) {
    const analysis::RoverResult computed = runShipped("field-slope-wet", 14.0);
    ASSERT_TRUE(computed.run.maps);
    SavedRoverRun run{computed.run, "field-slope-wet", json::object()};
    const std::array<double, 4> box = scenario::drivenArea(computed.scenario, run.run.series);
    run.run.maps = scenario::cropMaps(
        *computed.run.maps,
        scenario::windowOver(computed.run.maps->rut_depth_m, box[0], box[1], box[2], box[3]));
    const scenario::FieldMaps& maps = *run.run.maps;
    ASSERT_GT(maps.history.size(), 10u);
    const json saved = savedJson(run);
    const Result<SavedRoverRun> read = savedRoverRunFromJson(json::parse(saved.dump()), "rover");
    ASSERT_TRUE(read.ok()) << read.message();
    ASSERT_TRUE(read->run.maps);
    const scenario::FieldMaps& back = *read->run.maps;
    const auto a = scenario::mapRasters(maps), b = scenario::mapRasters(back);
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t m = 0; m < a.size(); ++m) {
        const field::Raster &x = *a[m].second, &y = *b[m].second;
        EXPECT_EQ(std::tie(x.cols, x.rows, x.x_min_m, x.y_min_m, x.cell_m),
                  std::tie(y.cols, y.rows, y.x_min_m, y.y_min_m, y.cell_m))
            << a[m].first;
        ASSERT_EQ(x.values.size(), y.values.size());
        for (std::size_t i = 0; i < x.values.size(); ++i) {
            ASSERT_TRUE(std::isnan(x.values[i]) ? std::isnan(y.values[i])
                                                : x.values[i] == y.values[i])
                << a[m].first << " " << i;
        }
    }
    EXPECT_EQ(back.history.time_s, maps.history.time_s);
    EXPECT_EQ(back.history.cell, maps.history.cell);
    EXPECT_EQ(back.history.values, maps.history.values);
    EXPECT_EQ(back.risk_depth_m, maps.risk_depth_m);

    json old = saved;
    old.erase("maps");
    const Result<SavedRoverRun> before = savedRoverRunFromJson(old, "rover");
    ASSERT_TRUE(before.ok()) << before.message();
    EXPECT_FALSE(before->run.maps);
    json bad = saved;
    bad["maps"]["history"]["cell"][0] = 1 << 30;
    Result<SavedRoverRun> refused = savedRoverRunFromJson(bad, "rover");
    ASSERT_FALSE(refused.ok());
    EXPECT_NE(refused.message().find("maps: history: cell 1073741824 is outside"),
              std::string::npos)
        << refused.message();
    bad = saved;
    bad["maps"]["rasters"]["passes"]["values"].erase(0);
    refused = savedRoverRunFromJson(bad, "rover");
    ASSERT_FALSE(refused.ok());
    EXPECT_NE(refused.message().find("passes"), std::string::npos) << refused.message();
}

}  // namespace
}  // namespace terra::project
