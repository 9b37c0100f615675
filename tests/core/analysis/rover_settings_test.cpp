// The rover's settings on their declared field list (RoverSettings::visitFields): the overrides
// scripts hold are read as before into their members, toJson writes what the reader reads back,
// a bad value is named with its range, and a struct built in code is checked in the reader's
// words when it runs.
#include <gtest/gtest.h>

#include <string>

#include "core/analysis/registry.h"
#include "core/analysis/rover.h"
#include "core/io/parameters_json.h"
#include "tests/core/test_support.h"

namespace terra::analysis {
namespace {

using terra::testing::contains;
using terra::testing::kLocations;
using terra::testing::messageOf;

std::pair<RoverSettings, std::vector<Issue>> readRoverOf(const nlohmann::json& json) {
    std::vector<Issue> issues;
    io::ObjectReader r(json, issues, "script.json", "analyses[0]");
    RoverSettings s;
    readRoverSettings(r, ReadContext{&kLocations, {}}, s);
    r.finish();
    return {s, issues};
}

std::string roverIssueAt(const std::vector<Issue>& issues, const std::string& key) {
    for (const Issue& issue : issues) {
        if (issue.where == "script.json: analyses[0]." + key) return issue.message;
    }
    return "(none)";
}

TEST(RoverSettingsKeys, EveryKeyOfAScriptIsReadIntoItsMember) {
    const nlohmann::json wheel = {{"name", "wide"}, {"r_m", 0.12}, {"b_m", 0.08}};
    const auto [s, issues] = readRoverOf({{"scenario", "straight"},
                                          {"duration_s", 3.0},
                                          {"time_step_s", 0.002},
                                          {"model", "quadratic"},
                                          {"controller", "optimal"},
                                          {"slip", 0.2},
                                          {"traction_limited", true},
                                          {"robust", "quantile"},
                                          {"quantile", 0.2},
                                          {"posterior_samples", 50},
                                          {"posterior_method", "samples"},
                                          {"identifier", "full"},
                                          {"chassis_mass_kg", 31.5},
                                          {"wheel", wheel},
                                          {"soils", {{"base", "clayey-soil"}}}});
    ASSERT_TRUE(issues.empty()) << formatIssues(issues);
    EXPECT_EQ(s.scenario, "straight");
    ASSERT_TRUE(s.loaded.has_value());  // resolved at once
    EXPECT_EQ(s.duration_s, 3.0);
    EXPECT_EQ(s.time_step_s, 0.002);
    EXPECT_EQ(s.model, contact::ContactModel::kQuadratic);
    EXPECT_EQ(s.controller, scenario::ControllerType::kOptimal);
    EXPECT_EQ(s.slip, 0.2);
    EXPECT_EQ(s.traction_limited, true);
    EXPECT_EQ(s.robust, scenario::RobustSlip::kQuantile);
    EXPECT_EQ(s.quantile, 0.2);
    EXPECT_EQ(s.posterior_samples, 50);
    EXPECT_EQ(s.posterior_method, scenario::PosteriorMethod::kSamples);
    EXPECT_EQ(s.identifier, scenario::SoilIdentifier::kFull);
    EXPECT_EQ(s.chassis_mass_kg, 31.5);
    ASSERT_TRUE(s.wheel.has_value());
    EXPECT_EQ(s.wheel->radius_m, 0.12);
    ASSERT_EQ(s.soils.size(), 1u);
    EXPECT_EQ(s.soils.at("base").name, io::resolveSoil(kLocations, "clayey-soil").value().name);

    // toJson writes every key (the wheel and soils as the objects they were resolved to), and
    // reads back to the same settings.
    const nlohmann::json j = toJson(s);
    EXPECT_EQ(j["controller"], "optimal");
    EXPECT_EQ(j["traction_limited"], true);
    EXPECT_EQ(j["posterior_samples"], 50);
    EXPECT_EQ(j["wheel"], io::toJson(*s.wheel));
    EXPECT_EQ(j["soils"]["base"], io::toJson(s.soils.at("base")));
    const auto [back, back_issues] = readRoverOf(j);
    ASSERT_TRUE(back_issues.empty()) << formatIssues(back_issues);
    EXPECT_EQ(toJson(back), j);

    // Every controller name reads as the scenario's own names say.
    for (const std::string& name : scenario::controllerNames()) {
        const auto [c, c_issues] = readRoverOf({{"scenario", "straight"}, {"controller", name}});
        ASSERT_TRUE(c_issues.empty()) << formatIssues(c_issues);
        EXPECT_EQ(c.controller, scenario::controllerFromName(name)) << name;
    }
}

TEST(RoverSettingsKeys, AbsentOverridesStayEmptyAndAreNotWritten) {
    const auto [s, issues] = readRoverOf({{"scenario", "straight"}});
    ASSERT_TRUE(issues.empty()) << formatIssues(issues);
    EXPECT_FALSE(s.duration_s || s.time_step_s || s.model || s.controller || s.slip ||
                 s.traction_limited || s.robust || s.quantile || s.posterior_samples ||
                 s.posterior_method || s.identifier || s.chassis_mass_kg || s.wheel);
    EXPECT_TRUE(s.soils.empty());
    EXPECT_EQ(toJson(s), (nlohmann::json{{"scenario", "straight"}}));
}

TEST(RoverSettingsKeys, BadValuesAreNamedWithTheirRanges) {
    const auto [s, issues] = readRoverOf({{"scenario", "straight"},
                                          {"duration_s", -1.0},
                                          {"slip", 1.5},
                                          {"posterior_samples", 5},
                                          {"traction_limited", "on"},
                                          {"controller", "optimall"},
                                          {"wheel", 3},
                                          {"duratin_s", 2.0}});
    EXPECT_EQ(issues.size(), 7u) << formatIssues(issues);
    EXPECT_EQ(roverIssueAt(issues, "duration_s"), "-1 is outside the allowed range (0, 86400] s");
    EXPECT_TRUE(contains(roverIssueAt(issues, "slip"), "1.5 is outside the allowed range"))
        << formatIssues(issues);
    EXPECT_EQ(roverIssueAt(issues, "posterior_samples"),
              "5 is outside the allowed range [10, 1e+05]");
    EXPECT_TRUE(contains(roverIssueAt(issues, "traction_limited"), "expected true or false"))
        << formatIssues(issues);
    EXPECT_TRUE(contains(roverIssueAt(issues, "controller"), "did you mean \"optimal\""))
        << formatIssues(issues);
    EXPECT_TRUE(contains(roverIssueAt(issues, "wheel"),
                         "expected a preset name, a file or an "
                         "object"))
        << formatIssues(issues);
    EXPECT_TRUE(contains(roverIssueAt(issues, "duratin_s"), "did you mean \"duration_s\""))
        << formatIssues(issues);

    const auto [t, missing] = readRoverOf(nlohmann::json::object());
    EXPECT_EQ(roverIssueAt(missing, "scenario"), "missing; expected a string");
}

// A struct built in code (the panel's, a test's) is checked in the reader's words when it runs.
TEST(RoverSettingsKeys, RunningChecksASettingsStructBuiltInCode) {
    RoverSettings s;
    s.loaded = scenario::resolveScenario(kLocations, "straight").value();
    s.posterior_samples = 5;
    s.slip = 1.5;
    const std::string message = messageOf([&] { roverScenario(s); });
    EXPECT_TRUE(contains(message, "posterior_samples: 5 is outside the allowed range [10, 1e+05]"))
        << message;
    EXPECT_TRUE(contains(message, "slip: 1.5 is outside the allowed range")) << message;
    s.posterior_samples.reset();
    s.slip.reset();
    s.duration_s = -1.0;
    EXPECT_EQ(messageOf([&] { roverScenario(s); }),
              "duration_s: -1 is outside the allowed range (0, 86400] s");
    s.duration_s = 2.0;
    EXPECT_EQ(roverScenario(s).duration_s, 2.0);
}

}  // namespace
}  // namespace terra::analysis
