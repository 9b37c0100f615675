#include "core/compaction/track_memory.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/contact/sinkage.h"
#include "core/contact/stress_field.h"
#include "core/contact/wheel_forces.h"
#include "tests/core/contact/test_soils.h"

namespace terra::compaction {
namespace {

contact::SinkageSolution solve(const contact::ContactParameters<double>& p, double load,
                               contact::OperatingPoint<double>* op = nullptr) {
    contact::EntryAngleProblem problem;
    problem.load_n = load;
    problem.slip = 0.2;
    const contact::SinkageSolution s = contact::solveEntryAngle(p, problem);
    EXPECT_TRUE(s.ok()) << s.message;
    if (op) *op = contact::operatingPoint(problem, s.entry_angle_rad);
    return s;
}

TEST(TrackMemory, AnUntouchedTrackIsTheThesisModelBitForBit) {
    const contact::ContactParameters<double> p = contact::testing::sandyLoam();
    const contact::ContactParameters<double> on = onTrack(p, TrackMemory{}, ReloadLaw{});
    contact::OperatingPoint<double> a, b;
    const auto sa = solve(p, 58.86, &a), sb = solve(on, 58.86, &b);
    EXPECT_EQ(sa.entry_angle_rad, sb.entry_angle_rad);
    const auto fa = contact::computeForces(p, a), fb = contact::computeForces(on, b);
    EXPECT_EQ(fa.fx, fb.fx);
    EXPECT_EQ(fa.my, fb.my);
    EXPECT_EQ(fa.fz, fb.fz);
}

TEST(TrackMemory, WongsLawAfterAPass) {
    const contact::ContactParameters<double> p = contact::testing::sandyLoam();
    ReloadLaw law;
    law.k0_pa_m = 2e6;
    law.au_pa_m2 = 4e8;
    const TrackMemory m = afterPass(TrackMemory{}, law, p, 0.02, 0.7, 0.004);
    // p_u = K_s z_u^N, k_u = k0 + A_u z_u, rut z_p = z_u − p_u/k_u (hand computation).
    const double p_u = p.pressure_modulus * std::pow(0.02, 0.7);
    const double k_u = 2e6 + 4e8 * 0.02;
    EXPECT_EQ(m.passes, 1);
    EXPECT_DOUBLE_EQ(m.max_pressure_pa, p_u);
    EXPECT_DOUBLE_EQ(m.rut_depth_m, 0.02 - p_u / k_u);
    EXPECT_DOUBLE_EQ(m.shear_m, 0.004);
    // A shallower wheel afterwards stays on the elastic branch: no new rut, the shear grows.
    const TrackMemory n = afterPass(m, law, p, 0.015, 0.7, 0.003);
    EXPECT_EQ(n.passes, 2);
    EXPECT_EQ(n.rut_depth_m, m.rut_depth_m);
    EXPECT_EQ(n.max_sinkage_m, m.max_sinkage_m);
    EXPECT_DOUBLE_EQ(n.shear_m, 0.007);
    // j_max caps the carried shear.
    EXPECT_DOUBLE_EQ(afterPass(n, law, p, 0.0, 0.7, 0.05).shear_m, p.max_shear_deformation_m);
}

TEST(TrackMemory, AReloadBelowThePreviousLargestPressureIsElastic) {
    // A heavy wheel first, then a light one: the light one's whole contact is on the reload line
    // σ = k_u d, d = r (cos θ − cos θ_f) below the rut's bottom.
    const contact::ContactParameters<double> p = contact::testing::sandyLoam();
    ReloadLaw law;
    law.k0_pa_m = 5e7;
    law.au_pa_m2 = 0.0;
    contact::OperatingPoint<double> heavy;
    const auto sh = solve(p, 150.0, &heavy);
    const TrackMemory m = afterPass(TrackMemory{}, law, p, sh.sinkage_m, 0.7, 0.0);
    const contact::ContactParameters<double> on = onTrack(p, m, law);
    contact::OperatingPoint<double> light;
    const auto sl = solve(on, 30.0, &light);
    const contact::StressField<double> field(on, light);
    const double theta = 0.5 * (field.maxStressAngle() + field.entryAngle());
    const double d = p.radius_m * (std::cos(theta) - std::cos(light.entry_angle_rad));
    ASSERT_LT(d, on.reload_depth_m);
    EXPECT_NEAR(field.normalStress(theta), 5e7 * d, 1e-9 * 5e7 * d);
    // It sinks less than the elastic depth: total depth below the untouched surface ≤ z_u.
    EXPECT_LE(m.rut_depth_m + sl.sinkage_m, m.max_sinkage_m);
    // F_z = W is met with the reload law (its integrals see the kink).
    EXPECT_NEAR(contact::computeForces(on, light).fz, 30.0, 1e-6 * 30.0);
}

TEST(TrackMemory, SinkageIncrementsFallPassAfterPass) {
    const contact::ContactParameters<double> p = contact::testing::sandyLoam();
    const ReloadLaw law;  // SCM's default stiffness
    TrackMemory m;
    double previous_increment = 1.0;
    for (int pass = 1; pass <= 6; ++pass) {
        const contact::ContactParameters<double> on = onTrack(p, m, law);
        const auto s = solve(on, 58.86);
        const double depth = m.rut_depth_m + s.sinkage_m;
        const double increment = depth - m.max_sinkage_m;
        EXPECT_GE(increment, 0.0) << pass;
        EXPECT_LT(increment, previous_increment) << pass;
        previous_increment = increment;
        m = afterPass(m, law, p, depth, 0.7, 0.0);
    }
}

}  // namespace
}  // namespace terra::compaction
