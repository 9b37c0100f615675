// The strict JSON parser: what nlohmann accepts silently or throws on (duplicated keys, numbers
// beyond a double) is reported with its position; syntax errors carry line and column; valid
// JSON reads as nlohmann reads it.
#include "core/io/json.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "tests/core/test_support.h"

namespace terra::io {
namespace {

using nlohmann::json;

using terra::testing::contains;

TEST(StrictJson, ValidTextReadsAsNlohmannReadsIt) {
    const std::string text =
        R"({"a": [1, -2, 3.5, 1e3, 0.25e-2], "b": {"c": "x\ty\u00e9\ud83d\ude00"},
        "d": true, "e": false, "f": null, "g": "", "h": [], "i": {}, "big": 18446744073709551615,
        "neg": -9223372036854775808, "name": "φ sandy loam"})";
    const Result<json> parsed = parseJson(text, "t.json");
    ASSERT_TRUE(parsed.ok()) << parsed.message();
    EXPECT_EQ(parsed.value(), json::parse(text));
    EXPECT_TRUE(parsed.value()["a"][0].is_number_integer());  // integers stay integers
    EXPECT_TRUE(parsed.value()["a"][3].is_number_float());
    EXPECT_EQ(parsed.value()["big"].get<std::uint64_t>(), 18446744073709551615u);
}

TEST(StrictJson, DuplicatedKeysAreNamedWithBothPositions) {
    // Line 3 column 5 holds the second "load_N" (four spaces of indentation).
    const std::string text =
        "{\"conditions\": {\n"
        "    \"load_N\": 58.86,\n"
        "    \"load_N\": 20},\n"
        " \"title\": \"a\", \"title\": \"b\"}";
    const Result<json> parsed = parseJson(text, "s.json");
    ASSERT_FALSE(parsed.ok());
    ASSERT_EQ(parsed.issues().size(), 2u) << parsed.message();
    EXPECT_EQ(parsed.issues()[0].where, "s.json:3:5");
    EXPECT_EQ(parsed.issues()[0].message,
              "duplicated key \"load_N\" in conditions (first at line 2, column 5)");
    EXPECT_EQ(parsed.issues()[1].where, "s.json:4:16");
    EXPECT_TRUE(contains(parsed.issues()[1].message, "\"title\" at the top level"));
}

// Fuzzing found it (script_json, 2026-12-02): a duplicated key inside an object whose own key was
// 1,300 characters echoed that parent key whole in "in <path>". The path is cut like the key.
TEST(StrictJson, ADuplicatedKeyUnderAHugeParentKeyIsNamedShort) {
    const std::string parent = std::string(1300, 'p') + "é";
    const std::string text = "{\"" + parent + "\": {\"a\": 1, \"a\": 2}}";
    const Result<json> parsed = parseJson(text, "s.json");
    ASSERT_FALSE(parsed.ok());
    ASSERT_EQ(parsed.issues().size(), 1u);
    const std::string& message = parsed.issues()[0].message;
    EXPECT_LT(message.size(), 200u) << message.substr(0, 300);
    EXPECT_TRUE(contains(message, "duplicated key \"a\" in " + std::string(77, 'p') + "..."))
        << message.substr(0, 300);
}

TEST(StrictJson, NumbersBeyondADoubleNameTheirFieldAndPosition) {
    const std::string text =
        "{\"analyses\": [{}, {}, {\"slip_count\": 1e999}],\n"
        " \"tiny\": -2.5e-400, \"sub\": 1e-310, \"neg\": -1E+400, \"zero\": 0.0e-999}";
    const Result<json> parsed = parseJson(text, "s.json");
    ASSERT_FALSE(parsed.ok());
    ASSERT_EQ(parsed.issues().size(), 4u) << parsed.message();
    EXPECT_EQ(parsed.issues()[0].where, "s.json:1:38");
    EXPECT_EQ(parsed.issues()[0].message,
              "analyses[2].slip_count: 1e999 is too large for a number (beyond ±1.8e308)");
    EXPECT_TRUE(contains(parsed.issues()[1].message, "tiny: -2.5e-400 is too small"))
        << parsed.message();
    EXPECT_TRUE(contains(parsed.issues()[2].message, "sub: 1e-310 is too small"))
        << parsed.message();
    EXPECT_TRUE(contains(parsed.issues()[3].message, "neg: -1E+400 is too large"))
        << parsed.message();
    // A written zero is a zero, whatever its exponent.
    EXPECT_TRUE(parseJson("[0.0e-999, 0e5, -0.0]", "").ok());
    // The largest and smallest normal doubles are fine.
    const Result<json> edges = parseJson("[1.7976931348623157e308, 2.2250738585072014e-308]", "");
    ASSERT_TRUE(edges.ok()) << edges.message();
    EXPECT_EQ(edges.value()[0].get<double>(), std::numeric_limits<double>::max());
    EXPECT_EQ(edges.value()[1].get<double>(), std::numeric_limits<double>::min());
}

TEST(StrictJson, MarkedNumbersAreNanInTheValueAndListedWithTheirPath) {
    const std::string text = "{\"a\": [1, 1e999], \"b\": {\"c\": -1e-320}, \"d\": 2}";
    std::vector<BadNumber> bad;
    const Result<json> parsed = parseJsonMarkingNumbers(text, "m.json", bad);
    ASSERT_TRUE(parsed.ok()) << parsed.message();
    EXPECT_TRUE(std::isnan(parsed.value()["a"][1].get<double>()));
    EXPECT_TRUE(std::isnan(parsed.value()["b"]["c"].get<double>()));
    EXPECT_EQ(parsed.value()["d"], 2);
    ASSERT_EQ(bad.size(), 2u);
    EXPECT_EQ(bad[0].path, "a[1]");
    EXPECT_EQ(bad[0].issue.where, "m.json:1:11");
    EXPECT_EQ(bad[0].issue.message, "a[1]: 1e999 is too large for a number (beyond ±1.8e308)");
    EXPECT_EQ(bad[1].path, "b.c");
    EXPECT_TRUE(contains(bad[1].issue.message, "b.c: -1e-320 is too small"))
        << bad[1].issue.message;
    // The plain parse of the same text fails with the same issues.
    const Result<json> strict = parseJson(text, "m.json");
    ASSERT_FALSE(strict.ok());
    ASSERT_EQ(strict.issues().size(), 2u);
    EXPECT_EQ(strict.issues()[0].message, bad[0].issue.message);
    // A syntax error still fails the marking parse.
    std::vector<BadNumber> none;
    EXPECT_FALSE(parseJsonMarkingNumbers("{\"a\": 1e999,}", "m.json", none).ok());
}

TEST(StrictJson, SyntaxErrorsGiveLineAndColumn) {
    struct Case {
        const char* text;
        const char* where;
        const char* message;
    };
    const Case cases[] = {
        {"{\"a\": 1,,\n}", "f:1:9", "expected a key"},
        {"{\"a\": 1\n\"b\": 2}", "f:2:1", "expected '}' or ','"},
        {"[1, 2", "f:1:6", "end of input"},
        {"{\"a\": tru}", "f:1:7", "expected a value"},
        {"{\"a\": 01}", "f:1:8", "leading zeros"},
        {"{\"a\": 1.}", "f:1:9", "after the decimal point"},
        {"{\"a\": NaN}", "f:1:7", "expected a value"},
        {"{\"a\": \"x\ny\"}", "f:1:9", "control character"},
        {"{\"a\": \"\\q\"}", "f:1:10", "invalid escape"},
        {"{\"a\": \"\\ud800x\"}", "f:1:14", "surrogate"},
        {"{\"é\": x}", "f:1:7", "expected a value"},  // columns count characters, not bytes
        {"{} {}", "f:1:4", "after the JSON value"},
        {"", "f:1:1", "end of input"},
        {"{\"a\": \"\xC3\x28\"}", "f:1:8", "invalid UTF-8"},
        {"{\"a\": \"\xED\xA0\x80\"}", "f:1:8", "invalid UTF-8"},  // an encoded surrogate
    };
    for (const Case& c : cases) {
        const Result<json> parsed = parseJson(c.text, "f");
        ASSERT_FALSE(parsed.ok()) << c.text;
        ASSERT_EQ(parsed.issues().size(), 1u) << c.text;
        EXPECT_EQ(parsed.issues()[0].where, c.where) << c.text << ": " << parsed.message();
        EXPECT_TRUE(contains(parsed.issues()[0].message, c.message))
            << c.text << ": " << parsed.message();
        EXPECT_TRUE(contains(parsed.issues()[0].message, "invalid JSON")) << parsed.message();
    }
}

TEST(StrictJson, DeepNestingIsAnErrorNotACrash) {
    const std::string text = std::string(100000, '[') + std::string(100000, ']');
    const Result<json> parsed = parseJson(text, "deep");
    ASSERT_FALSE(parsed.ok());
    EXPECT_TRUE(contains(parsed.message(), "nested deeper than 256")) << parsed.message();
}

TEST(StrictJson, ByteOrderMarkIsSkipped) {
    const Result<json> parsed = parseJson("\xEF\xBB\xBF{\"a\": 1}", "");
    ASSERT_TRUE(parsed.ok()) << parsed.message();
    EXPECT_EQ(parsed.value()["a"], 1);
}

TEST(StrictJson, MissingFileIsOneIssue) {
    const Result<json> parsed = readJsonFile("/nonexistent/dir/x.json");
    ASSERT_FALSE(parsed.ok());
    EXPECT_EQ(parsed.issues()[0].where, "/nonexistent/dir/x.json");
}

TEST(QuoteJson, LongValuesAreCutToEightyCharacters) {
    const json long_text = std::string(500, 'x');
    const std::string quoted = quoteJson(long_text);
    // 79 characters of the dump ('"' and 78 x) and the ellipsis: 80 characters.
    EXPECT_EQ(quoted, "\"" + std::string(78, 'x') + "…");
    EXPECT_EQ(quoteJson(json("short")), "\"short\"");
    // Invalid UTF-8 in a value built in code is replaced, not thrown.
    EXPECT_NO_THROW(quoteJson(json(std::string("\xff\xfe"))));
}

}  // namespace
}  // namespace terra::io
