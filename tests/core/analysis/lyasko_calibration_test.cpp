// `validate --calibrate --fit-slip-sinkage` (ValidationSettings::fit_slip_sinkage) recovers
// Lyasko's slip-sinkage coefficient S (docs/model.md, Eq. S.1) from a synthetic test made with a
// known S and Gaussian noise, from several given soils (the calibration's priors and starts).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/analysis/validation.h"
#include "core/common/units.h"
#include "core/io/parameters_json.h"
#include "tests/core/test_support.h"

namespace terra::analysis {
namespace {

using terra::testing::kLocations;

constexpr double kTrueS = 3.0;
constexpr double kSigmaFxN = 0.5, kSigmaMyNm = 0.1, kSigmaSinkageM = 3e-4;

Inputs dingSmoothOnHitLss1() {
    Inputs in;
    in.soil = io::resolveSoil(kLocations, "hit-lss1").value();
    in.wheel = io::resolveWheel(kLocations, "ding2011-smooth").value();
    return in;
}

// The test the truth (HIT-LSS1 with S = 3) predicts at W = 80 N, with noise of a fixed seed.
io::Experiment syntheticTest() {
    Inputs truth = dingSmoothOnHitLss1();
    truth.soil.slip_sinkage_coefficient = kTrueS;
    io::Experiment test;
    test.source = "synthetic.csv";
    for (double s : {0.0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6}) {
        io::ExperimentPoint p;
        p.load_n = 80.0;
        p.slip = s;
        p.measured[io::kExpFx] = 0.0;
        test.points.push_back(p);
    }
    const ValidationRun exact = predictExperiment(truth, test, false);
    std::mt19937 random(20261203);
    std::normal_distribution<double> normal;
    for (std::size_t i = 0; i < test.points.size(); ++i) {
        const PointComparison& c = exact.points[i];
        EXPECT_TRUE(c.predicted) << c.failure;
        auto& m = test.points[i].measured;
        m[io::kExpFx] = c.values[io::kExpFx] + kSigmaFxN * normal(random);
        m[io::kExpMy] = c.values[io::kExpMy] + kSigmaMyNm * normal(random);
        m[io::kExpSinkage] = c.values[io::kExpSinkage] + kSigmaSinkageM * normal(random);
    }
    return test;
}

ValidationSettings calibrateWithS(const io::Experiment& test) {
    ValidationSettings s;
    s.data = test;
    s.experiments = test.source;
    s.calibrate = true;
    s.fit_slip_sinkage = true;
    s.curves = false;
    s.noise[io::kExpFx] = kSigmaFxN;
    s.noise[io::kExpMy] = kSigmaMyNm;
    s.noise[io::kExpSinkage] = kSigmaSinkageM;
    return s;
}

TEST(LyaskoCalibration, RecoversSFromNoisySinkageFromSeveralStarts) {
    const io::Experiment test = syntheticTest();
    // The given soil is the calibration's prior and first start: the truth, and two soils off it.
    std::vector<soil::SoilParameters> given(3, dingSmoothOnHitLss1().soil);
    given[1].frictional_modulus *= 0.6;
    given[1].cohesive_modulus *= 0.6;
    given[1].friction_angle_rad -= units::degToRad(3.0);
    given[2].frictional_modulus *= 1.5;
    given[2].cohesive_modulus *= 1.5;
    given[2].sinkage_exponent += 0.1;
    constexpr double kSTol = 0.6;  // 20 % of S; the profile's std is ~0.2 at this noise
    for (std::size_t k = 0; k < given.size(); ++k) {
        Inputs in = dingSmoothOnHitLss1();
        in.soil = given[k];
        const ValidationResult r = computeValidation(in, calibrateWithS(test));
        ASSERT_TRUE(r.calibration && r.calibration->report.usable())
            << "start " << k << ": " << r.calibration->report.message;
        const Calibration& c = *r.calibration;
        ASSERT_TRUE(c.slip_sinkage.has_value());
        EXPECT_NEAR(*c.slip_sinkage, kTrueS, kSTol) << "start " << k;
        ASSERT_TRUE(c.slip_sinkage_std.has_value());
        EXPECT_GT(*c.slip_sinkage_std, 0.0);
        EXPECT_LT(std::abs(*c.slip_sinkage - kTrueS), 4.0 * *c.slip_sinkage_std) << "start " << k;
        EXPECT_EQ(c.soil.slip_sinkage_coefficient, *c.slip_sinkage);
        // The calibrated sinkage is at the noise level, not the thesis model's misfit.
        ASSERT_TRUE(c.after->metrics[io::kExpSinkage].has_value());
        EXPECT_LT(c.after->metrics[io::kExpSinkage]->rmse, 2.0 * kSigmaSinkageM) << "start " << k;
    }
    // Without S the same data cannot be followed: the thesis model's calibrated sinkage misses by
    // several noise levels.
    ValidationSettings thesis = calibrateWithS(test);
    thesis.fit_slip_sinkage = false;
    const ValidationResult r = computeValidation(dingSmoothOnHitLss1(), thesis);
    ASSERT_TRUE(r.calibration && r.calibration->report.usable());
    EXPECT_GT(r.calibration->after->metrics[io::kExpSinkage]->rmse, 3.0 * kSigmaSinkageM);
}

TEST(LyaskoCalibration, OneSlipSinkageModelAtATime) {
    ValidationSettings s = calibrateWithS(syntheticTest());
    s.fit_n1 = true;
    EXPECT_THROW(computeValidation(dingSmoothOnHitLss1(), s), std::invalid_argument);
}

}  // namespace
}  // namespace terra::analysis
