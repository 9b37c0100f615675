// Issue 27: a project's results saved beside it (core/project/results.h) read back to the same
// numbers, with a hash that changes exactly when the inputs do.
#include "core/project/results.h"

#include <gtest/gtest.h>

#include "core/io/atomic_file.h"
#include "core/io/table_json.h"
#include "core/project/project.h"
#include "tests/core/test_temp_dir.h"

namespace terra::project {
namespace {

using nlohmann::json;

const io::PresetLocations kLocations{{TERRA_RESOURCE_DIR}};

analysis::Inputs sandyLoam() {
    return {io::resolveSoil(kLocations, "sandy-loam").value(),
            io::resolveWheel(kLocations, "A").value(),
            {}};
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

TEST(SavedResults, BrokenOrForeignSidecarsAreReportedNotShown) {
    EXPECT_FALSE(savedResultsFromJson(json{{"format", "terrastudio-project"}}, "x").ok());
    EXPECT_FALSE(savedResultsFromJson(json{{"format", kResultsFormat}, {"version", 99}}, "x").ok());
    const Result<SavedResults> broken = savedResultsFromJson(
        json{{"format", kResultsFormat}, {"version", 1}, {"panels", {{"rover", {{"x", 1}}}}}},
        "p.terra.results");
    ASSERT_FALSE(broken.ok());
    EXPECT_NE(broken.message().find("panels.rover"), std::string::npos) << broken.message();
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
        analysis::computeGlobalSensitivity(sandyLoam(), s);
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
