#include "core/contact/stress_field.h"

#include <gtest/gtest.h>

#include <boost/multiprecision/cpp_bin_float.hpp>
#include <cmath>
#include <limits>

#include "tests/core/contact/test_soils.h"

namespace terra::contact {
namespace {

using testing::kDeg;
constexpr double kNoLimit = std::numeric_limits<double>::infinity();

OperatingPoint<double> slipAnglePoint(double s, double beta_deg, double theta_f_deg = 30.0) {
    return {s, beta_deg * kDeg, theta_f_deg * kDeg, 0.0, std::nullopt};
}

TEST(StressField, NoShearAtTheFrontEdge) {
    // j(θ_f) = 0 by Eq. 2.14, so τ = 0 at the entry point whatever the slip (Eq. 2.20).
    for (double s : {0.0, 0.3, -0.4}) {
        for (double beta : {0.0, 12.0}) {
            const StressField<double> field(testing::sandyLoam(), slipAnglePoint(s, beta));
            const StressSample<double> front = field.at(30.0 * kDeg);
            EXPECT_EQ(front.tau, 0.0) << "s = " << s << ", beta = " << beta;
            EXPECT_EQ(front.sigma, 0.0);
            EXPECT_EQ(front.shear, 0.0);
        }
    }
}

TEST(StressField, NormalStressFollowsBekkerInFrontOfThetaM) {
    // Eq. 2.17 front branch, by hand: K_s r^n (cos θ − cos θ_f)^n.
    const ContactParameters<double> p = testing::sandyLoam();
    const StressField<double> field(p, slipAnglePoint(0.3, 0.0));
    const double theta = 25.0 * kDeg;
    const double expected = (5.3e3 / 0.107 + 1.515e6) *
                            std::pow(0.092 * (std::cos(theta) - std::cos(30.0 * kDeg)), 0.7);
    EXPECT_NEAR(field.at(theta).sigma, expected, 1e-9 * expected);
}

TEST(StressField, NormalStressIsContinuousAndPeaksAtThetaM) {
    const StressField<double> field(testing::sandyLoam(), slipAnglePoint(0.3, 0.0));
    const double theta_m = field.maxStressAngle();
    EXPECT_NEAR(theta_m, (0.2 + 0.3 * 0.3) * 30.0 * kDeg, 1e-15);  // Eq. 2.18
    const double at = field.at(theta_m).sigma;
    EXPECT_NEAR(field.at(theta_m - 1e-9).sigma, at, 1e-5 * at);
    EXPECT_LT(field.at(theta_m + 0.01).sigma, at);
    EXPECT_LT(field.at(theta_m - 0.01).sigma, at);
    EXPECT_EQ(field.at(0.0).sigma, 0.0);  // θ_e = θ_f at the exit (Eq. 2.19)
}

TEST(StressField, ShearIsColinearWithShearVelocity) {
    // Eq. 2.22: (τ_t, τ_l) ∥ (1 − κ cos θ, κ tan β), with |(τ_t, τ_l)| = τ.
    const double s = 0.2, beta = 20.0 * kDeg;
    const StressField<double> field(testing::sandyLoam(kNoLimit), slipAnglePoint(s, 20.0));
    const double theta = 10.0 * kDeg;
    const StressSample<double> st = field.at(theta);
    const double vt = 1.0 - (1.0 - s) * std::cos(theta), vl = (1.0 - s) * std::tan(beta);
    EXPECT_NEAR(std::hypot(st.tau_t, st.tau_l), st.tau, 1e-12 * st.tau);
    EXPECT_NEAR(st.tau_t * vl - st.tau_l * vt, 0.0, 1e-12 * st.tau);
    EXPECT_GT(st.tau_t, 0.0);
}

TEST(StressField, ShearDeformationMatchesEq214) {
    const double s = 0.3, beta = 12.0 * kDeg, tf = 30.0 * kDeg, r = 0.092, theta = 5.0 * kDeg;
    const StressField<double> field(testing::sandyLoam(kNoLimit), slipAnglePoint(s, 12.0));
    const StressSample<double> st = field.at(theta);
    const double jt = r * ((tf - theta) - (1 - s) * (std::sin(tf) - std::sin(theta)));
    const double jl = r * (1 - s) * (tf - theta) * std::tan(beta);
    EXPECT_NEAR(st.shear_t, jt, 1e-15);
    EXPECT_NEAR(st.shear_l, jl, 1e-15);
    EXPECT_NEAR(st.shear, std::hypot(jt, jl), 1e-15);
    const double tau =
        (1.7e3 + st.sigma * std::tan(29.0 * kDeg)) * (1 - std::exp(-st.shear / 0.025));
    EXPECT_NEAR(st.tau, tau, 1e-12 * tau);
}

TEST(StressField, ShearLimitCapsDeformation) {
    // With j_max (Eq. 2.16) the deformation never exceeds the limit; far from θ_f it saturates.
    const StressField<double> field(testing::sandyLoam(0.002), slipAnglePoint(0.9, 0.0));
    EXPECT_DOUBLE_EQ(field.at(0.0).shear, 0.002);
    const StressSample<double> st = field.at(0.0);
    EXPECT_NEAR(st.tau, 1.7e3 * (1 - std::exp(-0.002 / 0.025)), 1e-9);  // σ(θ_r) = 0
}

TEST(StressField, BrakingUsesTheSkidKinematics) {
    // docs/model.md, Slip: κ = 1/(1 + s) for −1 < s < 0; near θ_f the soil moves faster than the
    // rim, so the tangential shear stress opposes rotation (negative).
    const double s = -0.5;
    const StressField<double> field(testing::sandyLoam(kNoLimit), slipAnglePoint(s, 0.0));
    EXPECT_DOUBLE_EQ(field.velocityRatio(), 2.0);
    EXPECT_LT(field.at(0.0).tau_t, 0.0);
    // The slip → 0 limits from both sides agree.
    const StressField<double> plus(testing::sandyLoam(), slipAnglePoint(1e-9, 5.0));
    const StressField<double> minus(testing::sandyLoam(), slipAnglePoint(-1e-9, 5.0));
    const double theta = 12.0 * kDeg;
    EXPECT_NEAR(plus.at(theta).tau_t, minus.at(theta).tau_t, 1e-6 * plus.at(theta).tau_t);
    EXPECT_NEAR(plus.at(theta).sigma, minus.at(theta).sigma, 1e-6 * plus.at(theta).sigma);
}

TEST(StressField, StagnationPointTakesTheDrivingDirection) {
    // s = 0, β = 0: the shear velocity vanishes at θ = 0; the one-sided limit (+1, 0)
    // (docs/model.md, Stagnation point).
    OperatingPoint<double> op = slipAnglePoint(0.0, 0.0);
    op.exit_angle_rad = -5.0 * kDeg;
    const StressField<double> field(testing::sandyLoam(), op);
    const StressSample<double> st = field.at(0.0);
    EXPECT_GT(st.tau, 0.0);
    EXPECT_DOUBLE_EQ(st.tau_t, st.tau);
    EXPECT_EQ(st.tau_l, 0.0);
}

TEST(StressField, NormalStressKeepsFullPrecisionAtTinyEntryAngles) {
    // Regression: cos θ − cos θ_f lost ~eps/θ_f² relative (2e-8 at θ_f = 1e-4 rad). Reference:
    // Eqs. 2.17 and 2.19 evaluated in 50-digit arithmetic.
    using Big = boost::multiprecision::cpp_bin_float_50;
    const ContactParameters<double> p = testing::clayeySoil();
    for (double tf : {1e-3, 1e-4, 1e-6}) {
        OperatingPoint<double> op{0.3, 0.0, tf, -0.5 * tf, std::nullopt};
        const StressField<double> field(p, op);
        const double tm = field.maxStressAngle(), tr = field.exitAngle();
        const Big slope = (Big(tf) - Big(tm)) / (Big(tm) - Big(tr));
        for (double fraction : {0.999, 0.9, 0.5, 0.1, -0.2, -0.45}) {
            const double theta = fraction * tf;
            const Big equivalent =
                theta >= tm ? Big(theta) : Big(tf) - (Big(theta) - Big(tr)) * slope;
            const Big base =
                boost::multiprecision::cos(equivalent) - boost::multiprecision::cos(Big(tf));
            const double expected =
                static_cast<double>(Big(p.pressure_modulus) *
                                    boost::multiprecision::pow(Big(p.radius_m) * base, Big(0.5)));
            EXPECT_NEAR(field.at(theta).sigma, expected, 1e-13 * expected)
                << "theta_f = " << tf << ", theta = " << fraction << " theta_f";
        }
    }
}

}  // namespace
}  // namespace terra::contact
