#include "core/contact/quadratic_model.h"

#include <gtest/gtest.h>

#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <cmath>
#include <numbers>
#include <string>

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
        {"sandy loam",
         testing::sandyLoam(INFINITY),
         {2.1623, 0.4808, 0.4315, 0.2121},
         {1.7427, 0.3558, 0.3214, 0.1524}},
        {"dry sand",
         testing::drySand(INFINITY),
         {0.0680, 0.0235, 0.0220, 0.0086},
         {0.0582, 0.0203, 0.0190, 0.0074}},
        {"clayey soil",
         testing::clayeySoil(INFINITY),
         {6.3563, 0.8712, 0.7798, 0.3883},
         {4.9637, 0.5657, 0.5072, 0.2511}},
    };
    for (const Printed& t : tables) {
        // docs/model.md, Tables 2.4–2.5: a uniform grid of θ from 0 to 30° in 0.01° steps.
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

// The corrected Eqs. 2.41–2.46 must equal adaptive Gauss–Kronrod quadrature of the same fitted
// parabolas (the approximation's own integrals, not the full model's).
void expectClosedFormsEqualQuadrature(const ContactParameters<double>& p,
                                      const OperatingPoint<double>& op, const std::string& what) {
    using GK = boost::math::quadrature::gauss_kronrod<double, 31>;
    const StressField<double> field(p, op);
    const QuadraticStress<double> q = fitQuadraticStress(field);
    auto integrate = [&](auto f) {
        double total = 0.0;
        if (field.maxStressAngle() > field.exitAngle()) {
            total += GK::integrate(f, field.exitAngle(), field.maxStressAngle(), 5, 1e-14);
        }
        if (field.entryAngle() > field.maxStressAngle()) {
            total += GK::integrate(f, field.maxStressAngle(), field.entryAngle(), 5, 1e-14);
        }
        return total;
    };
    const double rb = p.radius_m * p.width_m, r2b = rb * p.radius_m;
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
    const double tol = 1e-11 * (std::abs(fz) + std::abs(fx));
    EXPECT_NEAR(f.fx, fx, tol) << what;
    EXPECT_NEAR(f.fz, fz, tol) << what;
    EXPECT_NEAR(f.fy, fy, tol + 1e-11 * std::abs(fy)) << what;
    EXPECT_NEAR(f.mx, mx, (tol + 1e-11 * std::abs(fy)) * p.radius_m) << what;
    EXPECT_NEAR(f.my, my, tol * p.radius_m) << what;
    EXPECT_NEAR(f.mz, mz, (tol + 1e-11 * std::abs(fy)) * p.radius_m) << what;
}

TEST(QuadraticModel, ClosedFormsEqualQuadratureOfTheSamePolynomials) {
    for (double s : {0.0, 0.3, -0.4}) {
        for (double beta : {0.0, 20.0}) {
            const OperatingPoint<double> op{s, beta * kDeg, 32.0 * kDeg, -5.0 * kDeg, std::nullopt};
            expectClosedFormsEqualQuadrature(
                testing::sandyLoam(), op,
                "s = " + std::to_string(s) + ", beta = " + std::to_string(beta));
        }
    }
}

TEST(QuadraticModel, ClosedFormsStayAccurateOnTinyRegions) {
    // Regression: the antiderivatives hold terms of size a ~ Δ²p/h² (σ's parabola near θ_f has
    // a ~ σ/h²) that cancel, losing ~eps/h³ relative: with a front region 1e-6 rad wide the total
    // F_z was off by ~1e-4. Below 0.3 rad the moments are summed as series instead.
    const auto p = testing::clayeySoil();  // N = 0.5: σ ∝ √(θ_f − θ) at the entry
    const double tf = 30.0 * kDeg;
    struct Case {
        const char* what;
        OperatingPoint<double> op;
    };
    const Case cases[] = {
        {"front region 1e-6 rad", {0.3, 10.0 * kDeg, tf, -5.0 * kDeg, tf - 1e-6}},
        {"front region 1e-3 rad", {0.3, 10.0 * kDeg, tf, -5.0 * kDeg, tf - 1e-3}},
        {"rear region 1e-6 rad", {0.3, 10.0 * kDeg, tf, -5.0 * kDeg, -5.0 * kDeg + 1e-6}},
        {"whole contact 1e-4 rad", {0.3, 10.0 * kDeg, 1e-4, -0.5e-4, std::nullopt}},
        {"whole contact 1e-6 rad, braking", {-0.5, 10.0 * kDeg, 1e-6, -1e-6, std::nullopt}},
        {"regions 0.29 and 0.31 rad (series/closed form switch)",
         {0.2, 5.0 * kDeg, 0.6, 0.0, 0.31}},
        {"regions 0.31 and 0.29 rad", {0.2, 5.0 * kDeg, 0.6, 0.0, 0.29}},
    };
    for (const Case& c : cases) expectClosedFormsEqualQuadrature(p, c.op, c.what);
}

TEST(QuadraticModel, IsCloseToTheFullModel) {
    // The approximation is good to a few per cent for these soils (errors of Table 2.4 scale).
    const OperatingPoint<double> op{0.3, 12.0 * kDeg, 30.0 * kDeg, 0.0, std::nullopt};
    for (const auto& p : {testing::sandyLoam(), testing::drySand(), testing::clayeySoil()}) {
        const auto full = computeForces(p, op);
        const auto quad = computeQuadraticForces(p, op);
        EXPECT_NEAR(quad.fz, full.fz, 0.06 * full.fz);
        EXPECT_NEAR(quad.my, full.my, 0.06 * std::abs(full.my));
        // F_b does not depend on the stress model: both must give the corrected Eq. 2.30 (E1),
        // written here in the depth d = r cos θ_f (bulldozing.h uses the θ_f form and series):
        // F_b = 2 a_s (r² − d²)^{3/2}/3 + (b_s − a_s d)(r² acos(d/r) − d √(r² − d²)), Bekker's
        // a_s = γ c_s², b_s = 2 c c_s, c_s = tan(45° + φ/2).
        const double r = p.radius_m, d = r * std::cos(op.entry_angle_rad);
        const double cs = std::tan(std::numbers::pi / 4 + p.friction_angle_rad / 2);
        const double as = p.unit_weight_n_m3 * cs * cs, bs = 2 * p.cohesion_pa * cs;
        const double fb = 2 * as * std::pow(r * r - d * d, 1.5) / 3 +
                          (bs - as * d) * (r * r * std::acos(d / r) - d * std::sqrt(r * r - d * d));
        EXPECT_NEAR(quad.fb, fb, 1e-12 * fb);
        EXPECT_NEAR(full.fb, fb, 1e-12 * fb);
    }
}

}  // namespace
}  // namespace terra::contact
