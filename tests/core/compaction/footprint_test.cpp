#include "core/compaction/footprint.h"

#include <gtest/gtest.h>

#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <cmath>
#include <numbers>

#include "core/contact/sinkage.h"
#include "core/contact/wheel_forces.h"
#include "tests/core/contact/test_soils.h"

namespace terra::compaction {
namespace {

using contact::testing::kDeg;
constexpr double kLoad = 58.86;  // [N]

struct Solved {
    contact::ContactParameters<double> p;
    contact::OperatingPoint<double> op;
    contact::WheelForces<double> forces;
};

Solved solveFootprint(const contact::ContactParameters<double>& p, double slip, double beta_deg) {
    contact::EntryAngleProblem problem;
    problem.load_n = kLoad;
    problem.slip = slip;
    problem.slip_angle_rad = beta_deg * kDeg;
    const contact::SinkageSolution s = contact::solveEntryAngle(p, problem);
    EXPECT_TRUE(s.ok()) << s.message;
    const contact::OperatingPoint<double> op = contact::operatingPoint(problem, s.entry_angle_rad);
    return {p, op, contact::computeForces(p, op)};
}

Eigen::Vector3d total(const std::vector<PointLoad>& loads) {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (const PointLoad& l : loads) sum += l.force;
    return sum;
}

TEST(Footprint, TheLoadsSumToTheWheelsForces) {
    // Σ F on the soil is the reaction of the adaptive integrator's forces (a different rule).
    for (const double slip : {0.0, 0.2, 0.6}) {
        for (const double beta : {0.0, 10.0}) {
            const Solved w = solveFootprint(contact::testing::sandyLoam(), slip, beta);
            for (const WidthProfile width : {WidthProfile::kUniform, WidthProfile::kParabolic}) {
                const Eigen::Vector3d sum = total(wheelFootprint(w.p, w.op, {width, 10, 7}));
                EXPECT_NEAR(sum.z(), kLoad, 2e-3 * kLoad) << slip << " " << beta;
                EXPECT_NEAR(sum.x(), -w.forces.fx, 2e-3 * kLoad) << slip << " " << beta;
                EXPECT_NEAR(sum.y(), -w.forces.fy, 2e-3 * kLoad) << slip << " " << beta;
            }
        }
    }
}

TEST(Footprint, UniformAcrossTheWidthOrParabolic) {
    const Solved w = solveFootprint(contact::testing::sandyLoam(), 0.2, 0.0);
    const std::vector<PointLoad> uniform =
        wheelFootprint(w.p, w.op, {WidthProfile::kUniform, 10, 7});
    const std::vector<PointLoad> parabolic =
        wheelFootprint(w.p, w.op, {WidthProfile::kParabolic, 10, 7});
    ASSERT_EQ(uniform.size(), parabolic.size());
    // Uniform: a column of nodes at one θ carries F_z in proportion to the Gauss weights; the
    // parabolic profile weights them by (3/2)(1 − (2y/b)²).
    const contact::GaussRule& across = contact::gaussRule(7);
    const double b = w.p.width_m;
    double column = 0.0;
    for (int j = 0; j < 7; ++j) column += uniform[j].force.z();
    for (int j = 0; j < 7; ++j) {
        EXPECT_NEAR(uniform[j].force.z(), column * across.weights[j], 1e-12 * column);
        const double u = 2.0 * uniform[j].position.y() / b;
        EXPECT_NEAR(parabolic[j].force.z(), uniform[j].force.z() * 1.5 * (1.0 - u * u),
                    1e-12 * column);
        EXPECT_NEAR(uniform[j].position.y(), (across.nodes[j] - 0.5) * b, 1e-15);
    }
    // Centred: the parabolic profile loads the centre line more, so σ_z is larger just below.
    const StressPropagation a(uniform, 5.0), c(parabolic, 5.0);
    const double z = 0.06;
    EXPECT_GT(c.verticalStressAt({0.0, 0.0, z}), a.verticalStressAt({0.0, 0.0, z}));
    // Deep below, the width profile no longer matters (within 0.5 %).
    EXPECT_NEAR(c.verticalStressAt({0.0, 0.0, 0.6}), a.verticalStressAt({0.0, 0.0, 0.6}),
                0.005 * a.verticalStressAt({0.0, 0.0, 0.6}));
}

TEST(Footprint, EveryPlaneBelowTheWheelCarriesItsLoad) {
    // Vertical equilibrium of the issue: ∫σ_z dA at a depth equals the wheel's load within 1 %.
    using boost::math::quadrature::gauss_kronrod;
    const Solved w = solveFootprint(contact::testing::sandyLoam(), 0.3, 5.0);
    const StressPropagation propagation(wheelFootprint(w.p, w.op), 5.0);
    for (const double z : {0.1, 0.3, 0.6}) {
        // ∫∫ σ_z dx dy over the plane, x and y mapped from (−1, 1) by t/(1 − t²).
        auto mapped = [](double t) { return t / (1.0 - t * t); };
        auto jacobian = [](double t) { return (1.0 + t * t) / ((1.0 - t * t) * (1.0 - t * t)); };
        const double integral = gauss_kronrod<double, 31>::integrate(
            [&](double tx) {
                return gauss_kronrod<double, 31>::integrate(
                           [&](double ty) {
                               return propagation.verticalStressAt(
                                          {mapped(tx) * z, mapped(ty) * z, z}) *
                                      jacobian(ty) * z;
                           },
                           -1.0, 1.0, 10, 1e-8) *
                       jacobian(tx) * z;
            },
            -1.0, 1.0, 10, 1e-8);
        EXPECT_NEAR(integral, kLoad, 0.01 * kLoad) << "z = " << z;
    }
}

TEST(Footprint, LoadsSitOnTheRimBelowTheRutsBottom) {
    contact::ContactParameters<double> p = contact::testing::sandyLoam();
    const Solved w = solveFootprint(p, 0.2, 0.0);
    p.rut_depth_m = 0.01;
    for (const PointLoad& l : wheelFootprint(p, w.op)) {
        // The rim point at θ with x = r sin θ lies r (cos θ − cos θ_f) below the rut's bottom.
        const double theta = std::asin(l.position.x() / p.radius_m);
        EXPECT_NEAR(l.position.z(),
                    0.01 + p.radius_m * (std::cos(theta) - std::cos(w.op.entry_angle_rad)), 1e-12);
    }
}

}  // namespace
}  // namespace terra::compaction
