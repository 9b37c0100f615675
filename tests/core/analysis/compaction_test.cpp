// The compaction analysis (core/analysis/compaction.h) against its parts: pass 1 is the
// single-wheel model exactly; the envelope is the largest of the passes' profiles; the studies'
// compaction outputs (core/gsa/wheel_target.h) are the analysis's numbers for the same soil.
#include "core/analysis/compaction.h"

#include <gtest/gtest.h>

#include "core/analysis/operating_point.h"
#include "core/common/units.h"
#include "core/gsa/wheel_target.h"
#include "core/io/parameters_json.h"

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

}  // namespace
}  // namespace terra::analysis
