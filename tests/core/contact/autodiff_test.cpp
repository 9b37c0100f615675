// The model is written for a generic scalar: with ceres::Jet it must give the value of the
// double version and derivatives that agree with central finite differences.
#include <ceres/jet.h>
#include <gtest/gtest.h>

#include <cmath>

#include "core/contact/quadratic_model.h"
#include "core/contact/wheel_forces.h"
#include "tests/core/contact/test_soils.h"

namespace terra::contact {
namespace {

using testing::kDeg;
using Jet = ceres::Jet<double, 5>;

// Derivative seeds: 0 n, 1 c, 2 φ, 3 K, 4 K_s.
ContactParameters<Jet> seeded(const ContactParameters<double>& p) {
    ContactParameters<Jet> j = p.cast<Jet>();
    j.sinkage_exponent = Jet(p.sinkage_exponent, 0);
    j.cohesion_pa = Jet(p.cohesion_pa, 1);
    j.friction_angle_rad = Jet(p.friction_angle_rad, 2);
    j.shear_modulus_m = Jet(p.shear_modulus_m, 3);
    j.pressure_modulus = Jet(p.pressure_modulus, 4);
    return j;
}

ContactParameters<double> nudged(ContactParameters<double> p, int which, double h) {
    double* fields[] = {&p.sinkage_exponent, &p.cohesion_pa, &p.friction_angle_rad,
                        &p.shear_modulus_m, &p.pressure_modulus};
    *fields[which] += h;
    return p;
}

template <typename Compute>
void checkDerivatives(const ContactParameters<double>& p, const OperatingPoint<double>& op,
                      Compute compute) {
    const WheelForces<Jet> jet = compute(seeded(p), op.cast<Jet>());
    const WheelForces<double> value = compute(p, op);
    EXPECT_NEAR(jet.fx.a, value.fx, 1e-12 * std::abs(value.fz));
    EXPECT_NEAR(jet.fz.a, value.fz, 1e-12 * std::abs(value.fz));
    const double scales[] = {1e-6, 1e-3 * p.cohesion_pa, 1e-6, 1e-6, 1e-6 * p.pressure_modulus};
    for (int k = 0; k < 5; ++k) {
        const double h = scales[k];
        const auto plus = compute(nudged(p, k, h), op), minus = compute(nudged(p, k, -h), op);
        const double dfx = (plus.fx - minus.fx) / (2 * h), dfz = (plus.fz - minus.fz) / (2 * h),
                     dmy = (plus.my - minus.my) / (2 * h);
        const double tol = 1e-5;
        EXPECT_NEAR(jet.fx.v[k], dfx, tol * (std::abs(dfx) + std::abs(dfz) + 1e-3))
            << "d Fx/d p" << k;
        EXPECT_NEAR(jet.fz.v[k], dfz, tol * (std::abs(dfz) + 1e-3)) << "d Fz/d p" << k;
        EXPECT_NEAR(jet.my.v[k], dmy, tol * (std::abs(dmy) + 1e-3)) << "d My/d p" << k;
    }
}

TEST(Autodiff, FullModelDerivativesMatchFiniteDifferences) {
    // s = ±1: the spinning and the locked wheel (docs/model.md, "Full slip"); the locked wheel's
    // limit takes no arithmetic on an infinite κ, so its derivatives stay finite.
    for (double s : {0.1, 0.5, -0.3, 1.0, -1.0}) {
        const OperatingPoint<double> op{s, 10.0 * kDeg, 28.0 * kDeg, 0.0, std::nullopt};
        checkDerivatives(testing::sandyLoam(), op,
                         [](const auto& p, const auto& o) { return computeForces(p, o); });
        checkDerivatives(testing::clayeySoil(), op,
                         [](const auto& p, const auto& o) { return computeForces(p, o); });
    }
}

TEST(Autodiff, QuadraticModelDerivativesMatchFiniteDifferences) {
    for (double s : {0.3, 1.0, -1.0}) {
        const OperatingPoint<double> op{s, 10.0 * kDeg, 28.0 * kDeg, -2.0 * kDeg, std::nullopt};
        checkDerivatives(testing::sandyLoam(INFINITY), op,
                         [](const auto& p, const auto& o) { return computeQuadraticForces(p, o); });
    }
}

}  // namespace
}  // namespace terra::contact
