#include "core/io/experiment.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "core/io/parameters_json.h"
#include "tests/core/test_support.h"
#include "tests/core/test_temp_dir.h"

namespace terra::io {
namespace {

namespace fs = std::filesystem;

using terra::testing::contains;

TEST(ExperimentCsv, AnySubsetOfChannelsEmptyCellsAreNotMeasured) {
    const std::string text =
        "slip,load_N,Fx_N,sinkage_m\n"
        "0,80,-6.5,0.005\n"
        "# a comment\n"
        "0.1,80,11,\n"
        "0.6,80,,0.0175\n";
    const Result<Experiment> r = parseExperimentCsv(text, "t.csv");
    ASSERT_TRUE(r.ok()) << r.message();
    ASSERT_EQ(r->points.size(), 3u);
    const ExperimentPoint& a = r->points[0];
    EXPECT_EQ(a.load_n, 80.0);
    EXPECT_EQ(a.slip, 0.0);
    EXPECT_EQ(a.slip_angle_deg, 0.0);  // absent column: straight driving
    EXPECT_EQ(a.measured[kExpFx], -6.5);
    EXPECT_EQ(a.measured[kExpSinkage], 0.005);
    EXPECT_FALSE(a.measured[kExpMy].has_value());
    EXPECT_FALSE(r->points[1].measured[kExpSinkage].has_value());
    EXPECT_FALSE(r->points[2].measured[kExpFx].has_value());
    EXPECT_EQ(r->points[1].line, 4);  // the comment counts as a line
    EXPECT_TRUE(r->measures(kExpFx));
    EXPECT_FALSE(r->measures(kExpFy));
}

TEST(ExperimentCsv, EveryBadCellIsReportedWithItsLineColumnValueAndRange) {
    const std::string text =
        "load_N,slip,slip_angle_deg,Fx_N,My_Nm\n"
        "80,1.5,0,1,\n"    // slip out of range
        "-3,0.1,0,x,\n"    // load out of range, Fx not a number
        "80,0.2,90,1,2\n"  // β = 90 not allowed (open)
        "80,0.3,0,,\n"     // nothing measured
        ",0.4,0,1,2\n"     // load empty
        "80,0.5,0,1\n";    // a cell short
    const Result<Experiment> r = parseExperimentCsv(text, "t.csv");
    ASSERT_FALSE(r.ok());
    const auto& issues = r.issues();
    ASSERT_EQ(issues.size(), 7u) << r.message();
    EXPECT_EQ(issues[0].where, "t.csv:2");
    EXPECT_TRUE(contains(issues[0].message, "slip = 1.5 is outside the allowed range [-1, 1]"))
        << issues[0].message;
    EXPECT_EQ(issues[1].where, "t.csv:3");
    EXPECT_TRUE(
        contains(issues[1].message, "load_N = -3 is outside the allowed range (0, 1e+05] N"))
        << issues[1].message;
    EXPECT_EQ(issues[2].where, "t.csv:3");
    EXPECT_TRUE(contains(issues[2].message, "Fx_N = 'x' is not a number")) << issues[2].message;
    EXPECT_EQ(issues[3].where, "t.csv:4");
    EXPECT_TRUE(contains(issues[3].message, "slip_angle_deg = 90 is outside")) << issues[3].message;
    EXPECT_EQ(issues[4].where, "t.csv:5");
    EXPECT_TRUE(contains(issues[4].message, "no channel measured"));
    EXPECT_EQ(issues[5].where, "t.csv:6");
    EXPECT_TRUE(contains(issues[5].message, "load_N is empty"));
    EXPECT_EQ(issues[6].where, "t.csv:7");
    EXPECT_TRUE(contains(issues[6].message, "4 cells, the header has 5"));
}

TEST(ExperimentCsv, UnknownAndMissingColumnsAreNamed) {
    Result<Experiment> r = parseExperimentCsv("load_N,slip,Fx\n80,0,1\n", "t.csv");
    ASSERT_FALSE(r.ok());
    EXPECT_TRUE(contains(r.message(), "unknown column 'Fx'")) << r.message();
    EXPECT_TRUE(contains(r.message(), "did you mean Fx_N?")) << r.message();
    r = parseExperimentCsv("slip,Fx_N\n0,1\n", "t.csv");
    ASSERT_FALSE(r.ok());
    EXPECT_TRUE(contains(r.message(), "missing column load_N")) << r.message();
    r = parseExperimentCsv("load_N,slip\n80,0\n", "t.csv");
    ASSERT_FALSE(r.ok());
    EXPECT_TRUE(contains(r.message(), "no measured channel")) << r.message();
    r = parseExperimentCsv("load_N,slip,Fx_N\n", "t.csv");
    ASSERT_FALSE(r.ok());
    EXPECT_TRUE(contains(r.message(), "no measured points")) << r.message();
    r = parseExperimentCsv("load_N,slip,Fx_N,Fx_N\n80,0,1,1\n", "t.csv");
    EXPECT_FALSE(r.ok());  // a column twice: which would count?
}

TEST(ExperimentMetadata, ReadsStrictlyAndNamesTheField) {
    const std::string good = R"({
        "format": "terrastudio-experiment", "format_version": 1, "test": "t",
        "data_file": "t.csv",
        "wheel": {"name": "w", "r_m": 0.15, "b_m": 0.1, "grouser_height_m": 0.01,
                  "grouser_count": 12},
        "soil": {"preset": "hit-lss1", "parameters": {"n": 1.1, "phi_deg": 31.9}},
        "citation": {"authors": ["A. Author", "B. Author"], "title": "T", "journal": "J",
                     "volume": "48", "issue": "1", "pages": "27-45", "year": 2011, "doi": "10/x"},
        "channels": {"Fx_N": {"origin": "Fig. 9", "kind": "digitised", "uncertainty": "1 N"}}
    })";
    const Result<ExperimentMetadata> m = parseExperimentMetadata(good, "t.json");
    ASSERT_TRUE(m.ok()) << m.message();
    EXPECT_EQ(m->soil_preset, "hit-lss1");
    ASSERT_TRUE(m->wheel.has_value());
    EXPECT_EQ(m->wheel->grouser_count, 12.0);
    EXPECT_TRUE(m->wheel->lugged());
    EXPECT_EQ(m->citation, "A. Author, B. Author, T, J 48(1):27-45 (2011), doi:10/x");

    const std::string bad = R"({
        "format": "terrastudio-experiment", "format_version": 2, "tset": "t",
        "soil": {"parameters": {"phi_deg": 75}},
        "channels": {"Fx_N": {"kind": 3}}
    })";
    const Result<ExperimentMetadata> b = parseExperimentMetadata(bad, "t.json");
    ASSERT_FALSE(b.ok());
    const std::string msg = b.message();
    EXPECT_TRUE(contains(msg, "t.json: format_version")) << msg;
    EXPECT_TRUE(contains(msg, "t.json: soil.parameters.phi_deg: 75 is outside")) << msg;
    EXPECT_TRUE(contains(msg, "t.json: channels.Fx_N.kind")) << msg;
    EXPECT_TRUE(contains(msg, "t.json: tset")) << msg;
    EXPECT_TRUE(contains(msg, "did you mean \"test\"")) << msg;
}

// A number no double holds, in a metadata file: its position, key and the field's range.
TEST(Experiment, MetadataNumberBeyondADoubleNamesItsRange) {
    const std::string text =
        "{\"format\": \"terrastudio-experiment\", \"format_version\": 1,\n"
        " \"soil\": {\"parameters\": {\"phi_deg\": 1e999}}}";
    const Result<ExperimentMetadata> m = parseExperimentMetadata(text, "t.json");
    ASSERT_FALSE(m.ok());
    ASSERT_EQ(m.issues().size(), 1u) << m.message();
    EXPECT_EQ(m.issues()[0].where, "t.json:2:37");
    EXPECT_EQ(m.issues()[0].message,
              "soil.parameters.phi_deg: 1e999 is too large for a number (beyond ±1.8e308); "
              "allowed range [0, 60) deg");
}

TEST(Experiment, ReadFromTheCsvOrTheSidecarAndTheShippedDingTest) {
    const fs::path ding =
        fs::path(TERRA_RESOURCE_DIR) / "experiments" / "ding2011-smooth-hit-lss1-80N.csv";
    const Result<Experiment> a = readExperiment(ding);
    ASSERT_TRUE(a.ok()) << a.message();
    ASSERT_EQ(a->points.size(), 6u);
    ASSERT_TRUE(a->metadata.has_value());
    EXPECT_EQ(a->metadata->soil_preset, "hit-lss1");
    ASSERT_TRUE(a->metadata->wheel.has_value());
    EXPECT_EQ(a->metadata->wheel->radius_m, 0.15735);
    EXPECT_FALSE(a->metadata->wheel->lugged());
    EXPECT_EQ(a->points.back().measured[kExpSinkage], 0.0175);
    const Result<Experiment> b = readExperiment(fs::path(ding).replace_extension(".json"));
    ASSERT_TRUE(b.ok()) << b.message();
    EXPECT_EQ(b->points.size(), 6u);

    testing::TempDir dir;
    std::ofstream(dir.path() / "x.csv") << "load_N,slip,Fx_N\n80,0,1\n";
    std::ofstream(dir.path() / "x.json") << R"({"format": "terrastudio-experiment"})";
    const Result<Experiment> c = readExperiment(dir.path() / "x.csv");
    ASSERT_FALSE(c.ok());  // the sidecar is read strictly too
    EXPECT_TRUE(contains(c.message(), "x.json: format_version")) << c.message();
    EXPECT_FALSE(readExperiment(dir.path() / "none.csv").ok());
}

TEST(WheelGrousers, OptionalFieldsWithRangesAndRules) {
    Result<wheel::WheelParameters> w =
        wheelFromJson(nlohmann::json{{"name", "w"}, {"r_m", 0.1}, {"b_m", 0.1}}, "w.json");
    ASSERT_TRUE(w.ok());
    EXPECT_FALSE(w->lugged());
    EXPECT_EQ(w->grouser_height_m, 0.0);
    EXPECT_FALSE(toJson(w.value()).contains("grouser_count"));  // smooth: nothing written

    w = wheelFromJson(nlohmann::json{{"name", "w"},
                                     {"r_m", 0.1},
                                     {"b_m", 0.1},
                                     {"grouser_height_m", 0.005},
                                     {"grouser_count", 18},
                                     {"grouser_thickness_m", 0.002}},
                      "w.json");
    ASSERT_TRUE(w.ok()) << w.message();
    EXPECT_TRUE(w->lugged());
    const nlohmann::json back = toJson(w.value());
    EXPECT_EQ(back.at("grouser_count").get<double>(), 18.0);
    EXPECT_EQ(wheelFromJson(back, "").value().grouser_thickness_m, 0.002);

    w = wheelFromJson(nlohmann::json{{"name", "w"},
                                     {"r_m", 0.1},
                                     {"b_m", 0.1},
                                     {"grouser_height_m", 5},
                                     {"grouser_count", 2.5}},
                      "w.json");
    ASSERT_FALSE(w.ok());
    EXPECT_TRUE(contains(w.message(), "w.json: grouser_height_m: 5 is outside the allowed range"))
        << w.message();
    w = wheelFromJson(nlohmann::json{{"name", "w"},
                                     {"r_m", 0.1},
                                     {"b_m", 0.1},
                                     {"grouser_height_m", 0.2},
                                     {"grouser_count", 2.5}},
                      "w.json");
    ASSERT_FALSE(w.ok());
    EXPECT_TRUE(contains(w.message(), "w.json: grouser_count: 2.5 is not a whole number"))
        << w.message();
    w = wheelFromJson(nlohmann::json{{"name", "w"},
                                     {"r_m", 0.1},
                                     {"b_m", 0.1},
                                     {"grouser_height_m", 0.2},
                                     {"grouser_count", 2}},
                      "w.json");
    ASSERT_FALSE(w.ok());
    EXPECT_TRUE(contains(w.message(), "grouser_height_m: 0.2 m is not below the radius"))
        << w.message();
}

}  // namespace
}  // namespace terra::io
