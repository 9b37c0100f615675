#include "core/identification/decoupled_fit.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/identification/decoupled_model.h"
#include "core/identification/synthetic.h"
#include "tests/core/contact/test_soils.h"
#include "tests/core/identification/identification_test_support.h"
#include "tests/core/test_support.h"

namespace terra::identification {
namespace {

using terra::testing::kDeg;
using testing::kWheelA;

TEST(DecoupledModel, HatCoefficientsAreTheIntegralsOfTheHat) {
    // A = ∫ hat cos, B = ∫ hat sin, C = ∫ hat over [θ_r, θ_f] (Eqs. 4.5–4.7 with E5), checked by
    // a midpoint sum of the hat of Eq. 4.3.
    const double tf = 0.5, s = 0.3;
    const HatCoefficients<double> h = hatCoefficients(0.2, 0.3, s, tf);
    const double tm = (0.2 + 0.3 * s) * tf;
    double a = 0, b = 0, c = 0;
    const int n = 200000;
    for (int i = 0; i < n; ++i) {
        const double t = tf * (i + 0.5) / n;
        const double hat = t >= tm ? (tf - t) / (tf - tm) : t / tm;
        a += hat * std::cos(t) * tf / n;
        b += hat * std::sin(t) * tf / n;
        c += hat * tf / n;
    }
    EXPECT_NEAR(h.a, a, 1e-9);
    EXPECT_NEAR(h.b, b, 1e-9);
    EXPECT_NEAR(h.c, c, 1e-9);
    // The printed Eq. 4.6 (cos θ_r in the first numerator) is not the integral (E5).
    const double printed =
        (std::sin(tm) - std::cos(0.0)) / tm + (std::sin(tm) - std::sin(tf)) / (tf - tm);
    EXPECT_GT(std::abs(printed - b), 0.1);
}

TEST(DecoupledModel, EliminationIsConsistentWithTheForwardForm) {
    // Eqs. 4.12, 4.17, 4.18 evaluated on the forward model's own F_x, F_z, M_y give them back.
    const DecoupledParameters p{0.25, 0.2, 1.2e6, 0.8, 0.1, 2000.0, 31 * kDeg, 0.02};
    for (double s : {0.05, 0.4, 0.85}) {
        const double tf = 0.35;
        const DecoupledForces f = decoupledForward(p, kWheelA, s, tf);
        const HatCoefficients<double> h = hatCoefficients(p.a0, p.a1, s, tf);
        EXPECT_NEAR(decoupledDrawbarPull(h, 0.092, f.fz_n, f.my_nm), f.fx_n, 1e-10);
        EXPECT_NEAR(
            decoupledVerticalForce(h, 0.092, 0.107, p.pressure_modulus, p.n0, p.n1, s, tf, f.my_nm),
            f.fz_n, 1e-9);
        EXPECT_NEAR(decoupledTorque(h, 0.092, 0.107, p.cohesion_pa, p.friction_angle_rad,
                                    p.shear_modulus_m, s, tf, f.fz_n),
                    f.my_nm, 1e-12);
    }
}

TEST(DecoupledFit, RecoversTheTruthOnDataOfTheDecoupledModel) {
    // With E5 and E6 corrected (docs/model.md) the three steps are exact on their own model.
    const DecoupledParameters truth{0.2, 0.3, 1.5e6, 0.7, 0.05, 1700.0, 29 * kDeg, 0.025};
    DataSet data;
    for (int i = 0; i < 20; ++i) {
        const double s = 0.045 * i, tf = 0.3 + 0.1 * s;
        const DecoupledForces f = decoupledForward(truth, kWheelA, s, tf);
        Sample sample;
        sample.slip = s;
        sample.entry_angle_rad = tf;
        sample.fx_n = f.fx_n;
        sample.fz_n = f.fz_n;
        sample.my_nm = f.my_nm;
        data.samples.push_back(sample);
    }
    const DecoupledFit fit = fitDecoupled(data, kWheelA, DecoupledParameters{});  // thesis guesses
    ASSERT_TRUE(fit.usable());
    ASSERT_EQ(fit.steps.size(), 3u);
    const DecoupledParameters& p = fit.parameters;
    EXPECT_NEAR(p.a0, truth.a0, 1e-7);
    EXPECT_NEAR(p.a1, truth.a1, 1e-7);
    EXPECT_NEAR(p.pressure_modulus, truth.pressure_modulus, 1e-5 * truth.pressure_modulus);
    EXPECT_NEAR(p.n0, truth.n0, 1e-6);
    EXPECT_NEAR(p.n1, truth.n1, 1e-6);
    EXPECT_NEAR(p.cohesion_pa, truth.cohesion_pa, 1e-4);
    EXPECT_NEAR(p.friction_angle_rad, truth.friction_angle_rad, 1e-8);
    EXPECT_NEAR(p.shear_modulus_m, truth.shear_modulus_m, 1e-8);
    for (const StepReport& step : fit.steps)
        EXPECT_LT(step.squared_residual_norm, 1e-16) << step.name.text;
}

TEST(DecoupledFit, FullModelDataShowsTheLinearisationBias) {
    // Issue #3 (measured with an independent implementation): on full-model data a0, a1 land near
    // 0.23–0.35 / 0.15–0.26, K_s runs to a bound, and sandy loam's φ comes out near 56° (truth
    // 29°).
    SyntheticSpec spec;
    for (int i = 0; i < 60; ++i) spec.slips.push_back(0.9 * i / 59);
    const SyntheticData sandy = synthesize(contact::testing::sandyLoam(), spec);
    const DecoupledFit fit = fitDecoupled(sandy.data, kWheelA, DecoupledParameters{});
    ASSERT_TRUE(fit.usable());
    const DecoupledParameters& p = fit.parameters;
    EXPECT_GE(p.a0, 0.23);
    EXPECT_LE(p.a0, 0.35);
    EXPECT_GE(p.a1, 0.15);
    EXPECT_LE(p.a1, 0.26);
    const DecoupledBounds bounds;
    EXPECT_TRUE(std::abs(p.pressure_modulus - bounds.ks_min) < 1.0 ||
                std::abs(p.pressure_modulus - bounds.ks_max) < 1.0);
    EXPECT_GT(p.friction_angle_rad / kDeg, 50.0);
    // It still fits F_x well: Σ r² below 0.01 N² over 60 samples.
    EXPECT_LT(fit.steps[0].squared_residual_norm, 0.01);
}

TEST(DecoupledFit, EmptyDataIsRejected) {
    EXPECT_THROW(fitDecoupled(DataSet{}, kWheelA, DecoupledParameters{}), std::invalid_argument);
}

}  // namespace
}  // namespace terra::identification
