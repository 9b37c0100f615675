// The compaction analysis (core/analysis/compaction.h) against its parts: pass 1 is the
// single-wheel model exactly; the envelope is the largest of the passes' profiles; the studies'
// compaction outputs (core/gsa/wheel_target.h) are the analysis's numbers for the same soil; the
// summary a person reads against the JSON, and the status of a failed or cancelled run.
#include "core/analysis/compaction.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>

#include "core/analysis/operating_point.h"
#include "core/common/units.h"
#include "core/gsa/wheel_target.h"
#include "core/io/parameters_json.h"
#include "tests/core/test_support.h"

namespace terra::analysis {
namespace {

const io::PresetLocations& locations() {
    static const io::PresetLocations l{{TERRA_RESOURCE_DIR}};
    return l;
}

Inputs heavyWheel() {
    Inputs in;
    in.soil = io::resolveSoil(locations(), "sandy-loam").value();
    in.wheel = io::resolveWheel(locations(), "B").value();
    in.conditions.load_n = 800.0;
    return in;
}

CompactionSettings clayWet(int passes) {
    CompactionSettings s;
    s.slip = 0.2;
    s.passes = passes;
    s.profile = io::resolveProfile(locations(), "clay-wet").value();
    return s;
}

TEST(CompactionAnalysis, PassOneIsTheWheelCommand) {
    const Inputs in = heavyWheel();
    const CompactionResult r = computeCompaction(in, clayWet(1));
    PointSpec spec;
    spec.slip = 0.2;
    spec.load_n = 800.0;
    const PointResult point = evaluatePoint(in.contact(), spec);
    ASSERT_EQ(r.passes.size(), 1u);
    EXPECT_EQ(r.passes[0].forces.fx, point.forces.fx);
    EXPECT_EQ(r.passes[0].forces.my, point.forces.my);
    EXPECT_EQ(r.passes[0].sinkage_m, point.sinkage_m);
    EXPECT_EQ(r.passes[0].entry_angle_deg, point.entry_angle_deg);
}

TEST(CompactionAnalysis, TheEnvelopeIsTheLargestOfThePasses) {
    const CompactionResult r = computeCompaction(heavyWheel(), clayWet(3));
    ASSERT_EQ(r.passes.size(), 3u);
    for (std::size_t d = 0; d < r.envelope.size(); ++d) {
        double largest = 0.0;
        for (const CompactionPass& p : r.passes) {
            for (const DepthValues& v : p.profile)
                if (v.depth_m == r.envelope[d].depth_m) largest = std::max(largest, v.max.sigma_z);
        }
        EXPECT_EQ(r.envelope[d].max.sigma_z, largest) << r.envelope[d].depth_m;
    }
    // The rut deepens and the increments fall (Wong's reload law).
    EXPECT_LT(r.passes[0].rut_depth_m, r.passes[1].rut_depth_m);
    EXPECT_LT(r.passes[2].sinkage_increment_m, r.passes[1].sinkage_increment_m);
    EXPECT_LT(r.passes[1].sinkage_increment_m, r.passes[0].sinkage_increment_m);
    // The red topsoil compacts: its density grows, the subsoil's does not.
    EXPECT_GT(r.passes[0].bulk_density_kg_m3[0], 1250.0);
    EXPECT_EQ(r.passes[2].bulk_density_kg_m3[2], 1450.0);
    ASSERT_TRUE(r.red_to_depth_m);
    EXPECT_GT(*r.red_to_depth_m, 0.1);
}

TEST(CompactionAnalysis, StudyOutputsAreTheAnalysissNumbers) {
    const Inputs in = heavyWheel();
    gsa::WheelStudy study;
    study.soil = in.soil;
    study.wheel = in.wheel;
    study.grid.slips = {0.2};
    study.grid.load_n = 800.0;
    study.outputs = {gsa::Output::kRutDepth, gsa::Output::kRedDepth, gsa::Output::kMaxSigmaZ};
    study.parameters.add("n", gsa::Uniform{0.5, 1.0});
    study.compaction.passes = 2;
    study.compaction.depth_m = 0.3;
    study.compaction.profile = io::resolveProfile(locations(), "clay-wet").value();
    const gsa::WheelTarget target(study);
    Eigen::MatrixXd rows(2, 1);
    rows << 0.6, 0.9;
    const gsa::TargetValues values = target.evaluate(rows);
    for (Eigen::Index i = 0; i < rows.rows(); ++i) {
        Inputs sample = in;
        sample.soil.sinkage_exponent = rows(i, 0);
        CompactionSettings s = clayWet(2);
        s.depths_m = {0.1, 0.15, 0.2, 0.25, 0.3, 0.35, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0, 1.2};
        const CompactionResult r = computeCompaction(sample, s);
        EXPECT_EQ(values.values(i, 0), r.passes.back().rut_depth_m) << i;
        EXPECT_NEAR(values.values(i, 1), *r.red_to_depth_m, 1e-4) << i;
        double at_03 = 0.0;
        for (const DepthValues& v : r.envelope)
            if (v.depth_m == 0.3) at_03 = v.max.sigma_z / 1e3;
        EXPECT_NEAR(values.values(i, 2), at_03, 1e-6 * at_03) << i;
    }
}

// The summary row whose value sits at `pointer` in the JSON, or nullptr.
const SummaryRow* compactionRowAt(const Summary& summary, const std::string& pointer) {
    const auto at = std::find_if(summary.begin(), summary.end(),
                                 [&](const SummaryRow& row) { return row.json == pointer; });
    return at == summary.end() ? nullptr : &*at;
}

// Issue 26: the summary `terrastudio compaction` prints and the panel shows holds the JSON's
// numbers (ts.compaction returns that JSON): the last pass's rut and sinkage, the red zone (a
// warning) and each layer's density after the last pass.
TEST(CompactionAnalysis, ItsSummaryShowsTheJsonsValues) {
    const Inputs in = heavyWheel();
    const CompactionSettings s = clayWet(3);
    const CompactionResult r = computeCompaction(in, s);
    ASSERT_EQ(r.status(), Outcome::Status::kCompleted) << r.message;
    const nlohmann::json j = toJson(r);
    EXPECT_EQ(j.at("status"), "completed");
    const Summary summary = compactionSummary(in, s, r);
    terra::testing::expectSummaryIsTheJson(summary, j);
    EXPECT_NE(summary.front().value.find("W = 800 N, s = 0.2"), std::string::npos);
    EXPECT_NE(summary.front().value.find("3 passes"), std::string::npos);
    const SummaryRow* rut = compactionRowAt(summary, "/passes/2/rut_depth_m");
    ASSERT_NE(rut, nullptr);
    EXPECT_EQ(rut->label, "rut after pass 3");
    EXPECT_EQ(rut->number, r.passes[2].rut_depth_m);
    ASSERT_NE(compactionRowAt(summary, "/passes/2/sinkage_m"), nullptr);
    const SummaryRow* red = compactionRowAt(summary, "/red_to_depth_m");
    ASSERT_NE(red, nullptr);
    EXPECT_EQ(red->emphasis, SummaryRow::Emphasis::kWarning);
    EXPECT_GT(red->number, 0.1);
    EXPECT_EQ(compactionRowAt(summary, "/soil_profile/name")->value, "clay, wet");
    // A row per layer: the red topsoil denser than it was, the subsoil unchanged (1.45 Mg/m³).
    const std::size_t layers = s.profile->layers.size();
    for (std::size_t l = 0; l < layers; ++l)
        ASSERT_NE(compactionRowAt(summary, "/passes/2/bulk_density_Mg_m3/" + std::to_string(l)),
                  nullptr);
    const SummaryRow* top = compactionRowAt(summary, "/passes/2/bulk_density_Mg_m3/0");
    EXPECT_GT(top->number, s.profile->layers[0].bulk_density_kg_m3 / 1e3);
    EXPECT_EQ(top->detail.rfind("from ", 0), 0u) << top->detail;
    const SummaryRow* bottom =
        compactionRowAt(summary, "/passes/2/bulk_density_Mg_m3/" + std::to_string(layers - 1));
    EXPECT_EQ(bottom->value, "1.450");
    EXPECT_EQ(bottom->detail, "unchanged");
}

TEST(CompactionAnalysis, WithoutAProfileTheSummaryHasNoRisk) {
    const Inputs in = heavyWheel();
    CompactionSettings s;
    s.slip = 0.2;
    const CompactionResult r = computeCompaction(in, s);
    ASSERT_TRUE(r.ok()) << r.message;
    const Summary summary = compactionSummary(in, s, r);
    terra::testing::expectSummaryIsTheJson(summary, toJson(r));
    const auto profile = std::find_if(summary.begin(), summary.end(),
                                      [](const SummaryRow& row) { return row.label == "profile"; });
    ASSERT_NE(profile, summary.end());
    EXPECT_EQ(profile->value, "none");
    EXPECT_NE(summary.front().value.find("nu = 5"), std::string::npos) << summary.front().value;
    for (const SummaryRow& row : summary) {
        EXPECT_EQ(row.json.find("red_to_depth_m"), std::string::npos) << row.label;
        EXPECT_EQ(row.json.find("bulk_density"), std::string::npos) << row.label;
    }
}

TEST(CompactionAnalysis, ALoadWithoutEquilibriumFailsWithAWarning) {
    Inputs in = heavyWheel();
    in.wheel = io::resolveWheel(locations(), "A").value();  // the small wheel sinks to its axle
    in.conditions.load_n = 5000.0;
    const CompactionSettings s = clayWet(2);
    const CompactionResult r = computeCompaction(in, s);
    EXPECT_EQ(r.status(), Outcome::Status::kFailed);
    const nlohmann::json j = toJson(r);
    EXPECT_EQ(j.at("status"), "failed");
    const Summary summary = compactionSummary(in, s, r);
    terra::testing::expectSummaryIsTheJson(summary, j);
    const SummaryRow* failed = compactionRowAt(summary, "/message");
    ASSERT_NE(failed, nullptr);
    EXPECT_EQ(failed->label, "failed");
    EXPECT_EQ(failed->emphasis, SummaryRow::Emphasis::kWarning);
    EXPECT_NE(failed->value.find("no equilibrium"), std::string::npos) << failed->value;
}

TEST(CompactionAnalysis, ACancelledRunHasTheStatusCancelled) {
    const Inputs in = heavyWheel();
    const CompactionSettings s = clayWet(3);
    const std::atomic<bool> cancel{true};
    const CompactionResult r = computeCompaction(in, s, Control{&cancel});
    EXPECT_EQ(r.status(), Outcome::Status::kCancelled);
    EXPECT_TRUE(r.passes.empty());
    EXPECT_EQ(toJson(r).at("status"), "cancelled");
    EXPECT_EQ(compactionOutcome(r).status, Outcome::Status::kCancelled);
    const Summary summary = compactionSummary(in, s, r);
    const SummaryRow* cancelled = compactionRowAt(summary, "/message");
    ASSERT_NE(cancelled, nullptr);
    EXPECT_EQ(cancelled->label, "cancelled");
    EXPECT_EQ(cancelled->value, "cancelled after 0 of 3 passes");
}

}  // namespace
}  // namespace terra::analysis
