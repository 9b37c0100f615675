// The validation's settings on their declared field list (ValidationSettings::visitFields): the
// keys scripts hold are read as before, toJson writes what the reader reads back, a struct built
// in code is checked in the reader's words; and its summary shows the numbers of its JSON.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>

#include "core/analysis/registry.h"
#include "core/analysis/validation.h"
#include "tests/core/test_support.h"

namespace terra::analysis {
namespace {

using terra::testing::contains;
using terra::testing::expectSummaryIsTheJson;
using terra::testing::kLocations;
using terra::testing::messageOf;
using terra::testing::sandyLoamOnA;

const std::filesystem::path kExperimentsDir =
    std::filesystem::path(TERRA_RESOURCE_DIR) / "experiments";
// Ding 2011, smooth wheel, HIT-LSS1 at 80 N: F_x, M_y and sinkage at slips 0, 0.1, 0.2, 0.3, 0.4
// and 0.6 (docs/validation.md).
constexpr const char* kFig9 = "ding2011-smooth-fig9-hit-lss1-80N.csv";

// The settings of `json` and the issues of reading them (a script's analysis object, its
// files relative to the shipped experiments).
std::pair<ValidationSettings, std::vector<Issue>> readValidationOf(const nlohmann::json& json) {
    std::vector<Issue> issues;
    io::ObjectReader r(json, issues, "script.json", "analyses[0]");
    ValidationSettings s;
    readValidationSettings(r, ReadContext{&kLocations, kExperimentsDir}, s);
    r.finish();
    return {s, issues};
}

// The issue at `where` ("script.json: analyses[0].KEY"), or "(none)".
std::string issueAt(const std::vector<Issue>& issues, const std::string& key) {
    for (const Issue& issue : issues) {
        if (issue.where == "script.json: analyses[0]." + key) return issue.message;
    }
    return "(none)";
}

TEST(ValidationSettingsKeys, EveryKeyOfAScriptIsReadIntoItsMember) {
    const auto [s, issues] =
        readValidationOf({{"experiments", kFig9},
                          {"calibrate", true},
                          {"fit_slips", {0.0, 0.2, 0.6}},
                          {"noise", {{"Fx_N", 0.5}, {"My_Nm", 0.1}, {"sinkage_m", 0.0005}}},
                          {"fit_n1", true}});
    ASSERT_TRUE(issues.empty()) << formatIssues(issues);
    EXPECT_EQ(s.experiments, (kExperimentsDir / kFig9).string());  // relative to the script
    ASSERT_TRUE(s.data.has_value());                               // read at once
    EXPECT_EQ(s.data->points.size(), 6u);
    EXPECT_TRUE(s.calibrate);
    EXPECT_EQ(s.fit_slips, (std::vector<double>{0.0, 0.2, 0.6}));
    EXPECT_EQ(s.noise[io::kExpFx], 0.5);
    EXPECT_EQ(s.noise[io::kExpMy], 0.1);
    EXPECT_EQ(s.noise[io::kExpSinkage], 0.0005);
    EXPECT_EQ(s.noise[io::kExpFy], 0.0);  // never fitted
    EXPECT_TRUE(s.fit_n1);
    EXPECT_FALSE(s.fit_slip_sinkage);

    // toJson writes every key the reader read, and reads back to the same settings.
    const nlohmann::json j = toJson(s);
    EXPECT_EQ(j, (nlohmann::json{{"experiments", (kExperimentsDir / kFig9).string()},
                                 {"calibrate", true},
                                 {"fit_slips", {0.0, 0.2, 0.6}},
                                 {"noise", {{"Fx_N", 0.5}, {"My_Nm", 0.1}, {"sinkage_m", 0.0005}}},
                                 {"fit_n1", true},
                                 {"fit_slip_sinkage", false}}));
    const auto [back, back_issues] = readValidationOf(j);
    ASSERT_TRUE(back_issues.empty()) << formatIssues(back_issues);
    EXPECT_EQ(toJson(back), j);
    EXPECT_EQ(back.data->points.size(), 6u);
}

TEST(ValidationSettingsKeys, AbsentKeysKeepTheDefaultsAndANoiseNotGivenIsNotWritten) {
    const auto [s, issues] = readValidationOf({{"experiments", kFig9}});
    ASSERT_TRUE(issues.empty()) << formatIssues(issues);
    EXPECT_FALSE(s.calibrate);
    EXPECT_TRUE(s.fit_slips.empty());
    EXPECT_FALSE(s.fit_n1);
    EXPECT_FALSE(s.fit_slip_sinkage);
    EXPECT_TRUE(s.curves);  // code only
    for (std::size_t c = 0; c < io::kExperimentChannelCount; ++c) EXPECT_EQ(s.noise[c], 0.0) << c;
    // 0 is "estimated": left out, as a file gives it (a file's 0 is refused, below).
    const nlohmann::json j = toJson(s);
    EXPECT_EQ(j["noise"], nlohmann::json::object());
    EXPECT_FALSE(j.contains("fit_slips"));
    EXPECT_FALSE(j.contains("curves"));
    EXPECT_FALSE(j.contains("data"));
}

TEST(ValidationSettingsKeys, BadValuesAreNamedWithTheirRanges) {
    {
        const auto [s, issues] = readValidationOf({{"experiments", kFig9},
                                                   {"calibrate", true},
                                                   {"fit_slips", {1.5}},
                                                   {"noise", {{"Fx_N", -1.0}, {"My_Nm", 0.0}}},
                                                   {"calibrat", true}});
        EXPECT_EQ(issues.size(), 4u) << formatIssues(issues);
        EXPECT_EQ(issueAt(issues, "fit_slips[0]"), "1.5 is outside the allowed range [-1, 1]");
        EXPECT_EQ(issueAt(issues, "noise.Fx_N"), "-1 is outside the allowed range (0, 1e+06] N");
        EXPECT_EQ(issueAt(issues, "noise.My_Nm"), "0 is outside the allowed range (0, 1e+06] N·m");
        EXPECT_TRUE(contains(issueAt(issues, "calibrat"), "did you mean \"calibrate\""))
            << formatIssues(issues);
    }
    {
        // A slip the test does not have; the calibration's keys without it; one slip-sinkage
        // model at a time; an unknown channel.
        const auto [s, issues] = readValidationOf({{"experiments", kFig9},
                                                   {"fit_slips", {0.0, 0.25}},
                                                   {"noise", {{"Fy_N", 1.0}}},
                                                   {"fit_n1", true},
                                                   {"fit_slip_sinkage", true}});
        EXPECT_EQ(issues.size(), 6u) << formatIssues(issues);
        EXPECT_EQ(issueAt(issues, "fit_slips[1]"), "0.25 is not a slip of the test");
        EXPECT_EQ(issueAt(issues, "fit_slips"),
                  "belongs to the calibration: add \"calibrate\": true");
        EXPECT_EQ(issueAt(issues, "fit_n1"), "belongs to the calibration: add \"calibrate\": true");
        EXPECT_TRUE(contains(issueAt(issues, "noise.Fy_N"), "did you mean \"Fx_N\""))
            << formatIssues(issues);
        int sinkage = 0;
        for (const Issue& issue : issues)
            sinkage += issue.where == "script.json: analyses[0].fit_slip_sinkage" ? 1 : 0;
        EXPECT_EQ(sinkage, 2) << formatIssues(issues);  // without calibrate; with fit_n1
    }
    {
        // Required, and read at once.
        const auto [s, issues] = readValidationOf(nlohmann::json::object());
        EXPECT_EQ(issueAt(issues, "experiments"), "missing; expected a string");
        const auto [t, bad] = readValidationOf({{"experiments", "no-such-test.csv"}});
        ASSERT_EQ(bad.size(), 1u) << formatIssues(bad);
        EXPECT_TRUE(contains(bad[0].message, "no-such-test.csv")) << bad[0].message;
    }
}

// A struct built in code (a dialog's) is checked in the reader's words when computed.
TEST(ValidationSettingsKeys, ComputeChecksASettingsStructBuiltInCode) {
    ValidationSettings s;
    s.experiments = (kExperimentsDir / kFig9).string();
    s.noise[io::kExpFx] = -1.0;
    s.fit_n1 = true;  // without calibrate
    s.fit_slips = {0.25};
    const std::string message = messageOf([&] { computeValidation(sandyLoamOnA(), s); });
    EXPECT_TRUE(contains(message, "noise.Fx_N: -1 is outside the allowed range (0, 1e+06] N"))
        << message;
    EXPECT_TRUE(contains(message, "fit_n1: belongs to the calibration")) << message;
    EXPECT_TRUE(contains(message, "fit_slips: belongs to the calibration")) << message;
    s = {};
    s.experiments = (kExperimentsDir / kFig9).string();
    s.calibrate = true;
    s.fit_slips = {0.0, 0.25};
    EXPECT_EQ(messageOf([&] { computeValidation(sandyLoamOnA(), s); }),
              "fit_slips[1]: 0.25 is not a slip of the test");
    ValidationSettings fine;
    fine.experiments = s.experiments;
    EXPECT_EQ(computeValidation(sandyLoamOnA(), fine).status, Outcome::Status::kCompleted);
}

TEST(ValidationSummary, ItsRowsAreTheJsonsValues) {
    ValidationSettings s;
    s.experiments = (kExperimentsDir / kFig9).string();
    s.calibrate = true;
    s.fit_slips = {0.0, 0.2, 0.6};
    s.noise[io::kExpFx] = 0.5;
    s.noise[io::kExpMy] = 0.1;
    s.noise[io::kExpSinkage] = 0.0005;
    s.curves = false;
    Inputs in = sandyLoamOnA();
    in.soil = io::resolveSoil(kLocations, "hit-lss1").value();
    in.wheel = io::resolveWheel(kLocations, "ding2011-smooth").value();
    const ValidationResult r = computeValidation(in, s);
    ASSERT_EQ(r.status, Outcome::Status::kCompleted) << r.message;
    ASSERT_TRUE(r.calibration && r.calibration->report.usable());
    const nlohmann::json j = toJson(r);
    const Summary summary = validationSummary(r);
    expectSummaryIsTheJson(summary, j);
    // One row per measured channel and set of metrics (given, calibrated, held out before and
    // after: 3 channels each), seven parameters, the headings.
    int metric_rows = 0, parameters = 0, headings = 0;
    for (const SummaryRow& row : summary) {
        metric_rows += row.json.ends_with("/rmse") ? 1 : 0;
        parameters += row.json.starts_with("/calibration/parameters/") ? 1 : 0;
        headings += row.emphasis == SummaryRow::Emphasis::kHeading ? 1 : 0;
    }
    EXPECT_EQ(metric_rows, 4 * 3);
    EXPECT_EQ(parameters, 7);
    EXPECT_EQ(headings, 6);  // title, given, calibration, calibrated, held out ×2
    EXPECT_EQ(summary.front().value,
              "HIT-LSS1 lunar soil simulant on Ding 2011 smooth wheel against " + s.experiments);
    // The given soil's RMSE of F_x is the one docs/validation.md shows.
    const auto fx = std::find_if(summary.begin(), summary.end(), [](const SummaryRow& row) {
        return row.json == "/metrics/Fx_N/rmse";
    });
    ASSERT_NE(fx, summary.end());
    EXPECT_EQ(fx->label, "Fx RMSE");
    EXPECT_EQ(fx->value, "5.656");
    EXPECT_EQ(fx->unit, "N");
    EXPECT_EQ(fx->detail, "MAE 4.772 N, max relative error 84.0 %, 6 points");
    // Every detail's numbers are the JSON's metrics of that channel, in the units shown.
    for (const SummaryRow& row : summary) {
        if (!row.json.ends_with("/rmse")) continue;
        const nlohmann::json& m =
            j.at(nlohmann::json::json_pointer(row.json.substr(0, row.json.size() - 5)));
        const double k = row.unit == "mm" ? 1e3 : 1.0;
        char expected[160];
        std::snprintf(expected, sizeof expected,
                      "MAE %.3f %s, max relative error %.1f %%, %d points",
                      m["mae"].get<double>() * k, row.unit.c_str(),
                      100.0 * m["max_rel_error"].get<double>(), m["count"].get<int>());
        EXPECT_EQ(row.detail, expected) << row.json;
    }
}

}  // namespace
}  // namespace terra::analysis
