// Ding's slip-dependent sinkage exponent N = n + n₁ s in the identification's model
// (IdentifyOptions::sinkage_exponent_slip, docs/model.md "Slip-sinkage"): n₁ = 0 is the thesis
// model; at one slip, n₁ is the same as a constant exponent n + n₁ s; held at the truth, the
// identification from the load recovers the other seven parameters of data made with it.
#include <gtest/gtest.h>

#include <cmath>

#include "core/contact/sinkage.h"
#include "core/identification/identify.h"
#include "core/identification/observation_model.h"
#include "core/identification/synthetic.h"
#include "tests/core/contact/test_soils.h"
#include "tests/core/identification/identification_test_support.h"

namespace terra::identification {
namespace {

using testing::fromLoad;
using testing::truthOf;

namespace soils = contact::testing;
using testing::kWheelA;

TEST(SlipSinkage, AtOneSlipN1IsTheConstantExponentNPlusN1S) {
    const contact::ContactParameters<double> soil = soils::sandyLoam();
    DataSet data = fromLoad(soil, {58.86});
    const Result<ModelSetup> plain = setupModel(data, DataSource::kLoad, std::nullopt, 0.02);
    ASSERT_TRUE(plain.ok()) << plain.message();
    EXPECT_EQ(plain->sinkage_exponent_slip, 0.0);  // the default: the thesis model
    ModelSetup with_n1 = plain.value();
    with_n1.sinkage_exponent_slip = 0.4;
    const ObservationModel ding(data, kWheelA, with_n1);
    const ObservationModel thesis(data, kWheelA, plain.value());
    const ParameterVector p = truthOf(soil);
    for (std::size_t i : {std::size_t{0}, std::size_t{6}, std::size_t{15}}) {
        const double slip = data.samples[i].slip;
        ParameterVector shifted = p;
        shifted[kN] = p[kN] + 0.4 * slip;
        const Prediction a = ding.predict(i, p);
        const Prediction b = thesis.predict(i, shifted);
        ASSERT_TRUE(a.ok && b.ok) << i;
        EXPECT_NEAR(a.entry_angle_rad, b.entry_angle_rad, 1e-10) << "s = " << slip;
        for (int c : {kFxChannel, kMyChannel, kSinkageChannel})
            EXPECT_NEAR(a.values[c], b.values[c], 1e-9 * (1.0 + std::abs(b.values[c])))
                << "s = " << slip << ", channel " << channelNames()[c];
    }
    // And n₁ > 0 deepens the rut where s > 0 (h^N falls with N for h < 1 m): at s = 0.75 the
    // wheel sinks deeper than without n₁, at s = 0 exactly as deep.
    EXPECT_EQ(ding.predict(0, p).values[kSinkageChannel],
              thesis.predict(0, p).values[kSinkageChannel]);
    EXPECT_GT(ding.predict(15, p).values[kSinkageChannel],
              1.2 * thesis.predict(15, p).values[kSinkageChannel]);
}

TEST(SlipSinkage, HeldAtTheTruthTheFitFromTheLoadRecoversTheSoil) {
    contact::ContactParameters<double> soil = soils::sandyLoam();
    soil.sinkage_exponent_slip = 0.3;
    const DataSet data = fromLoad(soil, {40.0, 58.86, 80.0});
    IdentifyOptions o;
    o.max_shear_deformation_m = soil.max_shear_deformation_m;
    o.sinkage_exponent_slip = 0.3;
    const IdentificationReport r = identify(data, kWheelA, o);
    ASSERT_TRUE(r.usable()) << r.message;
    const ParameterVector truth = truthOf(soil);
    for (int k = 0; k < kJmax; ++k)
        EXPECT_NEAR(r.parameters[k], truth[k], 1e-4 * std::abs(truth[k]))
            << parameterInfo()[k].name;
    // With the thesis model (n₁ = 0) the same data do not fit: the χ² at the noise level of the
    // n₁ = 0.3 fit is far larger.
    o.sinkage_exponent_slip = 0.0;
    o.noise = r.noise;
    const IdentificationReport thesis = identify(data, kWheelA, o);
    ASSERT_TRUE(thesis.usable()) << thesis.message;
    EXPECT_GT(thesis.chi2, 1e3 * std::max(r.chi2, 1.0));
}

// docs/model.md's hand computation for the Ding wheel on HIT-LSS1 (W = 80 N, r = 0.15735 m,
// b = 0.165 m, K_s = 2.5019e6 Pa/m^N, N = 1.1): Bekker's h = 9.13 mm and
// d ln h/dN = (1/(3 − N) − ln h)/(N + ½) = 3.264, the rate at which n₁ deepens the rut.
TEST(SlipSinkage, BekkersRutDeepensWithTheExponentAsDerived) {
    contact::ContactParameters<double> p =
        soils::thesisSoil(1.1, 0.25, 31.9, 15.6, 2407.4, 0.011, 16.0, INFINITY, 0.15735, 0.165);
    const double h = contact::bekkerStaticSinkage(p, 80.0);
    EXPECT_NEAR(h, 0.0091299, 1e-6);
    const double derived = (1.0 / (3.0 - 1.1) - std::log(h)) / 1.6;
    EXPECT_NEAR(derived, 3.2641, 1e-4);
    const double dn = 1e-5;
    p.sinkage_exponent = 1.1 + dn;
    const double up = std::log(contact::bekkerStaticSinkage(p, 80.0));
    p.sinkage_exponent = 1.1 - dn;
    const double down = std::log(contact::bekkerStaticSinkage(p, 80.0));
    EXPECT_NEAR((up - down) / (2.0 * dn), derived, 1e-6);
}

}  // namespace
}  // namespace terra::identification
