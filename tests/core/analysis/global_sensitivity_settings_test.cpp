// The global sensitivity's and the uncertainty bands' settings on their declared field lists
// (StudyDefinition, GlobalSensitivitySettings and UncertaintyBandSettings::visitFields): the keys
// scripts hold are read as before, toJson writes what the reader reads back, a struct built in
// code is checked in the reader's words.
#include <gtest/gtest.h>

#include <string>

#include "core/analysis/global_sensitivity.h"
#include "tests/core/test_support.h"

namespace terra::analysis {
namespace global_sensitivity_settings_test {

using terra::testing::contains;
using terra::testing::messageOf;
using terra::testing::sandyLoamOnA;

template <typename Settings, typename Read>
std::pair<Settings, std::vector<Issue>> readStudyOf(const nlohmann::json& json, Read read) {
    std::vector<Issue> issues;
    io::ObjectReader r(json, issues, "script.json", "analyses[0]");
    Settings s;
    read(r, s);
    r.finish();
    return {s, issues};
}

std::pair<GlobalSensitivitySettings, std::vector<Issue>> readGsaOf(const nlohmann::json& json) {
    return readStudyOf<GlobalSensitivitySettings>(json, readGlobalSensitivitySettings);
}

std::pair<UncertaintyBandSettings, std::vector<Issue>> readBandsOf(const nlohmann::json& json) {
    return readStudyOf<UncertaintyBandSettings>(json, readUncertaintyBandSettings);
}

std::string studyIssueAt(const std::vector<Issue>& issues, const std::string& key) {
    for (const Issue& issue : issues) {
        if (issue.where == "script.json: analyses[0]." + key) return issue.message;
    }
    return "(none)";
}

// Every key of a study: two independent parameters (a range; a normal with bounds), a
// correlated pair, the grid, the compaction outputs' place and a model choice.
const nlohmann::json kStudy{
    {"parameters",
     {{{"key", "phi_deg"}, {"range", {20.0, 35.0}}},
      {{"key", "c_kPa"}, {"normal", {2.0, 0.5}}, {"bounds", {0.0, 5.0}}}}},
    {"correlated",
     {{"keys", {"n", "K_m"}}, {"mean", {0.8, 0.02}}, {"covariance", {{0.01, 0.0}, {0.0, 1e-5}}}}},
    {"outputs", {"Fx_N", "sinkage_m"}},
    {"slips", {0.2, 0.4}},
    {"slip_angles_deg", {0.0, 5.0}},
    {"load_N", 60.0},
    {"seed", 7},
    {"max_failed_fraction", 0.1},
    {"compaction",
     {{"depth_m", 0.4}, {"passes", 2}, {"concentration", 4.0}, {"risk_stress", "sigma_1"}}},
    {"bulldozing", "hegedus"}};

TEST(GlobalSensitivitySettingsKeys, EveryKeyIsReadIntoItsMemberAndWrittenBack) {
    nlohmann::json given = kStudy;
    given.update({{"method", "sobol"},
                  {"samples", 256},
                  {"levels", 6},
                  {"resamples", 50},
                  {"confidence", 0.9}});
    const auto [s, issues] = readGsaOf(given);
    ASSERT_TRUE(issues.empty()) << formatIssues(issues);
    const StudyDefinition& d = s.study;
    ASSERT_EQ(d.parameters.size(), 2u);
    EXPECT_EQ(d.parameters[0].key, "phi_deg");
    EXPECT_EQ(std::get<gsa::Uniform>(d.parameters[0].distribution).high, 35.0);
    const auto& normal = std::get<gsa::Normal>(d.parameters[1].distribution);
    EXPECT_EQ(normal.mean, 2.0);
    EXPECT_EQ(normal.sd, 0.5);
    EXPECT_EQ(normal.high, 5.0);
    ASSERT_TRUE(d.correlated.has_value());
    EXPECT_EQ(d.correlated->keys, (std::vector<std::string>{"n", "K_m"}));
    EXPECT_EQ(d.correlated->covariance[1][1], 1e-5);
    EXPECT_EQ(d.outputs, (std::vector<std::string>{"Fx_N", "sinkage_m"}));
    EXPECT_EQ(d.slips, (std::vector<double>{0.2, 0.4}));
    EXPECT_EQ(d.slip_angles_deg, (std::vector<double>{0.0, 5.0}));
    EXPECT_EQ(d.load_n.value_or(0.0), 60.0);
    EXPECT_FALSE(d.entry_angle_deg.has_value());
    EXPECT_EQ(d.seed, 7u);
    EXPECT_EQ(d.max_failed_fraction, 0.1);
    EXPECT_EQ(d.compaction.depth_m, 0.4);
    EXPECT_EQ(d.compaction.passes, 2);
    EXPECT_EQ(d.compaction.concentration.value_or(0.0), 4.0);
    EXPECT_EQ(d.compaction.measure, compaction::RiskMeasure::kMajor);
    EXPECT_EQ(d.model.bulldozing, contact::BulldozingModel::kHegedus);
    EXPECT_EQ(s.method, GsaMethod::kSobol);
    EXPECT_EQ(s.samples, 256u);
    EXPECT_EQ(s.levels, 6);
    EXPECT_EQ(s.resamples, 50);
    EXPECT_EQ(s.confidence_level, 0.9);

    const nlohmann::json j = toJson(s);
    EXPECT_EQ(j, given);
    const auto [back, back_issues] = readGsaOf(j);
    ASSERT_TRUE(back_issues.empty()) << formatIssues(back_issues);
    EXPECT_EQ(toJson(back), j);
}

TEST(GlobalSensitivitySettingsKeys, TheBandsKeysAreReadAndWrittenBack) {
    nlohmann::json given = kStudy;
    given.erase("slips");  // 0 … slip_max in slip_count points
    given.update({{"slip_count", 30}, {"samples", 64}, {"percentiles", {10.0, 50.0, 90.0}}});
    const auto [s, issues] = readBandsOf(given);
    ASSERT_TRUE(issues.empty()) << formatIssues(issues);
    EXPECT_TRUE(s.study.slips.empty());
    EXPECT_EQ(s.study.outputs, (std::vector<std::string>{"Fx_N", "sinkage_m"}));
    EXPECT_EQ(s.slip_count, 30);
    EXPECT_EQ(s.samples, 64u);
    EXPECT_EQ(s.percentiles, (std::vector<double>{10.0, 50.0, 90.0}));
    const nlohmann::json j = toJson(s);
    EXPECT_EQ(j, given);
    const auto [back, back_issues] = readBandsOf(j);
    ASSERT_TRUE(back_issues.empty()) << formatIssues(back_issues);
    EXPECT_EQ(toJson(back), j);
}

TEST(GlobalSensitivitySettingsKeys, AbsentKeysKeepTheDefaults) {
    const auto [s, issues] = readGsaOf(nlohmann::json::object());
    ASSERT_TRUE(issues.empty()) << formatIssues(issues);
    EXPECT_EQ(toJson(s), toJson(GlobalSensitivitySettings{}));
    EXPECT_EQ(toJson(s)["parameters"].size(), 4u);  // docs/sensitivity.md's example study
    const auto [b, band_issues] = readBandsOf(nlohmann::json::object());
    ASSERT_TRUE(band_issues.empty()) << formatIssues(band_issues);
    EXPECT_EQ(toJson(b), toJson(UncertaintyBandSettings{}));
    EXPECT_FALSE(toJson(b).contains("slips"));
    EXPECT_EQ(toJson(b)["outputs"], nlohmann::json({"Fx_N", "Fs_N"}));
}

TEST(GlobalSensitivitySettingsKeys, BadValuesAreNamedWithTheirRanges) {
    const auto [s, issues] =
        readGsaOf({{"parameters", {{{"key", "phi_deg"}, {"range", {20.0, 95.0}}}}},
                   {"outputs", {"sinkage"}},
                   {"slips", {0.3, 1.5}},
                   {"samples", 1},
                   {"levels", 3},
                   {"confidence", 1.0},
                   {"sampels", 100}});
    EXPECT_EQ(issues.size(), 7u) << formatIssues(issues);
    EXPECT_EQ(studyIssueAt(issues, "parameters[0].range[1]"),
              "95 is outside the allowed range [0, 60) deg");
    EXPECT_TRUE(contains(studyIssueAt(issues, "outputs[0]"), "did you mean \"sinkage_m\""))
        << formatIssues(issues);
    EXPECT_EQ(studyIssueAt(issues, "slips[1]"), "1.5 is outside the allowed range [-1, 1]");
    EXPECT_EQ(studyIssueAt(issues, "samples"), "1 is outside the allowed range [2, 16777216]");
    EXPECT_EQ(studyIssueAt(issues, "levels"), "3 must be even");
    EXPECT_EQ(studyIssueAt(issues, "confidence"), "1 is outside the allowed range (0, 1)");
    EXPECT_TRUE(contains(studyIssueAt(issues, "sampels"), "did you mean \"samples\""))
        << formatIssues(issues);

    const auto [b, band_issues] = readBandsOf({{"percentiles", {5.0, 150.0}}, {"slip_count", 1}});
    EXPECT_EQ(band_issues.size(), 2u) << formatIssues(band_issues);
    EXPECT_EQ(studyIssueAt(band_issues, "percentiles[1]"),
              "150 is outside the allowed range [0, 100] %");
    EXPECT_EQ(studyIssueAt(band_issues, "slip_count"), "1 is outside the allowed range [2, 10000]");
}

// A struct built in code (the panel's, Python's) is checked in the reader's words when computed.
TEST(GlobalSensitivitySettingsKeys, ComputeChecksASettingsStructBuiltInCode) {
    GlobalSensitivitySettings s;
    s.samples = 1;
    s.levels = 3;
    s.confidence_level = 1.0;
    s.study.slips = {0.3, 1.5};
    EXPECT_EQ(messageOf([&] { computeGlobalSensitivity(sandyLoamOnA(), s); }),
              "slips[1]: 1.5 is outside the allowed range [-1, 1]\n"
              "samples: 1 is outside the allowed range [2, 16777216]\n"
              "confidence: 1 is outside the allowed range (0, 1)\n"
              "levels: 3 must be even");
    s = {};
    s.method = GsaMethod::kMorris;
    s.study.parameters = {{"phi_deg", gsa::Normal{30.0, 2.0}}};
    EXPECT_EQ(messageOf([&] { computeGlobalSensitivity(sandyLoamOnA(), s); }),
              "parameters[0]: Morris screening needs ranges, not distributions");
    UncertaintyBandSettings b;
    b.percentiles = {5.0, 150.0};
    b.slip_count = 1;
    b.study.parameters = {{"phi", gsa::Uniform{20.0, 30.0}}};
    const std::string message = messageOf([&] { computeUncertaintyBands(sandyLoamOnA(), b); });
    EXPECT_TRUE(contains(message, "percentiles[1]: 150 is outside the allowed range [0, 100] %"))
        << message;
    EXPECT_TRUE(contains(message, "slip_count: 1 is outside the allowed range [2, 10000]"))
        << message;
    EXPECT_TRUE(contains(message,
                         "parameters[0].key: \"phi\" is not a soil field (did you mean "
                         "\"phi_deg\"?)"))
        << message;
}

}  // namespace global_sensitivity_settings_test
}  // namespace terra::analysis
