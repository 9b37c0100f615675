// The identification with a lugged wheel (docs/model.md, "Lugs"): its model is the forward model
// with the wheel fixed, so the wheel's shearing radius r_s = r + λ_s h_g reaches it through the
// wheel. Data made by the lugged forward model give back their soil when identified with the
// lugged wheel; the same data identified as if the wheel were smooth fit far worse.
#include <gtest/gtest.h>

#include <cmath>

#include "core/contact/contact_parameters.h"
#include "core/contact/wheel_forces.h"
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

// Wheel A with 12 mm grousers and λ_s = 0.5: r_s = 0.098 m.
wheel::WheelParameters luggedWheelA() {
    return {"A lugged", "", 0.092, 0.107, 0.012, 18.0, 0.002, 0.5};
}

TEST(LuggedIdentification, ObservationModelIsTheLuggedForwardModel) {
    contact::ContactParameters<double> soil = soils::sandyLoam();
    soil.lug_shear_offset_m = luggedWheelA().lugShearOffset();
    const DataSet data = fromLoad(soil, {58.86});
    const Result<ModelSetup> setup = setupModel(data, DataSource::kLoad, std::nullopt, 0.02);
    ASSERT_TRUE(setup.ok()) << setup.message();
    const ObservationModel model(data, luggedWheelA(), setup.value());
    for (std::size_t i : {std::size_t{0}, std::size_t{5}, std::size_t{15}}) {
        const Prediction p = model.predict(i, truthOf(soil));
        ASSERT_TRUE(p.ok) << i;
        const contact::OperatingPoint<double> op{data.samples[i].slip, 0.0, p.entry_angle_rad, 0.0,
                                                 std::nullopt};
        const contact::WheelForces<double> f = contact::computeForces(soil, op);
        EXPECT_NEAR(f.fz, 58.86, 1e-9 * 58.86) << i;  // the load found again
        EXPECT_NEAR(p.values[kFxChannel], f.fx, 1e-9 * (1.0 + std::abs(f.fx))) << i;
        EXPECT_NEAR(p.values[kMyChannel], f.my, 1e-9 * (1.0 + std::abs(f.my))) << i;
    }
}

TEST(LuggedIdentification, TheFitFromTheLoadRecoversTheSoilWithTheLuggedWheel) {
    contact::ContactParameters<double> soil = soils::sandyLoam();
    soil.lug_shear_offset_m = luggedWheelA().lugShearOffset();
    const DataSet data = fromLoad(soil, {40.0, 58.86, 80.0});
    IdentifyOptions o;
    o.max_shear_deformation_m = soil.max_shear_deformation_m;
    const IdentificationReport r = identify(data, luggedWheelA(), o);
    ASSERT_TRUE(r.usable()) << r.message;
    const ParameterVector truth = truthOf(soil);
    for (int k = 0; k < kJmax; ++k)
        EXPECT_NEAR(r.parameters[k], truth[k], 1e-4 * std::abs(truth[k]))
            << parameterInfo()[k].name;
    // The same data with the wheel taken as smooth (λ_s = 0): a far worse fit at the same noise.
    wheel::WheelParameters smooth = luggedWheelA();
    smooth.lug_effect_coefficient = 0.0;
    o.noise = r.noise;
    const IdentificationReport thesis = identify(data, smooth, o);
    ASSERT_TRUE(thesis.usable()) << thesis.message;
    EXPECT_GT(thesis.chi2, 1e3 * std::max(r.chi2, 1.0));
}

}  // namespace
}  // namespace terra::identification
