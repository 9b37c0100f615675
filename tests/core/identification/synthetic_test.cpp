#include "core/identification/synthetic.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/contact/wheel_forces.h"
#include "tests/core/contact/test_soils.h"

namespace terra::identification {
namespace {

SyntheticSpec thesisSpec() {
    SyntheticSpec spec;
    for (int i = 0; i < 10; ++i) spec.slips.push_back(0.09 * i);
    return spec;
}

TEST(Synthetic, NoiseFreeDataIsTheModelInEquilibrium) {
    const auto p = contact::testing::sandyLoam();
    const SyntheticData out = synthesize(p, thesisSpec());
    ASSERT_EQ(out.data.samples.size(), 10u);
    for (const Sample& s : out.data.samples) {
        EXPECT_NEAR(s.fz_n, 58.86, 1e-8);  // θ_f solved so that F_z = W
        const auto f = contact::computeForces(
            p, contact::OperatingPoint<double>{s.slip, 0.0, s.entry_angle_rad, 0.0, std::nullopt});
        EXPECT_NEAR(s.fx_n, f.fx, 1e-12);
        EXPECT_NEAR(s.my_nm, f.my, 1e-12);
        EXPECT_FALSE(s.load_n.has_value());  // one load: no W column
    }
}

TEST(Synthetic, SeveralLoadsCarryTheLoadColumn) {
    SyntheticSpec spec = thesisSpec();
    spec.loads_n = {40.0, 80.0};
    const SyntheticData out = synthesize(contact::testing::clayeySoil(), spec);
    ASSERT_EQ(out.data.samples.size(), 20u);
    EXPECT_EQ(out.data.samples.front().load_n, 40.0);
    EXPECT_EQ(out.data.samples.back().load_n, 80.0);
    EXPECT_NEAR(out.data.samples.back().fz_n, 80.0, 1e-8);
    EXPECT_NE(toCsv(out.data).find("W_N"), std::string::npos);
}

TEST(Synthetic, NoiseHasTheAskedSpreadAndTheSeedRepeats) {
    SyntheticSpec spec;
    for (int i = 0; i < 2000; ++i) spec.slips.push_back(0.3);  // same point: spread is pure noise
    spec.noise.fx.absolute = 0.5;
    spec.noise.fz.relative = 0.01;  // 1 % of max |F_z| = 0.5886 N
    spec.seed = 42;
    const auto p = contact::testing::sandyLoam();
    const SyntheticData a = synthesize(p, spec);
    const SyntheticData b = synthesize(p, spec);
    double mean_fz = 0, var_fx = 0, var_fz = 0;
    const double fx0 =
        contact::computeForces(
            p, contact::OperatingPoint<double>{0.3, 0.0, a.data.samples[0].entry_angle_rad, 0.0,
                                               std::nullopt})
            .fx;
    for (std::size_t i = 0; i < a.data.samples.size(); ++i) {
        EXPECT_EQ(a.data.samples[i].fx_n, b.data.samples[i].fx_n);  // same seed, same data
        var_fx += std::pow(a.data.samples[i].fx_n - fx0, 2);
        var_fz += std::pow(a.data.samples[i].fz_n - 58.86, 2);
        mean_fz += a.data.samples[i].fz_n;
    }
    const double n = static_cast<double>(a.data.samples.size());
    // σ estimates from 2000 draws are within ~3 % (1/√(2n) ≈ 1.6 %, two standard errors).
    EXPECT_NEAR(std::sqrt(var_fx / n), 0.5, 0.035);
    EXPECT_NEAR(std::sqrt(var_fz / n), 0.5886, 0.04);
    EXPECT_NEAR(mean_fz / n, 58.86, 4 * 0.5886 / std::sqrt(n));
    spec.seed = 43;
    EXPECT_NE(synthesize(p, spec).data.samples[0].fx_n, a.data.samples[0].fx_n);
}

TEST(Synthetic, LoadsWithoutEquilibriumAreReported) {
    SyntheticSpec spec = thesisSpec();
    spec.loads_n = {58.86, 5000.0};
    const SyntheticData out = synthesize(contact::testing::drySand(), spec);
    EXPECT_EQ(out.data.samples.size(), 10u);
    EXPECT_EQ(out.warnings.size(), 10u);
}

TEST(Synthetic, BadSpecThrowsWithTheField) {
    SyntheticSpec spec = thesisSpec();
    spec.noise.my.absolute = -1.0;
    try {
        synthesize(contact::testing::sandyLoam(), spec);
        FAIL();
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("noise.My"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace terra::identification
