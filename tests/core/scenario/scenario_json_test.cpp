// Scenario and robot files: the shipped ones load, bad ones are rejected naming the field.
#include "core/scenario/scenario_json.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "tests/core/test_support.h"

namespace terra::scenario {
namespace {

using terra::testing::kLocations;

nlohmann::json minimal() {
    return nlohmann::json::parse(R"({
        "duration_s": 1, "time_step_s": 0.001, "terrain": "sandy-loam",
        "wheels": {"all": {"omega_rad_s": 0.4}}})");
}

TEST(ScenarioJson, ShippedScenariosLoad) {
    int count = 0;
    for (const auto& entry :
         std::filesystem::directory_iterator(std::string(TERRA_RESOURCE_DIR) + "/scenarios")) {
        const Result<Scenario> s = loadScenario(entry.path(), kLocations);
        EXPECT_TRUE(s.ok()) << entry.path() << ": " << s.message();
        ++count;
    }
    EXPECT_GE(count, 4);
    const Result<Scenario> pulse = resolveScenario(kLocations, "pulse-steering");
    ASSERT_TRUE(pulse.ok()) << pulse.message();
    // Table 2.6: ω = 0.4 rad/s; the front wheels get the pulse, the rear ones stay straight.
    EXPECT_EQ(pulse->commandsAt(0.0)[dynamics::kRearLeft].spin_rate_rad_s, 0.4);
    EXPECT_NEAR(pulse->commandsAt(15.0)[dynamics::kFrontLeft].steer_angle_rad, 10 * M_PI / 180,
                1e-15);
    EXPECT_EQ(pulse->commandsAt(15.0)[dynamics::kRearRight].steer_angle_rad, 0.0);
    EXPECT_EQ(pulse->commandsAt(35.0)[dynamics::kFrontRight].steer_angle_rad, 0.0);
}

TEST(ScenarioJson, DefaultRobotCarriesSixKilogramsPerWheel) {
    const auto robot = resolveRobot(kLocations, "default");
    ASSERT_TRUE(robot.ok()) << robot.message();
    EXPECT_DOUBLE_EQ(robot->totalMass() / dynamics::kWheelCount, 6.0);  // Table 2.6
    EXPECT_EQ(robot->wheel.radius_m, 0.092);                            // wheel A
}

TEST(ScenarioJson, PerWheelInputsOverrideAll) {
    nlohmann::json j = minimal();
    j["wheels"]["RR"] = {{"omega_rad_s", 0.2}, {"steer_deg", -5}};
    const Result<Scenario> s = scenarioFromJson(j, "x.json", kLocations);
    ASSERT_TRUE(s.ok()) << s.message();
    EXPECT_EQ(s->commandsAt(0)[dynamics::kFrontLeft].spin_rate_rad_s, 0.4);
    EXPECT_EQ(s->commandsAt(0)[dynamics::kRearRight].spin_rate_rad_s, 0.2);
    EXPECT_NEAR(s->commandsAt(0)[dynamics::kRearRight].steer_angle_rad, -5 * M_PI / 180, 1e-15);
}

struct BadCase {
    const char* patch;     // JSON merged into the minimal scenario
    const char* expected;  // must appear in the message
};

TEST(ScenarioJson, BadFilesNameTheField) {
    const BadCase cases[] = {
        {R"({"time_step_s": 0.5})", "x.json: time_step_s"},
        {R"({"duration_s": -1})", "duration_s"},
        {R"({"duraton_s": 1})", "duraton_s: unknown key"},
        {R"({"terrain": "moon-dust"})", "moon-dust"},
        {R"({"terrain": {"soil": "sandy-loam", "patches": [{"soil": "clayey-soil", "x_min_m": "a"}]}})",
         "terrain.patches[0].x_min_m"},
        {R"({"wheels": {"all": null, "FL": {"omega_rad_s": 0.4}}})",
         "wheels.FR.omega_rad_s: missing"},
        {R"({"wheels": {"all": {"omega_rad_s": 0.4, "steer_deg": 75}}})", "wheels.all.steer_deg"},
        {R"({"wheels": {"all": {"omega_rad_s": {"type": "wiggle"}}}})",
         "wheels.all.omega_rad_s.type"},
        {R"({"wheels": {"all": {"omega_rad_s": {"type": "step", "value": 0.4}}}})",
         "wheels.all.omega_rad_s.amplitude: missing"},
        {R"({"wheels": {"all": {"omega_rad_s": {"type": "table", "t_s": [0, 0], "values": [1, 2]}}}})",
         "t_s[1]"},
        {R"({"model": "cubic"})", "x.json: model"},
        {R"({"robot": {"wheel": "A", "chassis_mass_kg": -3, "chassis_inertia_kg_m2": [1, 1, 1],
                       "wheel_mass_kg": 1, "wheelbase_m": 0.5, "track_m": 0.4}})",
         "robot.chassis_mass_kg"},
        {R"({"streaming": {"wheel": "XX"}})", "streaming.wheel"},
        // Missions (docs/field.md, "Missions"): the wheel signals give way to the path.
        {R"({"mission": {"waypoints": [[0, 0], [1, 0]], "speed_m_s": 0.5}})",
         "x.json: wheels: not used with a \"mission\""},
        {R"({"wheels": null, "mission": {"waypoints": [[0, 0]], "speed_m_s": 0.5}})",
         "mission.waypoints: holds 1 points"},
        {R"({"wheels": null, "mission": {"waypoints": [[0, 0], [1, "a"]], "speed_m_s": 0.5}})",
         "mission.waypoints[1]: expected a point"},
        {R"({"wheels": null, "mission": {"waypoints": [[0, 0], [2e6, 0]], "speed_m_s": 0.5}})",
         "mission.waypoints[1][0]"},
        {R"({"wheels": null, "mission": {"waypoints": [[0, 0], [1, 0]], "speed_m_s": 0}})",
         "mission.speed_m_s"},
        {R"({"wheels": null, "mission": {"waypoints": [[0, 0], [1, 0]]}})",
         "mission.speed_m_s: missing"},
        {R"({"wheels": null, "mission": {"waypoints": [[0, 0], [1, 0]], "speed_m_s": 0.5,
                                         "lookahead_m": 0}})",
         "mission.lookahead_m"},
        {R"({"wheels": null, "mission": {"waypoints": [[0, 0], [1, 0]], "speed_m_s": 0.5,
                                         "lookahed_m": 1}})",
         "mission.lookahed_m: unknown key"},
        {R"({"wheels": null, "mission": {"speed_m_s": 0.5}})", "mission: give either"},
        {R"({"wheels": null, "mission": {"speed_m_s": 0.5, "lanes": {"start": [0, 0],
             "heading_deg": 0, "length_m": 10, "spacing_m": 2, "count": 3, "turn_radius_m": 1.5}}})",
         "mission.lanes.turn_radius_m: 1.5 m is more than half the spacing"},
        {R"({"wheels": null, "mission": {"speed_m_s": 0.5, "lanes": {"start": [0, 0],
             "heading_deg": 0, "length_m": 10, "spacing_m": 2, "count": 0, "turn_radius_m": 1}}})",
         "mission.lanes.count"},
        {R"({"wheels": null, "mission": {"speed_m_s": 0.5, "lanes": {"start": [0],
             "heading_deg": 0, "length_m": 10, "spacing_m": 2, "count": 2, "turn_radius_m": 1}}})",
         "mission.lanes.start"},
        {R"({"wheels": null, "mission": {"speed_m_s": 0.5, "lanes": {"start": [0, 0],
             "heading_deg": 0, "length_m": 10, "spacing_m": 2, "count": 2, "turn_radius_m": 1,
             "side": "up"}}})",
         "mission.lanes.side"},
    };
    for (const BadCase& c : cases) {
        nlohmann::json j = minimal();
        j.merge_patch(nlohmann::json::parse(c.patch));
        const Result<Scenario> s = scenarioFromJson(j, "x.json", kLocations);
        ASSERT_FALSE(s.ok()) << c.patch;
        EXPECT_NE(s.message().find(c.expected), std::string::npos)
            << c.patch << "\n  gave: " << s.message();
        // Each problem once, even when it sits under "all" and applies to four wheels.
        EXPECT_EQ(s.message().find(c.expected), s.message().rfind(c.expected)) << s.message();
    }
}

TEST(ScenarioJson, MissionReadsWaypointsOrLanes) {
    nlohmann::json j = minimal();
    j.erase("wheels");
    j["mission"] = nlohmann::json::parse(R"({"lanes": {"start": [1, 2], "heading_deg": 90,
        "length_m": 10, "spacing_m": 3, "count": 4, "turn_radius_m": 1.5, "side": "right"},
        "speed_m_s": 0.4, "lookahead_m": 0.8, "max_steer_deg": 30, "interval_s": 0.02,
        "steer_by": "heading"})");
    const Result<Scenario> s = scenarioFromJson(j, "x.json", kLocations);
    ASSERT_TRUE(s.ok()) << s.message();
    ASSERT_TRUE(s->mission && s->mission->lanes);
    const LanesSpec& l = *s->mission->lanes;
    EXPECT_EQ(l.start_m, Eigen::Vector2d(1.0, 2.0));
    EXPECT_NEAR(l.heading_rad, M_PI / 2.0, 1e-15);
    EXPECT_EQ(l.count, 4);
    EXPECT_FALSE(l.to_left);
    EXPECT_EQ(s->mission->speed_m_s, 0.4);
    EXPECT_EQ(s->mission->lookahead_m, 0.8);
    EXPECT_NEAR(s->mission->max_steer_rad, M_PI / 6.0, 1e-15);
    EXPECT_EQ(s->mission->interval_s, 0.02);
    EXPECT_FALSE(s->mission->follow_course);
    j["mission"] = nlohmann::json::parse(R"({"waypoints": [[0, 0], [4, 1], [8, 0]],
        "speed_m_s": 0.4})");
    const Result<Scenario> w = scenarioFromJson(j, "x.json", kLocations);
    ASSERT_TRUE(w.ok()) << w.message();
    ASSERT_EQ(w->mission->waypoints.size(), 3u);
    EXPECT_EQ(w->mission->waypoints[1], Eigen::Vector2d(4.0, 1.0));
    EXPECT_FALSE(w->mission->lanes);
    EXPECT_TRUE(w->mission->follow_course);  // the default (M9)
}

TEST(ScenarioJson, MissingAndBrokenFiles) {
    EXPECT_NE(resolveScenario(kLocations, "no-such-scenario").message().find("straight"),
              std::string::npos);  // lists what exists
    const Result<Scenario> bad =
        loadScenario(std::string(TERRA_TEST_DATA_DIR) + "/nowhere.json", kLocations);
    EXPECT_FALSE(bad.ok());
}

}  // namespace
}  // namespace terra::scenario
