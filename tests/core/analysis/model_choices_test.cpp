// The contact-model choices on their declared field list (ModelChoices::visitFields): every key
// into its member and back, the angles converted bit for bit as before (units::degToRad read,
// roundSignificant(radToDeg) written), θ_r or λ but not both, and readModelChoices /
// writeModelChoices as the thin wrappers other code calls.
#include <gtest/gtest.h>

#include "core/analysis/analysis.h"
#include "core/common/units.h"
#include "core/io/declared_json.h"
#include "tests/core/test_support.h"

namespace terra::analysis {
namespace {

using terra::testing::contains;

std::pair<ModelChoices, std::vector<Issue>> readChoices(const nlohmann::json& json) {
    std::vector<Issue> issues;
    io::ObjectReader r(json, issues, "script.json", "analyses[0]");
    ModelChoices out;
    readModelChoices(r, out);
    r.finish();
    return {out, issues};
}

std::string choiceIssueAt(const std::vector<Issue>& issues, const std::string& key) {
    for (const Issue& issue : issues) {
        if (issue.where == "script.json: analyses[0]." + key) return issue.message;
    }
    return "(none)";
}

TEST(ModelChoicesKeys, EveryKeyIsReadIntoItsMemberAndWrittenBack) {
    const auto [m, issues] = readChoices(
        {{"exit_angle_deg", -7.5}, {"max_stress_angle_deg", 15.0}, {"bulldozing", "hegedus"}});
    ASSERT_TRUE(issues.empty()) << formatIssues(issues);
    EXPECT_EQ(m.exit.kind, contact::ExitCondition::Kind::kAngle);
    EXPECT_EQ(m.exit.value, units::degToRad(-7.5));  // bit for bit
    ASSERT_TRUE(m.max_stress_angle_rad.has_value());
    EXPECT_EQ(*m.max_stress_angle_rad, units::degToRad(15.0));
    EXPECT_EQ(m.bulldozing, contact::BulldozingModel::kHegedus);
    nlohmann::json j;
    writeModelChoices(m, j);
    EXPECT_EQ(j, (nlohmann::json{{"exit_angle_deg", -7.5},
                                 {"max_stress_angle_deg", 15.0},
                                 {"bulldozing", "hegedus"}}));
    EXPECT_EQ(io::fieldsToJson(m), j);
    const auto [back, back_issues] = readChoices(j);
    ASSERT_TRUE(back_issues.empty()) << formatIssues(back_issues);
    EXPECT_EQ(back.exit.value, m.exit.value);
    EXPECT_EQ(*back.max_stress_angle_rad, *m.max_stress_angle_rad);

    const auto [rut, rut_issues] = readChoices({{"rut_ratio", 0.4}});
    ASSERT_TRUE(rut_issues.empty()) << formatIssues(rut_issues);
    EXPECT_EQ(rut.exit.kind, contact::ExitCondition::Kind::kRutRatio);
    EXPECT_EQ(rut.exit.value, 0.4);
    EXPECT_EQ(io::fieldsToJson(rut), (nlohmann::json{{"rut_ratio", 0.4}}));
}

TEST(ModelChoicesKeys, TheDefaultsAreNotWritten) {
    const auto [m, issues] = readChoices(nlohmann::json::object());
    ASSERT_TRUE(issues.empty()) << formatIssues(issues);
    EXPECT_EQ(m.exit.kind, contact::ExitCondition::Kind::kAngle);
    EXPECT_EQ(m.exit.value, 0.0);
    EXPECT_FALSE(m.max_stress_angle_rad);
    EXPECT_EQ(m.bulldozing, contact::BulldozingModel::kBekker);
    // θ_r = 0, Eq. 2.18 and Bekker's: nothing written, as writeModelChoices always did.
    nlohmann::json j = nlohmann::json::object();
    writeModelChoices(m, j);
    EXPECT_EQ(j, nlohmann::json::object());
    // A bekker read is the default: not written either.
    const auto [b, b_issues] = readChoices({{"bulldozing", "bekker"}, {"exit_angle_deg", 0.0}});
    ASSERT_TRUE(b_issues.empty()) << formatIssues(b_issues);
    EXPECT_EQ(io::fieldsToJson(b), nlohmann::json::object());
}

TEST(ModelChoicesKeys, BadValuesAreNamedWithTheirRanges) {
    const auto [m, issues] = readChoices({{"exit_angle_deg", 5.0},
                                          {"max_stress_angle_deg", 95.0},
                                          {"bulldozing", "hegedos"},
                                          {"bulldozin", "bekker"}});
    EXPECT_EQ(issues.size(), 4u) << formatIssues(issues);
    EXPECT_EQ(choiceIssueAt(issues, "exit_angle_deg"),
              "5 is outside the allowed range [-90, 0] deg");
    EXPECT_EQ(choiceIssueAt(issues, "max_stress_angle_deg"),
              "95 is outside the allowed range [-90, 90] deg");
    EXPECT_TRUE(contains(choiceIssueAt(issues, "bulldozing"), "did you mean \"hegedus\""))
        << formatIssues(issues);
    EXPECT_TRUE(contains(choiceIssueAt(issues, "bulldozin"), "did you mean \"bulldozing\""))
        << formatIssues(issues);
    const auto [r, r_issues] = readChoices({{"rut_ratio", 1.5}});
    EXPECT_EQ(choiceIssueAt(r_issues, "rut_ratio"), "1.5 is outside the allowed range [0, 1]");
}

TEST(ModelChoicesKeys, ExitAngleOrRutRatioNotBoth) {
    const auto [m, issues] = readChoices({{"exit_angle_deg", -5.0}, {"rut_ratio", 0.5}});
    ASSERT_EQ(issues.size(), 1u) << formatIssues(issues);
    EXPECT_EQ(choiceIssueAt(issues, "rut_ratio"), "give exit_angle_deg or rut_ratio, not both");
}

// A struct that lists the choices with fields::members(model) reads and checks them the same way.
TEST(ModelChoicesKeys, AStructBuiltInCodeIsCheckedInTheReadersWords) {
    ModelChoices m;
    m.exit.value = units::degToRad(10.0);  // θ_r > 0
    m.max_stress_angle_rad = units::degToRad(-100.0);
    const std::string message = formatIssues(io::fieldIssues(m));
    EXPECT_TRUE(contains(message, "exit_angle_deg: 10 is outside the allowed range [-90, 0] deg"))
        << message;
    EXPECT_TRUE(
        contains(message, "max_stress_angle_deg: -100 is outside the allowed range [-90, 90] deg"))
        << message;
    EXPECT_TRUE(io::fieldIssues(ModelChoices{}).empty());
}

// The key table of the docs (fields::describeFields) lists the four keys, through a struct that
// holds the choices as members.
struct ChoicesHolder {
    ModelChoices model;
    template <typename Visitor>
    void visitFields(Visitor& v) {
        v(fields::members(model));
    }
};

TEST(ModelChoicesKeys, TheKeyTableListsTheChoices) {
    std::vector<std::string> keys;
    for (const fields::FieldDoc& doc : fields::describeFields<ChoicesHolder>())
        keys.push_back(doc.key);
    EXPECT_EQ(keys, (std::vector<std::string>{"exit_angle_deg", "rut_ratio", "max_stress_angle_deg",
                                              "bulldozing"}));
}

}  // namespace
}  // namespace terra::analysis
