#include "core/identification/full_fit.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/identification/synthetic.h"
#include "tests/core/contact/test_soils.h"
#include "tests/core/identification/identification_test_support.h"
#include "tests/core/test_support.h"

namespace terra::identification {
namespace {

using terra::testing::kDeg;
using testing::kWheelA;
// Sandy loam of Table 2.1 on wheel A: K_s = 5.3e3/0.107 + 1.515e6 Pa/m^n.
const std::array<double, kFullParameterCount> kTruth{
    0.2, 0.3, 5.3e3 / 0.107 + 1.515e6, 0.7, 1700.0, 29.0 * kDeg, 0.025};

using testing::valuesOf;

DataSet sandyLoamData(std::vector<double> loads, double noise, std::uint64_t seed) {
    SyntheticSpec spec;
    for (int i = 0; i < 60; ++i) spec.slips.push_back(0.9 * i / 59);
    spec.loads_n = std::move(loads);
    spec.noise.fx.absolute = noise;
    spec.noise.fz.absolute = noise;
    spec.noise.my.absolute = noise / 10;
    spec.seed = seed;
    return synthesize(contact::testing::sandyLoam(), spec).data;
}

RefineOptions refineOptionsFor(double noise) {
    RefineOptions o;
    o.max_shear_deformation_m = 0.02;  // the forward model's j_max (Table 2.6)
    if (noise > 0) {
        o.sigma_fx = noise;
        o.sigma_fz = noise;
        o.sigma_my = noise / 10;
    }
    return o;
}

TEST(RefineFullModel, RecoversEveryParameterOnNoiseFreeSingleLoadData) {
    // Issue #3: started from the (biased) decoupled estimate, the full-model fit recovers the
    // truth.
    const DataSet data = sandyLoamData({58.86}, 0.0, 1);
    const DecoupledFit start = fitDecoupled(data, kWheelA, DecoupledParameters{});
    const RefineResult result =
        refineFullModel(data, kWheelA, start.parameters, refineOptionsFor(0.0));
    ASSERT_TRUE(result.report.usable) << result.report.termination;
    const auto got = valuesOf(result.parameters);
    for (int k = 0; k < kJmax; ++k) {
        EXPECT_NEAR(got[k], kTruth[k], 1e-7 * std::abs(kTruth[k])) << parameterInfo()[k].name;
    }
}

TEST(RefineFullModel, NoisyMultiLoadEstimatesLieWithinTheirStandardDeviations) {
    const double noise = 0.02;  // [N]; M_y noise 0.002 N·m
    const DataSet data = sandyLoamData({30.0, 58.86, 90.0}, noise, 11);
    const DecoupledFit start = fitDecoupled(data, kWheelA, DecoupledParameters{});
    const RefineResult result =
        refineFullModel(data, kWheelA, start.parameters, refineOptionsFor(noise));
    ASSERT_TRUE(result.report.usable) << result.report.termination;
    ASSERT_TRUE(result.uncertainty.computed);
    const auto got = valuesOf(result.parameters);
    for (int k = 0; k < kJmax; ++k) {
        EXPECT_GT(result.uncertainty.std[k], 0.0) << parameterInfo()[k].name;
        EXPECT_LT(std::abs(got[k] - kTruth[k]), 5.0 * result.uncertainty.std[k])
            << parameterInfo()[k].name;
    }
    // χ² of a right model with the right noise levels is about the number of residuals (540 − 7).
    EXPECT_NEAR(result.report.squared_residual_norm, 533.0, 4 * std::sqrt(2 * 533.0));
    const std::vector<std::string> c_phi{"c_kPa", "phi_deg"};  // the flag of the c–φ valley
    for (const ParameterText& flag : result.uncertainty.flags) {
        EXPECT_NE(flag.parameters(), c_phi) << flag.text;
    }
}

TEST(RefineFullModel, SingleLoadNoiseCannotSeparateCohesionAndFriction) {
    // Issue #3: with noise and one load only c + σ tan φ is identified; say so.
    const DataSet data = sandyLoamData({58.86}, 0.02, 5);
    const DecoupledFit start = fitDecoupled(data, kWheelA, DecoupledParameters{});
    const RefineResult result =
        refineFullModel(data, kWheelA, start.parameters, refineOptionsFor(0.02));
    bool flagged = false;
    for (const ParameterText& flag : result.uncertainty.flags) {
        flagged |= flag.parameters() == std::vector<std::string>{"c_kPa", "phi_deg"} &&
                   flag.text.find("several loads") != std::string::npos;
    }
    EXPECT_TRUE(flagged);
}

TEST(RefineFullModel, FixedParametersKeepTheirValues) {
    const DataSet data = sandyLoamData({40.0, 80.0}, 0.0, 1);
    DecoupledParameters start = fitDecoupled(data, kWheelA, DecoupledParameters{}).parameters;
    start.a0 = 0.2;
    start.a1 = 0.3;
    RefineOptions options = refineOptionsFor(0.0);
    options.fixed[kA0] = options.fixed[kA1] = true;
    const RefineResult result = refineFullModel(data, kWheelA, start, options);
    EXPECT_EQ(result.parameters.a0, 0.2);
    EXPECT_EQ(result.parameters.a1, 0.3);
    EXPECT_EQ(result.uncertainty.std[kA0], 0.0);
    EXPECT_NEAR(result.parameters.friction_angle_rad, kTruth[kPhi], 1e-8);
}

}  // namespace
}  // namespace terra::identification
