// The object reader: every field named by its path, types named, ranges checked before any
// conversion, unknown keys reported with the nearest known one, every problem collected.
#include "core/io/json_reader.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <limits>

#include "core/common/units.h"
#include "tests/core/test_support.h"

namespace terra::io {
namespace {

using nlohmann::json;

using terra::testing::contains;

TEST(ObjectReader, ReadsTypedFieldsWithDefaultsForAbsentOnes) {
    const json j = json::parse(R"({"n": 3, "x": 0.5, "on": true, "name": "a", "mode": "fast",
                                   "list": [1, 2.5], "words": ["p", "q"], "_comment": "ignored"})");
    std::vector<Issue> issues;
    ObjectReader r(j, issues, "f.json");
    int n = 0;
    double x = 0.0, absent = 7.0;
    bool on = false;
    std::string name;
    enum class Mode { kSlow, kFast } mode = Mode::kSlow;
    std::vector<double> list;
    std::vector<std::string> words;
    EXPECT_TRUE(r.integer("n", n, 0, 10));
    EXPECT_TRUE(r.number("x", x, {0.0, 1.0}));
    EXPECT_FALSE(r.number("absent", absent, {0.0, 10.0}));
    EXPECT_TRUE(r.boolean("on", on));
    EXPECT_TRUE(r.text("name", name));
    EXPECT_TRUE(r.choice<Mode>("mode", mode, {{"slow", Mode::kSlow}, {"fast", Mode::kFast}}));
    EXPECT_TRUE(r.numbers("list", list, {0.0, 5.0}));
    EXPECT_TRUE(r.texts("words", words));
    r.finish();
    EXPECT_TRUE(issues.empty()) << formatIssues(issues);
    EXPECT_EQ(n, 3);
    EXPECT_EQ(x, 0.5);
    EXPECT_EQ(absent, 7.0);
    EXPECT_TRUE(on);
    EXPECT_EQ(name, "a");
    EXPECT_EQ(mode, Mode::kFast);
    EXPECT_EQ(list, (std::vector<double>{1.0, 2.5}));
    EXPECT_EQ(words, (std::vector<std::string>{"p", "q"}));
}

// The measured cases of issue 10: a string where an object belongs, a number where a string
// belongs, a misspelt key, an integer of 1e308.
// An unknown key is user text: a huge one (found by fuzzing, tests/fuzz/crashes/soil_json/) is
// quoted to ~80 characters with its length, in the location and nowhere else in full.
TEST(ObjectReader, AHugeUnknownKeyIsQuotedNotEchoed) {
    const std::string key(5000, 'k');
    const json object = {{"n", 0.7}, {key, 1.0}};
    std::vector<Issue> issues;
    ObjectReader r(object, issues, "soil.json");
    double n = 0.0;
    r.number("n", n, Range{0.0, 2.0});
    r.finish();
    ASSERT_EQ(issues.size(), 1u);
    EXPECT_LT(issues[0].where.size() + issues[0].message.size(), 400u)
        << issues[0].where << ": " << issues[0].message;
    EXPECT_NE(issues[0].where.find("(5000 characters)"), std::string::npos) << issues[0].where;
    EXPECT_NE(issues[0].message.find("unknown key"), std::string::npos);
    // A short unknown key is named as typed.
    issues.clear();
    const json typo = {{"nn", 0.7}};
    ObjectReader q(typo, issues, "soil.json");
    q.number("n", n, Range{0.0, 2.0});
    q.finish();
    ASSERT_EQ(issues.size(), 1u);
    EXPECT_EQ(issues[0].where, "soil.json: nn");
}

TEST(ObjectReader, WrongTypesNameTheFieldAndTheExpectedType) {
    const json j = json::parse(R"({"conditions": "x", "title": 12, "condtions": {},
                                   "analyses": [{"slip_count": 1e308}, {"slip_count": 2.5}]})");
    std::vector<Issue> issues;
    ObjectReader r(j, issues, "s.json");
    ObjectReader conditions = r.object("conditions");
    conditions.finish();
    std::string title;
    EXPECT_FALSE(r.text("title", title));
    const json* analyses = r.array("analyses");
    ASSERT_NE(analyses, nullptr);
    for (std::size_t i = 0; i < analyses->size(); ++i) {
        ObjectReader a = r.element("analyses", *analyses, i);
        int slip_count = 50;
        EXPECT_FALSE(a.integer("slip_count", slip_count, 2, 10000));
        EXPECT_EQ(slip_count, 50);  // untouched
        a.finish();
    }
    r.finish();
    ASSERT_EQ(issues.size(), 5u) << formatIssues(issues);
    EXPECT_EQ(issues[0].where, "s.json: conditions");
    EXPECT_EQ(issues[0].message, "expected a JSON object, got string \"x\"");
    EXPECT_EQ(issues[1].where, "s.json: title");
    EXPECT_EQ(issues[1].message, "expected a string, got number 12");
    EXPECT_EQ(issues[2].where, "s.json: analyses[0].slip_count");
    EXPECT_EQ(issues[2].message, "1e+308 is outside the allowed range [2, 10000]");
    EXPECT_EQ(issues[3].where, "s.json: analyses[1].slip_count");
    EXPECT_EQ(issues[3].message,
              "2.5 is not a whole number; expected a whole number in [2, 10000]");
    EXPECT_EQ(issues[4].where, "s.json: condtions");
    EXPECT_TRUE(contains(issues[4].message, "unknown key; did you mean \"conditions\"?"))
        << issues[4].message;
}

TEST(ObjectReader, IntegersBeyondTheirTypeAreRangeErrorsNeverWrapped) {
    const json j = json::parse(
        R"({"a": 1e308, "b": -1e308, "c": 4294967296, "seed": 1e20, "s2": -1, "s3": 18446744073709551615})");
    std::vector<Issue> issues;
    ObjectReader r(j, issues);
    int a = 0, b = 0, c = 0;
    EXPECT_FALSE(r.integer("a", a, 0, std::numeric_limits<int>::max()));
    EXPECT_FALSE(r.integer("b", b, std::numeric_limits<int>::min(), 0));
    EXPECT_FALSE(r.integer("c", c, 0, std::numeric_limits<int>::max()));
    std::uint64_t seed = 0, s2 = 0, s3 = 0;
    EXPECT_FALSE(r.integer("seed", seed, 0, std::numeric_limits<std::uint64_t>::max()));
    EXPECT_FALSE(r.integer("s2", s2, 0, 10));
    EXPECT_TRUE(r.integer("s3", s3, 0, std::numeric_limits<std::uint64_t>::max()));
    EXPECT_EQ(s3, std::numeric_limits<std::uint64_t>::max());
    EXPECT_EQ(issues.size(), 5u) << formatIssues(issues);
    EXPECT_EQ(a, 0);
    EXPECT_EQ(seed, 0u);
}

TEST(ObjectReader, MissingRequiredKeysSayWhatWasExpected) {
    std::vector<Issue> issues;
    const json j = json::object();
    ObjectReader r(j, issues, "w.json");
    double radius = 0.0;
    r.number("r_m", radius, {0.0, 5.0, true, false}, "m", Presence::kRequired);
    std::string mode;
    r.choiceName("model", mode, {"full", "quadratic"}, Presence::kRequired);
    ASSERT_EQ(issues.size(), 2u);
    EXPECT_EQ(issues[0].where, "w.json: r_m");
    EXPECT_EQ(issues[0].message, "missing; expected a number in (0, 5] m");
    EXPECT_EQ(issues[1].message, "missing; expected one of full, quadratic");
}

TEST(ObjectReader, ChoicesSuggestTheNearestName) {
    const json j = json::parse(R"({"model": "quadratc", "other": "cubic", "n": 5})");
    std::vector<Issue> issues;
    ObjectReader r(j, issues);
    std::string model = "full", other = "full", n;
    EXPECT_FALSE(r.choiceName("model", model, {"full", "quadratic"}));
    EXPECT_FALSE(r.choiceName("other", other, {"full", "quadratic"}));
    EXPECT_FALSE(r.choiceName("n", n, {"full", "quadratic"}));
    ASSERT_EQ(issues.size(), 3u);
    EXPECT_EQ(issues[0].message,
              "\"quadratc\" is not one of full, quadratic (did you mean \"quadratic\"?)");
    EXPECT_EQ(issues[1].message, "\"cubic\" is not one of full, quadratic");
    EXPECT_EQ(issues[2].message, "expected a string, one of full, quadratic, got number 5");
    EXPECT_EQ(model, "full");
}

TEST(ObjectReader, ArraysReportEachBadElementByIndex) {
    const json j = json::parse(R"({"angles": [5, "ten", 95, null], "few": [1]})");
    std::vector<Issue> issues;
    ObjectReader r(j, issues, "", "conditions");
    std::vector<double> angles{1.0}, few;
    EXPECT_FALSE(r.numbers("angles", angles, {-90.0, 90.0, true, true}, "deg"));
    EXPECT_FALSE(r.numbers("few", few, {0.0, 1.0}, "", 2, 3));
    ASSERT_EQ(issues.size(), 4u) << formatIssues(issues);
    EXPECT_EQ(issues[0].where, "conditions.angles[1]");
    EXPECT_EQ(issues[0].message, "expected a number in (-90, 90) deg, got string \"ten\"");
    EXPECT_EQ(issues[1].where, "conditions.angles[2]");
    EXPECT_EQ(issues[1].message, "95 is outside the allowed range (-90, 90) deg");
    EXPECT_EQ(issues[2].where, "conditions.angles[3]");
    EXPECT_EQ(issues[3].message, "1 values; expected an array of 2 to 3 numbers in [0, 1]");
    EXPECT_EQ(angles, std::vector<double>{1.0});  // untouched
}

TEST(ObjectReader, FieldTablesReadInUserUnitsAndStoreSi) {
    const FieldInfo phi{
        "phi_deg", "deg", "φ", "friction angle", "", {0.0, 60.0, false, true}, units::kPi / 180.0};
    const json j = json::parse(R"({"phi_deg": 30})");
    std::vector<Issue> issues;
    ObjectReader r(j, issues);
    double phi_rad = 0.0;
    EXPECT_TRUE(r.field(phi, phi_rad, Presence::kRequired));
    EXPECT_DOUBLE_EQ(phi_rad, units::kPi / 6.0);
    const json bad = json::parse(R"({"phi_deg": 75})");
    ObjectReader b(bad, issues, "s.json");
    EXPECT_FALSE(b.field(phi, phi_rad));
    ASSERT_EQ(issues.size(), 1u);
    EXPECT_EQ(issues[0].message, "75 is outside the allowed range [0, 60) deg");
}

TEST(ObjectReader, LongValuesAreQuotedShortInMessages) {
    const json j = {{"title", json::array({std::string(300, 'a')})}};
    std::vector<Issue> issues;
    ObjectReader r(j, issues);
    std::string title;
    r.text("title", title);
    ASSERT_EQ(issues.size(), 1u);
    EXPECT_LT(issues[0].message.size(), 120u) << issues[0].message;
}

TEST(ObjectReader, UnknownKeysListTheAllowedOnesAndSkipComments) {
    const json j = json::parse(R"({"phi": 29, "zzz": 1, "_why": "a comment"})");
    std::vector<Issue> issues;
    ObjectReader r(j, issues, "soil.json");
    double value = 0.0;
    r.number("phi_deg", value, {0.0, 60.0});
    r.number("c_kPa", value, {0.0, 200.0});
    r.finish();
    ASSERT_EQ(issues.size(), 2u) << formatIssues(issues);
    EXPECT_EQ(issues[0].where, "soil.json: phi");
    EXPECT_EQ(issues[0].message,
              "unknown key; did you mean \"phi_deg\"? Allowed keys: phi_deg, c_kPa");
    EXPECT_EQ(issues[1].message, "unknown key; allowed keys: phi_deg, c_kPa");
}

TEST(ObjectReader, NotAnObjectIsOneIssueAndReadsFindNothing) {
    const json j = json::array({1, 2});
    std::vector<Issue> issues;
    ObjectReader r(j, issues, "f.json");
    double x = 3.0;
    EXPECT_FALSE(r.number("x", x, {0.0, 1.0}, "", Presence::kRequired));
    r.finish();
    ASSERT_EQ(issues.size(), 1u);
    EXPECT_EQ(issues[0].where, "f.json");
    EXPECT_EQ(issues[0].message, "expected a JSON object, got array [1,2]");
}

TEST(NearestName, OneEditPerThreeCharactersOrTheUnitLeftOut) {
    const std::vector<std::string> keys{"conditions", "title", "slip_count", "phi_deg", "n"};
    EXPECT_EQ(nearestName("condtions", keys), "conditions");
    EXPECT_EQ(nearestName("Titel", keys), "title");  // a swap, case ignored
    EXPECT_EQ(nearestName("slipcount", keys), "slip_count");
    EXPECT_EQ(nearestName("phi", keys), "phi_deg");
    EXPECT_EQ(nearestName("color", keys), "");
    EXPECT_EQ(nearestName("", keys), "");
}

// The loaders' way (readJsonFileWith): a number no double holds keeps its position and gains the
// range that the field's reader states, here for a number, an array element and an integer.
TEST(ReadJsonFileWith, BadNumbersNameTheRangeOfTheirField) {
    const std::filesystem::path file = std::filesystem::temp_directory_path() /
                                       ("terra_marked_" + std::to_string(::getpid()) + ".json");
    std::ofstream(file) << "{\"x\": 1e999,\n \"list\": [1, 1e-320], \"n\": -1e999, \"_c\": 1e999}";
    auto read = [](const json& j, const std::string& source) -> Result<double> {
        std::vector<Issue> issues;
        ObjectReader r(j, issues, source);
        double x = 0.0;
        std::vector<double> list;
        int n = 0;
        r.number("x", x, {0.0, 5.0}, "m");
        r.numbers("list", list, {-1.0, 1.0});
        r.integer("n", n, 2, 10);
        r.finish();
        if (!issues.empty()) return issues;
        return x;
    };
    const Result<double> result = readJsonFileWith<double>(file, read);
    std::filesystem::remove(file);
    ASSERT_FALSE(result.ok());
    const std::string source = file.string();
    ASSERT_EQ(result.issues().size(), 4u) << result.message();
    EXPECT_EQ(result.issues()[0].where, source + ":1:7");
    EXPECT_EQ(result.issues()[0].message,
              "x: 1e999 is too large for a number (beyond ±1.8e308); allowed range [0, 5] m");
    EXPECT_EQ(result.issues()[1].where, source + ":2:14");
    EXPECT_TRUE(contains(result.issues()[1].message,
                         "list[1]: 1e-320 is too small for a number (below 2.2e-308, it would "
                         "lose its digits); allowed range [-1, 1]"))
        << result.issues()[1].message;
    EXPECT_TRUE(contains(result.issues()[2].message, "n: -1e999 is too large for a number"));
    EXPECT_TRUE(contains(result.issues()[2].message, "; allowed range [2, 10]"));
    // A comment key is read by no one: the message stays, without a range, and the file fails.
    EXPECT_EQ(result.issues()[3].message, "_c: 1e999 is too large for a number (beyond ±1.8e308)");
}

}  // namespace
}  // namespace terra::io
