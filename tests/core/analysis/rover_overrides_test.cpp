// The rover analysis's overrides of the robot and its soils (a study of many missions,
// docs/field.md "Mission studies"): what each key changes, checked against the scenario changed
// by hand, a static balance and the presets read directly; and the errors naming the key.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "core/analysis/registry.h"
#include "core/analysis/rover.h"
#include "core/io/json_reader.h"
#include "core/io/parameters_json.h"
#include "core/scenario/scenario_json.h"
#include "tests/core/test_support.h"

namespace terra::analysis {
namespace {

using terra::testing::contains;
using terra::testing::kLocations;

/// The settings read from `json` as a run script's rover object; the issues in `issues`.
RoverSettings readOverrides(const nlohmann::json& json, std::vector<Issue>& issues) {
    RoverSettings out;
    io::ObjectReader r(json, issues);
    readRoverSettings(r, ReadContext{&kLocations, {}}, out);
    r.finish();
    return out;
}

std::string joined(const std::vector<Issue>& issues) {
    std::string text;
    for (const Issue& issue : issues) text += issue.where + ": " + issue.message + "\n";
    return text;
}

TEST(RoverOverrides, AFieldClassTakesTheGivenSoilAndKeepsItsProfile) {
    std::vector<Issue> issues;
    const RoverSettings settings =
        readOverrides({{"scenario", "field-slope-wet"},
                       {"soils", {{"2", "clayey-soil"}, {"base", "sandy-loam"}}}},
                      issues);
    ASSERT_TRUE(issues.empty()) << joined(issues);
    const scenario::Scenario changed = roverScenario(settings);
    const scenario::Scenario& original = *settings.loaded;
    ASSERT_TRUE(changed.field && original.field);
    const Result<soil::SoilParameters> clayey = io::resolveSoil(kLocations, "clayey-soil");
    ASSERT_TRUE(clayey.ok());
    const soil::SoilParameters& wet = changed.field->legend.at(2);
    EXPECT_EQ(wet.name, clayey.value().name);
    EXPECT_EQ(wet.friction_angle_rad, clayey.value().friction_angle_rad);
    EXPECT_EQ(wet.cohesion_pa, clayey.value().cohesion_pa);
    EXPECT_EQ(wet.shear_modulus_m, clayey.value().shear_modulus_m);
    // The preset has no profile: the class keeps the wet clay's (compaction still has layers).
    ASSERT_TRUE(wet.profile.has_value());
    ASSERT_TRUE(original.field->legend.at(2).profile.has_value());
    EXPECT_EQ(wet.profile->name, original.field->legend.at(2).profile->name);
    // The other classes and the scenario's own field are untouched (a field is shared).
    EXPECT_EQ(changed.field->legend.at(1).friction_angle_rad,
              original.field->legend.at(1).friction_angle_rad);
    EXPECT_NE(original.field->legend.at(2).name, clayey.value().name);
}

// The patch terrain's clay patch replaced by the base soil is the scenario without the patch,
// built by hand: the same run, number for number.
TEST(RoverOverrides, APatchReplacedByTheBaseSoilRunsAsTheScenarioWithoutIt) {
    std::vector<Issue> issues;
    RoverSettings settings = readOverrides({{"scenario", "soil-border"},
                                            {"duration_s", 35.0},  // the front wheels reach x = 1 m
                                            {"model", "quadratic"},
                                            {"soils", {{"1", "sandy-loam"}}}},
                                           issues);
    ASSERT_TRUE(issues.empty()) << joined(issues);
    ASSERT_EQ(settings.loaded->terrain.patches.size(), 1u);
    ASSERT_NE(settings.loaded->terrain.patches[0].soil.name, "sandy loam");
    const RoverResult overridden = runRover(settings);

    RoverSettings by_hand = settings;
    by_hand.soils.clear();
    by_hand.loaded->terrain.patches[0].soil = by_hand.loaded->terrain.base;
    const RoverResult reference = runRover(by_hand);
    ASSERT_EQ(overridden.run.status, scenario::RunResult::Status::kCompleted);
    EXPECT_EQ(overridden.run.summary.x_m, reference.run.summary.x_m);
    EXPECT_EQ(overridden.run.summary.energy_j, reference.run.summary.energy_j);
    EXPECT_EQ(overridden.run.series.rows.size(), reference.run.series.rows.size());
    // And not the run with the patch (the override did something).
    RoverSettings with_patch = settings;
    with_patch.soils.clear();
    EXPECT_NE(runRover(with_patch).run.summary.energy_j, overridden.run.summary.energy_j);
}

// At rest on flat soil the four wheels carry the whole robot: (m_chassis + 4 m_wheel) g.
TEST(RoverOverrides, TheChassisMassIsCarriedByTheWheels) {
    std::vector<Issue> issues;
    const double chassis_kg = 31.5;
    const RoverSettings settings = readOverrides(
        {{"scenario", "straight"}, {"duration_s", 1.0}, {"chassis_mass_kg", chassis_kg}}, issues);
    ASSERT_TRUE(issues.empty()) << joined(issues);
    const scenario::Scenario s = roverScenario(settings);
    EXPECT_EQ(s.robot.chassis_mass_kg, chassis_kg);
    const RoverResult result = runRover(settings);
    ASSERT_TRUE(result.run.usable());
    const Table& series = result.run.series;
    // At the end of the second: the robot starts at the equilibrium of its own sinkage and
    // settles in a few tenths of a second (critically damped, docs/dynamics.md).
    const std::vector<double>& last = series.rows.back();
    double load = 0.0;
    for (const char* corner : {"FL", "FR", "RL", "RR"})
        load += last[series.column(std::string(corner) + "_load_N")];
    const double weight = (chassis_kg + 4.0 * s.robot.wheel_mass_kg) * 9.81;
    EXPECT_NEAR(load, weight, 0.01 * weight);
}

TEST(RoverOverrides, TheWheelOfAllFourCornersIsTheGivenOne) {
    std::vector<Issue> issues;
    const nlohmann::json wheel = {{"name", "wide"}, {"r_m", 0.12}, {"b_m", 0.08}};
    const RoverSettings settings =
        readOverrides({{"scenario", "straight"}, {"wheel", wheel}}, issues);
    ASSERT_TRUE(issues.empty()) << joined(issues);
    const scenario::Scenario s = roverScenario(settings);
    EXPECT_EQ(s.robot.wheel.radius_m, 0.12);
    EXPECT_EQ(s.robot.wheel.width_m, 0.08);
}

TEST(RoverOverrides, BadOverridesNameTheKeyAndWhatIsAllowed) {
    std::vector<Issue> issues;
    readOverrides({{"scenario", "field-slope-wet"}, {"soils", {{"7", "sandy-loam"}}}}, issues);
    EXPECT_TRUE(contains(joined(issues), "soils.7")) << joined(issues);
    EXPECT_TRUE(contains(joined(issues), "1, 2, 3")) << joined(issues);

    issues.clear();
    readOverrides({{"scenario", "soil-border"}, {"soils", {{"3", "sandy-loam"}}}}, issues);
    EXPECT_TRUE(contains(joined(issues), "patch number from 1 to 1")) << joined(issues);

    issues.clear();
    readOverrides({{"scenario", "straight"}, {"chassis_mass_kg", -2.0}}, issues);
    EXPECT_TRUE(contains(joined(issues), "chassis_mass_kg")) << joined(issues);

    issues.clear();
    readOverrides({{"scenario", "straight"}, {"wheel", 5}}, issues);
    EXPECT_TRUE(contains(joined(issues), "wheel")) << joined(issues);
    EXPECT_TRUE(contains(joined(issues), "preset name")) << joined(issues);

    issues.clear();
    readOverrides({{"scenario", "straight"}, {"soils", {{"base", "no-such-soil"}}}}, issues);
    EXPECT_TRUE(contains(joined(issues), "soils.base")) << joined(issues);

    issues.clear();
    readOverrides({{"scenario", "straight"}, {"soils", {{"base", {{"phi_deg", 95}}}}}}, issues);
    EXPECT_TRUE(contains(joined(issues), "soils.base")) << joined(issues);
}

}  // namespace
}  // namespace terra::analysis
