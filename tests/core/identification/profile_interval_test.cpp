// Profile-likelihood intervals (profile_interval.h). Independent checks: where χ² is nearly
// quadratic (three loads) the profile interval at Δχ² = 9 is the linearised ±3σ interval (a
// second method: the covariance); at one load, where the c–φ valley is curved, it still holds the
// truth (Table 2.1 written out by hand) where the linearised interval may not.
#include "core/identification/profile_interval.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/identification/synthetic.h"
#include "tests/core/contact/test_soils.h"
#include "tests/core/identification/identification_test_support.h"

namespace terra::identification {
namespace {

using testing::truthOf;

namespace soils = contact::testing;
using testing::kWheelA;

DataSet sweeps(std::vector<double> loads, std::uint64_t seed, int slips) {
    SyntheticSpec spec;
    for (int i = 0; i < slips; ++i) spec.slips.push_back(0.9 * i / (slips - 1));
    spec.loads_n = std::move(loads);
    spec.noise.fx.relative = spec.noise.fz.relative = spec.noise.my.relative = 0.01;
    spec.seed = seed;
    return synthesize(soils::sandyLoam(), spec).data;
}

IdentifyOptions options() {
    IdentifyOptions o;
    o.max_shear_deformation_m = 0.02;
    return o;
}

TEST(ProfileInterval, EqualsTheLinearisedThreeSigmaIntervalWhereChiSquaredIsQuadratic) {
    const DataSet data = sweeps({30.0, 58.86, 90.0}, 1, 31);
    const IdentificationReport fit = identify(data, kWheelA, options());
    ASSERT_TRUE(fit.usable() && fit.uncertainty.computed);
    std::array<bool, kFullParameterCount> which{};
    which[kN] = which[kC] = which[kPhi] = true;
    const auto intervals = profileIntervals(data, kWheelA, options(), fit, which);
    for (int k = 0; k < kJmax; ++k) {
        const ProfileInterval& i = intervals[k];
        EXPECT_EQ(i.computed, which[k]) << parameterInfo()[k].name;
        if (!which[k]) continue;
        const double sd = fit.uncertainty.std[k];
        EXPECT_FALSE(i.lower_at_bound || i.upper_at_bound);
        // Each end within 10 % of 3σ from the estimate (Δ = 9 ± 0.3 and a little curvature).
        EXPECT_NEAR(fit.parameters[k] - i.lower, 3.0 * sd, 0.3 * sd) << parameterInfo()[k].name;
        EXPECT_NEAR(i.upper - fit.parameters[k], 3.0 * sd, 0.3 * sd) << parameterInfo()[k].name;
        EXPECT_LE(i.fits, 12);
    }
}

TEST(ProfileInterval, OneLoadFlagsTheTradeOffAndTheProfileHoldsTheTruth) {
    const ParameterVector truth = truthOf(soils::sandyLoam());
    for (std::uint64_t seed : {1u, 2u, 3u}) {
        SCOPED_TRACE(seed);
        const DataSet data = sweeps({58.86}, seed, 46);
        const IdentificationReport fit = identify(data, kWheelA, options());
        ASSERT_TRUE(fit.usable());
        const auto flagged = tradeOffParameters(fit);
        EXPECT_TRUE(flagged[kC] && flagged[kPhi]);  // one load: c + σ tan φ
        std::array<bool, kFullParameterCount> which{};
        which[kC] = which[kPhi] = true;
        const auto intervals = profileIntervals(data, kWheelA, options(), fit, which);
        for (int k : {kC, kPhi}) {
            const ProfileInterval& i = intervals[k];
            ASSERT_TRUE(i.computed);
            EXPECT_LE(i.lower, fit.parameters[k]);
            EXPECT_GE(i.upper, fit.parameters[k]);
            EXPECT_LE(i.lower, truth[k]) << parameterInfo()[k].name;
            EXPECT_GE(i.upper, truth[k]) << parameterInfo()[k].name;
        }
    }
}

TEST(ProfileInterval, NothingWithoutAUsableFitOrForAHeldParameter) {
    const DataSet data = sweeps({30.0, 58.86, 90.0}, 1, 11);
    IdentifyOptions o = options();
    o.fixed[kA0] = 0.7;
    const IdentificationReport fit = identify(data, kWheelA, o);
    ASSERT_TRUE(fit.usable());
    std::array<bool, kFullParameterCount> which{};
    which[kA0] = true;
    EXPECT_FALSE(profileIntervals(data, kWheelA, o, fit, which)[kA0].computed);
    EXPECT_FALSE(profileIntervals(data, kWheelA, o, IdentificationReport{}, which)[kA0].computed);
}

}  // namespace
}  // namespace terra::identification
