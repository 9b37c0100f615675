// The best slip's settings on their declared field list (TractionSettings::visitFields): the keys
// scripts hold are read as before, toJson writes what the reader reads back, a bad value is named
// with its range, and a struct built in code is checked in the reader's words.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "core/analysis/registry.h"
#include "core/analysis/traction.h"
#include "tests/core/test_support.h"

namespace terra::analysis {
namespace {

using terra::testing::contains;
using terra::testing::messageOf;
using terra::testing::sandyLoamOnA;

// The settings of `json` (a script's analysis object) and the issues of reading them.
std::pair<TractionSettings, std::vector<Issue>> readTractionOf(
    const nlohmann::json& json, const std::filesystem::path& base_dir = {}) {
    std::vector<Issue> issues;
    io::ObjectReader r(json, issues, "script.json", "analyses[0]");
    TractionSettings s;
    readTractionSettings(r, s, base_dir);
    r.finish();
    return {s, issues};
}

// The issue at `key` ("script.json: analyses[0].KEY"), or "(none)".
std::string tractionIssueAt(const std::vector<Issue>& issues, const std::string& key) {
    for (const Issue& issue : issues) {
        if (issue.where == "script.json: analyses[0]." + key) return issue.message;
    }
    return "(none)";
}

const nlohmann::json kTractionPosterior = {{"parameters", {"phi_deg", "c_kPa"}},
                                           {"mean", {29.0, 1.2}},
                                           {"covariance", {{1.0, 0.1}, {0.1, 0.25}}}};

TEST(TractionSettingsKeys, EveryKeyOfAScriptIsReadIntoItsMember) {
    const nlohmann::json script = {{"slip_angle_deg", 5.0},
                                   {"objective", "drawbar"},
                                   {"max_sinkage_m", 0.02},
                                   {"slip_min", 0.05},
                                   {"slip_max", 0.7},
                                   {"curve_points", 40},
                                   {"posterior_samples", 300},
                                   {"seed", 7},
                                   {"quantile", 0.25},
                                   {"posterior_method", "sigma-points"},
                                   {"posterior", kTractionPosterior},
                                   {"bulldozing", "hegedus"}};
    const auto [s, issues] = readTractionOf(script);
    ASSERT_TRUE(issues.empty()) << formatIssues(issues);
    EXPECT_EQ(s.slip_angle_deg, 5.0);
    EXPECT_EQ(s.objective, TractionObjective::kDrawbar);
    ASSERT_TRUE(s.max_sinkage_m.has_value());
    EXPECT_EQ(*s.max_sinkage_m, 0.02);
    EXPECT_EQ(s.slip_min, 0.05);
    EXPECT_EQ(s.slip_max, 0.7);
    EXPECT_EQ(s.curve_points, 40);
    EXPECT_EQ(s.posterior_samples, 300);
    EXPECT_EQ(s.seed, 7u);
    EXPECT_EQ(s.quantile, 0.25);
    EXPECT_EQ(s.posterior_method, scenario::PosteriorMethod::kSigmaPoints);
    ASSERT_TRUE(s.posterior.has_value());
    EXPECT_EQ(s.posterior->parameters, (std::vector<std::string>{"phi_deg", "c_kPa"}));
    EXPECT_EQ(s.posterior->mean, (std::vector<double>{29.0, 1.2}));
    EXPECT_EQ(s.model.bulldozing, contact::BulldozingModel::kHegedus);

    // toJson writes every key the reader read (the model choices beside them), and reads back
    // to the same settings.
    const nlohmann::json j = toJson(s);
    EXPECT_EQ(j, script);
    const auto [back, back_issues] = readTractionOf(j);
    ASSERT_TRUE(back_issues.empty()) << formatIssues(back_issues);
    EXPECT_EQ(toJson(back), j);
}

TEST(TractionSettingsKeys, DefaultsAndAPosteriorFileRelativeToTheScript) {
    const auto [s, issues] = readTractionOf(nlohmann::json::object());
    ASSERT_TRUE(issues.empty()) << formatIssues(issues);
    const TractionSettings defaults;
    EXPECT_EQ(toJson(s), toJson(defaults));
    EXPECT_FALSE(toJson(s).contains("posterior"));
    EXPECT_FALSE(toJson(s).contains("max_sinkage_m"));
    EXPECT_EQ(s.objective, TractionObjective::kEfficiency);

    // A soil file holding "posterior" (identify --save-soil), named relative to the script.
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / "terra-traction-settings-test";
    std::filesystem::create_directories(dir);
    std::ofstream(dir / "ident.json") << nlohmann::json{{"posterior", kTractionPosterior}}.dump();
    const auto [f, file_issues] = readTractionOf({{"posterior", "ident.json"}}, dir);
    ASSERT_TRUE(file_issues.empty()) << formatIssues(file_issues);
    ASSERT_TRUE(f.posterior.has_value());
    EXPECT_EQ(f.posterior->mean, (std::vector<double>{29.0, 1.2}));
    const auto [missing, missing_issues] = readTractionOf({{"posterior", "no-such.json"}}, dir);
    EXPECT_TRUE(contains(tractionIssueAt(missing_issues, "posterior"), "no-such.json"))
        << formatIssues(missing_issues);
    std::filesystem::remove_all(dir);
}

TEST(TractionSettingsKeys, BadValuesAreNamedWithTheirRanges) {
    const auto [s, issues] = readTractionOf({{"slip_min", 1.2},
                                             {"curve_points", 3},
                                             {"posterior_samples", 5},
                                             {"quantile", 1.5},
                                             {"objective", "effciency"},
                                             {"posterior", 3},
                                             {"slip_maxx", 0.5}});
    EXPECT_EQ(issues.size(), 7u) << formatIssues(issues);
    EXPECT_EQ(tractionIssueAt(issues, "slip_min"), "1.2 is outside the allowed range [0, 0.99]");
    EXPECT_EQ(tractionIssueAt(issues, "curve_points"), "3 is outside the allowed range [5, 10000]");
    EXPECT_EQ(tractionIssueAt(issues, "posterior_samples"),
              "5 is outside the allowed range [10, 1e+05]");
    EXPECT_TRUE(contains(tractionIssueAt(issues, "quantile"), "1.5 is outside the allowed range"))
        << formatIssues(issues);
    EXPECT_TRUE(contains(tractionIssueAt(issues, "objective"), "did you mean \"efficiency\""))
        << formatIssues(issues);
    EXPECT_EQ(tractionIssueAt(issues, "posterior"), "expected an object or a file, got number 3");
    EXPECT_TRUE(contains(tractionIssueAt(issues, "slip_maxx"), "did you mean \"slip_max\""))
        << formatIssues(issues);

    // The rules a list cannot say: the slips' order, the posterior's fields and shape.
    const auto [t, rules] = readTractionOf(
        {{"slip_min", 0.8},
         {"slip_max", 0.2},
         {"posterior", {{"parameters", {"friction"}}, {"mean", {29.0}}, {"covariance", {{1.0}}}}}});
    EXPECT_EQ(tractionIssueAt(rules, "slip_max"), "0.2 must be above slip_min = 0.8");
    EXPECT_TRUE(
        contains(tractionIssueAt(rules, "posterior.parameters"), "friction' is not a soil field"))
        << formatIssues(rules);
}

// A struct built in code (the rover's planner's, a test's) is checked in the reader's words.
TEST(TractionSettingsKeys, ComputeChecksASettingsStructBuiltInCode) {
    TractionSettings s;
    s.curve_points = 3;
    s.slip_min = 1.2;
    const std::string message = messageOf([&] { computeTraction(sandyLoamOnA(), s); });
    EXPECT_TRUE(contains(message, "curve_points: 3 is outside the allowed range [5, 10000]"))
        << message;
    EXPECT_TRUE(contains(message, "slip_min: 1.2 is outside the allowed range [0, 0.99]"))
        << message;
    s = {};
    s.slip_min = 0.8;
    s.slip_max = 0.2;
    EXPECT_EQ(messageOf([&] { computeTraction(sandyLoamOnA(), s); }),
              "slip_max: 0.2 must be above slip_min = 0.8");
    s = {};
    s.posterior = SoilPosterior{{"phi_deg", "n"}, {29.0, 0.7}, {{1.0, 2.0}, {2.0, 1.0}}, {}};
    EXPECT_EQ(messageOf([&] { computeTraction(sandyLoamOnA(), s); }),
              "posterior.covariance: is not symmetric positive definite");
    EXPECT_TRUE(computeTraction(sandyLoamOnA(), TractionSettings{}).ok());
}

}  // namespace
}  // namespace terra::analysis
