// The identification's settings on their declared field list (IdentificationSettings::
// visitFields): the keys scripts and projects already hold are read as before, toJson writes
// what the reader reads back, and a struct built in code is checked in the reader's words.
#include <gtest/gtest.h>

#include "core/analysis/identification.h"
#include "core/analysis/registry.h"
#include "tests/core/test_support.h"

namespace terra::analysis {
namespace {

using terra::testing::contains;
using terra::testing::kLocations;
using terra::testing::messageOf;
using terra::testing::sandyLoamOnA;

// The settings of `json` and the issues of reading them (a script's analysis object).
std::pair<IdentificationSettings, std::vector<Issue>> readSettingsOf(const nlohmann::json& json) {
    std::vector<Issue> issues;
    io::ObjectReader r(json, issues, "script.json", "analyses[0]");
    IdentificationSettings s;
    readIdentificationSettings(r, ReadContext{&kLocations, {}}, s);
    r.finish();
    return {s, issues};
}

TEST(IdentificationSettingsKeys, EveryKeyOfAScriptIsReadIntoItsMember) {
    const auto [s, issues] = readSettingsOf({{"noise_percent", 1.5},
                                             {"seed", 7},
                                             {"loads_N", {30.0, 60.0}},
                                             {"slip_count", 20},
                                             {"refine", true},
                                             {"fix", {{"a0", 0.2}}},
                                             {"noise", {{"Fx_N", 0.3}, {"My_Nm", 0.02}}},
                                             {"jmax_m", 0.02},
                                             {"priors", {"phi_deg=30±5"}},
                                             {"prior_soil", "sandy-loam"},
                                             {"loss", "squared"},
                                             {"folds", 5},
                                             {"starts", 32},
                                             {"load_N", 58.86},
                                             {"profile", true}});
    ASSERT_TRUE(issues.empty()) << formatIssues(issues);
    EXPECT_EQ(s.synthetic.noise_percent, 1.5);
    EXPECT_EQ(s.synthetic.seed, 7u);
    EXPECT_EQ(s.synthetic.loads_n, (std::vector<double>{30.0, 60.0}));
    EXPECT_EQ(s.synthetic.slip_count, 20);
    EXPECT_EQ(s.fixed, (std::vector<std::pair<std::string, double>>{{"a0", 0.2}}));
    EXPECT_EQ(s.noise.fx_n, 0.3);
    EXPECT_EQ(s.noise.fz_n, 0.0);  // absent: estimated
    EXPECT_EQ(s.noise.my_nm, 0.02);
    EXPECT_EQ(s.max_shear_deformation_m, 0.02);
    EXPECT_EQ(s.prior_items, (std::vector<std::string>{"phi_deg=30±5"}));
    ASSERT_TRUE(s.prior_soil.has_value());  // resolved at once
    EXPECT_EQ(s.prior_soil->friction_angle_rad, sandyLoamOnA().soil.friction_angle_rad);
    EXPECT_EQ(s.loss, identification::Loss::kSquared);  // "squared": the older name of l2
    EXPECT_EQ(s.folds, 5);
    EXPECT_EQ(s.design_points, 32);
    EXPECT_EQ(s.load_n, 58.86);
    EXPECT_TRUE(s.profile);

    // toJson writes what the reader reads back (the resolved prior soil by its name).
    const nlohmann::json j = toJson(s);
    EXPECT_EQ(j["loss"], "l2");
    EXPECT_EQ(j["fix"]["a0"], 0.2);
    EXPECT_EQ(j["noise"]["Fx_N"], 0.3);
    EXPECT_FALSE(j.contains("holdout"));  // 0: none
    const auto [back, back_issues] = readSettingsOf(j);
    ASSERT_TRUE(back_issues.empty()) << formatIssues(back_issues);
    EXPECT_EQ(toJson(back), j);
}

TEST(IdentificationSettingsKeys, AbsentKeysKeepTheDefaults) {
    const auto [s, issues] = readSettingsOf(nlohmann::json::object());
    ASSERT_TRUE(issues.empty()) << formatIssues(issues);
    const IdentificationSettings defaults;
    EXPECT_EQ(toJson(s), toJson(defaults));
    EXPECT_EQ(s.design_points, identification::IdentifyOptions{}.design_points);
    EXPECT_FALSE(s.max_shear_deformation_m.has_value());
    EXPECT_FALSE(s.load_n.has_value());
}

TEST(IdentificationSettingsKeys, BadValuesAreNamedWithTheirRange) {
    struct Case {
        nlohmann::json json;
        std::string said;
    };
    const std::vector<Case> cases{
        {{{"folds", 1}}, "analyses[0].folds: 1 is outside the allowed range [2, 1000]"},
        {{{"holdout", 1.0}}, "analyses[0].holdout: 1 is outside the allowed range (0, 1)"},
        {{{"holdout", 0.2}, {"folds", 3}},
         "analyses[0].holdout: give a holdout fraction or folds, not both"},
        {{{"jmax_m", 0.02}, {"fit_jmax", true}},
         "analyses[0].fit_jmax: give jmax_m (held) or fit_jmax (identified), not both"},
        {{{"loss", "l1"}}, "analyses[0].loss: \"l1\" is not one of l2, huber, cauchy"},
        {{{"fix", {{"n1", 0.1}}}}, "analyses[0].fix.n1: unknown key"},
        {{{"fix", {{"phi_deg", 80}}}}, "analyses[0].fix.phi_deg: 80 is outside the allowed range"},
        {{{"noise", {{"Fx_N", -1}}}},
         "analyses[0].noise.Fx_N: -1 is outside the allowed range [0, 1e+06] N"},
        {{{"priors", {"phi=30±5"}}}, "analyses[0].priors: "},
        {{{"prior_soil", "no-such-soil"}}, "analyses[0].prior_soil: "},
        {{{"starts", -3}}, "analyses[0].starts: -3 is outside the allowed range [0, 1e+05]"},
        {{{"profiel", true}}, "analyses[0].profiel: unknown key; did you mean \"profile\"?"},
    };
    for (const Case& c : cases) {
        const auto [s, issues] = readSettingsOf(c.json);
        EXPECT_TRUE(contains(formatIssues(issues), "script.json: " + c.said))
            << c.json.dump() << "\n"
            << formatIssues(issues);
    }
}

// Settings built in code (a panel's, Python's) are checked by the same list, in its words.
TEST(IdentificationSettingsKeys, ComputeChecksASettingsStructByItsFieldList) {
    IdentificationSettings s;
    s.folds = 1;
    EXPECT_TRUE(contains(messageOf([&] { computeIdentification(sandyLoamOnA(), s); }),
                         "folds: 1 is outside the allowed range [2, 1000]"));
    s.folds = 0;
    s.synthetic.noise_percent = 150.0;
    EXPECT_TRUE(contains(messageOf([&] { computeIdentification(sandyLoamOnA(), s); }),
                         "noise_percent: 150 is outside the allowed range [0, 100] %"));
    s.synthetic.noise_percent = 2.0;
    s.holdout_fraction = 0.2;
    s.folds = 3;
    EXPECT_TRUE(contains(messageOf([&] { computeIdentification(sandyLoamOnA(), s); }),
                         "holdout: give a holdout fraction or folds, not both"));
}

}  // namespace
}  // namespace terra::analysis
