// The streaming identification's settings on their declared field list
// (StreamingSettings::visitFields): the keys scripts hold, the estimator's "window", "load_N" and
// "jmax_m" among them, are read as before into their members, toJson writes what the reader reads
// back, a bad value is named with its range, and a struct built in code is checked in the reader's
// words.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include "core/analysis/registry.h"
#include "core/analysis/streaming_identification.h"
#include "core/io/parameters_json.h"
#include "tests/core/test_support.h"

namespace terra::analysis {
namespace {

using terra::testing::contains;
using terra::testing::kLocations;
using terra::testing::messageOf;
using terra::testing::sandyLoamOnA;

class StreamingSettingsKeys : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = std::filesystem::temp_directory_path() /
               ("terra-streaming-settings-" +
                std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
        std::filesystem::create_directories(dir_);
        std::ofstream(dir_ / "data.csv")
            << "slip,entry_angle_deg,Fx_N,Fz_N,My_Nm\n0.3,20,5,58.86,1.2\n0.4,21,6,58.86,1.3\n";
    }
    void TearDown() override { std::filesystem::remove_all(dir_); }

    std::pair<StreamingSettings, std::vector<Issue>> read(const nlohmann::json& json) const {
        std::vector<Issue> issues;
        io::ObjectReader r(json, issues, "script.json", "analyses[0]");
        StreamingSettings s;
        readStreamingSettings(r, ReadContext{&kLocations, dir_}, s);
        r.finish();
        return {s, issues};
    }
    static std::string issueAt(const std::vector<Issue>& issues, const std::string& key) {
        for (const Issue& issue : issues) {
            if (issue.where == "script.json: analyses[0]." + key) return issue.message;
        }
        return "(none)";
    }

    std::filesystem::path dir_;
};

TEST_F(StreamingSettingsKeys, EveryKeyOfAScriptIsReadIntoItsMember) {
    const auto [s, issues] = read({{"csv", "data.csv"},
                                   {"skip_bad_rows", true},
                                   {"second_soil", "dry-sand"},
                                   {"noise_percent", 2.5},
                                   {"seed", 9},
                                   {"window", 8},
                                   {"load_N", 60.0},
                                   {"jmax_m", 0.02}});
    ASSERT_TRUE(issues.empty()) << formatIssues(issues);
    EXPECT_EQ(s.csv, (dir_ / "data.csv").string());  // relative to the script
    EXPECT_TRUE(s.skip_bad_rows);
    EXPECT_EQ(s.second_soil, "dry-sand");
    ASSERT_TRUE(s.second.has_value());  // resolved at once
    EXPECT_EQ(s.second->name, io::resolveSoil(kLocations, "dry-sand").value().name);
    EXPECT_EQ(s.noise_percent, 2.5);
    EXPECT_EQ(s.seed, 9u);
    EXPECT_EQ(s.options.window, 8u);
    EXPECT_EQ(s.options.fit.load_n, 60.0);
    EXPECT_EQ(s.options.fit.max_shear_deformation_m, 0.02);  // the model's j_max held [m]

    const nlohmann::json j = toJson(s);
    EXPECT_EQ(j, (nlohmann::json{{"csv", (dir_ / "data.csv").string()},
                                 {"skip_bad_rows", true},
                                 {"second_soil", "dry-sand"},
                                 {"noise_percent", 2.5},
                                 {"seed", 9},
                                 {"window", 8},
                                 {"load_N", 60.0},
                                 {"jmax_m", 0.02}}));
    const auto [back, back_issues] = read(j);
    ASSERT_TRUE(back_issues.empty()) << formatIssues(back_issues);
    EXPECT_EQ(toJson(back), j);
}

TEST_F(StreamingSettingsKeys, AbsentKeysKeepTheDefaults) {
    const auto [s, issues] = read(nlohmann::json::object());
    ASSERT_TRUE(issues.empty()) << formatIssues(issues);
    EXPECT_EQ(toJson(s), toJson(StreamingSettings{}));
    EXPECT_FALSE(toJson(s).contains("load_N"));  // none: the data's loads
    EXPECT_FALSE(toJson(s).contains("jmax_m"));  // none: no shear-deformation limit
    EXPECT_EQ(s.options.fit.max_shear_deformation_m, std::numeric_limits<double>::infinity());
    EXPECT_EQ(s.options.window, identification::StreamingEstimatorOptions{}.window);
    ASSERT_TRUE(s.second.has_value());  // no CSV: the default second soil is resolved
    EXPECT_EQ(s.second->name, io::resolveSoil(kLocations, "clayey-soil").value().name);
}

TEST_F(StreamingSettingsKeys, BadValuesAreNamedWithTheirRanges) {
    const auto [s, issues] = read({{"noise_percent", 150.0},
                                   {"window", 0},
                                   {"load_N", 0.0},
                                   {"csv", "no-such.csv"},
                                   {"second_soil", "no-such-soil"},
                                   {"windw", 5}});
    EXPECT_EQ(issues.size(), 6u) << formatIssues(issues);
    EXPECT_EQ(issueAt(issues, "noise_percent"), "150 is outside the allowed range [0, 100] %");
    EXPECT_EQ(issueAt(issues, "window"), "0 is outside the allowed range [1, 1000]");
    EXPECT_EQ(issueAt(issues, "load_N"), "0 is outside the allowed range [0.01, 1e+05] N");
    EXPECT_TRUE(contains(issueAt(issues, "csv"), "no-such.csv")) << formatIssues(issues);
    EXPECT_TRUE(contains(issueAt(issues, "second_soil"), "no-such-soil")) << formatIssues(issues);
    EXPECT_TRUE(contains(issueAt(issues, "windw"), "did you mean \"window\""))
        << formatIssues(issues);
}

// A struct built in code (the studio's playback, a test's) is checked in the reader's words.
TEST_F(StreamingSettingsKeys, ComputeChecksASettingsStructBuiltInCode) {
    StreamingSettings s;
    s.second = io::resolveSoil(kLocations, "clayey-soil").value();
    s.noise_percent = 150.0;
    s.options.window = 0;
    const std::string message = messageOf([&] { computeStreaming(sandyLoamOnA(), s); });
    EXPECT_TRUE(contains(message, "noise_percent: 150 is outside the allowed range [0, 100] %"))
        << message;
    EXPECT_TRUE(contains(message, "window: 0 is outside the allowed range [1, 1000]")) << message;
    s.noise_percent = 1.0;
    s.options.window = 5;
    s.options.fit.load_n = -3.0;
    EXPECT_EQ(messageOf([&] { streamSource(sandyLoamOnA(), s); }),
              "load_N: -3 is outside the allowed range [0.01, 1e+05] N");
}

}  // namespace
}  // namespace terra::analysis
