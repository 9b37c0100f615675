#include "core/contact/quadratic_model.h"

#include <gtest/gtest.h>

#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <cmath>

#include "tests/core/contact/test_soils.h"

namespace terra::contact {
namespace {

using testing::kDeg;

// Table 2.3: wheel A, s = 0.3, β = 12°, θ_f = 30°, θ_r = 0, θ_m fixed at 15°, no j_max.
OperatingPoint<double> table23() { return {0.3, 12.0 * kDeg, 30.0 * kDeg, 0.0, 15.0 * kDeg}; }

struct Printed {
    const char* soil;
    ContactParameters<double> params;
    double rmse[4];  // σ, τ, τ_t, τ_l [kPa], Table 2.4 (E11: sandy loam τ_l 0.2121)
    double mae[4];   // Table 2.5
};

TEST(QuadraticModel, ReproducesTables24And25ToFourDecimals) {
    const Printed tables[] = {
        {"sandy loam", testing::sandyLoam(INFINITY), {2.1623, 0.4808, 0.4315, 0.2121},
         {1.7427, 0.3558, 0.3214, 0.1524}},
        {"dry sand", testing::drySand(INFINITY), {0.0680, 0.0235, 0.0220, 0.0086},
         {0.0582, 0.0203, 0.0190, 0.0074}},
        {"clayey soil", testing::clayeySoil(INFINITY), {6.3563, 0.8712, 0.7798, 0.3883},
         {4.9637, 0.5657, 0.5072, 0.2511}},
    };
    for (const Printed& t : tables) {
        // MODEL-NOTES: a uniform grid of θ from 0 to 30° in 0.01° steps.
        const auto errors = quadraticApproximationErrors(t.params, table23(), 0.01 * kDeg);
        for (int k = 0; k < 4; ++k) {
            EXPECT_NEAR(errors[k].rmse / 1e3, t.rmse[k], 0.5e-4) << t.soil << " RMSE " << k;
            EXPECT_NEAR(errors[k].mae / 1e3, t.mae[k], 0.5e-4) << t.soil << " MAE " << k;
            EXPECT_LE(errors[k].mae, errors[k].rmse);
        }
    }
}

TEST(QuadraticModel, ParabolasInterpolateTheExactStressAtTheirNodes) {
    const ContactParameters<double> p = testing::clayeySoil();
    const OperatingPoint<double> op{0.4, 10.0 * kDeg, 35.0 * kDeg, -4.0 * kDeg, std::nullopt};
    const StressField<double> field(p, op);
    const QuadraticStress<double> q = fitQuadraticStress(field);
    const double tm = field.maxStressAngle(), tf = field.entryAngle(), tr = field.exitAngle();
    for (double theta : {tm, (tm + tf) / 2, tf, (tm + tr) / 2, tr}) {  // Eq. 2.36 nodes
        const auto exact = field.at(theta), approx = q.at(theta);
        EXPECT_NEAR(approx.sigma, exact.sigma, 1e-9 * (1 + exact.sigma)) << theta;
        EXPECT_NEAR(approx.tau_t, exact.tau_t, 1e-9 * (1 + std::abs(exact.tau_t)));
        EXPECT_NEAR(approx.tau_l, exact.tau_l, 1e-9 * (1 + std::abs(exact.tau_l)));
    }
}

TEST(QuadraticModel, ClosedFormsEqualQuadratureOfTheSamePolynomials) {
    // Eqs. 2.41–2.46 (corrected) against adaptive Gauss–Kronrod of the fitted parabolas.
    using GK = boost::math::quadrature::gauss_kronrod<double, 31>;
    for (double s : {0.0, 0.3, -0.4}) {
        for (double beta : {0.0, 20.0}) {
            const ContactParameters<double> p = testing::sandyLoam();
            const OperatingPoint<double> op{s, beta * kDeg, 32.0 * kDeg, -5.0 * kDeg, std::nullopt};
            const StressField<double> field(p, op);
            const QuadraticStress<double> q = fitQuadraticStress(field);
            auto integrate = [&](auto f) {
                return GK::integrate(f, field.exitAngle(), field.maxStressAngle(), 5, 1e-14) +
                       GK::integrate(f, field.maxStressAngle(), field.entryAngle(), 5, 1e-14);
            };
            const double rb = 0.092 * 0.107, r2b = rb * 0.092;
            const double fx = rb * integrate([&](double t) {
                const auto st = q.at(t);
                return st.tau_t * std::cos(t) - st.sigma * std::sin(t);
            });
            const double fz = rb * integrate([&](double t) {
                const auto st = q.at(t);
                return st.sigma * std::cos(t) + st.tau_t * std::sin(t);
            });
            const double fy = -rb * integrate([&](double t) { return q.at(t).tau_l; });
            const double mx = -r2b * integrate([&](double t) { return q.at(t).tau_l * std::cos(t); });
            const double my = r2b * integrate([&](double t) { return q.at(t).tau_t; });
            const double mz = -r2b * integrate([&](double t) { return q.at(t).tau_l * std::sin(t); });
            const auto f = computeQuadraticForces(p, op);
            const double tol = 1e-11 * std::abs(fz);
            EXPECT_NEAR(f.fx, fx, tol) << "s = " << s << " beta = " << beta;
            EXPECT_NEAR(f.fz, fz, tol);
            EXPECT_NEAR(f.fy, fy, tol);
            EXPECT_NEAR(f.mx, mx, tol * 0.092);
            EXPECT_NEAR(f.my, my, tol * 0.092);
            EXPECT_NEAR(f.mz, mz, tol * 0.092);
        }
    }
}

TEST(QuadraticModel, IsCloseToTheFullModel) {
    // The approximation is good to a few per cent for these soils (errors of Table 2.4 scale).
    const OperatingPoint<double> op{0.3, 12.0 * kDeg, 30.0 * kDeg, 0.0, std::nullopt};
    for (const auto& p : {testing::sandyLoam(), testing::drySand(), testing::clayeySoil()}) {
        const auto full = computeForces(p, op);
        const auto quad = computeQuadraticForces(p, op);
        EXPECT_NEAR(quad.fz, full.fz, 0.06 * full.fz);
        EXPECT_NEAR(quad.my, full.my, 0.06 * std::abs(full.my));
        EXPECT_DOUBLE_EQ(quad.fb, full.fb);
    }
}

}  // namespace
}  // namespace terra::contact
