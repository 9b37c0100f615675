#include "core/contact/bulldozing.h"

#include <gtest/gtest.h>

#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <cmath>

#include "tests/core/contact/test_soils.h"

namespace terra::contact {
namespace {

using testing::kDeg;

// Eq. 2.29 integrated numerically over the submerged circular segment, in polar coordinates about
// the wheel centre: for each θ in ±θ_f the radius t runs from the soil surface d / cos θ
// (d = r cos θ_f) to the rim r; the depth is h = t cos θ − d (Eq. 2.28), the pressure
// σ = a_s h + b_s (Eq. 2.26) and the area element t dt dθ.
double bulldozingByQuadrature(const ContactParameters<double>& p, double theta_f,
                              BulldozingModel m) {
    double a_s = 0, b_s = 0;
    bulldozingCoefficients(p, m, a_s, b_s);
    const double r = p.radius_m, d = r * std::cos(theta_f);
    using GK = boost::math::quadrature::gauss_kronrod<double, 31>;
    auto ray = [&](double th) {
        auto pressure = [&](double t) { return (a_s * (t * std::cos(th) - d) + b_s) * t; };
        return GK::integrate(pressure, d / std::cos(th), r, 0, 1e-14);
    };
    return GK::integrate(ray, -theta_f, theta_f, 8, 1e-13);
}

TEST(Bulldozing, ClosedFormMatchesDoubleIntegralOfEq229) {
    const ContactParameters<double> p = testing::sandyLoam();
    for (BulldozingModel m : {BulldozingModel::kBekker, BulldozingModel::kHegedus}) {
        for (double deg : {0.5, 5.0, 14.0, 14.4, 30.0, 60.0, 89.0}) {
            const double closed = bulldozingForce(p, deg * kDeg, m);
            const double numeric = bulldozingByQuadrature(p, deg * kDeg, m);
            EXPECT_NEAR(closed, numeric, 1e-8 * numeric) << deg << " deg";
        }
    }
}

TEST(Bulldozing, CoefficientsOfEq227) {
    const ContactParameters<double> p = testing::sandyLoam();
    const double cs = std::tan(std::numbers::pi / 4 + 29.0 * kDeg / 2);
    double a = 0, b = 0;
    bulldozingCoefficients(p, BulldozingModel::kBekker, a, b);
    EXPECT_NEAR(a, 15.2e3 * cs * cs, 1e-9 * a);
    EXPECT_NEAR(b, 2 * 1.7e3 * cs, 1e-9 * b);
    bulldozingCoefficients(p, BulldozingModel::kHegedus, a, b);
    EXPECT_NEAR(a, 2 * 15.2e3 * cs * (cs + cs * cs * std::tan(29.0 * kDeg)), 1e-9 * a);
}

TEST(Bulldozing, SeriesAndDirectFormulaAgreeAtTheSwitch) {
    // Below 0.25 rad the closed form uses Taylor series; on both sides of the switch it must
    // match the independent double integral.
    const ContactParameters<double> p = testing::clayeySoil();
    for (double theta : {0.25 - 1e-9, 0.25 + 1e-9, 0.01}) {
        const double closed = bulldozingForce(p, theta, BulldozingModel::kBekker);
        const double numeric = bulldozingByQuadrature(p, theta, BulldozingModel::kBekker);
        EXPECT_NEAR(closed, numeric, 1e-10 * numeric) << theta;
    }
}

TEST(Bulldozing, PrintedEq230OverestimatesAsMODELNOTESSays) {
    // The printed form (a_s d + b)(…) with r d √(1 − d²/r²) is 1.2× to 11× too large (E1).
    const ContactParameters<double> p = testing::sandyLoam();
    double a_s = 0, b_s = 0;
    bulldozingCoefficients(p, BulldozingModel::kBekker, a_s, b_s);
    const double r = p.radius_m, tf = 30.0 * kDeg, d = r * std::cos(tf);
    const double printed =
        2 * a_s * r * std::sqrt(1 - d * d / r / r) * (r * r - d * d) / 3 +
        (a_s * d + b_s) * (r * r * std::acos(d / r) - r * d * std::sqrt(1 - d * d / r / r));
    const double ratio = printed / bulldozingForce(p, tf, BulldozingModel::kBekker);
    EXPECT_GT(ratio, 1.2);
    EXPECT_LT(ratio, 11.0);
}

}  // namespace
}  // namespace terra::contact
