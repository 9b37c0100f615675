// The best slip (core/analysis/traction.h): s* against a brute-force scan of the model; η at one
// point from the wheel's own forces; the sinkage cap; the posterior's band and robust slip.
#include "core/analysis/traction.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/analysis/operating_point.h"
#include "core/io/parameters_json.h"

namespace terra::analysis {
namespace {

Inputs sandyLoamOnA(bool quadratic) {
    const io::PresetLocations locations{{TERRA_RESOURCE_DIR}};
    Inputs in;
    in.soil = io::resolveSoil(locations, "sandy-loam").value();
    in.wheel = io::resolveWheel(locations, "A").value();
    in.conditions.quadratic = quadratic;
    return in;
}

// The best slip of a dense scan, to `step`.
double bruteForce(const Inputs& in, const TractionSettings& s, double step) {
    double best_slip = 0.0, best = -1e300;
    for (double slip = s.slip_min; slip <= s.slip_max + 1e-12; slip += step) {
        const double v = objectiveValue(
            s.objective,
            tractionPoint(in.contact(), in.conditions.load_n, slip, s, in.conditions.model()));
        if (v > best) best = v, best_slip = slip;
    }
    return best_slip;
}

TEST(Traction, OptimalSlipMatchesABruteForceScan) {
    for (const bool quadratic : {true, false}) {
        const Inputs in = sandyLoamOnA(quadratic);
        TractionSettings s;
        s.slip_min = 0.3;
        s.slip_max = 0.9;
        const TractionResult r = computeTraction(in, s);
        ASSERT_TRUE(r.ok()) << r.message;
        // The scan at 1e-4 finds the same maximiser to within its step.
        EXPECT_NEAR(*r.optimal_slip, bruteForce(in, s, 1e-4), 1.5e-4) << quadratic;
        EXPECT_GT(*r.optimal_slip, 0.5);
        EXPECT_LT(*r.optimal_slip, 0.75);
    }
}

TEST(Traction, EfficiencyIsOutputOverInputPower) {
    // η = F_x v / (M_y ω) with v = r ω (1 − s): from the `wheel` command's forces at s = 0.6.
    const Inputs in = sandyLoamOnA(false);
    PointSpec spec;
    spec.slip = 0.6;
    spec.load_n = in.conditions.load_n;
    const PointResult w = evaluatePoint(in.contact(), spec);
    const double by_hand = w.forces.fx * in.wheel.radius_m * 0.4 / w.forces.my;
    const TractionPoint p =
        tractionPoint(in.contact(), in.conditions.load_n, 0.6, {}, in.conditions.model());
    EXPECT_DOUBLE_EQ(p.efficiency, by_hand);
    EXPECT_GT(p.efficiency, 0.0);
    EXPECT_LT(p.efficiency, 1.0);
}

TEST(Traction, ASinkageCapMovesTheOptimumToTheCap) {
    const Inputs in = sandyLoamOnA(false);
    TractionSettings s;
    const TractionResult free = computeTraction(in, s);
    s.max_sinkage_m = 0.5 * (free.at_optimum.sinkage_m + free.curve.front().sinkage_m);
    const TractionResult capped = computeTraction(in, s);
    ASSERT_TRUE(capped.ok());
    EXPECT_LT(*capped.optimal_slip, *free.optimal_slip);
    EXPECT_LE(capped.at_optimum.sinkage_m, *s.max_sinkage_m);
    EXPECT_NEAR(capped.at_optimum.sinkage_m, *s.max_sinkage_m, 2e-6);  // on the boundary
    s.max_sinkage_m = 1e-4;                                            // no slip meets it
    EXPECT_FALSE(computeTraction(in, s).ok());
}

TEST(Traction, APosteriorGivesABandAndARobustSlip) {
    const Inputs in = sandyLoamOnA(true);
    TractionSettings s;
    s.posterior = SoilPosterior{{"phi_deg", "n"}, {29.0, 0.7}, {{4.0, -0.05}, {-0.05, 0.0025}}};
    s.posterior_samples = 100;
    const TractionResult r = computeTraction(in, s);
    ASSERT_TRUE(r.ok()) << r.message;
    ASSERT_EQ(r.band.size(), r.curve.size());
    for (const TractionBand& b : r.band) {
        EXPECT_LE(b.p5, b.p50);
        EXPECT_LE(b.p50, b.p95);
        EXPECT_LE(b.quantile, b.p50);  // the 10 % quantile
    }
    ASSERT_TRUE(r.robust_slip);
    // The robust slip's quantile is at least the quantile at every slip of the curve.
    for (const TractionBand& b : r.band) EXPECT_GE(r.robust_value, b.quantile - 1e-12);
    // The same seed, the same band; another seed, other draws.
    const TractionResult again = computeTraction(in, s);
    EXPECT_EQ(again.band[10].p50, r.band[10].p50);
    s.seed = 2;
    EXPECT_NE(computeTraction(in, s).band[10].p50, r.band[10].p50);
}

TEST(Traction, ANarrowPosteriorIsTheNominalSoil) {
    const Inputs in = sandyLoamOnA(true);
    TractionSettings s;
    s.slip_min = 0.4;
    s.slip_max = 0.8;
    s.posterior = SoilPosterior{{"phi_deg"}, {29.0}, {{1e-10}}};
    s.posterior_samples = 20;
    const TractionResult r = computeTraction(in, s);
    ASSERT_TRUE(r.robust_slip);
    EXPECT_NEAR(*r.robust_slip, *r.optimal_slip, 1e-3);
}

TEST(Traction, BadSettingsAreNamed) {
    TractionSettings s;
    s.slip_min = 0.8;
    s.slip_max = 0.2;
    EXPECT_THROW(computeTraction(sandyLoamOnA(true), s), std::invalid_argument);
    s = {};
    s.posterior = SoilPosterior{{"phi"}, {29.0}, {{1.0}}};
    try {
        computeTraction(sandyLoamOnA(true), s);
        FAIL();
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("posterior.parameters"), std::string::npos);
    }
    s.posterior = SoilPosterior{{"phi_deg", "n"}, {29.0, 0.7}, {{1.0, 2.0}, {2.0, 1.0}}};
    EXPECT_THROW(computeTraction(sandyLoamOnA(true), s), std::invalid_argument);  // not SPD
}

}  // namespace
}  // namespace terra::analysis
