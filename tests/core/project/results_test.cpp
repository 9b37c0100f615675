// Issue 27: a project's results saved beside it (core/project/results.h) read back to the same
// numbers, with a hash that changes exactly when the inputs do.
#include "core/project/results.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/io/atomic_file.h"
#include "core/io/table_json.h"
#include "core/project/project.h"
#include "core/project/result_json.h"
#include "tests/core/test_support.h"
#include "tests/core/test_temp_dir.h"

namespace terra::project {
namespace {

using nlohmann::json;

using terra::testing::kLocations;

using terra::testing::sandyLoamOnA;

// A data file is known by its bytes: the same bytes elsewhere are the same inputs, one byte
// changed is not, a missing file and no file are each their own stamp.
TEST(SavedResults, AFileStampIsItsContentNotItsPath) {
    const testing::TempDir dir;
    const std::string text = "slip,Fx_N\n0.1,3.25\n0.2,5.5\n";
    ASSERT_FALSE(io::writeFileAtomically(dir.path() / "a.csv", text));
    std::filesystem::create_directories(dir.path() / "moved");
    ASSERT_FALSE(io::writeFileAtomically(dir.path() / "moved" / "b.csv", text));
    ASSERT_FALSE(io::writeFileAtomically(dir.path() / "c.csv", "slip,Fx_N\n0.1,3.25\n0.2,5.6\n"));
    EXPECT_EQ(fileStamp(dir.path() / "a.csv"), fileStamp(dir.path() / "moved" / "b.csv"));
    EXPECT_NE(fileStamp(dir.path() / "a.csv"), fileStamp(dir.path() / "c.csv"));
    EXPECT_EQ(fileStamp(dir.path() / "none.csv"), "missing");
    EXPECT_TRUE(fileStamp("").is_null());
    // FNV-1a of the bytes, as inputsHash of a JSON text: the empty file's is the offset basis.
    ASSERT_FALSE(io::writeFileAtomically(dir.path() / "empty.csv", ""));
    EXPECT_EQ(fileStamp(dir.path() / "empty.csv"), "cbf29ce484222325");
}

TEST(SavedResults, TheInputsHashIsStableAndChangesWithTheInputs) {
    const json inputs{{"soil", {{"phi_deg", 30.0}}}, {"samples", 1024}};
    EXPECT_EQ(inputsHash(inputs), inputsHash(json::parse(inputs.dump())));
    EXPECT_EQ(inputsHash(inputs).size(), 16u);
    json other = inputs;
    other["soil"]["phi_deg"] = 30.5;
    EXPECT_NE(inputsHash(inputs), inputsHash(other));
    EXPECT_EQ(resultsPathFor("/a/field/p.terra"),
              std::filesystem::path("/a/field/p.terra.results"));
}

TEST(SavedResults, WhatIsWrittenReadsBackTheSame) {
    SavedResults results;
    SavedResult& r = results.panels["global-sensitivity"];
    r.inputs_hash = "0123456789abcdef";
    r.partial = true;
    r.summary = "512 model evaluations";
    r.result = json{{"method", "sobol"}};
    Table t;
    t.columns = {"slip", "Fx_N"};
    t.rows = {{0.1, 12.5}, {0.3, std::numeric_limits<double>::quiet_NaN()}};
    t.label_column = "point";
    t.labels = {"a", "b"};
    r.tables.push_back({"indices", std::nullopt, t});

    const testing::TempDir dir;
    const std::filesystem::path path = dir.path() / "p.terra.results";
    ASSERT_FALSE(saveResults(path, results));
    const Result<SavedResults> read = loadResults(path);
    ASSERT_TRUE(read.ok()) << read.message();
    const SavedResult& back = read->panels.at("global-sensitivity");
    EXPECT_EQ(back.inputs_hash, r.inputs_hash);
    EXPECT_TRUE(back.partial);
    EXPECT_EQ(back.summary, r.summary);
    EXPECT_EQ(back.result, r.result);
    ASSERT_EQ(back.tables.size(), 1u);
    EXPECT_EQ(back.tables[0].table.columns, t.columns);
    EXPECT_EQ(back.tables[0].table.labels, t.labels);
    EXPECT_DOUBLE_EQ(back.tables[0].table.rows[0][1], 12.5);
    EXPECT_TRUE(std::isnan(back.tables[0].table.rows[1][1]));  // null in the file
    // No temporary file is left beside it.
    EXPECT_FALSE(std::filesystem::exists(io::temporaryPathFor(path)));
    // No results: the sidecar goes, so old results are never shown for new inputs.
    ASSERT_FALSE(saveResults(path, SavedResults{}));
    EXPECT_FALSE(std::filesystem::exists(path));
}

TEST(SavedResults, ForeignOrNewerSidecarsAreRefusedWithTheReason) {
    EXPECT_FALSE(savedResultsFromJson(json{{"format", "terrastudio-project"}}, "x").ok());
    const Result<SavedResults> newer =
        savedResultsFromJson(json{{"format", kResultsFormat}, {"version", 99}}, "p.terra.results");
    ASSERT_FALSE(newer.ok());
    EXPECT_NE(newer.message().find("p.terra.results: version"), std::string::npos)
        << newer.message();
    EXPECT_NE(newer.message().find("99"), std::string::npos) << newer.message();
    EXPECT_FALSE(
        savedResultsFromJson(json{{"format", kResultsFormat}, {"version", "2"}}, "x").ok());
}

// A damaged section costs that section only: the others read, the damaged one is named.
TEST(SavedResults, ABrokenSectionIsListedAndTheOthersRead) {
    SavedResults results;
    SavedResult& good = results.panels["identification"];
    good.inputs_hash = "00000000000000aa";
    good.version = 3;
    good.summary = "20 samples";
    good.result = json{{"x", 1.5}};
    json document = toJson(results);
    document["panels"]["rover"] = {{"inputs_hash", "1"}, {"partial", "no"}};
    const Result<SavedResults> read = savedResultsFromJson(document, "p.terra.results");
    ASSERT_TRUE(read.ok()) << read.message();
    ASSERT_EQ(read->panels.size(), 1u);
    EXPECT_EQ(read->panels.at("identification"), good);
    ASSERT_EQ(read->unreadable.size(), 1u);
    EXPECT_EQ(read->unreadable[0].where, "p.terra.results: panels.rover");
}

// A file cut short by a crash elsewhere (not by the atomic save) is refused with its position.
TEST(SavedResults, ACorruptFileIsRefusedWithItsLine) {
    SavedResults results;
    results.panels["rover"].result = json{{"series", std::vector<double>(50, 1.25)}};
    const testing::TempDir dir;
    const std::filesystem::path path = dir.path() / "p.terra.results";
    ASSERT_FALSE(saveResults(path, results));
    std::string text;
    ASSERT_FALSE(io::readFile(path, text));
    ASSERT_FALSE(io::writeFileAtomically(path, text.substr(0, text.size() / 2)));
    const Result<SavedResults> read = loadResults(path);
    ASSERT_FALSE(read.ok());
    EXPECT_NE(read.message().find("p.terra.results:1"), std::string::npos) << read.message();
}

// Version 1 (the global study alone, no section versions) reads as version 2.
TEST(SavedResults, AVersionOneFileStillReads) {
    const json v1{{"format", kResultsFormat},
                  {"version", 1},
                  {"panels",
                   {{"global-sensitivity",
                     {{"inputs_hash", "0123456789abcdef"},
                      {"partial", false},
                      {"summary", "512 model evaluations"},
                      {"result", {{"method", "sobol"}}},
                      {"tables", json::array()}}}}}};
    const Result<SavedResults> read = savedResultsFromJson(v1, "old.terra.results");
    ASSERT_TRUE(read.ok()) << read.message();
    EXPECT_EQ(read->panels.at("global-sensitivity").version, kGlobalSensitivityVersion);
    EXPECT_TRUE(read->unreadable.empty());
}

TEST(SavedResults, NumbersKeepTheirInfinitiesAndStrangersAreRefused) {
    EXPECT_EQ(saved::number(std::numeric_limits<double>::infinity()), "inf");
    EXPECT_EQ(saved::numberOf(json("-inf")), -std::numeric_limits<double>::infinity());
    EXPECT_TRUE(std::isnan(saved::numberOf(json(nullptr))));
    EXPECT_EQ(saved::numberOf(json(2.5)), 2.5);
    EXPECT_THROW(saved::numberOf(json("nan")), std::invalid_argument);
    EXPECT_THROW(saved::numberOf(json(true)), std::invalid_argument);
    std::array<double, 3> three{};
    using Three = saved::Value<std::array<double, 3>>;
    EXPECT_THROW(Three::read(json{1.0, 2.0}, three), std::invalid_argument);
}

TEST(UncertaintyBandsRoundTrip, ReadsBackToTheSameBands) {
    analysis::UncertaintyBandSettings s;
    s.samples = 32;
    s.slip_count = 4;
    s.study.outputs = {"Fx_N", "sinkage_m"};
    s.study.threads = 1;
    const analysis::UncertaintyBandResult computed =
        analysis::computeUncertaintyBands(sandyLoamOnA(), s);
    ASSERT_TRUE(computed.bands.usable());
    const json saved = savedJson(computed);
    const Result<analysis::UncertaintyBandResult> read =
        uncertaintyBandsFromJson(json::parse(saved.dump()), "bands");
    ASSERT_TRUE(read.ok()) << read.message();
    // The same table (every percentile, mean, sample count and nominal value).
    EXPECT_EQ(io::toJson(read->table()), io::toJson(computed.table()));
    EXPECT_EQ(read->nominal, computed.nominal);
    EXPECT_EQ(read->bands.used, computed.bands.used);
    EXPECT_EQ(savedJson(*read), saved);
    // Bands that do not fit the grid are refused.
    json bad = saved;
    bad["percentiles"] = {50.0};
    EXPECT_FALSE(uncertaintyBandsFromJson(bad, "bands").ok());
}

class GlobalStudyRoundTrip : public ::testing::TestWithParam<analysis::GsaMethod> {};

TEST_P(GlobalStudyRoundTrip, ReadsBackToTheSameIndices) {
    analysis::GlobalSensitivitySettings s;
    s.method = GetParam();
    s.samples = GetParam() == analysis::GsaMethod::kSobol ? 64 : 8;
    s.resamples = 50;
    s.study.slips = {0.1, 0.4};
    s.study.outputs = {"Fx_N", "sinkage_m"};
    s.study.threads = 1;
    const analysis::GlobalSensitivityResult computed =
        analysis::computeGlobalSensitivity(sandyLoamOnA(), s);
    const json saved = savedJson(computed);
    const Result<analysis::GlobalSensitivityResult> read =
        globalSensitivityResultFromJson(json::parse(saved.dump()), "result");
    ASSERT_TRUE(read.ok()) << read.message();
    // The same table (every index, interval and sample count) and the same JSON report.
    EXPECT_EQ(io::toJson(read->table()), io::toJson(computed.table()));
    EXPECT_EQ(read->toJson(), computed.toJson());
    EXPECT_EQ(read->grid().load_n, computed.grid().load_n);
    // A matrix that does not fit the grid is refused.
    json bad = saved;
    bad["outputs"] = {"Fx_N"};
    EXPECT_FALSE(globalSensitivityResultFromJson(bad, "result").ok());
}

INSTANTIATE_TEST_SUITE_P(Methods, GlobalStudyRoundTrip,
                         ::testing::Values(analysis::GsaMethod::kSobol,
                                           analysis::GsaMethod::kMorris));

}  // namespace
}  // namespace terra::project
