// Issue 27, item 2: the quick panels' results saved with a project (core/project/
// saved_analyses.h) read back to the same numbers — the tables compared cell by cell through the
// analyses' own outcome tables (the command line's writer of each result), the scalars one by
// one; NaN and the infinities kept as such; a damaged section refused with the key it breaks.
#include "core/project/saved_analyses.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/io/experiment.h"
#include "tests/core/test_support.h"

namespace terra::project {
namespace {

using nlohmann::json;
using terra::testing::contains;
using terra::testing::kExact;
using terra::testing::kLocations;
using terra::testing::sandyLoamOnA;

/// Equal to 1e-12 relative (NaN equal to NaN, an infinity to the same infinity).
bool sameSavedNumber(double a, double b) {
    if (std::isnan(a) || std::isnan(b)) return std::isnan(a) && std::isnan(b);
    if (std::isinf(a) || std::isinf(b)) return a == b;
    return std::abs(a - b) <= kExact * std::max(1.0, std::max(std::abs(a), std::abs(b)));
}

void expectSameSavedTable(const Table& read, const Table& computed, const std::string& what) {
    EXPECT_EQ(read.columns, computed.columns) << what;
    EXPECT_EQ(read.labels, computed.labels) << what;
    ASSERT_EQ(read.rows.size(), computed.rows.size()) << what;
    for (std::size_t r = 0; r < read.rows.size(); ++r) {
        ASSERT_EQ(read.rows[r].size(), computed.rows[r].size()) << what;
        for (std::size_t c = 0; c < read.rows[r].size(); ++c)
            EXPECT_TRUE(sameSavedNumber(read.rows[r][c], computed.rows[r][c]))
                << what << " row " << r << " " << computed.columns[c] << ": " << read.rows[r][c]
                << " read, " << computed.rows[r][c] << " computed";
    }
}

/// Every table of two outcomes (the analyses' own writers of their results).
void expectSameOutcomeTables(const analysis::Outcome& read, const analysis::Outcome& computed) {
    ASSERT_EQ(read.tables.size(), computed.tables.size());
    for (std::size_t i = 0; i < read.tables.size(); ++i)
        expectSameSavedTable(read.tables[i].table, computed.tables[i].table,
                             computed.tables[i].name);
    EXPECT_EQ(read.notes, computed.notes);
}

/// Through text, as the results file holds it.
json throughText(const json& j) { return json::parse(j.dump()); }

TEST(SavedAnalyses, StressesReadBackToTheSameNumbers) {
    analysis::StressSettings settings;
    settings.slip = 0.3;
    settings.slip_angle_deg = 10.0;
    const analysis::StressResult computed = analysis::computeStresses(sandyLoamOnA(), settings);
    ASSERT_GT(computed.table.rows.size(), 10u);
    const Result<analysis::StressResult> read =
        stressResultFromJson(throughText(savedJson(computed)), "stresses");
    ASSERT_TRUE(read.ok()) << read.message();
    expectSameOutcomeTables(analysis::stressOutcome(*read), analysis::stressOutcome(computed));
    for (std::size_t i = 0; i < 4; ++i) {
        EXPECT_TRUE(sameSavedNumber(read->errors[i].rmse, computed.errors[i].rmse));
        EXPECT_TRUE(sameSavedNumber(read->errors[i].mae, computed.errors[i].mae));
    }
    EXPECT_TRUE(sameSavedNumber(read->entry_angle_deg, computed.entry_angle_deg));
    EXPECT_TRUE(sameSavedNumber(read->max_stress_angle_deg, computed.max_stress_angle_deg));
    EXPECT_EQ(read->message, computed.message);
}

TEST(SavedAnalyses, NaNAndInfinitiesAreKeptAndOtherTextIsRefused) {
    analysis::StressResult r;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    r.table.columns = {"a", "b", "c"};
    r.table.rows = {{nan, inf, -inf}, {1.0 / 3.0, -2.5e-300, 6.02e23}};
    r.entry_angle_deg = nan;
    r.max_stress_angle_deg = -inf;
    r.message = "no equilibrium";
    const json saved = throughText(savedJson(r));
    EXPECT_TRUE(saved["entry_angle_deg"].is_null());
    EXPECT_EQ(saved["max_stress_angle_deg"], "-inf");
    const Result<analysis::StressResult> read = stressResultFromJson(saved, "stresses");
    ASSERT_TRUE(read.ok()) << read.message();
    expectSameSavedTable(read->table, r.table, "table");
    EXPECT_TRUE(std::isnan(read->entry_angle_deg));
    EXPECT_EQ(read->max_stress_angle_deg, -inf);
    // Exact, not only to 1e-12: JSON's shortest round-trip form.
    EXPECT_EQ(read->table.rows[1][0], 1.0 / 3.0);
    EXPECT_EQ(read->table.rows[1][1], -2.5e-300);

    json damaged = saved;
    damaged["errors"][2]["mae"] = "NaN";  // only null, "inf" and "-inf" stand for non-numbers
    Result<analysis::StressResult> refused = stressResultFromJson(damaged, "stresses");
    ASSERT_FALSE(refused.ok());
    EXPECT_TRUE(contains(refused.message(), "stresses")) << refused.message();
    EXPECT_TRUE(contains(refused.message(), "errors: mae: \"NaN\" is not a number"))
        << refused.message();
    damaged = saved;
    damaged.erase("table");
    refused = stressResultFromJson(damaged, "stresses");
    ASSERT_FALSE(refused.ok());
    EXPECT_TRUE(contains(refused.message(), "table")) << refused.message();
    damaged = saved;
    damaged["errors"].erase(3);  // four stresses, always
    EXPECT_FALSE(stressResultFromJson(damaged, "stresses").ok());
}

TEST(SavedAnalyses, CompactionReadsBackToTheSamePassesEnvelopeAndMap) {
    analysis::CompactionSettings settings;
    settings.passes = 3;
    settings.profile = io::resolveProfile(kLocations, "loam-moist").value();
    settings.map_x_points = 12;
    settings.map_z_points = 8;
    settings.map_pass = 2;
    const analysis::CompactionResult computed =
        analysis::computeCompaction(sandyLoamOnA(), settings);
    ASSERT_EQ(computed.passes.size(), 3u);
    ASSERT_TRUE(computed.profile.has_value());
    ASSERT_FALSE(computed.map.rows.empty());
    const Result<analysis::CompactionResult> read =
        compactionResultFromJson(throughText(savedJson(computed)), "compaction");
    ASSERT_TRUE(read.ok()) << read.message();
    expectSameOutcomeTables(analysis::compactionOutcome(*read),
                            analysis::compactionOutcome(computed));
    expectSameSavedTable(read->map, computed.map, "map");
    for (std::size_t p = 0; p < computed.passes.size(); ++p) {
        const analysis::CompactionPass& a = read->passes[p];
        const analysis::CompactionPass& b = computed.passes[p];
        EXPECT_EQ(a.pass, b.pass);
        for (const auto& [x, y] : {std::pair{a.forces.fx, b.forces.fx},
                                   {a.forces.fs, b.forces.fs},
                                   {a.forces.my, b.forces.my},
                                   {a.rut_depth_m, b.rut_depth_m},
                                   {a.sinkage_increment_m, b.sinkage_increment_m}})
            EXPECT_TRUE(sameSavedNumber(x, y)) << x << " " << y;
        ASSERT_EQ(a.bulk_density_kg_m3.size(), b.bulk_density_kg_m3.size());
        for (std::size_t l = 0; l < a.bulk_density_kg_m3.size(); ++l)
            EXPECT_TRUE(sameSavedNumber(a.bulk_density_kg_m3[l], b.bulk_density_kg_m3[l]));
        ASSERT_EQ(a.profile.size(), b.profile.size());
        for (std::size_t d = 0; d < a.profile.size(); ++d) {
            EXPECT_EQ(a.profile[d].risk, b.profile[d].risk);
            EXPECT_TRUE(sameSavedNumber(a.profile[d].max.major, b.profile[d].max.major));
        }
    }
    EXPECT_EQ(read->red_to_depth_m, computed.red_to_depth_m);
    ASSERT_EQ(read->profile->layers.size(), computed.profile->layers.size());
    for (std::size_t l = 0; l < computed.profile->layers.size(); ++l)
        EXPECT_TRUE(sameSavedNumber(read->profile->layers[l].bulk_density_kg_m3,
                                    computed.profile->layers[l].bulk_density_kg_m3));
    EXPECT_EQ(read->cancelled, computed.cancelled);
    EXPECT_EQ(read->notes, computed.notes);

    // A risk this studio does not know, a pass of another depth grid: refused, named.
    json damaged = throughText(savedJson(computed));
    damaged["passes"][1]["profile"][0]["risk"] = 7;
    Result<analysis::CompactionResult> refused = compactionResultFromJson(damaged, "compaction");
    ASSERT_FALSE(refused.ok());
    EXPECT_TRUE(contains(refused.message(), "passes: 1: profile: 0: risk: 7 is not a known value"))
        << refused.message();
    damaged = throughText(savedJson(computed));
    damaged["passes"][2]["profile"].erase(0);
    refused = compactionResultFromJson(damaged, "compaction");
    ASSERT_FALSE(refused.ok());
    EXPECT_TRUE(contains(refused.message(), "pass 3 does not match")) << refused.message();
}

TEST(SavedAnalyses, SensitivityReadsBackToTheSameFamilyAndTornado) {
    analysis::SensitivitySettings settings;
    settings.parameter = "n";
    const analysis::SensitivityResult computed =
        analysis::computeSensitivity(sandyLoamOnA(), settings);
    ASSERT_FALSE(computed.tornado.rows.empty());
    const Result<analysis::SensitivityResult> read =
        sensitivityResultFromJson(throughText(savedJson(computed)), "sensitivity");
    ASSERT_TRUE(read.ok()) << read.message();
    expectSameOutcomeTables(analysis::sensitivityOutcome(*read),
                            analysis::sensitivityOutcome(computed));
    EXPECT_EQ(read->parameter_keys, computed.parameter_keys);
    EXPECT_EQ(read->tornado_keys, computed.tornado_keys);
    EXPECT_EQ(read->family.warnings, computed.family.warnings);
}

TEST(SavedAnalyses, ForcesReadBackWithTheirSoilCurvesAndTest) {
    analysis::Inputs inputs;
    inputs.soil = io::resolveSoil(kLocations, "hit-lss1").value();
    inputs.wheel = io::resolveWheel(kLocations, "ding2011-smooth").value();
    SavedForces computed;
    computed.sweep = analysis::computeForceSweep(inputs);
    computed.soil = analysis::computeSoilCurves(inputs);
    analysis::ValidationSettings settings;
    settings.experiments = TERRA_RESOURCE_DIR "/experiments/ding2011-smooth-hit-lss1-80N.csv";
    settings.data = io::readExperiment(settings.experiments).value();
    settings.curves = false;
    computed.validation = analysis::computeValidation(inputs, settings);
    analysis::Inputs at_test = inputs;
    at_test.conditions.load_n = 80.0;
    computed.test_sweeps.push_back({80.0, analysis::computeForceSweep(at_test).table});
    // The static-sinkage curve has points without equilibrium (NaN) at the largest loads.
    bool has_nan = false;
    for (const auto& row : computed.soil.static_sinkage.rows)
        for (double v : row) has_nan = has_nan || std::isnan(v);

    const Result<SavedForces> read =
        savedForcesFromJson(throughText(savedJson(computed)), "forces");
    ASSERT_TRUE(read.ok()) << read.message();
    expectSameOutcomeTables(analysis::forcesOutcome(read->sweep),
                            analysis::forcesOutcome(computed.sweep));
    expectSameOutcomeTables(analysis::soilCurvesOutcome(read->soil),
                            analysis::soilCurvesOutcome(computed.soil));
    EXPECT_TRUE(sameSavedNumber(read->soil.load_n, computed.soil.load_n));
    ASSERT_TRUE(read->validation.has_value());
    EXPECT_EQ(analysis::toJson(*read->validation), analysis::toJson(*computed.validation));
    ASSERT_EQ(read->test_sweeps.size(), 1u);
    EXPECT_EQ(read->test_sweeps[0].load_n, 80.0);
    expectSameSavedTable(read->test_sweeps[0].table, computed.test_sweeps[0].table, "test sweep");
    if (has_nan) {
        const json saved = savedJson(computed);
        EXPECT_TRUE(contains(saved["soil"]["static_sinkage"].dump(), "null"));
    }

    // Without a test: no validation, no sweeps at the test's loads.
    SavedForces plain = computed;
    plain.validation.reset();
    plain.test_sweeps.clear();
    const Result<SavedForces> read_plain = savedForcesFromJson(savedJson(plain), "forces");
    ASSERT_TRUE(read_plain.ok()) << read_plain.message();
    EXPECT_FALSE(read_plain->validation.has_value());
    EXPECT_TRUE(read_plain->test_sweeps.empty());
}

}  // namespace
}  // namespace terra::project
