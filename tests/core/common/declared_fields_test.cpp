// The declared field lists (core/common/declared_fields.h) and their JSON reader and writer
// (core/io/declared_json.h), on a small struct with one field of each kind.
#include "core/common/declared_fields.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/io/declared_json.h"
#include "tests/core/test_support.h"

namespace terra {
namespace {

using testing::contains;
using testing::kDeg;

const FieldInfo kProbeAngleField{"tilt_deg",       "deg", "α", "tilt", "the probe's tilt [deg]",
                                 Range{0.0, 45.0}, kDeg};

enum class ProbeMode { kFast, kSlow };

// A nested object, in its own JSON object ("inner").
struct ProbeInner {
    double force_n = 1.5;
    int count = 3;

    template <typename Visitor>
    void visitFields(Visitor& v) {
        v(fields::number("force_N", force_n, {0.0, 100.0}, "N", "a force"));
        v(fields::integer("count", count, 1, 9, "a count"));
    }
};

// Members of a struct kept in the enclosing object.
struct ProbeExtra {
    std::string note = "none";

    template <typename Visitor>
    void visitFields(Visitor& v) {
        v(fields::text("note", note, "a note"));
    }
};

struct Probe {
    double ratio = 0.5;
    double tilt_rad = 10.0 * kDeg;
    std::optional<double> limit_n;
    int folds = 0;  // 0: none
    std::uint64_t seed = 1;
    bool verbose = false;
    ProbeMode mode = ProbeMode::kFast;
    std::string file;
    std::vector<std::string> tags;
    std::vector<double> loads_n;
    ProbeInner inner;
    ProbeExtra extra;

    template <typename Visitor>
    void visitFields(Visitor& v) {
        v(fields::number("ratio", ratio, {0.0, 1.0}, "", "a fraction"));
        v(fields::field(kProbeAngleField, tilt_rad));
        v(fields::number("limit_N", limit_n, {0.0, 1e3}, "N", "a limit; absent: none"));
        v(fields::integer("folds", folds, 2, 10, "folds (0: none)", 0));
        v(fields::integer("seed", seed, 0, 1000, "a seed"));
        v(fields::flag("verbose", verbose, "say more"));
        v(fields::choice("mode", mode,
                         {{"fast", ProbeMode::kFast},
                          {"slow", ProbeMode::kSlow},
                          {"quick", ProbeMode::kFast, true}},
                         "how"));
        v(fields::path("file", file, "a file"));
        v(fields::texts("tags", tags, "tags"));
        v(fields::numbers("loads_N", loads_n, {1.0, 1e3}, "N", "loads", 1));
        v(fields::object("inner", inner, "the inner part"));
        v(fields::members(extra));
    }
};

// The issues of reading `json` into `out` (whose values are kept where a key is absent).
std::vector<Issue> readProbe(const nlohmann::json& json, Probe& out,
                             const std::filesystem::path& base_dir = {}) {
    std::vector<Issue> issues;
    io::ObjectReader r(json, issues, "probe.json");
    io::readFields(r, out, base_dir);
    r.finish();
    return issues;
}

// The one issue of reading `json`, as "where: message" (or a note that there was not one).
std::string oneIssue(const nlohmann::json& json) {
    Probe p;
    const std::vector<Issue> issues = readProbe(json, p);
    if (issues.size() != 1)
        return std::to_string(issues.size()) + " issues: " + formatIssues(issues);
    return issues.front().where + ": " + issues.front().message;
}

TEST(DeclaredFields, AbsentKeysKeepTheDefaults) {
    Probe p;
    p.ratio = 0.25;  // a caller's default, not the struct's
    EXPECT_TRUE(readProbe(nlohmann::json::object(), p).empty());
    EXPECT_EQ(p.ratio, 0.25);
    EXPECT_EQ(p.tilt_rad, 10.0 * kDeg);
    EXPECT_FALSE(p.limit_n.has_value());
    EXPECT_EQ(p.folds, 0);
    EXPECT_EQ(p.mode, ProbeMode::kFast);
    EXPECT_EQ(p.inner.count, 3);
    EXPECT_EQ(p.extra.note, "none");
}

TEST(DeclaredFields, WhatIsWrittenReadsBackTheSame) {
    Probe p;
    p.ratio = 0.75;
    p.tilt_rad = 29.0 * kDeg;
    p.limit_n = 12.5;
    p.folds = 5;
    p.seed = 77;
    p.verbose = true;
    p.mode = ProbeMode::kSlow;
    p.file = "/data/run.csv";
    p.tags = {"a", "b"};
    p.loads_n = {30.0, 60.0};
    p.inner = {7.25, 8};
    p.extra.note = "wet";
    const nlohmann::json j = io::fieldsToJson(p);
    // The file's units and names: degrees for the field table's angle, the enumeration's name.
    EXPECT_EQ(j["tilt_deg"].get<double>(), 29.0);
    EXPECT_EQ(j["mode"], "slow");
    EXPECT_EQ(j["inner"]["force_N"].get<double>(), 7.25);
    EXPECT_EQ(j["note"], "wet");  // members of a member struct: in the same object
    Probe back;
    ASSERT_TRUE(readProbe(j, back).empty()) << formatIssues(readProbe(j, back));
    EXPECT_EQ(back.ratio, 0.75);
    EXPECT_EQ(back.tilt_rad, p.tilt_rad);  // 29° → rad → 29 → rad: the same double
    EXPECT_EQ(back.limit_n, 12.5);
    EXPECT_EQ(back.folds, 5);
    EXPECT_EQ(back.seed, 77u);
    EXPECT_TRUE(back.verbose);
    EXPECT_EQ(back.mode, ProbeMode::kSlow);
    EXPECT_EQ(back.file, "/data/run.csv");
    EXPECT_EQ(back.tags, p.tags);
    EXPECT_EQ(back.loads_n, p.loads_n);
    EXPECT_EQ(back.inner.force_n, 7.25);
    EXPECT_EQ(back.inner.count, 8);
    EXPECT_EQ(back.extra.note, "wet");
}

TEST(DeclaredFields, EmptyOptionalsListsAndUnsetValuesAreLeftOut) {
    const nlohmann::json j = io::fieldsToJson(Probe{});
    for (const char* key : {"limit_N", "folds", "tags", "loads_N"})
        EXPECT_FALSE(j.contains(key)) << key << " in " << j.dump();
    for (const char* key : {"ratio", "tilt_deg", "seed", "verbose", "mode", "file", "inner"})
        EXPECT_TRUE(j.contains(key)) << key << " not in " << j.dump();
    Probe back;
    EXPECT_TRUE(readProbe(j, back).empty());
    EXPECT_EQ(back.folds, 0);
}

TEST(DeclaredFields, EachErrorNamesTheFieldAndWhatIsAllowed) {
    EXPECT_EQ(oneIssue({{"ratio", 1.5}}),
              "probe.json: ratio: 1.5 is outside the allowed range [0, 1]");
    EXPECT_EQ(oneIssue({{"ratio", "half"}}),
              "probe.json: ratio: expected a number in [0, 1], got string \"half\"");
    EXPECT_EQ(oneIssue({{"tilt_deg", 50}}),
              "probe.json: tilt_deg: 50 is outside the allowed range [0, 45] deg");
    EXPECT_EQ(oneIssue({{"limit_N", -1}}),
              "probe.json: limit_N: -1 is outside the allowed range [0, 1000] N");
    // The unset value is the member's, never a file's.
    EXPECT_EQ(oneIssue({{"folds", 0}}),
              "probe.json: folds: 0 is outside the allowed range [2, 10]");
    EXPECT_EQ(oneIssue({{"folds", 2.5}}),
              "probe.json: folds: 2.5 is not a whole number; expected a whole number in [2, 10]");
    EXPECT_EQ(oneIssue({{"verbose", 1}}),
              "probe.json: verbose: expected true or false, got number 1");
    EXPECT_EQ(oneIssue({{"mode", "fsat"}}),
              "probe.json: mode: \"fsat\" is not one of fast, slow (did you mean \"fast\"?)");
    EXPECT_EQ(oneIssue({{"loads_N", nlohmann::json::array()}}),
              "probe.json: loads_N: 0 values; expected an array of 1 or more numbers in [1, 1000] "
              "N");
    EXPECT_EQ(oneIssue({{"inner", {{"count", 0}}}}),
              "probe.json: inner.count: 0 is outside the allowed range [1, 9]");
    EXPECT_TRUE(contains(oneIssue({{"ratoi", 0.5}}),
                         "probe.json: ratoi: unknown key; did you mean \"ratio\"?"))
        << oneIssue({{"ratoi", 0.5}});
    EXPECT_TRUE(contains(oneIssue({{"inner", {{"cuont", 2}}}}),
                         "probe.json: inner.cuont: unknown key; did you mean \"count\"?"))
        << oneIssue({{"inner", {{"cuont", 2}}}});
}

TEST(DeclaredFields, AnAliasIsReadButTheListedNameIsWritten) {
    Probe p;
    p.mode = ProbeMode::kSlow;
    ASSERT_TRUE(readProbe({{"mode", "quick"}}, p).empty());
    EXPECT_EQ(p.mode, ProbeMode::kFast);
    EXPECT_EQ(io::fieldsToJson(p)["mode"], "fast");
}

TEST(DeclaredFields, RelativePathsAreReadAgainstTheFilesDirectory) {
    Probe p;
    ASSERT_TRUE(readProbe({{"file", "data/a.csv"}}, p, "/runs").empty());
    EXPECT_EQ(std::filesystem::path(p.file), std::filesystem::path("/runs/data/a.csv"));
    ASSERT_TRUE(readProbe({{"file", "/abs/b.csv"}}, p, "/runs").empty());
    EXPECT_EQ(p.file, "/abs/b.csv");
}

TEST(DeclaredFields, AStructBuiltInCodeIsCheckedInTheReadersWords) {
    Probe p;
    EXPECT_TRUE(io::fieldIssues(p).empty());
    p.ratio = 2.0;
    p.inner.count = 12;
    const std::vector<Issue> issues = io::fieldIssues(p);
    ASSERT_EQ(issues.size(), 2u) << formatIssues(issues);
    EXPECT_EQ(issues[0].where, "ratio");
    EXPECT_EQ(issues[0].message, "2 is outside the allowed range [0, 1]");
    EXPECT_EQ(issues[1].where, "inner.count");
}

TEST(DeclaredFields, TheKeyTableListsEveryKeyWithItsRangeAndDefault) {
    const std::vector<fields::FieldDoc> docs = fields::describeFields<Probe>();
    std::vector<std::string> keys;
    for (const fields::FieldDoc& d : docs) keys.push_back(d.key);
    EXPECT_EQ(keys, (std::vector<std::string>{"ratio", "tilt_deg", "limit_N", "folds", "seed",
                                              "verbose", "mode", "file", "tags", "loads_N", "inner",
                                              "inner.force_N", "inner.count", "note"}));
    EXPECT_EQ(docs[1].allowed, "[0, 45] deg");
    EXPECT_EQ(docs[1].default_value, "10");
    EXPECT_EQ(docs[2].default_value, "none");
    EXPECT_EQ(docs[3].default_value, "none");
    EXPECT_EQ(docs[6].allowed, "fast, slow");  // the alias is not listed
    EXPECT_EQ(docs[11].allowed, "[0, 100] N");
    EXPECT_EQ(docs[11].default_value, "1.5");
}

}  // namespace
}  // namespace terra
